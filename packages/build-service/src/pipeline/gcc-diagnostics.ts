/**
 * The diagnostics of a job's build, as the API reports them, and where they point to. The parsers
 * of gcc's output are gcc-json.ts (JSON lines) and gcc-text.ts (text lines).
 */
import { posix } from 'node:path';
import { visibleText } from '@contract-studio/conventions';
import { regionAt, type ProtectedRegion } from './protected-regions.js';
import { withMigrationHint } from './migration-hints.js';
import type { OrphanedDefinitions } from './orphan-hints.js';

/** One gcc problem, located in the job's tree (see docs/build-service-api.md). */
export interface GccDiagnostic {
  severity: 'error' | 'warning' | 'note';
  message: string;
  option?: string;
  /** Relative to the tree root the job reports against (src-gen/ for Cactal projects). */
  file: string | null;
  line: number | null;
  column: number | null;
  endLine?: number;
  endColumn?: number;
  protectedRegion: ProtectedRegion | null;
  children: GccDiagnostic[];
  /** `run`: not a compiler's diagnostic but the run's (a module crashed at this line: crash-reports.ts); absent for gcc's and ld's. */
  origin?: 'run';
}

/**
 * Where diagnostics point to: gcc reports paths relative to the directory make ran it in (or
 * absolute, inside the sandbox). `resolve` turns such a path into a path relative to the reported
 * tree root, or null when the file is outside it (system headers).
 */
export interface DiagnosticContext {
  /** The sandbox-side absolute directory gcc ran in (make's current directory). */
  cwd: string;
  /** The sandbox-side absolute path of the reported tree root. */
  root: string;
  /** Protected regions of the files of the tree, indexed by root-relative path (trusted, read before the build). */
  regions: ReadonlyMap<string, readonly ProtectedRegion[]>;
  /**
   * The user's own copies of the tree's files that are not the file built (a Cactal project's
   * src-gen/ older than its model: the build generates a copy of its own), indexed as `regions`:
   * a diagnostic in one of these files is told at the user's line (userCopyPlace).
   */
  userCopies?: ReadonlyMap<string, UserCopy>;
  /** The functions defined only in the project's src-gen/orphans/ copies (orphan-hints.ts): a link error missing one names its copy. */
  orphanedDefinitions?: OrphanedDefinitions;
}

/** The user's own copy of a file of the tree, when it is not the file built. */
export interface UserCopy {
  /** Its protected regions; null when the user has no copy of that file (src-gen/ never generated, or without it). */
  regions: readonly ProtectedRegion[] | null;
}

/** What a diagnostic in a file the user's copy of which differs says: the line is the built file's. */
const NOT_YOUR_LINE = (line: number, copy: UserCopy): string =>
  ` (line ${line} of the file as this build generated it: ${copy.regions === null ? 'src-gen/ has no copy of it' : 'your copy in src-gen/ differs, older than the model'}; contract generate, or Generate All in the IDE, brings src-gen/ up to date)`;

/**
 * A diagnostic of a file built from a model newer than the user's src-gen/ copy, told in the
 * user's copy: a line inside a protected region is moved to that region in the user's file (the
 * build carried its text over, byte for byte: the same lines, at another place); any other line
 * keeps the built file's number, and the message says so.
 */
export function userCopyPlace(d: GccDiagnostic, copy: UserCopy): GccDiagnostic {
  if (d.line === null) return d;
  const built = d.protectedRegion;
  const mine = built ? copy.regions?.find((r) => r.id === built.id) : undefined;
  return (built && mine && movedToRegion(d, built, mine)) || { ...d, message: d.message + NOT_YOUR_LINE(d.line, copy) };
}

/**
 * `d`, at a line of region `built` of the file compiled, moved to the same line of region `mine`
 * of the user's file (its text carried over byte for byte: the same lines at another place; its
 * end too when it is in the region); undefined when `mine` is not as long (another text). The
 * build's placement (userCopyPlace) and the simulator's (compile-diagnostics.ts) both move so.
 */
export function movedToRegion(d: GccDiagnostic, built: ProtectedRegion, mine: ProtectedRegion): GccDiagnostic | undefined {
  if (d.line === null || mine.endLine - mine.startLine !== built.endLine - built.startLine) return undefined;
  const shift = mine.startLine - built.startLine;
  const { endLine, endColumn, ...rest } = d;
  const end = endLine !== undefined && endLine >= built.startLine && endLine <= built.endLine ? { endLine: endLine + shift, ...(endColumn !== undefined ? { endColumn } : {}) } : {};
  return { ...rest, ...end, line: d.line + shift, protectedRegion: mine };
}

export function relativeToRoot(file: string, ctx: DiagnosticContext): string | null {
  const abs = posix.resolve(ctx.cwd, file);
  const rel = posix.relative(ctx.root, abs);
  if (rel.startsWith('..') || posix.isAbsolute(rel)) return null;
  return rel;
}

export function severityOf(kind: unknown): GccDiagnostic['severity'] {
  if (kind === 'error' || kind === 'fatal error' || kind === 'fatal') return 'error';
  if (kind === 'warning') return 'warning';
  return 'note';
}

/**
 * Places a diagnostic in the tree: root-relative file (when inside it) and its protected region;
 * its message is written visibly (a control character of a `#warning` as its escape, `\u0007`), and gets the hint of a problem of code carried over from the ContrACT Eclipse tool (migration-hints.ts).
 */
export function located(
  found: Omit<GccDiagnostic, 'file' | 'protectedRegion'>,
  rawFile: string | null,
  ctx: DiagnosticContext,
): GccDiagnostic {
  // a message says the user's text (a `#warning`'s): its control and invisible characters are written as their escapes (visibleText), as shown everywhere
  const base = { ...found, message: withMigrationHint(visibleText(found.message)) };
  const file = rawFile === null ? null : (relativeToRoot(rawFile, ctx) ?? rawFile);
  const regions = file ? ctx.regions.get(file) : undefined;
  const protectedRegion = regions && base.line !== null ? regionAt(regions, base.line) : null;
  const copy = file ? ctx.userCopies?.get(file) : undefined;
  return copy ? userCopyPlace({ ...base, file, protectedRegion }, copy) : { ...base, file, protectedRegion };
}

/** gcc-like one-line rendering, for the text log. */
export function renderDiagnostic(d: GccDiagnostic): string {
  const where = d.file ? `${d.file}:${d.line ?? 0}${d.column === null ? '' : `:${d.column}`}: ` : '';
  const opt = d.option ? ` [${d.option}]` : '';
  const region = d.protectedRegion ? ` (in protected region ${d.protectedRegion.id})` : '';
  return `${where}${d.severity}: ${d.message}${opt}${region}`;
}

/** Whether a line begins as make's "Entering directory" or "Leaving directory" (its first bytes are enough). */
export function beginsAsMakeDirectory(head: string): boolean {
  return /^g?make(?:\[\d+\])?: (?:Entering|Leaving) directory /.test(head);
}

/** make's "make[1]: Entering directory '/work/x'" -> '/work/x'. */
export function makeEnteringDirectory(line: string): string | null {
  const m = /^g?make(?:\[\d+\])?: Entering directory [`'"](.*)['"]$/.exec(line);
  return m?.[1] ?? null;
}
export function makeLeavingDirectory(line: string): string | null {
  const m = /^g?make(?:\[\d+\])?: Leaving directory [`'"](.*)['"]$/.exec(line);
  return m?.[1] ?? null;
}
