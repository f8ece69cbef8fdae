/**
 * One job: prepare -> build -> run (run only for action "run"), each sandboxed step with its wall
 * time limit, output caps and live events; cancel stops everything within CANCEL_DEADLINE_MS.
 */
import { createHash } from 'node:crypto';
import { posix } from 'node:path';
import type { Readable } from 'node:stream';
import type { LimitHit, Limits } from '../limits.js';
import { buildJobs, CANCEL_GRACE_MS, STOP_BUDGET_MARGIN_MS, describeLimitHit, longestDuration, formatBytes, LimitHitError, memoryHeldByFiles, runLogDiskReserve, runLogMaxBytes, runProcessesMemoryBytes, RUN_LOG_MAX_BYTES, RUN_LOG_MIN_BYTES, SERVICE_BOUNDS, workDiskBytes } from '../limits.js';
import type { Mechanisms, RealtimeBudgetShare, Sandbox, SandboxProcess } from '../sandbox/types.js';
import { workDiskState } from '../sandbox/work-disk.js';
import { LineSplitter } from '../util/line-splitter.js';
import { looksLikeGccJson } from './gcc-json.js';
import { removeTreeNoFollow } from '../util/safe-fs.js';
import { hostWorkTreeDigest } from './work-tree-digest.js';
import { describeWorkUsage, hostWorkUsage, type WorkUsage } from './work-usage.js';
import { artifactBoundsFor, collectRunArtifacts, hostWorkDirReader, LOG_DIR, RUN_DIR, type Artifact, type ArtifactBounds, type RunArtifacts } from './artifacts.js';
import type { CactalProblem } from './cactal-adapter.js';
import { beginsAsMakeDirectory, type GccDiagnostic, type UserCopy } from './gcc-diagnostics.js';
import type { ProtectedRegion } from './protected-regions.js';
import { JobEvents, type JobStatus, type JobStep, type StreamName } from './job-events.js';
import { BuildOutputRouter, makeRecipeStatus, routeRunLine } from './output-router.js';
import { generatedMakefileArgs, makeDir, PrepareError, prepareWorkspace, treeRoot, type ProjectKind, type ProjectSource } from './prepare.js';
import { stageStdinFiles } from './stdin-files.js';
import { stdinModulesProblem } from '@contract-studio/codegen/run-executables';
import { SERVICE_AFFINITY } from './service-affinity.js';
import { LauncherCrashes } from './launcher-crashes.js';
import { addr2lineArgs, crashSite, crashSiteLine, CrashReports, MAX_ADDR2LINE_CHARS, parseAddr2line } from './crash-reports.js';
import { crashHeadText } from './crash-frames.js';
import { captureInSandbox } from './sandbox-capture.js';
import { holdsUnderProcessLimit } from './process-limit-warning.js';
import { describeIssues, RunIssues, type RunIssue } from './run-issues.js';
import { budgetThrottling, throttlingWarning, type Throttling } from './realtime-throttling.js';
import { moduleOfLog } from '../trace/parse.js';
import { TRACE_TAIL_BOUNDS, TraceTail } from './trace-tail.js';
import type { RuntimeCache, RuntimeSources } from './runtime-cache.js';
import type { GenerationCache } from '../cache/generation-cache.js';
import type { AcquireHooks, Workspace } from './workspaces.js';
import { DEFAULT_READY_TIMEOUT_SECONDS, LAUNCHER_PROCESS_NAME, SANDBOX_RUNTIME_DIR, visibleText, type StopReason } from '@contract-studio/conventions';

/** make's line when the run recipe (contract-launch) died by SIGKILL. */
const LAUNCHER_KILLED = /^make(?:\[\d{1,4}\])?: \*\*\* \[[^\]]{0,300}: run\] Killed$/;

/**
 * The job's warning when its build step's output went past the output limit: the lines after the
 * cut are in no log, event or artifact (a build's output is kept nowhere else); a service with a
 * higher limit keeps more.
 */
export function buildOutputCutWarning(stream: 'stdout' | 'stderr', limitBytes: number): string {
  return `the build's ${stream} was cut at the output limit (${formatBytes(limitBytes)} per stream, outputBytesPerStream): its later lines are not kept anywhere (not in the log, the events or the artifacts; gcc's diagnostics in them are still read, as the job's diagnostics): the whole output cannot be got from this job; a higher outputBytesPerStream keeps more (contract build or contract run --limit outputBytesPerStream=N; a service's own: contract serve --limit)`;
}

/** The stop of a run that found no launcher to ask (a run of something that is not an architecture, or one ending already). */
export const NO_LAUNCHER_ASKED = `no ${LAUNCHER_PROCESS_NAME} process to ask (not an architecture, or it was ending)`;

/** How long a cancelled job waits for the host-side work it let go of (a generation stopping at its next check) before releasing its workspace. */
const ABANDONED_WAIT_MS = 10_000;

/**
 * What a run whose `duration` did not fit in its run time limit is told (it is shortened to fit):
 * one of the job's `warnings` (the 201, the job, the CLI's JSON) and its run's service line; null
 * when the duration was not shortened.
 */
export function durationCapMessage(request: Pick<JobRequest, 'duration' | 'durationAsked' | 'limits' | 'readyTimeout'>): string | null {
  if (request.durationAsked === undefined || request.duration === undefined) return null;
  const inits = request.readyTimeout !== undefined && request.readyTimeout > DEFAULT_READY_TIMEOUT_SECONDS ? ` (its modules' inits may take ${request.readyTimeout} s)` : '';
  return `duration ${request.durationAsked} s capped to ${request.duration} s: the run time limit is ${request.limits.runSeconds} s, of which ${request.limits.runSeconds - request.duration} s are kept to start and stop the architecture${inits}`;
}

export interface JobRequest {
  action: 'build' | 'run';
  project: ProjectSource;
  /** Real path of project.dir (workspace reuse key), null for inline files. */
  projectKey: string | null;
  kind: ProjectKind;
  start?: string;
  duration?: number;
  /** The duration the request asked for, when it was capped (limits.ts longestDuration). */
  durationAsked?: number;
  /** Seconds every module's init may take before the start request (`make run READY_TIMEOUT=…`, contract-launch --ready-timeout; default 10). */
  readyTimeout?: number;
  /** CPU list every module is pinned to (`make run CPUS=…`, contract-launch --cpus). */
  cpus?: string;
  /** Real-time mode (run only): modules take their SCHED_FIFO priorities, bounded (docs/sandbox.md "Real-time mode"). */
  realtime?: boolean;
  /** A Cactal project's own code compiled with -Werror: a warning fails the build (`contract build/run --werror`). */
  werror?: boolean;
  /** Run only: module name -> a file of the project it reads on its stdin (stdin-files.ts); the others read /dev/null. */
  stdin?: Record<string, string>;
  limits: Limits;
}

export interface JobResult {
  ok: boolean;
  step: JobStep;
  exitCode: number | null;
  signal: string | null;
  message: string;
  limitHit: LimitHit | null;
  /** What went wrong in the run step without a crash (run-issues.ts): any makes ok false. */
  issues: RunIssue[];
  truncated: { stdout: boolean; stderr: boolean };
  durations_ms: Partial<Record<JobStep, number>>;
  mechanisms: Mechanisms | null;
}

export interface JobContext {
  sandbox: Sandbox;
  sandboxNote: string;
  acquireWorkspace(job: Job, hooks: AcquireHooks): Promise<Workspace>;
  runtime: RuntimeCache | null;
  /** Generated trees by inputs (the persistent build cache only). */
  generated?: GenerationCache | null;
}

const MAX_DIAGNOSTICS = SERVICE_BOUNDS.diagnosticsPerJob;
/** Crashed modules whose crash site is looked for (addr2line each), at most. */
const CRASH_SITES_TOLD = 4;
/** addr2line's time in the sandbox, at most. */
const CRASH_SITE_TIMEOUT_MS = 10_000;

class Cancelled extends Error {}

