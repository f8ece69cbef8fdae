/**
 * The ONE place where the build service's sandbox limits are defined (docs/sandbox.md mirrors it).
 *
 * Isolation guarantees (not numbers, always on for bwrap and docker, impossible for `none`):
 *   - network:    no network at all (own empty network namespace / docker NetworkMode "none")
 *   - filesystem: read-only root; only the job's work dir and a private /tmp are writable
 *   - user:       a non-root uid (a distinct host uid per running job slot under bwrap)
 *   - privileges: no new privileges (PR_SET_NO_NEW_PRIVS / docker no-new-privileges, CapDrop ALL)
 *
 * Numeric limits (configurable per server, and per job downwards only):
 */
import { availableParallelism } from 'node:os';
import { DEFAULT_PROCESS_LIMIT, DEFAULT_READY_TIMEOUT_SECONDS } from '@contract-studio/conventions';
import { TRACE_LINES_KEPT } from './trace/replay-bound.js';
export interface Limits {
  /** Memory of the whole job (all processes, tmpfs included), MiB. */
  memoryMiB: number;
  /** Processes/threads alive at once in the job. */
  processes: number;
  /** Wall time of the build step (make all), seconds. */
  buildSeconds: number;
  /** Wall time of the run step (make run), seconds. */
  runSeconds: number;
  /** Bytes kept per output stream (stdout, stderr) of each step; then a truncation notice. */
  outputBytesPerStream: number;
  /** Size of the job's writable /work (sources, generated tree, build products, logs), MiB. */
  workDiskMiB: number;
  /** Size of the job's private /tmp (a tmpfs in bwrap and Docker; counted in memoryMiB too), MiB. */
  tmpMiB: number;
  /** Wall time of the host-side prepare step (Cactal load + validate + generate), seconds. */
  prepareSeconds: number;
  /** Bytes of Cactal model (`.contract` files) one job may hand to the generator. */
  modelBytes: number;
  /** Files the generator may write for one job. */
  generatedFiles: number;
}

export const DEFAULT_LIMITS: Readonly<Limits> = Object.freeze({
  memoryMiB: 512,
  processes: DEFAULT_PROCESS_LIMIT,
  buildSeconds: 120,
  runSeconds: 60,
  outputBytesPerStream: 1024 * 1024,
  workDiskMiB: 256,
  tmpMiB: 256,
  prepareSeconds: 30,
  modelBytes: 1024 * 1024,
  generatedFiles: 5000,
});

/**
 * Host-side bounds on what comes back from a sandbox and on what clients send (not per job).
 * Output of a sandboxed process is untrusted text: these bound the work and memory the service
 * spends on it (docs/sandbox.md, "Limits"; docs/build-service-api.md, POST /api/jobs).
 */
