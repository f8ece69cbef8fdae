/**
 * JSON shapes that the IDE server sends and the browser client (src/api.ts) reads: one definition
 * for both sides. Types only — the browser imports this file, so it imports nothing but types
 * (the packages' own: codegen's report, the simulator's step records; docs/architecture.md "Seams").
 */
import type { GenerationReport } from '@contract-studio/codegen';
import type { RuleChange, SimTraceRecord, StepRecord, StepResult } from '@contract-studio/simulator';

/** One entry of the workspace tree (GET /api/tree, /api/snapshot). */
/** A job the IDE server announces to its tabs on /api/events (`job`, `jobs`: server/shared-runs.ts). */
/**
 * A recent Build & Run job of the workspace (`GET /api/recent-runs`: the build service's listing of the
 * IDE server's jobs), for the Monitor's run list of every tab.
 */
export interface RecentRun {
  id: string;
  /** The project folder, relative to the workspace ('' = the workspace itself). */
  project: string;
  /** The build service's status: queued, preparing, building, running, succeeded, failed, cancelled. */
  status: string;
  /** When it was submitted and when it ended (ms since the epoch; null while it goes on). */
  createdAt: number;
  finishedAt: number | null;
  /** Its result (null until it ended): ok, and the service's message. */
  ok: boolean | null;
  message: string | null;
}

export interface SharedJob {
  id: string;
  action: 'build' | 'run';
  /** The project folder, relative to the workspace ('' = the workspace itself). */
  project: string;
}

/** A generated file whose protected regions hold user code (GET /api/user-code, /api/folder-contents). */
export interface HeldUserCode {
  /** Workspace-relative. */
  path: string;
  /** Its regions holding code (recorded first, as a build records them). */
  regions: string[];
  /** Whether the next generation restores them if the file is deleted (from its tree's copy of that code). */
  restorable: boolean;
}

/** GET /api/folder-contents?path=F: what deleting folder F deletes (its delete confirmation). */
export interface FolderContents {
  /** The files in it, as the Explorer lists them (links left out). */
  files: number;
  /** The listing stopped at its bounds (file-tree.ts): at least `files`. */
  cut: boolean;
  /** Its generated files holding user code in protected regions, in path order. */
  userCode: HeldUserCode[];
}

export interface TreeEntry {
  name: string;
  /** Workspace-relative path with '/' separators. */
  path: string;
  type: 'file' | 'dir';
  children?: TreeEntry[];
  /** A folder whose content is not listed: deeper than the tree's depth bound, or past its entry bound (file-tree.ts). */
  truncated?: true;
}

/** What Generate All did: codegen's report of generateArchitecture (Seam 4), paths relative to src-gen. */
export type GenerateReport = GenerationReport;

/** The answer of POST /api/generate: the report, the workspace-relative src-gen folder and the time taken. */
export interface GenerateResponse extends GenerateReport {
  srcGen: string;
  /** Trees of the project that are not used (a second `src-gen/` below its root), each said (docs/codegen.md "Where a project is"). */
  layoutWarnings: string[];
  ms: number;
}

/** The answer of GET /api/file. */
export interface FileReadResponse {
  path: string;
  content: string;
  mtimeMs: number;
  /** SHA-256 (hex) of the file's bytes: the base a save of this text names (`If-Match`). */
  version: string;
  /**
   * Set when the file holds bytes that are not UTF-8 (Latin-1, binary): the first line with one.
   * `content` shows each as U+FFFD; the tab opens read-only, and a save of another text is refused.
   */
  undecodableLine?: number;
}

/** The details of a 409 answer to a save made on a stale base (the file on disk now). */
export interface StaleSaveDetails {
  stale: true;
  content: string;
  version: string;
}

/** The answer of PUT /api/file. */
export interface FileWriteResponse {
  path: string;
  mtimeMs: number;
  /** The version of the text now on disk (the next save's base). */
  version: string;
  /**
   * Set when the file is generated and its generated code (outside the protected regions) differed
   * from the file on disk: the server kept the disk's code, wrote the incoming regions into it, and
   * `content` is the text now on disk — the client reloads the tab from it.
   */
  merged?: true;
  reason?: string;
  content?: string;
}

/** A problem of a scenario or of the model, with its place (1-based). */
export interface SimulateDiagnostic {
  /** Workspace-relative file for model errors; absent for the scenario itself. */
  file?: string;
  line: number;
  column: number;
  endLine?: number;
  endColumn?: number;
  severity: 'error' | 'warning' | 'info';
  message: string;
  code?: string;
}

/** One rule change of a simulated step, as the `sup_rule` records of a real run (docs/simulation.md §4). */
export type SimulateRuleChange = RuleChange;
export type { SimTraceRecord };