/**
 * A fault of the service itself while it handled a job (a parser or callback that threw on the
 * sandbox's output): the job is stopped and fails with "internal error: ...", its clean-up still
 * runs, and the service goes on (docs/build-service-api.md, "internal error").
 */
class InternalFault extends Error {}

/**
 * What a successful build's message says of its compiler diagnostics: ` (1 compiler warning)`,
 * ` (3 compiler warnings, 1 other compiler diagnostic)`, or nothing. Said as the compiler's: the
 * model's own hints and warnings (`contract check`'s) are told apart from them by whoever prints both.
 */
export function compilerDiagnosticsCount(diagnostics: readonly { severity: string }[]): string {
  const warnings = diagnostics.filter((d) => d.severity === 'warning').length;
  const others = diagnostics.length - warnings;
  const parts: string[] = [];
  if (warnings) parts.push(`${warnings} compiler warning${warnings === 1 ? '' : 's'}`);
  if (others) parts.push(`${others} other compiler diagnostic${others === 1 ? '' : 's'}`);
  return parts.length ? ` (${parts.join(', ')})` : '';
}

export class Job {
  readonly events = new JobEvents();
  readonly createdAt = Date.now();
  startedAt: number | null = null;
  finishedAt: number | null = null;
  status: JobStatus = 'queued';
  result: JobResult | null = null;
  readonly diagnostics: GccDiagnostic[] = [];
  prepareDiagnostics: CactalProblem[] = [];
  /** The makefiles of the generated tree prepare refused the project for (foreign-makefiles.ts), project-relative; empty otherwise. */
  foreignMakefiles: readonly string[] = [];
  readonly warnings: string[] = [];
  /** How many lines of gcc's JSON diagnostics the build could not read (GCC_JSON_UNREADABLE): their diagnostics are not reported. */
  unreadableDiagnosticLines = 0;
  /** What sandbox was picked and why ("sandbox auto: picked bwrap (...)"). */
  sandboxNote = '';
  /** The run's CSV logs (and what was left out), collected from the sandbox once the run step ended. */
  artifacts: RunArtifacts | null = null;
  /** How long collecting them took (ms). */
  artifactsCollectMs: number | null = null;
  /** What filled the work dir when the disk limit stopped the step (its message's `filled by ...`), reused for a log the disk reserve stopped. */
  private workUsageAtEnd: WorkUsage | null = null;
  /**
   * The crash sites the job mapped after its run, as `contract trace` tells a crash file (each
   * module's head line, then its frames: crash-frames.ts), given with the artifacts (its MODULE.crash
   * files) so that a replay of the job's logs tells them mapped.
   */
  private readonly mappedCrashSites: string[] = [];
  /** How long resolving the sandbox (probing it, the first time in a service) took (ms). */
  sandboxProbeMs: number | null = null;

  private current: SandboxProcess | null = null;
  private currentStep: 'build' | 'run' | null = null;
  /** A cancelled run whose launcher stopped the architecture itself: its logs are whole. */
  private stoppedGracefully = false;
  private cancelRequested = false;
  /** The limit whose hit is stopping the run (its launcher asked to stop: stopOnLimit), else null. */
  private limitStopping: LimitHit | null = null;
  private cancelSignal!: () => void;
  /**
   * The collection of the run's logs under way, aborted by a cancel that comes during it (the job
   * ends within CANCEL_DEADLINE_MS); a cancel before it (during the run) lets it collect what the
   * stopped run wrote.
   */
  private collectAbort: AbortController | null = null;
  private readonly cancelled = new Promise<void>((r) => (this.cancelSignal = r));
  /** The first internal fault of this job (see InternalFault), null while there is none. */
  private fault: InternalFault | null = null;
  private readonly durations: Partial<Record<JobStep, number>> = {};
  private readonly truncated = { stdout: false, stderr: false };
  /** gcc diagnostics a build read past its output cap (LineSplitter's pastCap): the job's, in no log line. */
  private diagnosticsPastCap = 0;
  /** Errors kept past the job's diagnostics bound (addDiagnostic). */
  private errorsPastBound = 0;
  private mechanisms: Mechanisms | null = null;
  private readonly runIssues = new RunIssues();
  /** A real-time run's own CPU budget (a per-job cpu cgroup): its ORD log is read for throttling (realtime-throttling.ts). */
  private realtimeBudget: RealtimeBudgetShare | null = null;
  private finalStatus: 'succeeded' | 'failed' | 'cancelled' | null = null;
  private finishedSignal!: () => void;
  /** Resolves when the job has ended and released everything it held. */
  readonly finished = new Promise<void>((r) => (this.finishedSignal = r));

  /** Digest of the submitting client's key (X-Contract-Client): who may list this job. */
  owner: string | undefined;

  constructor(
    readonly id: string,
    readonly request: JobRequest,
    readonly sandboxName: string,
  ) {
    this.events.append({ type: 'status', status: 'queued' });
  }

  get isDone(): boolean {
    return this.status === 'succeeded' || this.status === 'failed' || this.status === 'cancelled';
  }

  private setStatus(status: JobStatus, step?: JobStep): void {
    this.status = status;
    this.events.append({ type: 'status', status, ...(step ? { step } : {}) });
  }

  private line(step: JobStep, source: string, stream: StreamName, line: string): void {
    // a sandbox stream may still deliver bytes after the job ended (its pumps are waited for a
    // bounded time only): they belong to no event log any more
    if (this.events.isEnded) return;
    this.events.append({ type: 'line', step, source, stream, line });
  }

  /**
   * Contains an exception thrown while handling the job's output or events (outside the
   * pipeline's own try): records it once, logs it, and stops the job's sandbox; execute() then
   * ends the job as failed, after its clean-up. Never throws.
   */
  private contain(e: unknown, where: string): void {
    if (this.fault || this.isDone) return;
    const msg = e instanceof Error ? e.message : String(e);
    this.fault = new InternalFault(`internal error: ${where}: ${msg.split('\n')[0]}`);
    try {
      this.system(this.status === 'running' ? 'run' : 'build', `error: ${this.fault.message}`);
    } catch {
      /* the log itself failed: the result still says it */
    }
    this.cancelSignal();
    this.current?.kill().catch(() => {});
  }

  /** Runs a callback of a stream or timer of this job; an exception is contained (see contain). */
  private guarded<A extends unknown[]>(where: string, fn: (...args: A) => void): (...args: A) => void {
    return (...args: A) => {
      try {
        fn(...args);
      } catch (e) {
        this.contain(e, where);
      }
    };
  }

  private system(step: JobStep, line: string): void {
    this.line(step, 'service', 'system', line);
  }

  /** One `time: what N ms` line per piece of a step (the CLI's --verbose; docs/getting-started.md "The build cache"). */
  private timed(step: JobStep, what: string, since: number): void {
    this.system(step, `time: ${what} ${Date.now() - since} ms`);
  }

  /** Ends a job that never started (cancelled while queued, or refused). */
  finishUnstarted(message: string, status: 'cancelled' | 'failed'): void {
    if (this.isDone) return;
    this.result = this.makeResult('prepare', false, null, null, message, null);
    this.finish(status);
    this.emitEnd();
    this.finishedSignal();
  }

  /**
   * Cancels; the job ends with status "cancelled". A running architecture is first asked to stop
   * as at the end of a run (its launcher gets SIGTERM: the supervisors undo what they did, every
   * module writes its last records and its exit record), for CANCEL_GRACE_MS at most; whatever still
   * runs then, and any other step (a build), is killed.
   */
  async cancel(): Promise<void> {
    if (this.isDone) return;
    // a run already being stopped by a limit (stopOnLimit) ends by it, within the same grace: a
    // cancel then (Ctrl+C at the stop's lines) would only hide why it ended
    if (this.limitStopping && this.currentStep === 'run') {
      this.system('run', `cancel asked while the run was being stopped by the ${describeLimitHit(this.limitStopping)}: it ends by the limit`);
      return;
    }
    this.cancelRequested = true;
    this.cancelSignal();
    this.collectAbort?.abort();
    const proc = this.current;
    if (!proc) return;
    if (this.currentStep === 'run') await this.stopArchitecture(proc, 'cancel');
    else await proc.kill();
  }