export interface ServiceBounds {
  /** Bytes of one line of a step's output; a longer line is split (outputs of a sandbox, util/line-splitter.ts). */
  outputLineBytes: number;
  /**
   * Bytes of one line of gcc's JSON diagnostics (a line that begins as gcc's does: `[{"kind"`), in
   * place of outputLineBytes: gcc writes a compilation's diagnostics as one line, about 400 bytes
   * each (gcc 12, a `#warning`), so that diagnosticsPerJsonLine of them fit with room for their
   * notes. A longer one is read up to its last complete diagnostic, errors first, and the cut is
   * said (pipeline/gcc-json-salvage.ts); one past the stream's outputBytesPerStream is still read
   * whole up to this bound, kept in no log (util/past-cap-lines.ts).
   */
  gccJsonLineBytes: number;
  /** Characters of one output line looked at by the diagnostic/tag parsers (the rest is cut with a marker). */
  parsedLineChars: number;
  /** Characters kept of a diagnostic's message, file or option (the rest is cut with a marker). */
  diagnosticTextChars: number;
  /** Diagnostics in one gcc JSON line (one compilation); more: the line stays plain text. */
  diagnosticsPerJsonLine: number;
  /** Nesting of `children` in a gcc JSON diagnostic; deeper: the line stays plain text. */
  diagnosticDepth: number;
  /**
   * `children` (and `locations`) of one gcc JSON diagnostic; more: the line stays plain text. As
   * many as diagnosticsPerJsonLine: gcc 12 puts a compilation's preprocessor diagnostics (`#warning`)
   * and the errors after them in the first one's `children`.
   */
  diagnosticChildren: number;
  /** Entries of a run's logs/ and run/ looked at when collecting artifacts; the rest are not listed. */
  listedEntries: number;
  /**
   * Names of a run's logs/ read on the host (bwrap, none) to find the runtime's logs, listed first
   * (names only, none kept but theirs): the inode count of the default 256 MiB work disk.
   */
  scannedLogNames: number;
  /** Bytes of a POST /api/jobs body; a larger Content-Length is refused (413) before any byte is read. */
  requestBodyBytes: number;
  /** Request bodies read at once; beyond, 503 before reading (memory stays below this x requestBodyBytes). */
  requestBodiesAtOnce: number;
  /** Seconds a request body may take to arrive (a slow client must not hold a reading slot for ever): then 408. */
  requestBodySeconds: number;
  /** Bytes of one WebSocket message from a client (only {"type":"cancel"} is understood). */
  wsMessageBytes: number;
  /**
   * Bytes of live events a client's event stream (SSE or WebSocket) may leave unread, beyond its
   * replay: a client that falls further behind (stalled, too slow for a 1 kHz trace) is
   * disconnected, so that it never holds the service's memory without end; it may resume from the
   * last event id it got (http/sse.ts, http/ws.ts).
   */
  streamBufferedBytes: number;
  /**
   * Bytes all the streaming clients of one server may leave unread together (their replays
   * included): past it, the client with the most unread bytes is disconnected, until the others
   * fit (http/stream-budget.ts). Thirty stalled monitors of a 1 kHz run held half a gigabyte.
   */
  streamsBufferedBytes: number;
  /** Milliseconds between two reads of a running job's CSV logs for the live trace channel (pipeline/trace-tail.ts). */
  tracePollMs: number;
  /** Bytes of the CSV logs read per poll, over all the files (the rest is read at the next polls). */
  traceReadBytesPerPoll: number;
  /** Milliseconds a record is held back at most to put the logs in mono_ns order, while some log has no flush mark (docs/build-service-api.md "Trace channel"). */
  traceOrderWindowMs: number;
  /** The same when every log has its flush mark (the order is then exact: this only bounds what a module that holds its records, or died holding them, costs the others). */
  traceMarkHoldMs: number;
  /** Milliseconds from a change of the logs folder (inotify) to the read it wakes (changes in that time are read together), unless every module has written its log for the last flush boundary: then at once. */
  traceWakeMs: number;
  /** Flush delay (ms) asked of the modules through their flush marks while a client follows the job (else their own, 50 ms). */
  traceWatchedFlushMs: number;
  /** Log files tailed per job (the artifact collector's file bound); more are left to the collected logs. */
  traceFiles: number;
  /** Record lines of one trace event. */
  traceLinesPerEvent: number;
  /** Bytes of one file of a project a job is given (inline or read from its folder). */
  projectFileBytes: number;
  /** Bytes of all the files of a project a job is given. */
  projectBytes: number;
  /** Files of a project a job is given (inline, or read from its folder): more are refused, not left out. */
  projectFiles: number;
  /** Bytes of one inline file's path (`project.files`; a part at most 255, the file systems' bound). */
  inlinePathBytes: number;
  /** gcc diagnostics kept per job (the rest stay in the log as text), and errors kept past them (job.ts addDiagnostic). */
  diagnosticsPerJob: number;
  /** Trace lines kept in a job's event log (for replay); later lines go live to the attached clients only (one system line says so). */
  traceLinesKept: number;
  /**
   * Ended jobs whose trace records stay for replay (the newest ones); an older ended job's trace
   * events replay empty, the first with `dropped` (JobEvents.dropTrace): its CSV logs hold them.
   */
  traceReplayEndedJobs: number;
  /**
   * Trace lines that are no record (they do not begin with a `mono_ns`: junk a module wrote into
   * `logs/`) sent per job; the later ones are counted, not sent (a wire entry says how many, trace/wire.ts `unsent`),
   * so that they neither fill the stream nor take the room of the records kept for replay.
   */
  traceUnreadableKept: number;
  /**
   * Project workspaces the persistent build cache keeps (each a work tree: a tmpfs in memory when
   * the service is root). A process's first acquire removes the least recently used beyond this
   * number, and those whose project folder is gone; one a command holds stays.
   */
  keptProjectWorkspaces: number;
  /**
   * Built simulators (`sim/sim-<key>/`, about 0.6 MB each, a new key per model simulated) the
   * build cache keeps: a new one removes the least recently used beyond this number (none used in
   * the last hour).
   */
  keptSimulators: number;
  /** Generated trees (`generated/<key>.json.gz`) the build cache keeps, likewise. */
  keptGeneratedTrees: number;
  /** Built runtimes (`runtime/runtime-<key>/`, about 5 MB, a new key per version or compiler), likewise. */
  keptRuntimes: number;
}

