import type { WorkUsage } from '../pipeline/work-usage.js';
import type { Readable } from 'node:stream';
import type { LimitHit, Limits, Mechanism } from '../limits.js';
import type { DirListing } from '../pipeline/artifacts.js';

export type { SandboxName, SandboxChoice } from '@contract-studio/conventions';
import type { SandboxName, StopReason } from '@contract-studio/conventions';

/** Which mechanism enforced each guarantee/limit for one sandboxed process (reported in job results). */
export interface Mechanisms {
  memory: Mechanism;
  processes: Mechanism;
  network: Mechanism;
  filesystem: Mechanism;
  user: string;
  time: Mechanism;
  output: Mechanism;
  /** The bound of the writable /work (workDiskMiB). */
  disk: Mechanism;
  /** Real-time mode only: how SCHED_FIFO was granted and bounded (docs/sandbox.md "Real-time mode"). */
  realtime?: string;
}

/** Whether the opt-in real-time mode can be granted: how, or why not, said to the user as is. */
export type RealtimeSupport = { ok: true; detail: string; budget?: RealtimeBudgetShare } | { ok: false; reason: string };

/** A real-time job's own CPU budget, when it has one (a per-job cpu cgroup): µs per period on each CPU. */
export interface RealtimeBudgetShare {
  runtimeUs: number;
  periodUs: number;
}

/** One command to run in the sandbox. */
export interface SandboxCommand {
  /** Unique per job step (names the cgroup / container). */
  name: string;
  /** The job's id (docker: the contract-studio.job label). Default: name. */
  jobId?: string;
  /** Host path of the job's work dir: the only writable place besides a private /tmp. */
  workDir: string;
  /** Working directory, relative to the work dir. */
  cwd: string;
  argv: string[];
  env: Record<string, string>;
  limits: Limits;
  /** Host path of the prebuilt runtime, mounted read-only at the sandbox's runtimePath (bwrap/none). */
  runtimeDir?: string;
  /** Host identity owning the work dir; the sandboxed processes run as this uid (bwrap). */
  owner?: { uid: number; gid: number };
  /** Real-time mode: the processes may take SCHED_FIFO priorities, within REALTIME_BOUNDS. */
  realtime?: boolean;
  /**
   * What a limit hit (memory, processes, disk) does before it kills everything: SIGTERM to the
   * processes named `processName` (the run's launcher, which then stops the modules as at the
   * end of a run, so that each writes its last records), then the kill `graceMs` later, or as
   * soon as every process is gone. Without it (a build step), a limit hit kills at once.
   */
  stopOnLimit?: StopOnLimit;
}

/** SandboxCommand.stopOnLimit. */
export interface StopOnLimit {
  processName: string;
  graceMs: number;
  /** Told when a limit hit is about to ask `processName` to stop, before asking (the job says it in its log). */
  stopping?: (hit: LimitHit) => void;
  /** Told when no process named `processName` was asked (none, or none left): everything is killed at once. */
  unanswered?: (hit: LimitHit) => void;
}

export interface SandboxExit {
  exitCode: number | null;
  signal: string | null;
  /** A memory or process limit detected by the sandbox itself (time and output are the job's). */
  limitHit: LimitHit | null;
}

export interface SandboxProcess {
  readonly stdout: Readable;
  readonly stderr: Readable;
  readonly mechanisms: Mechanisms;
  /** Resolves once every process of the command is gone. */
  readonly done: Promise<SandboxExit>;
  /** Stops every process of the command (idempotent); resolves when they are gone. */
  kill(): Promise<void>;
  /**
   * Sends SIGTERM to the command's processes named `name` (the kernel's `comm`, compared on its 15
   * characters), inside the sandbox and nowhere else; resolves with whether one was found. A
   * program may take any name: this only asks, `kill` still ends everything. `reason`: why, queued
   * with the signal (STOP_REASON_CODES; queueTerm) where this host can, a plain SIGTERM elsewhere.
   */
  terminateNamed(name: string, reason?: StopReason): Promise<boolean>;
  /**
   * Every output line the job reads from the process: the sandbox may recognise a limit hit that
   * only shows in the output (a refused fork under RLIMIT_NPROC or in Docker, an allocation refused
   * under RLIMIT_AS) and report it in `done`.
   */
  noteLine(line: string): void;
}

/**
 * Where the live trace channel (pipeline/trace-tail.ts) may read a job's work dir on this host:
 * `root` is a host folder that IS the work dir the sandboxed processes write (docs/sandbox.md,
 * "What the host reads while a job runs"), or a one-line reason why there is none here.
 */
export type LiveWorkRoot = { ok: true; root: string } | { ok: false; reason: string };

export interface SandboxProbe {
  available: boolean;
  detail: string;
}

export interface Sandbox {
  readonly name: SandboxName;
  /** Where the work dir is seen by the sandboxed processes. */
  workPath(workDir: string): string;
  /** Where the runtime is seen by the sandboxed processes (the CONTRACT_RUNTIME value). */
  runtimePath(runtimeDir: string): string;
  /** Whether the runtime must be prebuilt on the host and passed as runtimeDir. */
  readonly needsHostRuntime: boolean;
  /** Limits this sandbox cannot enforce (named in warnings). */
  readonly unenforced: readonly string[];
  probe(): Promise<SandboxProbe>;
  /** Whether real-time mode can be granted here (asked before a realtime job's first step). */
  realtimeSupport(): Promise<RealtimeSupport>;
  start(cmd: SandboxCommand): Promise<SandboxProcess>;
  /** Called when a job's work dir is no longer needed (docker: removes the volume). */
  release?(workDir: string): Promise<void>;
  /**
   * Called once when the service closes, after its jobs ended (docker: removes any container or
   * volume it still owns). Never throws.
   */
  close?(): Promise<unknown>;
  /**
   * Digest of the work dir as the sandbox sees it (pipeline/work-tree-digest.ts), null when it
   * cannot be taken; absent = the work dir is on the host and is digested there.
   */
  workTreeDigest?(workDir: string): Promise<string | null>;
  /**
   * The biggest files of the work dir as the sandbox sees it (pipeline/work-usage.ts), for a disk
   * limit hit; absent = the work dir is on the host and is measured there.
   */
  workUsage?(workDir: string): Promise<WorkUsage | null>;
  /**
   * Lists folders of the work dir (relative paths) without following links, for collecting a
   * run's artifacts; absent = the work dir is on the host (bwrap, none) and is read there.
   */
  readWorkDirs?(workDir: string, rels: string[], maxBytes: number, maxEntries: number): Promise<Map<string, DirListing>>;
  /**
   * For a sandbox whose work dir is not a host folder (readWorkDirs): removes what earlier runs
   * left in it (logs/, run/) without following links; false when it could not (the job then
   * empties the work dir). Called before a job's first step, no job process alive.
   */
  removeRunOutputs?(workDir: string): Promise<boolean>;
  /**
   * For a sandbox whose work dir is not a host folder (readWorkDirs): a host folder that is proven
   * to be the same work dir as the sandboxed processes see it (docker: the work volume's
   * mountpoint on a local engine), for the live trace channel; called between two steps of a job
   * (no job process runs), never throws. Absent = no live channel for such a sandbox.
   */
  liveWorkRoot?(workDir: string): Promise<LiveWorkRoot>;
}