  /**
   * Asks the run's launcher to stop the architecture as at the end of a run (Stop, the run time
   * limit); what still runs CANCEL_GRACE_MS later, or a run with no launcher, is killed.
   */
  private async stopArchitecture(proc: SandboxProcess, reason: StopReason): Promise<void> {
    // the grace counts from now: asking (an exec in Docker, on a loaded engine) is part of it
    let timer: NodeJS.Timeout | undefined;
    const graceOver = new Promise<false>((r) => (timer = setTimeout(() => r(false), CANCEL_GRACE_MS)));
    // said before asking: what the launcher prints as it stops comes after it in the log
    this.system('run', `stopping the architecture as at the end of a run (what still runs after ${CANCEL_GRACE_MS} ms is killed)`);
    // null: asking took the whole grace
    const asked = await Promise.race([proc.terminateNamed(LAUNCHER_PROCESS_NAME, reason).catch(() => false), graceOver.then(() => null)]);
    if (asked === null) this.system('run', `the architecture did not stop within ${CANCEL_GRACE_MS} ms: killed`);
    else if (!asked) this.system('run', `${NO_LAUNCHER_ASKED}: killed`);
    else {
      const ended = await Promise.race([proc.done.then(() => true), graceOver]);
      this.stoppedGracefully = ended;
      if (!ended) this.system('run', `the architecture did not stop within ${CANCEL_GRACE_MS} ms: killed`);
    }
    clearTimeout(timer);
    await proc.kill();
  }