export const SERVICE_BOUNDS: Readonly<ServiceBounds> = Object.freeze({
  outputLineBytes: 64 * 1024,
  gccJsonLineBytes: 1024 * 1024,
  parsedLineChars: 8192,
  diagnosticTextChars: 4096,
  diagnosticsPerJsonLine: 1000,
  diagnosticDepth: 8,
  diagnosticChildren: 1000,
  listedEntries: 1024,
  scannedLogNames: 65_536,
  requestBodyBytes: 80 * 1024 * 1024,
  requestBodiesAtOnce: 2,
  requestBodySeconds: 30,
  wsMessageBytes: 4096,
  streamBufferedBytes: 64 * 1024 * 1024,
  streamsBufferedBytes: 128 * 1024 * 1024,
  tracePollMs: 50,
  traceReadBytesPerPoll: 1024 * 1024,
  traceOrderWindowMs: 150,
  traceMarkHoldMs: 1000,
  traceWakeMs: 10,
  traceWatchedFlushMs: 25,
  traceFiles: 256,
  traceLinesPerEvent: 1000,
  traceLinesKept: TRACE_LINES_KEPT,
  traceReplayEndedJobs: 4,
  traceUnreadableKept: 1000,
  projectFileBytes: 8 * 1024 * 1024,
  projectBytes: 64 * 1024 * 1024,
  projectFiles: 10_000,
  inlinePathBytes: 1024,
  diagnosticsPerJob: 1000,
  keptProjectWorkspaces: 32,
  keptSimulators: 64,
  keptGeneratedTrees: 256,
  keptRuntimes: 4,
});

/**
 * Bounds of the opt-in real-time mode (`realtime: true`, `contract run --realtime`): what lets the
 * modules take their SCHED_FIFO priorities in the sandbox, and what stops a runaway FIFO loop from
 * freezing the host (docs/sandbox.md, "Real-time mode").
 */
export interface RealtimeBounds {
  /** Highest SCHED_FIFO priority a job's process may take (RLIMIT_RTPRIO, or the priority its run starts at). */
  priorityCeiling: number;
  /** Microseconds of CPU a job's real-time processes may use per period on each CPU (its cgroup's cpu.rt_runtime_us). */
  cpuRuntimeUs: number;
  /** Length of that period, microseconds (cpu.rt_period_us). */
  cpuPeriodUs: number;
  /** Microseconds one process may run under SCHED_FIFO without blocking before SIGXCPU (RLIMIT_RTTIME soft). */
  cpuWithoutBlockingSoftUs: number;
  /** ...and before SIGKILL (RLIMIT_RTTIME hard). */
  cpuWithoutBlockingHardUs: number;
}

export const REALTIME_BOUNDS: Readonly<RealtimeBounds> = Object.freeze({
  priorityCeiling: 99,
  cpuRuntimeUs: 40_000,
  cpuPeriodUs: 100_000,
  cpuWithoutBlockingSoftUs: 500_000,
  cpuWithoutBlockingHardUs: 1_000_000,
});

