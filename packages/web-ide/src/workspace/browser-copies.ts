/**
 * The browser copies of a file's unsaved edits (docs/ide.md "Saving"): one localStorage entry per
 * file and address, holding one copy per tab (page load) that edited it, so that two tabs of one
 * browser editing the same file while the server is away keep both texts: one tab's copy never
 * overwrites another's. A tab drops only its own copy once the server confirms its save; another
 * tab's copy left there (that tab closed, or reloaded, before it could save) is taken up by a tab
 * that loads the file, or that saved it, and merged with the disk as any restored copy is.
 * Pure: parse and update the stored text (browser-copies.test.ts).
 */

/** One tab's copy: its text and the base it was edited from. */
export interface BrowserCopy {
  text: string;
  /** The disk's text the tab edited (undefined: a bare copy of an older version). */
  baseText?: string;
  baseVersion?: string;
  /** A save in flight when the copy was made: if the disk holds it after a reload, it landed and is the base. */
  sentText?: string;
  /** When it was kept (ms since the epoch): copies are taken up oldest first. */
  at?: number;
}

/** What the entry holds: the copies by tab. */
interface Stored {
  v: 2;
  copies: Record<string, BrowserCopy>;
}

/** The tab id of a copy made by a version that kept one copy per file (one text for all tabs). */
export const SHARED_COPY = 'shared';

function copyOf(v: unknown): BrowserCopy | undefined {
  const c = v as Partial<BrowserCopy> | null;
  if (!c || typeof c !== 'object' || typeof c.text !== 'string') return undefined;
  return {
    text: c.text,
    ...(typeof c.baseText === 'string' ? { baseText: c.baseText } : {}),
    ...(typeof c.baseVersion === 'string' ? { baseVersion: c.baseVersion } : {}),
    ...(typeof c.sentText === 'string' ? { sentText: c.sentText } : {}),
    ...(typeof c.at === 'number' && Number.isFinite(c.at) ? { at: c.at } : {}),
  };
}

/**
 * The copies in a stored entry, by tab: the current form; a single copy (`v: 1`, made before copies
 * were kept by tab) or a bare text (before versions) as the one copy of SHARED_COPY. Nothing stored: none.
 */
export function parseCopies(raw: string | null): Map<string, BrowserCopy> {
  const out = new Map<string, BrowserCopy>();
  if (raw === null) return out;
  let v: unknown;
  try {
    v = JSON.parse(raw);
  } catch {
    out.set(SHARED_COPY, { text: raw }); // an old bare copy
    return out;
  }
  const o = v as { v?: unknown; copies?: unknown; baseText?: unknown } | null;
  if (o && o.v === 2 && o.copies && typeof o.copies === 'object') {
    for (const [tab, c] of Object.entries(o.copies as Record<string, unknown>)) {
      const copy = copyOf(c);
      if (copy) out.set(tab, copy);
    }
    return out;
  }
  const single = o && o.v === 1 && typeof o.baseText === 'string' ? copyOf(o) : undefined;
  out.set(SHARED_COPY, single ?? { text: typeof v === 'string' ? v : raw });
  return out;
}

/** The entry to store: `raw` with tab `tab`'s copy set to `copy` (undefined: removed); null when no copy is left. */
export function withCopy(raw: string | null, tab: string, copy: BrowserCopy | undefined): string | null {
  const copies = parseCopies(raw);
  if (copy) copies.set(tab, copy);
  else copies.delete(tab);
  if (!copies.size) return null;
  const stored: Stored = { v: 2, copies: Object.fromEntries(copies) };
  return JSON.stringify(stored);
}

/** The copies of other tabs than `tab`, oldest first. */
export function othersCopies(raw: string | null, tab: string): Array<[string, BrowserCopy]> {
  return [...parseCopies(raw)].filter(([id]) => id !== tab).sort((a, b) => (a[1].at ?? 0) - (b[1].at ?? 0));
}