  async execute(ctx: JobContext): Promise<void> {
    this.startedAt = Date.now();
    this.system('prepare', ctx.sandboxNote);
    if (this.sandboxProbeMs !== null) this.system('prepare', `time: sandbox choice (probe) ${this.sandboxProbeMs} ms`);
    for (const w of this.warnings) this.line('prepare', 'service', 'system', `warning: ${w}`);
    let ws: Workspace | null = null;
    let step: JobStep = 'prepare';
    try {
      this.setStatus('preparing', 'prepare');
      if (this.request.realtime) {
        // refused before any work: the user learns at once what the host lacks and what to do
        const rt = await ctx.sandbox.realtimeSupport();
        if (!rt.ok) {
          const message = `real-time mode refused: ${rt.reason}`;
          this.system('prepare', message);
          this.result = this.makeResult('prepare', false, null, null, message, null);
          this.finish('failed');
          return;
        }
        this.system('prepare', `real-time mode: ${rt.detail}`);
        this.realtimeBudget = rt.budget ?? null;
      }
      const t0 = Date.now();
      // Cactal trees link against the runtime (Seam 3): prebuilt on the host for bwrap/none, in
      // the image for docker. Plain Makefile projects get the image's path and no bind. Which one
      // is known before the work tree is checked: its build products are trusted only for the
      // runtime they were built with (another one, a version switched to and back, has its own
      // file dates, which make would not see as newer); it is built once the project is prepared
      const hostRuntime = this.request.kind === 'cactal' && ctx.sandbox.needsHostRuntime ? ctx.runtime : null;
      let runtimeSources: RuntimeSources | null = null;
      if (hostRuntime) {
        const tr = Date.now();
        runtimeSources = await this.orCancel(hostRuntime.sources());
        this.timed('prepare', 'runtime (sources hash)', tr);
      }
      const builtWith = runtimeSources?.name ?? null;
      const acquiring = ctx.acquireWorkspace(this, {
        onWait: (holder) => this.system('prepare', `waiting for the other command using this project (${holder}) to finish ...`),
        cancelled: this.cancelled,
      });
      try {
        ws = await this.orCancel(acquiring);
      } catch (e) {
        // cancelled while the workspace was being acquired (its lock taken, its folders checked):
        // released once it is, else the project stayed locked and every later job of it waited for ever
        void acquiring.then((w) => w.release(), () => {}).catch(() => {});
        throw e;
      }
      this.timed('prepare', 'workspace (lock, checks)', t0);
      let t = Date.now();
      if (ws.reused) {
        await this.orCancel(this.checkBuildOutputs(ctx.sandbox, ws, builtWith));
        this.timed('prepare', 'work tree check (digest)', t);
      }
      if (!ctx.sandbox.readWorkDirs) {
        // a kept work tree still holds the logs of earlier runs, collected by their own jobs (and
        // saved by the CLI into the project): removed when any job starts, so that they count
        // neither against this job's disk limit (a build step blamed for a log it never wrote)
        // nor among its run's logs. No job process lives now (the workspace lock is held);
        // rm -rf --one-file-system never follows what a job left there.
        const tl = Date.now();
        await removeTreeNoFollow(posix.join(ws.workDir, LOG_DIR));
        await removeTreeNoFollow(posix.join(ws.workDir, RUN_DIR));
        this.timed('prepare', 'earlier run logs removed', tl);
      } else if (ws.reused && ctx.sandbox.removeRunOutputs) {
        // the same in a work dir the sandbox keeps itself (a Docker volume): else an earlier run's
        // logs would be collected as this one's, and a link a module left as logs/previous would
        // break every later run
        const tl = Date.now();
        if (!(await this.orCancel(ctx.sandbox.removeRunOutputs(ws.workDir)))) {
          this.system('prepare', "what earlier runs left in the work dir (logs/, run/) could not be removed: it is emptied, building from scratch");
          await ws.reset();
        }
        this.timed('prepare', 'earlier run logs removed', tl);
      }
      t = Date.now();
      const prep = await this.orCancel(
        prepareWorkspace(ws, this.request.project, this.request.kind, this.request.limits, (l) => this.system('prepare', l), this.cancelled, ctx.generated ?? undefined),
      );
      // the check's warning about the default process limit is not this job's when its own limit fits
      this.prepareDiagnostics = prep.problems.filter((p) => holdsUnderProcessLimit(p, this.request.limits.processes));
      this.timed('prepare', 'generation + copy into the work tree', t);
      let runtimePath = SANDBOX_RUNTIME_DIR;
      let runtimeDir: string | undefined;
      if (prep.ok && hostRuntime && runtimeSources) {
        t = Date.now();
        // the runtime's build is the service's, shared by its jobs, outside the workspace: a cancel
        // lets it go on without this job (not awaited: it ends now, not once the build is done),
        // and its later lines go to the jobs still waiting for it, not into this job's log
        runtimeDir = await this.orCancel(hostRuntime.ensureBuilt(runtimeSources, (l, s) => this.line('prepare', 'runtime', s, l), this.cancelled), { detached: true });
        runtimePath = ctx.sandbox.runtimePath(runtimeDir);
        this.timed('prepare', 'runtime (cache)', t);
      }
      this.durations.prepare = Date.now() - t0;
      if (!prep.ok) {
        const n = prep.problems.filter((p) => p.severity === 'error').length;
        this.result = this.makeResult('prepare', false, null, null, `project has ${n} error(s)`, null);
        this.finish('failed');
        return;
      }

      // a stdin file for no module is refused before the build (make run would refuse it only after it)
      const stdinRefused = this.request.stdin && prep.executables ? stdinModulesProblem(this.request.stdin, prep.executables, (name) => `stdin.${name}`) : null;
      if (stdinRefused) throw new PrepareError(`${stdinRefused}; nothing was built or run`);

      step = 'build';
      this.setStatus('building', 'build');
      const work = ctx.sandbox.workPath(ws.workDir);
      const dir = makeDir(this.request.kind) || '.';
      const vars = [`CONTRACT_RUNTIME=${runtimePath}`];
      // a generated tree builds its modules in parallel (its Makefile is made for it), each module's
      // output in one block (--output-sync) with stderr in the same order (2>&1): the router follows
      // make's directories through them; -k: every module is compiled, so one build reports the
      // errors of all (with -j, which modules a first error stops would be timing); a plain
      // Makefile project builds as its author wrote it
      // a generated tree is built by its generated Makefile, named (-f): never by a GNUmakefile or
      // makefile beside it, which make would read first (foreign-makefiles.ts)
      const makefile = generatedMakefileArgs(this.request.kind);
      // werror: the project's code (not the runtime, prebuilt warning-free) with -Werror; every module
      // compiled again (its executable removed first): one built before without it is up to date for
      // make, its warnings never seen (make -B would rebuild the runtime too, in its read-only folder)
      const strict = this.request.werror === true && this.request.kind === 'cactal';
      const make = ['make', '-C', dir, ...makefile, 'all', ...vars, `EXTRA_CFLAGS=-fdiagnostics-format=json${strict ? ' -Werror' : ''}`];
      const parallel = this.request.kind === 'cactal';
      const parallelMake = ['make', '-k', `-j${buildJobs(this.request.limits)}`, '--output-sync=recurse', ...make.slice(1)];
      const argv = !parallel ? make
        : strict ? ['sh', '-c', 'for d in "$1"/modules/*_mod; do m=${d##*/}; rm -f -- "$d/${m%_mod}"; done; shift; exec "$@" 2>&1', 'sh', dir, ...parallelMake]
          : ['sh', '-c', 'exec "$@" 2>&1', 'sh', ...parallelMake];
      const router = new BuildOutputRouter({
        startDir: posix.join(work, makeDir(this.request.kind)),
        root: posix.join(work, treeRoot(this.request.kind)),
        regions: prep.regions,
        userCopies: prep.userCopies,
        orphanedDefinitions: prep.orphanedDefinitions,
        ...(parallel ? { diagnosticsOnStdout: true } : {}),
      });
      ws.acceptedOutputs = null;
      const build = await this.runStep(ctx.sandbox, ws, runtimeDir, 'build', argv, this.request.limits.buildSeconds, (line, stream) => {
        const routed = router.route(line, stream);
        for (const d of routed.diagnostics) this.addDiagnostic(d);
        if (routed.unreadable && this.unreadableDiagnosticLines++ === 0) {
          // said once among the job's warnings and in its log; the build's message counts them
          this.warnings.push(routed.unreadable);
          this.system('build', `warning: ${routed.unreadable}`);
        }
        if (routed.cut) {
          // said among the job's warnings and in its log, before the diagnostics read from the line
          this.warnings.push(routed.cut);
          this.system('build', `warning: ${routed.cut}`);
        }
        return routed.lines;
      }, {}, parallel ? `${parallelMake.join(' ')} 2>&1` : undefined);
      // what this build step left (it ended by itself) is what the next job may build on
      if (!this.cancelRequested && !build.limitHit && build.exitCode !== null) {
        const td = Date.now();
        ws.acceptedOutputs = acceptance(await this.workTreeDigest(ctx.sandbox, ws), builtWith);
        this.timed('build', 'work tree digest', td);
      }
      if (!build.ok) {
        const errors = this.diagnostics.filter((d) => d.severity === 'error').length;
        const message = (build.message ?? (errors ? `build failed: ${errors} error(s) (make exit ${build.exitCode})` : `build failed (make exit ${build.exitCode})`)) + this.unreadableDiagnostics() + this.buildOutputCut();
        this.result = this.makeResult('build', false, build.exitCode, build.signal, message, build.limitHit);
        this.finish(this.cancelRequested ? 'cancelled' : 'failed');
        return;
      }
      if (this.request.action === 'build') {
        this.result = this.makeResult('build', true, 0, null, `build succeeded${compilerDiagnosticsCount(this.diagnostics)}${this.buildOutputCut()}`, null);
        this.finish('succeeded');
        return;
      }

      step = 'run';
      this.setStatus('running', 'run');
      const runVars = [...vars, `RUN_DIR=${posix.join(work, 'run')}`, `LOG_DIR=${posix.join(work, 'logs')}`];
      if (this.request.start !== undefined) runVars.push(`START=${this.request.start}`);
      if (this.request.duration !== undefined) runVars.push(`DURATION=${this.request.duration}`);
      if (this.request.durationAsked !== undefined)
        this.system('run', durationCapMessage(this.request)!);
      if (this.request.readyTimeout !== undefined) runVars.push(`READY_TIMEOUT=${this.request.readyTimeout}`);
      if (this.request.cpus !== undefined) runVars.push(`CPUS=${this.request.cpus}`);
      if (this.request.stdin) runVars.push(...(await stageStdinFiles(this.request.project, this.request.stdin, ws.workDir, work, ws.owner)));
      // each module's CSV log is capped before it can fill the work dir (the disk limit would stop the
      // whole run); a plain Makefile project has no runtime to read it
      const logBound = this.request.kind === 'cactal' ? await this.runLogBound(ctx.sandbox, ws.workDir) : null;
      // a log is read and collected up to that bound when it is above the collector's default (a large work dir's ORD log)
      const collectBounds = artifactBoundsFor(logBound?.maxBytes ?? null);
      // the live trace channel: the run's CSV logs as they grow, drained before the artifacts and the end
      const tail = await this.startTraceTail(ctx.sandbox, ws.workDir, collectBounds);
      // a run pinned to CPUs has them to itself: the service's threads (the channel's work) keep off them
      const keptOff = this.request.cpus !== undefined ? await SERVICE_AFFINITY.keepOff(this.request.cpus) : null;
      if (keptOff?.said) this.system('run', keptOff.said);
      let run: Awaited<ReturnType<Job['runStep']>>;
      const tRun = Date.now();
      const crashes = new LauncherCrashes();
      // the crash reports crashed modules wrote on their stderr (runtime crash_report.c): where they crashed
      const crashReports = new CrashReports();
      // the launcher's exit status, as make's "*** [...: run] Error N" line gives it (make itself exits 2)
      let launcherStatus: number | null = null;
      // make's `*** [...: run] Killed`: the launcher itself got a SIGKILL (not the service's: it stops the run by its launcher)
      let launcherKilled = false;
      try {
        // with a live channel the modules keep a flush mark beside each log: the exact order (trace-order.ts)
        // a stop asked for (cancel, the run time limit) is killed CANCEL_GRACE_MS later: the launcher fits its
        // waits in that, so that a module not answering its KILL is still terminated by it (its last records written)
        // and the run stops by the longest duration after its launch whatever its inits took: it ends on its own, said,
        // before the run time limit (which counts from the launch) rather than at it
        const runEnv: Record<string, string> = {
          CONTRACT_STOP_BUDGET_MS: String(CANCEL_GRACE_MS - STOP_BUDGET_MARGIN_MS),
          CONTRACT_END_BY_S: String(longestDuration(this.request.limits.runSeconds)),
          // past the output limit the launcher drops the modules' lines itself (read, not relayed to be
          // dropped here): a module printing past it is drained at the launcher's speed and keeps its period
          CONTRACT_OUTPUT_LIMIT_BYTES: String(this.request.limits.outputBytesPerStream),
          ...(logBound !== null ? {
            CONTRACT_LOG_MAX_BYTES: String(logBound.maxBytes),
            CONTRACT_LOG_DISK_RESERVE_BYTES: String(logBound.reserve.modules),
            CONTRACT_LOG_ENGINE_DISK_RESERVE_BYTES: String(logBound.reserve.ord),
            CONTRACT_LOG_SUPERVISOR_DISK_RESERVE_BYTES: String(logBound.reserve.supervisors),
          } : {}),
          ...(tail ? { CONTRACT_LOG_MARK: '1' } : {}),
        };
        run = await this.runStep(ctx.sandbox, ws, runtimeDir, 'run', ['make', '-C', dir, ...makefile, 'run', ...runVars], this.request.limits.runSeconds, (line) => {
          const routed = routeRunLine(line);
          if (routed.source === 'run') {
            const failed = makeRecipeStatus(routed.line);
            if (failed?.target === 'run') launcherStatus = failed.status;
            if (LAUNCHER_KILLED.test(routed.line)) launcherKilled = true;
          }
          this.runIssues.line(routed.line, routed.source);
          if (routed.source === 'launcher') crashes.line(routed.line);
          else if (routed.source !== 'run') {
            crashReports.line(routed.line, routed.source);
            crashes.moduleLine(routed.source, routed.line);
          }
          return [routed];
        }, runEnv);
      } catch (e) {
        this.events.onSubscribers = null;
        await tail?.stop();
        await keptOff?.release();
        throw e;
      }
      await keptOff?.release();
      this.events.onSubscribers = null;
      // a run the launcher stopped (Stop, Ctrl+C) wrote its logs to the end: all of them are sent
      if (this.cancelRequested && !this.stoppedGracefully) await tail?.stop();
      else await tail?.finish();
      if (run.limitHit && !this.cancelRequested) this.runIssues.limit(run.limitHit);
      // the launcher refused the run before starting anything (too many modules, a CPU list...): said as such
      const refused = launcherStatus !== null && !this.cancelRequested ? this.runIssues.launcherExit(launcherStatus) : undefined;
      // the sandboxed processes are gone, the live trace sent: the collection of the logs starts now
      this.timed('run', 'run (the sandboxed processes)', tRun);
      // a cancelled run's logs too: what it wrote until it was stopped is the user's record of it
      // (a cancel during the collection stops it: what was read by then is kept)
      await this.collectArtifacts(ctx.sandbox, ws.workDir, collectBounds);
      if (this.cancelRequested && run.ok) throw new Cancelled();
      const issues = this.runIssues.all;
      if (!run.ok) {
        // the failure is the message; the issues (a limit, cut output...) stay in result.issues
        // a module's crash is the failure to name (make's status alone reads like a build failure)
        const sites = this.request.kind === 'cactal' ? await this.crashSites(ctx.sandbox, ws, runtimeDir, runtimePath, crashes, crashReports, prep) : undefined;
        const crashed = crashes.summary(run.limitHit, sites);
        const launcher = launcherStatus !== null ? `contract-launch exit ${launcherStatus}; ` : '';
        const why = crashed ? `: ${crashed}` : refused ? `: ${refused}` : launcherKilled && !this.cancelRequested
          ? ': contract-launch was killed (SIGKILL) before the run ended — a module\'s code can do that (kill(getppid(), SIGKILL)), or the kernel; the modules\' output it had not relayed yet is lost, their CSV logs are what they wrote'
          : '';
        const message = run.message ?? `run failed${why} (${launcher}make exit ${run.exitCode}${run.signal ? `, signal ${run.signal}` : ''})`;
        this.result = this.makeResult('run', false, run.exitCode, run.signal, message, run.limitHit);
        this.finish(this.cancelRequested ? 'cancelled' : 'failed');
        return;
      }
      if (issues.length) {
        // the processes ended well, but the run did not go as designed or its record is not whole
        for (const i of issues) this.system('run', `problem: ${i.message}`);
        this.result = this.makeResult('run', false, 0, null, `run finished with ${describeIssues(issues)}`, null);
        this.finish('failed');
        return;
      }
      this.result = this.makeResult('run', true, 0, null, 'run finished (exit 0)', null);
      this.finish('succeeded');
    } catch (e) {
      if (this.fault) {
        this.result = this.makeResult(step, false, null, null, this.fault.message, null);
        this.finish('failed');
      } else if (e instanceof Cancelled || this.cancelRequested) {
        this.result = this.makeResult(step, false, null, null, 'cancelled', null);
        this.finish('cancelled');
      } else if (e instanceof LimitHitError) {
        // a limit of the host-side prepare step (model size, prepare time, generated files, heap)
        this.events.append({ type: 'limit', limitHit: e.hit });
        this.system(step, `${step}: stopped: ${e.message}`);
        this.result = this.makeResult(step, false, null, null, `${step} stopped: ${e.message}`, e.hit);
        this.finish('failed');
      } else {
        const msg = (e as Error).message;
        if (e instanceof PrepareError) this.foreignMakefiles = e.foreignMakefiles;
        this.system(step, `error: ${msg}`);
        this.result = this.makeResult(step, false, null, null, `${step} failed: ${msg}`, null);
        this.finish('failed');
      }
    } finally {
      // the job's processes are all gone here (runStep awaits them), so the work dir is safe to touch
      // once the host-side work a cancel let go of has stopped too (a generation writing into it)
      if (this.abandoned.size) {
        let timer: NodeJS.Timeout | undefined;
        await Promise.race([Promise.all(this.abandoned), new Promise((r) => (timer = setTimeout(r, ABANDONED_WAIT_MS)))]);
        clearTimeout(timer); // else it kept a CLI that was done alive for 10 s (Ctrl+C in prepare)
      }
      if (ws) {
        const tr = Date.now();
        await ws.release().catch(() => {});
        this.timed(step, 'workspace release', tr);
      }
      if (!this.finalStatus) {
        this.result ??= this.makeResult(step, false, null, null, 'internal error: job ended without a result', null);
        this.finish('failed');
      }
      this.emitEnd();
      this.finishedSignal();
    }
  }