/** Time a cancel may take, end to end (documented guarantee, checked by the tests). */
export const CANCEL_DEADLINE_MS = 2000;
/**
 * Seconds of the run step kept besides the architecture's duration: make, the modules' start and
 * their stop (supervisors first, contract-launch). A request's duration is capped at runSeconds
 * minus this (half of runSeconds when that is less), so that a run asked for the longest ends on
 * its own and is not cut by the time limit.
 */
export const RUN_STOP_ROOM_SECONDS = 5;

/**
 * The longest duration of an architecture's run under `runSeconds` (RUN_STOP_ROOM_SECONDS), less
 * what a `readyTimeout` longer than the launcher's default may add before the start (the modules'
 * inits): a run asked for the longest still ends on its own.
 */
export function longestDuration(runSeconds: number, readyTimeout?: number): number {
  const longest = runSeconds - Math.min(RUN_STOP_ROOM_SECONDS, runSeconds / 2);
  const initsExtra = readyTimeout === undefined ? 0 : Math.max(0, readyTimeout - DEFAULT_READY_TIMEOUT_SECONDS);
  return Math.max(Math.min(longest, DEFAULT_READY_TIMEOUT_SECONDS), longest - initsExtra);
}

/**
 * Part of it a cancelled run's launcher has to stop the architecture itself (as at the end of a
 * run, so that every module writes its last records) before everything is killed.
 */
export const CANCEL_GRACE_MS = 1000;
/**
 * Of that grace, what the launcher leaves unused when it stops by a signal (CONTRACT_STOP_BUDGET_MS =
 * CANCEL_GRACE_MS minus this): its last SIGKILL and its own exit come before the grace ends.
 */
export const STOP_BUDGET_MARGIN_MS = 100;

/** The runtime's own bound of a module's CSV log (runtime/src/csvlog.c, CONTRACT_LOG_MAX_BYTES' default when unset). */
export const RUNTIME_LOG_MAX_BYTES = 256 * 1024 * 1024;
/**
 * The most CONTRACT_LOG_MAX_BYTES the service gives a run, and so the most it collects of one log
 * (pipeline/artifacts.ts artifactBoundsFor): half of what it collects of a run's logs in all
 * (ARTIFACT_BOUNDS.totalBytes, 2 GiB), so that ORD's log at its bound leaves as much to the
 * others. About 25 minutes of ORD at 1 kHz (0.7 MB/s), where the runtime's own 256 MiB default
 * held about 6.5. The collection reads a log as bytes, never as one string (V8's longest is 2^29 -
 * 24 characters, less than this).
 */
export const RUN_LOG_MAX_BYTES = 1024 * 1024 * 1024;
/**
 * The least CONTRACT_LOG_MAX_BYTES the service gives a run: room for about a thousand records (the
 * runtime refuses a bound under 4 records of 1280 bytes, and would then use its 256 MiB default).
 */
export const RUN_LOG_MIN_BYTES = 64 * 1024;

/**
 * CONTRACT_LOG_MAX_BYTES of a run (docs/sandbox.md "The disk limit"): 3/4 of the room left in its
 * work dir when the run starts (`roomBytes`: the disk limit less what the build left there), so
 * that a larger work dir keeps a longer log (ORD's, the schedule's trace, writes most), at most
 * RUN_LOG_MAX_BYTES and at least RUN_LOG_MIN_BYTES. A module that floods its CSV log is
 * then capped (a `log-capped` record, the run goes on) before the disk limit stops the whole run;
 * the last quarter keeps room for the other modules' logs.
 */
export function runLogMaxBytes(roomBytes: number): number {
  const room = Number.isFinite(roomBytes) ? Math.max(0, roomBytes) : 0;
  return Math.max(RUN_LOG_MIN_BYTES, Math.min(RUN_LOG_MAX_BYTES, Math.floor((room * 3) / 4)));
}

/**
 * Memory a run keeps for its processes when its work dir's files count against its memory limit
 * (bwrap and docker: the work dir is a tmpfs, its pages charged to the job's memory cgroup): a
 * quarter of memoryMiB, at least 16 MiB. The CSV logs stop before the work dir holds more than
 * memoryMiB less this (runLogDiskReserve).
 */