/**
 * One step of POST /api/simulate: the simulator's step result (scenario line, its record's time, ok
 * and message) with what its record changed and the state after it, bounded by the server.
 */
export type SimulateStep = Pick<StepResult, 'line' | 'source' | 'timeNs' | 'kind' | 'ok' | 'message' | 'trimmed'>
  & Pick<StepRecord, 'rules' | 'actions' | 'output' | 'error' | 'dropped'> & Partial<Pick<StepRecord, 'log' | 'records'>>
  & Required<Pick<StepRecord, 'schemas' | 'locals'>>;

/** The answer of POST /api/simulate (200: the scenario ran; 422: diagnostics, nothing ran). */
export interface SimulateResponse {
  title?: string;
  passed: boolean;
  endNs: number;
  steps: SimulateStep[];
  failures: Array<{ line: number; message: string }>;
  /** A problem of the run itself (harness crashed, timed out). */
  error?: string;
  /**
   * The steps' records passed the simulator's bound on a scenario's records: from step `line` on
   * (0: the end), the steps were kept without their actions, typed records, schemas and locals;
   * from `bareLine` on, without their rule changes and output either (each step's `trimmed`).
   * `message` says it in the panel's words. The verdicts and failures are the whole scenario's.
   */
  trimmed?: { line: number; timeNs: number; bareLine?: number; bareTimeNs?: number; message: string };
  warnings: string[];
  eventsProcessed: number;
  /** Wall time of the request on the server, and of the harness run alone. */
  ms: number;
  runMs: number;
}

/**
 * POST /api/rename-entity: the generated tree carried over for a rename (codegen's
 * renameInGeneratedTree for an entity naming generated files; renameIdentifiersInGeneratedTree for
 * a name the user code uses), paths relative to src-gen.
 */
export interface RenameEntityResponse {
  movedPaths: Array<{ from: string; to: string }>;
  regionIds: Array<{ file: string; from: string; to: string }>;
  /** Uses of the old name in protected-region code rewritten (a port's or parameter's only in its module's files). */
  rewritten: Array<{ file: string; line: number; id: string; occurrences: number }>;
  /** Why no use was rewritten (the new name is already a word of that code), else absent. */
  refused?: string;
  /** Mentions of the old name left in protected regions: code (the build fails until changed by hand), comments, literals. */
  remaining: Array<{ file: string; line: number; id: string; word: string; context: string }>;
  /** Lines of the project's `.scenario` files that named the entity, rewritten (file: workspace path). */
  scenarios: Array<{ file: string; line: number; before: string; after: string }>;
  /** `.scenario` files that named the entity but were not rewritten, and why (changed meanwhile, not a regular file...). */
  scenariosLeft: Array<{ file: string; reason: string }>;
  /** The renamed `.contract` files of the request written (workspace path), with the version now on disk. */
  written: Array<{ file: string; version: string }>;
  /** Those not written, and why (changed on disk since the version the rename was made on...). */
  filesLeft: Array<{ file: string; reason: string }>;
}

/** The answer of GET /api/log-folder. */
export interface LogFolderListing {
  /** Workspace-relative paths of the folder's `*.csv` regular files, by name, the first FOLDER_LOGS_MAX (256, server/log-api.ts). */
  logs: string[];
  /** The size in bytes of each of `logs`, in its order, when listed (0 for one gone meanwhile): a replay keeps the small ones first under its bound. */
  sizes?: number[];
  /** Regular `*.csv` files past FOLDER_LOGS_MAX (not in `logs`). */
  more: number;
  /** FOLDER_LOGS_MAX: the logs of one folder a replay reads at most. */
  max: number;
  /** `*.csv` entries that are no regular file, never read (`PWD_1.csv: a symbolic link, not read ...`), the first 20. */
  notRead: string[];
  /** All such entries (notRead names the first). */
  notReadCount: number;
  /**
   * What the folder's crash files say (`MODULE.crash`, saved by contract-launch: docs/runtime-api.md
   * "Crash file"), line by line: each crashed module's signal and frames as raw offsets, and the
   * addr2line command that maps them (`contract trace` maps them itself); a file not read, why.
   */
  crashSites?: string[];
  /**
   * The launcher's end lines of the folder's `contract-launch.log` (written by contract-launch alone:
   * docs/runtime-api.md "contract-launch"), each with its time (mono_ns, as the records'), in time
   * order: `{ monoNs: '123456789', line: 'module MAB (pid 41) died by signal 9 (Killed)' }`. The page
   * takes one only when its pid is the module's own (its module_started record's). Absent: none.
   */
  launcherLines?: { monoNs: string; line: string }[];
  /** Why the folder's contract-launch.log was not read, or was read in part. */
  launcherLinesProblem?: string;
}