  /**
   * Where each module that crashed (died by a signal) crashed, from the crash report it wrote
   * (crash-reports.ts): addr2line, in the job's sandbox, maps its frames in its executable to
   * function, file and line; the site is the first place in the project's code (` at FILE:LINE in
   * its protected region ID (function)`), told in the run's message, as an error at that line
   * among the job's diagnostics (the IDE's Problems panel), and its frames in the job's log. At
   * most CRASH_SITES_TOLD modules; none when no report or no place is known. Never throws.
   */
  private async crashSites(sandbox: Sandbox, ws: Workspace, runtimeDir: string | undefined, runtimePath: string, crashes: LauncherCrashes, reports: CrashReports, prep: { regions: ReadonlyMap<string, readonly ProtectedRegion[]>; userCopies?: ReadonlyMap<string, UserCopy> }): Promise<Map<string, string>> {
    const sites = new Map<string, string>();
    if (this.cancelRequested || this.fault) return sites; // a stop asked for: no more sandboxed work
    const work = sandbox.workPath(ws.workDir);
    const crashed = crashes.failures().filter((f) => !f.killed && f.how?.startsWith('died by signal')).slice(0, CRASH_SITES_TOLD);
    for (const f of crashed) {
      const report = reports.of(f.module);
      if (!report) continue;
      // the module's executable as the generated Makefile builds it: never a path the module's output names
      const moduleDir = posix.join(work, makeDir(this.request.kind), 'modules', `${f.module}_mod`);
      const argv = addr2lineArgs(report, posix.join(moduleDir, f.module));
      if (!argv.length) continue;
      const t0 = Date.now();
      const out = await captureInSandbox(sandbox, { name: `${this.id}-crash-site`, jobId: this.id, workDir: ws.workDir, cwd: '', argv, env: {}, limits: this.request.limits, runtimeDir, owner: ws.owner }, MAX_ADDR2LINE_CHARS, CRASH_SITE_TIMEOUT_MS);
      this.timed('run', `crash site of ${f.module} (addr2line)`, t0);
      if (out === null) {
        this.system('run', `${f.module}'s crash report could not be mapped to its code (addr2line failed in the sandbox)`);
        continue;
      }
      const ctx = { cwd: moduleDir, root: posix.join(work, treeRoot(this.request.kind)), regions: prep.regions, ...(prep.userCopies ? { userCopies: prep.userCopies } : {}) };
      const site = crashSite(report, parseAddr2line(out), ctx, treeRoot(this.request.kind), runtimePath);
      if (!site) continue;
      sites.set(f.module, site.said);
      this.mappedCrashSites.push(crashHeadText(report), ...site.frames.map((frame) => `  ${frame}`));
      this.system('run', crashSiteLine(f.module, site));
      for (const frame of site.frames) this.system('run', `${f.module} crash frame ${frame}`);
      if (site.diagnostic) this.addDiagnostic(site.diagnostic);
    }
    return sites;
  }