export function runProcessesMemoryBytes(limits: Limits): number {
  const memory = Math.floor(limits.memoryMiB * 1024 * 1024);
  return Math.min(memory, Math.max(16 * 1024 * 1024, Math.floor(memory / 4)));
}

/**
 * The part of the work dir the run's CSV logs may fill (docs/sandbox.md "The disk limit"): the disk
 * limit, or, when the work dir's files count against the memory limit (`memoryBacked`) and the
 * disk limit is larger than what the memory limit leaves beside the processes
 * (runProcessesMemoryBytes), that: a 3 GiB work dir under a 512 MiB memory limit filled the memory
 * with logs, and the kernel's OOM killer killed every process one after the other (killing frees no
 * tmpfs page) before the service could stop the run.
 */
export function runLogUsableBytes(limits: Limits, memoryBacked: boolean): number {
  const disk = workDiskBytes(limits);
  if (!memoryBacked) return disk;
  const memory = Math.floor(limits.memoryMiB * 1024 * 1024);
  return Math.max(0, Math.min(disk, memory - runProcessesMemoryBytes(limits)));
}

/**
 * The logs' disk reserve of a run, in bytes of the work dir's free space (the runtime's
 * CONTRACT_LOG_DISK_RESERVE_BYTES, CONTRACT_LOG_ENGINE_DISK_RESERVE_BYTES and
 * CONTRACT_LOG_SUPERVISOR_DISK_RESERVE_BYTES, docs/runtime-api.md "CSV log"): a module's log stops
 * (a `log-capped` record, the run goes on) once the work dir has less than `modules` free, ORD's
 * less than `ord`, a supervisor's less than `supervisors`, so that the
 * logs together never fill the work dir (the disk limit killed the run: each log's own bound,
 * runLogMaxBytes, holds for one log only) nor the memory the work dir's files take. `base` is a
 * sixteenth of the usable part (runLogUsableBytes), at least 1 MiB: room for what the logs write
 * at the same moment past their looks at the free space (a buffer each at most) and for the last records; ORD
 * keeps a quarter of it, a supervisor an eighth (its rule changes and its end outlast ORD's log).
 * `unusable`: the part of the disk limit the memory limit cannot hold.
 */
export function runLogDiskReserve(limits: Limits, memoryBacked: boolean): { modules: number; ord: number; supervisors: number; usable: number; unusable: number } {
  const usable = runLogUsableBytes(limits, memoryBacked);
  const unusable = workDiskBytes(limits) - usable;
  const base = Math.max(1024 * 1024, Math.floor(usable / 16));
  return { modules: unusable + base, ord: unusable + Math.floor(base / 4), supervisors: unusable + Math.floor(base / 8), usable, unusable };
}

export type LimitName = keyof Limits;

export const LIMIT_NAMES: readonly LimitName[] = [
  'memoryMiB',
  'processes',
  'buildSeconds',
  'runSeconds',
  'outputBytesPerStream',
  'workDiskMiB',
  'tmpMiB',
  'prepareSeconds',
  'modelBytes',
  'generatedFiles',
];

/** How a limit was enforced for a job, reported in its result. */
export type Mechanism =
  | 'cgroup-v1'
  | 'cgroup-v2'
  | 'rlimit-as'
  | 'rlimit-nproc'
  | 'docker'
  | 'netns'
  | 'docker-network-none'
  | 'bwrap-ro-binds'
  | 'docker-readonly-rootfs'
  | 'service-timer'
  | 'service-counter'
  | 'service-check'
  | 'worker-heap'
  | 'tmpfs-size'
  | 'docker-tmpfs-volume'
  | 'none';

export interface LimitHit {
  name: 'memory' | 'processes' | 'buildSeconds' | 'runSeconds' | 'outputBytesPerStream' | 'workDiskMiB' | 'prepareSeconds' | 'modelBytes' | 'generatedFiles';
  value: number;
  unit: 'bytes' | 'count' | 's';
  mechanism: Mechanism;
  /** The process limit: the module most of the job's processes descended from at the hit (its code forks; forking-module.ts), when one was. */
  module?: string;
  /** ... and how many of them were. */
  moduleProcesses?: number;
  /**
   * The memory limit, read from the job's cgroup: bytes of it the job's files in its tmpfs mounts
   * held at the hit (the work dir, /tmp, /dev/shm: memory.stat `shmem`), which no kill frees.
   */
  memoryFilesBytes?: number;
}

