/**
 * The IDE's own commands (Generate All, Build & Run, open a view, ...) with their shortcuts. One
 * window-level key listener (capture phase, so it runs before Monaco's) dispatches the shortcuts;
 * the command palette lists the commands with their shortcuts (docs/ide.md "Keyboard").
 */
export interface Command {
  id: string;
  label: string;
  /** `Ctrl+Shift+G`, `Alt+Shift+D`, `F1`, `Shift+F5`: Ctrl also matches ⌘ on a Mac. */
  keys?: string[];
  /** Listed in the palette (false: a shortcut only, e.g. the palette itself). */
  inPalette?: boolean;
  run(): unknown;
}

interface Chord {
  ctrl: boolean;
  shift: boolean;
  alt: boolean;
  key: string;
}

export function parseChord(text: string): Chord {
  const parts = text.split('+');
  const key = parts.pop()!.toLowerCase();
  const mods = new Set(parts.map((p) => p.toLowerCase()));
  return { ctrl: mods.has('ctrl'), shift: mods.has('shift'), alt: mods.has('alt'), key };
}

/** The key of an event as the chord names it: the letter or digit of the physical key (Alt+Shift on some layouts changes `e.key`). */
function keyOf(e: KeyboardEvent): string {
  if (/^Key[A-Z]$/.test(e.code)) return e.code.slice(3).toLowerCase();
  if (/^Digit\d$/.test(e.code)) return e.code.slice(5);
  return e.key.toLowerCase();
}

export function chordMatches(chord: Chord, e: KeyboardEvent): boolean {
  return chord.ctrl === (e.ctrlKey || e.metaKey) && chord.shift === e.shiftKey && chord.alt === e.altKey && chord.key === keyOf(e);
}

export class CommandRegistry {
  private readonly commands: Command[] = [];

  constructor(target: Window = window) {
    target.addEventListener('keydown', (e) => {
      if (e.defaultPrevented) return;
      const cmd = this.commands.find((c) => c.keys?.some((k) => chordMatches(parseChord(k), e)));
      if (!cmd || document.querySelector('.dialog-overlay, [aria-modal="true"]')) return; // a dialog open: its keys are its own
      e.preventDefault(); // Ctrl+P is the browser's print otherwise
      e.stopPropagation();
      if (!e.repeat) void Promise.resolve().then(() => cmd.run());
    }, { capture: true });
  }

  add(...commands: Command[]): void {
    this.commands.push(...commands);
  }

  get(id: string): Command | undefined {
    return this.commands.find((c) => c.id === id);
  }

  /** The commands the palette lists, in registration order. */
  list(): Command[] {
    return this.commands.filter((c) => c.inPalette !== false);
  }
}