  /**
   * The run's CONTRACT_LOG_MAX_BYTES (limits.ts runLogMaxBytes): 3/4 of the room its work dir has
   * left now (the build step ended, the earlier runs' logs are gone), said in one line. The room is
   * the tmpfs's own free count (statfs) when the work dir is one, else the disk limit less the
   * regular files' sizes (find, on the host or in the sandbox); the whole limit when neither answers.
   * No job process runs now. Never throws.
   */
  private async runLogBound(sandbox: Sandbox, workDir: string): Promise<{ maxBytes: number; reserve: ReturnType<typeof runLogDiskReserve> }> {
    const t0 = Date.now();
    const limit = workDiskBytes(this.request.limits);
    // the work dir's files count against the memory limit where it is enforced (a tmpfs charged to the job's cgroup)
    const reserve = runLogDiskReserve(this.request.limits, sandbox.name !== 'none');
    let room: number | null = null;
    try {
      const disk = sandbox.readWorkDirs ? null : await workDiskState(workDir);
      if (disk) room = Math.min(disk.freeBytes, limit);
      else {
        const usage = await (sandbox.workUsage ? sandbox.workUsage(workDir) : hostWorkUsage(workDir));
        if (usage && !usage.partial) room = Math.max(0, limit - usage.totalBytes);
      }
    } catch {
      room = null;
    }
    // the room the logs have: what the work dir has left, less the part the memory limit cannot hold
    const usableRoom = Math.max(0, Math.min(room ?? limit, room === null ? reserve.usable : reserve.usable - (limit - room)));
    const bytes = runLogMaxBytes(usableRoom);
    this.timed('run', 'work dir room (the CSV log bound)', t0);
    const left = room === null ? `what the work dir holds could not be measured (its disk limit: ${formatBytes(limit)})` : `the work dir has ${formatBytes(room)} left of its ${formatBytes(limit)} disk limit`;
    const why = bytes === RUN_LOG_MAX_BYTES
      ? `the most the service collects of one log: ${left}`
      : bytes === RUN_LOG_MIN_BYTES
        ? `the least the service gives: ${left}`
        : room === null
          ? `3/4 of the disk limit: ${left}`
          : usableRoom < room
            ? `3/4 of the ${formatBytes(usableRoom)} the logs may still fill: ${left}, and its files count against the memory limit`
            : `3/4 of the ${formatBytes(room)} the work dir has left of its ${formatBytes(limit)} disk limit`;
    this.system('run', `CSV logs capped at ${formatBytes(bytes)} per module (CONTRACT_LOG_MAX_BYTES: ${why}); a module's log past it ends with a log-capped record and the run goes on`);
    const memory = reserve.unusable > 0
      ? ` (the work dir's files count against the ${this.request.limits.memoryMiB} MiB memory limit: the logs may fill ${formatBytes(reserve.usable)} of its ${formatBytes(limit)}, the memory limit less ${formatBytes(runProcessesMemoryBytes(this.request.limits))} kept for the processes; raise memoryMiB with workDiskMiB for more)`
      : '';
    this.system('run', `CSV logs stopped together before the work dir is full: a module's once it has less than ${formatBytes(reserve.modules - reserve.unusable)} free, ORD's less than ${formatBytes(reserve.ord - reserve.unusable)}, a supervisor's less than ${formatBytes(reserve.supervisors - reserve.unusable)}${memory}; each then ends with a log-capped record and the run goes on`);
    return { maxBytes: bytes, reserve };
  }

  private workTreeDigest(sandbox: Sandbox, ws: Workspace): Promise<string | null> {
    return (sandbox.workTreeDigest ? sandbox.workTreeDigest(ws.workDir) : hostWorkTreeDigest(ws.workDir)).catch(() => null);
  }

  /**
   * A reused work dir is built on only as the last build step left it (docs/sandbox.md, "Build
   * products between jobs"): a run (or anything after that build) that rewrote, re-dated or added
   * a file outside logs/ and run/ makes the whole work dir untrusted, and it is emptied.
   */
  private async checkBuildOutputs(sandbox: Sandbox, ws: Workspace, builtWith: string | null): Promise<void> {
    const accepted = ws.acceptedOutputs;
    const now = accepted === null ? null : acceptance(await this.workTreeDigest(sandbox, ws), builtWith);
    if (accepted !== null && now === accepted) return;
    this.system('prepare', accepted === null
      ? 'no build ended in this workspace since it was emptied: building from scratch'
      : `the work dir changed after the last build ended${builtWith ? `, or it was built with another runtime than ${builtWith}` : ''}: its build products are not trusted, building from scratch`);
    await ws.reset();
  }

  /**
   * Starts the live trace channel (pipeline/trace-tail.ts) on the work dir's host folder: the
   * work dir itself for bwrap and none; for a sandbox that reads its work dirs itself (docker: a
   * volume), the folder it proves to be that work dir on this host (liveWorkRoot), or no channel,
   * with one line saying why (docs/build-service-api.md "Trace channel"). No job process runs now
   * (the build step ended, the run has not started). Never throws.
   *
   * The tail orders records by their mono_ns against process.hrtime (CLOCK_MONOTONIC): a Docker
   * container has the host's CLOCK_MONOTONIC (Docker gives it no time namespace; the proof
   * refuses a holder whose time namespace differs), so the same comparison holds for it.
   */
  private async startTraceTail(sandbox: Sandbox, workDir: string, bounds: ArtifactBounds): Promise<TraceTail | null> {
    let root = workDir;
    if (sandbox.readWorkDirs) {
      const t0 = Date.now();
      const live = sandbox.liveWorkRoot
        ? await sandbox.liveWorkRoot(workDir).catch((e: unknown) => ({ ok: false as const, reason: (e as Error).message.split('\n')[0] ?? String(e) }))
        : { ok: false as const, reason: 'its work dir is not a host folder' };
      this.timed('run', 'live trace folder (the work volume on this host, proven once per volume)', t0);
      if (!live.ok) {
        this.system('run', `trace: no live trace channel in the ${this.sandboxName} sandbox: ${live.reason}; the records are in the collected logs`);
        return null;
      }
      root = live.root;
    }
    const tail = await TraceTail.start(root, {
      trace: (records) => {
        if (!this.events.isEnded) this.events.append({ type: 'trace', records });
      },
      live: (records) => this.events.broadcast({ type: 'trace', records }),
      system: (line) => this.system('run', line),
      tampered: (file, why) => this.runIssues.logTampered(file, why),
    }, { ...TRACE_TAIL_BOUNDS, fileBytes: bounds.fileBytes });
    // the modules write their logs sooner only while a client follows the job
    tail.setWatched(this.events.subscriberCount > 0);
    this.events.onSubscribers = (count) => tail.setWatched(count > 0);
    return tail;
  }