/**
 * A memory limit hit whose memory was mostly the job's files in its tmpfs mounts (memoryFilesBytes:
 * half of the limit or more): the kernel's OOM killer then kills one process after the other, none
 * of them the cause. Those bytes, else undefined.
 */
export function memoryHeldByFiles(hit: LimitHit): number | undefined {
  return hit.name === 'memory' && hit.memoryFilesBytes !== undefined && hit.memoryFilesBytes * 2 >= hit.value ? hit.memoryFilesBytes : undefined;
}

/** The longest time limit (`buildSeconds`, `runSeconds`, `prepareSeconds`): a timer's range, 2^31-1 ms. */
export const MAX_LIMIT_SECONDS = 2_147_483;

/**
 * The limits that are counts or sizes (every limit but the `...Seconds` ones): whole numbers,
 * written as they are to a cgroup file or a Docker field (`pids.max` refuses `10.5`), and at most
 * this much (a size in MiB: so that its bytes are a safe integer; a process count: the kernel's
 * highest pid_max).
 */
const MAX_WHOLE_LIMIT: Record<string, number> = {
  memoryMiB: 2 ** 33, workDiskMiB: 2 ** 33, tmpMiB: 2 ** 33,
  processes: 4_194_304,
};

/**
 * The least a limit may be, for every sandbox (a job asking for less is refused at submit, 400):
 * `memoryMiB` 32 — the Docker Engine refuses a container under 6 MiB (the job then failed with the
 * engine's raw message after it was accepted), under 16 MiB neither make nor gcc starts in any
 * sandbox (the job's /tmp and /dev/shm count in it too), and at 16 MiB the prepare step's generation
 * (its worker's heap is the memory limit too) stopped on the tutorial once its model changed.
 */
export const MIN_WHOLE_LIMIT: Readonly<Partial<Record<LimitName, number>>> = Object.freeze({
  memoryMiB: 32,
});

/**
 * Merges overrides onto a base; with `lowerOnly`, an override above the base is an error.
 * `written`: overrides as the user wrote them (`contract serve --limit NAME=VALUE`, by name): a
 * message quotes that text, not the number it became (`99999999999999999` is no `100000000000000000`),
 * and a count or a size must be written as the whole number it is (`10.0000000000000001` became 10).
 */
export function mergeLimits(base: Limits, overrides: unknown, lowerOnly: boolean, written: Readonly<Record<string, string>> = {}): Limits {
  if (overrides === undefined || overrides === null) return { ...base };
  if (typeof overrides !== 'object' || Array.isArray(overrides)) {
    throw new LimitsError('limits must be an object');
  }
  const out: Limits = { ...base };
  for (const [key, value] of Object.entries(overrides as Record<string, unknown>)) {
    if (!(LIMIT_NAMES as readonly string[]).includes(key)) {
      throw new LimitsError(`unknown limit "${key}" (known: ${LIMIT_NAMES.join(', ')})`);
    }
    const text = Object.hasOwn(written, key) ? written[key] : undefined;
    const shown = text ?? JSON.stringify(value);
    if (typeof value !== 'number' || !Number.isFinite(value) || value <= 0) {
      throw new LimitsError(`limit ${key} must be a positive number, got ${shown}`);
    }
    if (!key.endsWith('Seconds')) {
      const max = MAX_WHOLE_LIMIT[key] ?? Number.MAX_SAFE_INTEGER;
      const whole = text === undefined ? (Number.isInteger(value) ? BigInt(value) : undefined) : wholeNumberWritten(text);
      if (whole === undefined) throw new LimitsError(`limit ${key} must be a whole number (a count or a size), got ${shown}`);
      // compared as written: a max is a safe integer, so a value at most that is the number written
      if (whole > BigInt(max)) throw new LimitsError(`limit ${key} must be at most ${max}, got ${shown}`);
      const min = MIN_WHOLE_LIMIT[key as LimitName];
      if (min !== undefined && whole < BigInt(min)) throw new LimitsError(`limit ${key} must be at least ${min}${key.endsWith('MiB') ? ' MiB' : ''} (the least every sandbox can enforce and run a build in), got ${shown}`);
    }
    // at least a millisecond: a tinier one (1e-300) went as `DURATION=5e-301` to make and the launcher
    if (key.endsWith('Seconds') && value < 0.001) {
      throw new LimitsError(`limit ${key} must be at least 0.001 s, got ${shown}`);
    }
    // the service's timers hold at most 2^31-1 ms: a longer time limit would fire at once
    if (key.endsWith('Seconds') && value > MAX_LIMIT_SECONDS) {
      throw new LimitsError(`limit ${key} must be at most ${MAX_LIMIT_SECONDS} s (about 24.8 days, a timer's range), got ${shown}`);
    }
    const name = key as LimitName;
    if (lowerOnly && value > base[name]) {
      throw new LimitsError(`limit ${key}=${shown} is above the server's ${base[name]}`);
    }
    out[name] = value;
  }
  return out;
}

