/**
 * Turns the raw output lines of a step into job events:
 *   build: tracks make's current directory ("Entering directory"), reads gcc diagnostics (JSON
 *          lines from -fdiagnostics-format=json, or gcc's text format) and maps them to the tree;
 *   run:   attributes each line to the module named by the launcher's tag ("[MAA] text").
 */
import { posix } from 'node:path';
import { SERVICE_BOUNDS } from '../limits.js';
import { makeEnteringDirectory, makeLeavingDirectory, renderDiagnostic, type GccDiagnostic, type UserCopy } from './gcc-diagnostics.js';
import type { OrphanedDefinitions } from './orphan-hints.js';
import { errorsFirst, looksLikeGccJson, parseCutGccJsonLine, parseGccJsonLine, parseOverfullGccJsonLine } from './gcc-json.js';
import { parseGccTextLine } from './gcc-text.js';
import { LinkErrorReader, parseLinkerLine } from './ld-text.js';
import { parseAssemblerLine } from './as-text.js';
import type { ProtectedRegion } from './protected-regions.js';

export interface RoutedLine {
  source: string;
  line: string;
}

export interface BuildRouterOptions {
  /** Sandbox-side absolute directory make starts in. */
  startDir: string;
  /** Sandbox-side absolute tree root diagnostics are reported against. */
  root: string;
  regions: ReadonlyMap<string, readonly ProtectedRegion[]>;
  /** The user's copies of the tree's files that are not the files built (DiagnosticContext.userCopies). */
  userCopies?: ReadonlyMap<string, UserCopy>;
  /** The functions defined only in the project's orphans copies (DiagnosticContext.orphanedDefinitions). */
  orphanedDefinitions?: OrphanedDefinitions;
  /** gcc's JSON diagnostics come on stdout too (a build whose stderr is merged into its stdout, 2>&1). */
  diagnosticsOnStdout?: boolean;
}

export class BuildOutputRouter {
  private readonly dirs: string[];
  /** The assembler's and ld's errors: each says one again for every use of what is wrong. */
  private readonly linkErrors = new LinkErrorReader();

  constructor(private readonly options: BuildRouterOptions) {
    this.dirs = [options.startDir];
  }

  private get cwd(): string {
    return this.dirs[this.dirs.length - 1] ?? this.options.startDir;
  }

  /**
   * Returns the lines to log and the diagnostics found in one output line; `cut` says when they
   * were read from a gcc JSON line that was cut (the job's warning), what followed being lost.
   */
  route(line: string, stream: 'stdout' | 'stderr'): { lines: RoutedLine[]; diagnostics: GccDiagnostic[]; cut?: string; unreadable?: string } {
    // untrusted text: no regular expression sees more than the parsed-line bound (docs/sandbox.md)
    const head = line.length > SERVICE_BOUNDS.parsedLineChars ? line.slice(0, SERVICE_BOUNDS.parsedLineChars) : line;
    const entering = makeEnteringDirectory(head);
    if (entering) this.dirs.push(posix.resolve(this.cwd, entering));
    else if (makeLeavingDirectory(head) && this.dirs.length > 1) this.dirs.pop();
    const ctx = { cwd: this.cwd, root: this.options.root, regions: this.options.regions, ...(this.options.userCopies ? { userCopies: this.options.userCopies } : {}), ...(this.options.orphanedDefinitions ? { orphanedDefinitions: this.options.orphanedDefinitions } : {}) };
    if ((stream === 'stderr' || this.options.diagnosticsOnStdout) && looksLikeGccJson(line)) {
      const diags = parseGccJsonLine(line, ctx);
      // the log in gcc's order; the job's diagnostics errors first
      if (diags) return { lines: rendered(diags), diagnostics: errorsFirst(diags) };
      // a whole line of more diagnostics than are read: its errors first, the rest said left out
      const overfull = parseOverfullGccJsonLine(line, ctx);
      if (overfull) {
        const said = gccJsonOverfullMessage(overfull.diagnostics, overfull.left);
        return { lines: rendered(overfull.diagnostics), diagnostics: errorsFirst(overfull.diagnostics), cut: said };
      }
      // a compilation's line that an output bound cut (it does not close): its complete diagnostics
      const cut = parseCutGccJsonLine(line, ctx);
      if (cut) {
        const said = gccJsonCutMessage(line.length, cut.readChars, cut.diagnostics);
        return { lines: rendered(cut.diagnostics), diagnostics: errorsFirst(cut.diagnostics), cut: said };
      }
      // gcc's line that cannot be read at all: logged as text, and said (its errors are not reported)
      return { lines: [{ source: 'build', line }], diagnostics: [], unreadable: GCC_JSON_UNREADABLE };
    }
    const text = parseGccTextLine(line, ctx);
    if (text) return { lines: [{ source: 'build', line }], diagnostics: text.severity !== 'note' ? [text] : [] };
    // the assembler's (as-text.ts) and the linker's (ld-text.ts) errors at the user's files, each once
    const asm = parseAssemblerLine(line, ctx);
    const ld = asm ? { kind: 'diagnostic' as const, diagnostic: asm } : parseLinkerLine(line, ctx);
    const d = this.linkErrors.read(ld);
    if (!d || !this.linkErrors.first(renderDiagnostic(d))) return { lines: [{ source: 'build', line }], diagnostics: [] };
    return { lines: [{ source: 'build', line }], diagnostics: [d] };
  }
}