  /** Copies the run's logs out of the sandbox (its processes are gone); a failure is a warning line. */
  private async collectArtifacts(sandbox: Sandbox, workDir: string, bounds: ArtifactBounds): Promise<void> {
    const t0 = Date.now();
    const abort = (this.collectAbort = new AbortController());
    try {
      const reader = sandbox.readWorkDirs ? sandbox.readWorkDirs.bind(sandbox) : hostWorkDirReader;
      let throttled: Throttling | undefined;
      const budget = this.realtimeBudget;
      const collected = await collectRunArtifacts(reader, workDir, bounds, (name, data) => {
        this.runIssues.log(data, name);
        if (budget && moduleOfLog(name) === 'ORD') throttled = budgetThrottling(data, budget.periodUs * 1000, budget.runtimeUs * 1000);
      }, {
        launchedModules: this.runIssues.launchedModules,
        signal: abort.signal,
        // a log stopped at the disk reserve says what filled the work dir: the disk hit's measure, else one now
        workFilledBy: async () => {
          const usage = this.workUsageAtEnd ?? await (sandbox.workUsage ? sandbox.workUsage(workDir) : hostWorkUsage(workDir)).catch(() => null);
          return usage ? describeWorkUsage(usage) : null;
        },
      });
      // a cancelled run's processes were killed: the mailboxes and pid files they leave say nothing
      this.artifacts = this.cancelRequested ? { ...collected, runDirLeftovers: [] } : collected;
      this.artifactsCollectMs = Date.now() - t0;
      const a = this.artifacts;
      this.runIssues.artifacts(a);
      if (throttled && budget && !this.cancelRequested) {
        // among the job's warnings (the CLI's closing lines, GET, JSON) and in its log, as a build's cut output
        const warning = throttlingWarning(throttled, budget.runtimeUs, budget.periodUs);
        this.warnings.push(warning);
        this.system('run', `warning: ${warning}`);
      }
      this.system('run', `collected ${a.files.length} artifact(s) in ${this.artifactsCollectMs} ms${a.skipped.length ? `; left out: ${a.skipped.map((s) => `${visibleText(s.name, { escapeTab: true })} (${s.reason})`).join(', ')}` : ''}`);
    } catch (e) {
      this.system('run', `warning: the run's logs could not be collected: ${(e as Error).message.split('\n')[0]}`);
    } finally {
      this.collectAbort = null;
    }
  }

  /** One collected artifact by name (GET /api/jobs/:id/artifacts/<name>). */
  artifact(name: string): Artifact | undefined {
    return this.artifacts?.files.find((f) => f.name === name);
  }

  /** The JSON listing of the artifacts (no bytes), null when the job has not run. */
  artifactsJSON(): { files: { name: string; path: string; size: number; gzipSize: number; capped: string | null }[]; skipped: RunArtifacts['skipped']; runDirLeftovers: string[]; collect_ms: number | null; crashSites?: string[] } | null {
    const a = this.artifacts;
    if (!a) return null;
    // the crash files' sites, mapped in the sandbox right after the run (crashSites: the executable that crashed)
    const mapped = this.mappedCrashSites.length ? { crashSites: [...this.mappedCrashSites] } : {};
    return { files: a.files.map(({ name, path, size, gzip, capped }) => ({ name, path, size, gzipSize: gzip.length, capped })), skipped: a.skipped, runDirLeftovers: a.runDirLeftovers, collect_ms: this.artifactsCollectMs, ...mapped };
  }

  /**
   * `p`, or a rejection as soon as the job is cancelled (or faulted). The work `p` stands for goes
   * on meanwhile (prepareWorkspace stops at its next check of the cancel): its end is always
   * observed — a rejection nobody handled ended the whole service (a Stop 60 ms into a run: the
   * generator's 'cancelled') — and awaited before the job lets its workspace go (abandoned),
   * unless `detached` (work outside the workspace that other jobs share: the runtime's build).
   */
  private orCancel<T>(p: Promise<T>, { detached = false }: { detached?: boolean } = {}): Promise<T> {
    const settled = p.then(() => undefined, () => undefined);
    // detached: work that never touches the job's workspace (the shared runtime build): not waited for
    if (!detached) {
      this.abandoned.add(settled);
      void settled.then(() => this.abandoned.delete(settled));
    }
    if (this.cancelRequested || this.fault) return Promise.reject(this.fault ?? new Cancelled());
    return Promise.race([p, this.cancelled.then(() => Promise.reject(this.fault ?? new Cancelled()))]);
  }

  /** Work an orCancel let go of that has not ended yet: awaited (bounded) before the workspace is released. */
  private readonly abandoned = new Set<Promise<void>>();

  /** Whether the job takes no more diagnostics: its bound is full, and so is the errors' room past it. */
  private get diagnosticsFull(): boolean {
    return this.diagnostics.length >= MAX_DIAGNOSTICS && this.errorsPastBound >= MAX_DIAGNOSTICS;
  }

  /** Keys of the diagnostics kept (sameDiagnosticKey): a header two modules include gives its problems once. */
  private readonly diagnosticKeys = new Set<string>();

  /**
   * Keeps a gcc diagnostic: up to the job's bound, and an error past it in a room of its own (errors
   * first: a flood of warnings does not hide it). One already kept (the same file, place and
   * message: a header or a `.c` of your own that two modules include) is not kept again.
   */
  private addDiagnostic(d: GccDiagnostic): void {
    const key = sameDiagnosticKey(d);
    if (key !== undefined) {
      if (this.diagnosticKeys.has(key)) return;
      this.diagnosticKeys.add(key);
    }
    if (this.diagnostics.length >= MAX_DIAGNOSTICS) {
      if (d.severity !== 'error' || this.errorsPastBound >= MAX_DIAGNOSTICS) return;
      this.errorsPastBound++;
    }
    this.diagnostics.push(d);
    this.events.append({ type: 'diagnostic', diagnostic: d });
  }