/** The whole number `text` writes (decimal digits, perhaps a point and zeros), else undefined. */
function wholeNumberWritten(text: string): bigint | undefined {
  const m = /^(\d+)(?:\.0*)?$/.exec(text);
  return m ? BigInt(m[1]!) : undefined;
}

export class LimitsError extends Error {}

/**
 * make jobs of a generated tree's build step: one per CPU of this machine, at most 4, and at most
 * one per 128 MiB of the job's memory limit (each gcc of a module takes up to about 100 MiB).
 */
export function buildJobs(limits: Limits, cpus: number = availableParallelism()): number {
  return Math.max(1, Math.min(cpus, 4, Math.floor(limits.memoryMiB / 128)));
}

export function memoryBytes(limits: Limits): number {
  return Math.floor(limits.memoryMiB * 1024 * 1024);
}

export function workDiskBytes(limits: Limits): number {
  return Math.floor(limits.workDiskMiB * 1024 * 1024);
}

export function tmpBytes(limits: Limits): number {
  return Math.floor(limits.tmpMiB * 1024 * 1024);
}

/** The error a step throws when one of its limits is hit outside a sandboxed process (prepare). */
export class LimitHitError extends Error {
  constructor(readonly hit: LimitHit) {
    super(describeLimitHit(hit));
  }
}

/**
 * "memory limit 512 MiB", "process limit 256", "run time limit 60 s", "output limit 1 MiB per stream",
 * "disk limit 256 MiB (work dir)", "prepare time limit 30 s", "model size limit 1 MiB", "generated file limit 5000".
 */
export function describeLimitHit(hit: LimitHit): string {
  switch (hit.name) {
    case 'memory':
      return `memory limit ${formatBytes(hit.value)}`;
    case 'processes':
      return `process limit ${hit.value}`;
    case 'buildSeconds':
      return `build time limit ${hit.value} s`;
    case 'runSeconds':
      return `run time limit ${hit.value} s`;
    case 'outputBytesPerStream':
      return `output limit ${formatBytes(hit.value)} per stream`;
    case 'workDiskMiB':
      return `disk limit ${formatBytes(hit.value)} (work dir)`;
    case 'prepareSeconds':
      return `prepare time limit ${hit.value} s`;
    case 'modelBytes':
      return `model size limit ${formatBytes(hit.value)}`;
    case 'generatedFiles':
      return `generated file limit ${hit.value}`;
  }
}

export function formatBytes(bytes: number): string {
  if (bytes >= 1024 * 1024 * 1024 && bytes % (1024 * 1024 * 1024) === 0) return `${bytes / 1024 ** 3} GiB`;
  if (bytes >= 1024 * 1024) return `${+(bytes / 1024 ** 2).toFixed(2)} MiB`;
  if (bytes >= 1024) return `${+(bytes / 1024).toFixed(2)} KiB`;
  return `${bytes} B`;
}