/** The log lines of a compilation's diagnostics: each, then its notes. */
function rendered(diags: GccDiagnostic[]): RoutedLine[] {
  return diags.flatMap((d) => [d, ...d.children]).map((d) => ({ source: 'build', line: renderDiagnostic(d) }));
}

/**
 * What a build says of a line that begins as gcc's JSON diagnostics and cannot be read, not even
 * with its raw control characters escaped (gcc-json-controls.ts), nor as a cut line: the
 * diagnostics it held are not reported.
 */
export const GCC_JSON_UNREADABLE = "a line of gcc's JSON diagnostics (one compilation's) could not be read (not JSON of gcc's shape, even with its control characters escaped): "
  + "the diagnostics it held, its errors among them, are not reported; the line is in the build's log as text (--verbose, GET /api/jobs/:id/log)";

/** What a build says of a gcc JSON line that held more diagnostics than are read: which were, how many were not. */
export function gccJsonOverfullMessage(diags: readonly GccDiagnostic[], left: number): string {
  const errors = diags.filter((d) => d.severity === 'error').length;
  return `a line of gcc's JSON diagnostics (one compilation's) held more than the ${SERVICE_BOUNDS.diagnosticsPerJsonLine} diagnostics read `
    + `(diagnosticsPerJsonLine, diagnosticChildren): ${diags.length} read, its errors first (${errors} error(s)), ${left} other(s) not reported`;
}

/** What a build says of a gcc JSON line that was cut: how much of it was read, what is lost. */
export function gccJsonCutMessage(lineChars: number, readChars: number, diags: readonly GccDiagnostic[]): string {
  const errors = diags.filter((d) => d.severity === 'error').length;
  return `a line of gcc's JSON diagnostics (one compilation's) was cut after ${lineChars} characters by an output bound `
    + `(gccJsonLineBytes ${SERVICE_BOUNDS.gccJsonLineBytes} bytes, or the step's outputBytesPerStream): its first ${diags.length} complete `
    + `diagnostic(s) (${errors} error(s)) were read from its first ${readChars} characters, those after them are lost`;
}

// only a bounded prefix is matched; the rest is sliced off, so a module line holding a bare CR
// (or U+2028) is still that module's line, not make's
const MODULE_TAG = /^\[([A-Za-z_][A-Za-z0-9_.-]{0,63})\]\s?/;
/** The longest prefix MODULE_TAG can match ("[" + 64 + "]" + one space). */
const MODULE_TAG_CHARS = 67;

/**
 * "[MAA] hello" -> {source: 'MAA', line: 'hello'} (the launcher's module tags);
 * "contract-launch: ..." -> source 'launcher'; other untagged lines (make) -> source 'run'.
 */
export function routeRunLine(line: string): RoutedLine {
  const m = MODULE_TAG.exec(line.slice(0, MODULE_TAG_CHARS));
  if (m) return { source: m[1]!, line: line.slice(m[0].length) };
  if (line.startsWith('contract-launch: ')) return { source: 'launcher', line: line.slice('contract-launch: '.length) };
  return { source: 'run', line };
}

// make's own line for a recipe that failed: "make: *** [Makefile:40: run] Error 1" (make[1] in a sub-make)
const MAKE_RECIPE_ERROR = /^make(?:\[\d{1,4}\])?: \*\*\* \[[^\]]{0,300}: ([A-Za-z0-9_.-]{1,64})\] Error (\d{1,3})$/;

/**
 * The target and exit status make names for a recipe that failed ("Error 1": the recipe's own
 * status; make itself then exits 2), or null for any other line. The run step's message gives
 * both, so that the `Error 1` the user sees in the log and make's exit 2 do not read as a contradiction.
 */
export function makeRecipeStatus(line: string): { target: string; status: number } | null {
  if (line.length > 400 || !line.startsWith('make')) return null;
  const m = MAKE_RECIPE_ERROR.exec(line);
  return m ? { target: m[1]!, status: Number(m[2]) } : null;
}