  private async runStep(
    sandbox: Sandbox,
    ws: Workspace,
    runtimeDir: string | undefined,
    step: 'build' | 'run',
    argv: string[],
    seconds: number,
    route: (line: string, stream: 'stdout' | 'stderr') => { source: string; line: string }[],
    env: Record<string, string> = {},
    /** The command as the log shows it (default: argv joined). */
    shown?: string,
  ): Promise<{ ok: boolean; exitCode: number | null; signal: string | null; limitHit: LimitHit | null; message: string | null }> {
    if (this.fault) throw this.fault;
    if (this.cancelRequested) throw new Cancelled();
    const t0 = Date.now();
    this.system(step, `$ ${shown ?? argv.join(' ')}`);
    const proc = await sandbox.start({
      name: `${this.id}-${step}`,
      jobId: this.id,
      workDir: ws.workDir,
      cwd: '',
      argv,
      env,
      limits: this.request.limits,
      runtimeDir,
      owner: ws.owner,
      ...(step === 'run' && this.request.realtime ? { realtime: true } : {}),
      // a limit hit during the run stops the architecture as Stop does (every module still running
      // writes its last records), then kills; a build is killed at once
      ...(step === 'run' ? { stopOnLimit: {
        processName: LAUNCHER_PROCESS_NAME,
        graceMs: CANCEL_GRACE_MS,
        stopping: (hit: LimitHit) => {
          if (this.cancelRequested) return; // Stop came first: the run ends as cancelled, the limit in limitHit
          this.limitStopping = hit;
          this.system('run', `${describeLimitHit(hit)} reached: stopping the architecture as at the end of a run (what still runs after ${CANCEL_GRACE_MS} ms is killed)`);
        },
        unanswered: () => {
          if (this.limitStopping) this.system('run', `${NO_LAUNCHER_ASKED}: killed`);
        },
      } } : {}),
    });
    this.current = proc;
    this.currentStep = step;
    this.mechanisms = proc.mechanisms;
    this.timed(step, `sandbox start (limits set-up: memory ${proc.mechanisms.memory}, processes ${proc.mechanisms.processes}, disk ${proc.mechanisms.disk})`, t0);
    const note = (line: string): void => proc.noteLine(line);
    let timeHit: LimitHit | null = null;
    const timer = setTimeout(this.guarded('time limit', () => {
      timeHit = {
        name: step === 'build' ? 'buildSeconds' : 'runSeconds',
        value: seconds,
        unit: 's',
        mechanism: 'service-timer',
      };
      this.events.append({ type: 'limit', limitHit: timeHit });
      (step === 'run' ? this.stopArchitecture(proc, 'runSeconds') : proc.kill()).catch(() => {});
    }), seconds * 1000);
    if (this.cancelRequested || this.fault) proc.kill().catch(() => {});
    const pump = (stream: Readable, name: 'stdout' | 'stderr'): Promise<void> =>
      new Promise((resolve) => {
        const splitter = new LineSplitter({
          maxBytes: this.request.limits.outputBytesPerStream,
          // a build's gcc JSON line (a compilation's diagnostics, one line) has a bound of its own
          ...(step === 'build' ? { longLine: { maxBytes: SERVICE_BOUNDS.gccJsonLineBytes, begins: looksLikeGccJson } } : {}),
          // past the cap a build's gcc diagnostics are still read (make's directory lines say where
          // gcc ran), up to the job's diagnostics bound: kept in no log, but an error after a flood
          // of warnings is still the job's, at its line (addDiagnostic)
          ...(step === 'build' ? { pastCap: {
            wanted: (head: string) => !this.diagnosticsFull && (looksLikeGccJson(head) || beginsAsMakeDirectory(head)),
            boundOf: (head: string) => (looksLikeGccJson(head) ? SERVICE_BOUNDS.gccJsonLineBytes : SERVICE_BOUNDS.outputLineBytes),
            onLine: (line: string) => {
              if (this.fault) return;
              const before = this.diagnostics.length;
              route(line, name); // its log lines are not kept: the cap bounds the log
              this.diagnosticsPastCap += this.diagnostics.length - before;
            },
          } } : {}),
          onLine: (line) => {
            if (this.fault) return; // the job is being stopped: its output is only drained
            note(line);
            for (const r of route(line, name)) this.line(step, r.source, name, r.line);
          },
          onTruncated: () => {
            this.truncated[name] = true;
            if (step === 'run') this.runIssues.outputTruncated(name, this.request.limits.outputBytesPerStream);
            this.system(step, `[output truncated: ${name} limit ${formatBytes(this.request.limits.outputBytesPerStream)} reached]`);
            // a build's output is kept nowhere else: said among the job's warnings (the 201's
            // listeners, GET, the CLI's closing lines) and in its log, not in `truncated` alone
            if (step === 'build') {
              const warning = buildOutputCutWarning(name, this.request.limits.outputBytesPerStream);
              this.warnings.push(warning);
              this.system(step, `warning: ${warning}`);
            }
          },
        });
        // the sandbox's output is untrusted: whatever its handling throws stops this job, never the service
        stream.on('data', this.guarded(`${step} ${name}`, (chunk: Buffer) => splitter.push(chunk)));
        stream.on('error', () => {});
        stream.on('close', () => {
          this.guarded(`${step} ${name}`, () => splitter.end())();
          resolve();
        });
      });
    const pumps = Promise.all([pump(proc.stdout, 'stdout'), pump(proc.stderr, 'stderr')]);
    const exit = await proc.done;
    // the pumps get 1.5 s at most after the exit; the timer must not keep a CLI process alive
    let pumpTimer: NodeJS.Timeout | undefined;
    await Promise.race([pumps, new Promise((r) => (pumpTimer = setTimeout(r, 1500)))]);
    clearTimeout(pumpTimer);
    clearTimeout(timer);
    this.current = null;
    this.currentStep = null;
    this.durations[step] = Date.now() - t0;
    const limitHit: LimitHit | null = exit.limitHit ?? timeHit;
    if (exit.limitHit) this.events.append({ type: 'limit', limitHit: exit.limitHit });
    if (this.fault) throw this.fault;
    let message: string | null = null;
    if (this.cancelRequested) message = 'cancelled';
    else if (limitHit) message = `killed: ${describeLimitHit(limitHit)}`;
    const workUsage = () => (sandbox.workUsage ? sandbox.workUsage(ws.workDir) : hostWorkUsage(ws.workDir)).catch(() => null);
    const memoryFiles = limitHit && !this.cancelRequested ? memoryHeldByFiles(limitHit) : undefined;
    if (limitHit?.name === 'workDiskMiB' && !this.cancelRequested) {
      // say which files (which module's logs, which build products) took the space
      const usage = await workUsage();
      this.workUsageAtEnd = usage;
      if (usage) message = `${message}: filled by ${describeWorkUsage(usage)}`;
    } else if (memoryFiles !== undefined) {
      // the job's cgroup counted the OOM kill and says what held the memory: its files, not a process
      const usage = await workUsage();
      message = `${message}: ${formatBytes(memoryFiles)} of it were the job's files in its tmpfs mounts (the work dir, /tmp, /dev/shm), which no kill frees${usage ? `; the work dir held ${describeWorkUsage(usage)}` : ''}`;
    }
    const ok = !this.cancelRequested && !limitHit && exit.exitCode === 0;
    const cut = step === 'build' ? this.buildOutputCut() : '';
    this.system(step, ok ? `${step} finished in ${this.durations[step]} ms${cut}` : `${step}: ${message ?? `exit ${exit.exitCode}${exit.signal ? ` (${exit.signal})` : ''}`}${cut}`);
    return { ok, exitCode: exit.exitCode, signal: exit.signal, limitHit, message };
  }

  /** `; 1 line(s) of gcc's JSON diagnostics could not be read: ...` when some could not (their errors unreported), else ''. */
  private unreadableDiagnostics(): string {
    const n = this.unreadableDiagnosticLines;
    return n ? `; ${n} line(s) of gcc's JSON diagnostics could not be read: their diagnostics, errors among them, are not reported (the build's log has them as text)` : '';
  }

  /** `; its stdout was cut at the output limit (...)` when the build step's output was cut, else ''. */
  private buildOutputCut(): string {
    const cut = (['stdout', 'stderr'] as const).filter((n) => this.truncated[n]);
    if (!cut.length) return '';
    const read = this.diagnosticsPastCap ? ` (${this.diagnosticsPastCap} gcc diagnostic(s) in it still read)` : '';
    return `; its ${cut.join(' and ')} ${cut.length > 1 ? 'were' : 'was'} cut at the output limit (${formatBytes(this.request.limits.outputBytesPerStream)} per stream): the rest is not kept${read}`;
  }

  private makeResult(
    step: JobStep,
    ok: boolean,
    exitCode: number | null,
    signal: string | null,
    message: string,
    limitHit: LimitHit | null,
  ): JobResult {
    return {
      ok,
      step,
      exitCode,
      signal,
      message,
      limitHit,
      issues: [...this.runIssues.all],
      truncated: { ...this.truncated },
      durations_ms: { ...this.durations },
      mechanisms: this.mechanisms,
    };
  }

  /** Records the final status; the job's events end once its resources are released (emitEnd). */
  private finish(status: 'succeeded' | 'failed' | 'cancelled'): void {
    this.finalStatus ??= status;
  }

  private emitEnd(): void {
    if (this.isDone || !this.finalStatus) return;
    this.finishedAt = Date.now();
    this.setStatus(this.finalStatus);
    this.events.append({ type: 'end', result: this.result });
  }

  /** The JSON view of GET /api/jobs/:id. */
  toJSON(): Record<string, unknown> {
    return {
      id: this.id,
      action: this.request.action,
      kind: this.request.kind,
      sandbox: this.sandboxName,
      sandboxNote: this.sandboxNote,
      status: this.status,
      createdAt: this.createdAt,
      startedAt: this.startedAt,
      finishedAt: this.finishedAt,
      warnings: this.warnings,
      result: this.result,
      diagnostics: this.diagnostics,
      prepareDiagnostics: this.prepareDiagnostics,
      artifacts: this.artifactsJSON(),
    };
  }
}

/**
 * What a workspace accepts a build step's work tree as: its digest, bound to the runtime it was
 * built with (`runtime-<key>`, none for a runtime in the image): another runtime is another
 * acceptance, so the next build starts from scratch instead of linking old objects to it.
 */
export function acceptance(digest: string | null, builtWith: string | null): string | null {
  if (digest === null || builtWith === null) return digest;
  return createHash('sha256').update(digest).update('\0').update(builtWith).digest('hex');
}

/**
 * What makes two gcc diagnostics one problem told twice: the same severity, message and place in a
 * file of the tree (each module including it compiles it again). A diagnostic with no file (a
 * linker's) is each module's own: undefined (never merged).
 */
export function sameDiagnosticKey(d: GccDiagnostic): string | undefined {
  if (d.file === null) return undefined;
  return JSON.stringify([d.severity, d.file, d.line, d.column, d.option ?? null, d.message]);
}
