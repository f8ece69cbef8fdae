/**
 * The in-process build service: validates job requests, picks the sandbox, queues jobs with
 * bounded concurrency (429 beyond concurrency + queueSize), runs them, keeps finished jobs (their
 * full event log and result) up to `keepJobs`, and cleans everything up on close.
 */
import { randomBytes } from 'node:crypto';
import { chmodSync, mkdirSync, mkdtempSync, promises as fsp, realpathSync } from 'node:fs';
import { availableParallelism, cpus, tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { DEFAULT_LIMITS, LimitsError, SERVICE_BOUNDS, longestDuration, mergeLimits, workDiskBytes, type Limits } from './limits.js';
import { durationCapMessage, Job, type JobRequest } from './pipeline/job.js';
import type { ProjectKind, ProjectSource } from './pipeline/prepare.js';
import { RuntimeCache } from './pipeline/runtime-cache.js';
import { GenerationCache } from './cache/generation-cache.js';
import { WorkspaceManager } from './pipeline/workspaces.js';
import { serviceFolder } from './pipeline/dead-service-folders.js';
import type { BwrapOptions } from './sandbox/bwrap.js';
import type { DockerOptions } from './sandbox/docker.js';
import type { SweepReport } from './sandbox/docker-sweep.js';
import { SANDBOX_CHOICES, SandboxRegistry, SandboxUnavailableError } from './sandbox/select.js';
import type { SandboxChoice, SandboxName } from './sandbox/types.js';
import { ServiceError } from './service-errors.js';
import { checkRelativePath, isInside, removeTreeNoFollow, UnsafePathError } from './util/safe-fs.js';
import { parseStdinField } from './pipeline/stdin-files.js';
import { JSON_BODY_NOT_OBJECT, MIN_READY_TIMEOUT_SECONDS, cpuMissingFrom, isCpuList } from '@contract-studio/conventions';

/** Characters no inline file path holds: controls, line separators, bidirectional overrides (a name shown as another one). */
const INLINE_NAME_UNSAFE = /[\x00-\x1f\x7f-\x9f\u2028\u2029\u202a-\u202e\u2066-\u2069]/;

export interface BuildServiceOptions {
  /** Default sandbox of jobs that name none. Default 'auto'. */
  sandbox?: SandboxChoice;
  /** Jobs running at once. Default: the number of cores. */
  concurrency?: number;
  /** Jobs waiting beyond the running ones; more are refused (429). Default 2 x concurrency. */
  queueSize?: number;
  /** Overrides of DEFAULT_LIMITS for this service (jobs may only lower them). */
  limits?: Partial<Limits>;
  /** The limits as the user wrote them (`contract serve --limit NAME=VALUE`): quoted in a refusal, and a count or size checked exactly. */
  limitTexts?: Readonly<Record<string, string>>;
  /** Folders a job's project.dir must be inside. Default [] (inline files only). */
  projectRoots?: string[];
  /** Where workspaces and the runtime cache live. Default: a fresh temp dir, removed on close. */
  cacheDir?: string;
  /**
   * Project workspaces (`project.dir` jobs) outlive the service in `<cacheDir>/projects/`, so the
   * next service on the same cache folder (the next `contract build`, the IDE) finds its work tree
   * as the last build left it (docs/getting-started.md "The build cache"). Default false: every
   * workspace is removed on close. Needs `cacheDir`.
   */
  persistentWorkspaces?: boolean;
  /** The runtime source folder (Seam 3). Default: the repository's runtime/. */
  runtimeSource?: string;
  /** Finished jobs kept for GET. Default 50. */
  keepJobs?: number;
  bwrap?: BwrapOptions;
  docker?: DockerOptions;
  /**
   * The service's own log lines (what the Docker sweep removed or left, shutdown clean-up).
   * Default: stderr, prefixed "[build-service] ".
   */
  log?: (line: string) => void;
}

const here = dirname(fileURLToPath(import.meta.url));
export const DEFAULT_RUNTIME_SOURCE = resolve(here, '..', '..', '..', 'runtime');

export class JobService {
  readonly limits: Limits;
  readonly concurrency: number;
  readonly queueSize: number;
  readonly defaultSandbox: SandboxChoice;
  readonly sandboxes: SandboxRegistry;
  private readonly jobs = new Map<string, Job>();
  private readonly running = new Set<Job>();
  private readonly waiting: { job: Job; start: () => void }[] = [];
  private readonly projectRoots: string[];
  private readonly cacheDir: string;
  private readonly ownsCacheDir: boolean;
  private readonly workspaces: WorkspaceManager;
  private readonly runtime: RuntimeCache;
  private readonly generated: GenerationCache | null;
  private readonly keepJobs: number;
  private closed = false;
  private readonly log: (line: string) => void;
  private readonly submittedListeners = new Set<(job: Job) => void>();
  /** The start-up sweep of the Docker engine (when docker is the default or auto picks it). */
  private readonly startupSweep: Promise<unknown>;

  constructor(options: BuildServiceOptions = {}) {
    this.limits = mergeLimits(DEFAULT_LIMITS, options.limits, false, options.limitTexts);
    this.concurrency = Math.max(1, options.concurrency ?? availableParallelism());
    this.queueSize = Math.max(0, options.queueSize ?? 2 * this.concurrency);
    this.defaultSandbox = options.sandbox ?? 'auto';
    this.keepJobs = options.keepJobs ?? 50;
    this.log = options.log ?? ((line) => process.stderr.write(`[build-service] ${line}\n`));
    const log = options.docker?.log ?? options.log;
    this.sandboxes = new SandboxRegistry({ bwrap: options.bwrap, docker: { ...options.docker, ...(log ? { log } : {}) } });
    this.projectRoots = (options.projectRoots ?? []).map((r) => realpathSync(r));
    this.ownsCacheDir = !options.cacheDir;
    this.cacheDir = options.cacheDir ?? mkdtempSync(join(tmpdir(), 'contract-build-'));
    mkdirSync(this.cacheDir, { recursive: true, mode: 0o711 });
    chmodSync(this.cacheDir, 0o711); // job uids must traverse it to reach their own work dir
    this.workspaces = new WorkspaceManager(serviceFolder(join(this.cacheDir, 'ws')), {
      onRemove: async (workDir) => {
        await this.sandboxes.sandboxes.docker.release?.(workDir);
      },
      persistentDir: options.persistentWorkspaces && options.cacheDir ? join(this.cacheDir, 'projects') : undefined,
      sweepDeadSiblings: true,
    });
    this.generated = options.persistentWorkspaces && options.cacheDir ? new GenerationCache(join(this.cacheDir, 'generated')) : null;
    this.runtime = new RuntimeCache(options.runtimeSource ?? DEFAULT_RUNTIME_SOURCE, join(this.cacheDir, 'runtime'));
    this.startupSweep = this.sweepAtStart();
  }

  /**
   * In the background (start-up stays fast and never fails for want of Docker): when the default
   * sandbox is docker, or auto and it picks docker, sweeps what dead services left in the engine.
   */
  private async sweepAtStart(): Promise<void> {
    try {
      const choice = this.defaultSandbox;
      if (choice !== 'docker' && choice !== 'auto') return;
      const picked = choice === 'auto' ? (await this.sandboxes.resolve('auto')).sandbox.name : (await this.sandboxes.probe('docker')).available ? 'docker' : null;
      if (picked === 'docker' && !this.closed) await this.sandboxes.docker.sweep();
    } catch {
      // no sandbox at all: the jobs will say so
    }
  }

  /**
   * Sweeps the Docker engine for containers and volumes of dead services (once per service; the
   * first job in docker and the start-up sweep share it). Resolves with what was removed and left.
   */
  sweepDocker(): Promise<SweepReport> {
    return this.sandboxes.docker.sweep();
  }

  /** True from close() on: no job is taken any more (503 closing), the running ones are being cancelled. */
  get closing(): boolean {
    return this.closed;
  }

  get stats(): { running: number; queued: number; concurrency: number; queueSize: number } {
    return { running: this.running.size, queued: this.waiting.length, concurrency: this.concurrency, queueSize: this.queueSize };
  }

  get(id: string): Job | undefined {
    return this.jobs.get(id);
  }

  /**
   * Calls `listener` with every job accepted from now on, as soon as it has its id (before it
   * starts). Returns the function that stops the calls. A listener that throws is logged and
   * the job goes on.
   */
  onSubmitted(listener: (job: Job) => void): () => void {
    this.submittedListeners.add(listener);
    return () => this.submittedListeners.delete(listener);
  }

  /** The jobs kept, newest first; with `owner`, only the jobs submitted with that owner. */
  list(owner?: string): Job[] {
    const all = [...this.jobs.values()].reverse();
    return owner === undefined ? all : all.filter((j) => j.owner === owner);
  }

  /** Validates a request body (the JSON of POST /api/jobs); throws ServiceError 400/403. */
  parseRequest(body: unknown): { request: JobRequest; sandbox: SandboxChoice } {
    if (!body || typeof body !== 'object' || Array.isArray(body)) throw new ServiceError(400, 'bad_request', JSON_BODY_NOT_OBJECT);
    const b = body as Record<string, unknown>;
    const known = new Set(['action', 'project', 'kind', 'sandbox', 'start', 'duration', 'readyTimeout', 'cpus', 'realtime', 'werror', 'limits', 'stdin']);
    for (const k of Object.keys(b)) if (!known.has(k)) throw new ServiceError(400, 'bad_request', `unknown field "${k}"`);
    const action = b.action ?? 'build';
    if (action !== 'build' && action !== 'run') throw new ServiceError(400, 'bad_request', 'action must be "build" or "run"');
    const kind = (b.kind ?? 'cactal') as ProjectKind;
    if (kind !== 'cactal' && kind !== 'make') throw new ServiceError(400, 'bad_request', 'kind must be "cactal" or "make"');
    const sandbox = (b.sandbox ?? this.defaultSandbox) as SandboxChoice;
    if (!SANDBOX_CHOICES.includes(sandbox)) throw new ServiceError(400, 'bad_request', `sandbox must be one of ${SANDBOX_CHOICES.join(', ')}`);
    // START ends up inside a shell-quoted make recipe ('$(START)'): no quotes, $, backslash or backtick
    if (b.start !== undefined && (typeof b.start !== 'string' || b.start.length > 4096 || !/^[\w .,:;=+\-(){}[\]"]*$/.test(b.start))) {
      throw new ServiceError(400, 'bad_request', 'start must be one line like GLB.mission(consigne={1.0,2.0,3.0}) (letters, digits, spaces, . , : ; = + - ( ) { } [ ] " only)');
    }
    if (b.duration !== undefined && (typeof b.duration !== 'number' || !(b.duration > 0) || !Number.isFinite(b.duration))) {
      throw new ServiceError(400, 'bad_request', 'duration must be a positive number of seconds');
    }
    // CPUS ends up in the make command line: digits, commas and dashes only
    if (b.cpus !== undefined && (typeof b.cpus !== 'string' || b.cpus.length > 256 || !isCpuList(b.cpus))) {
      throw new ServiceError(400, 'bad_request', 'cpus must be a CPU list such as "1", "0-1" or "0,2"');
    }
    // the sandbox runs on this machine: a CPU it does not have is refused now, not after the build by contract-launch
    const online = cpus().length;
    const missing = typeof b.cpus === 'string' && online > 0 ? cpuMissingFrom(b.cpus, online) : undefined;
    if (missing !== undefined) throw new ServiceError(400, 'bad_request', `cpus: CPU ${missing} is not available here (${online} CPUs online: 0-${online - 1})`);
    if (b.realtime !== undefined && typeof b.realtime !== 'boolean') throw new ServiceError(400, 'bad_request', 'realtime must be true or false');
    if (b.realtime === true && action !== 'run') throw new ServiceError(400, 'bad_request', 'realtime applies to action "run" only');
    if (b.werror !== undefined && typeof b.werror !== 'boolean') throw new ServiceError(400, 'bad_request', 'werror must be true or false');
    if (b.werror === true && kind !== 'cactal') throw new ServiceError(400, 'bad_request', 'werror applies to a Cactal project only (a Makefile project sets its own flags)');
    let stdin: Record<string, string> | undefined;
    if (b.stdin !== undefined) {
      if (action !== 'run') throw new ServiceError(400, 'bad_request', 'stdin applies to action "run" only');
      try {
        stdin = parseStdinField(b.stdin);
      } catch (e) {
        throw new ServiceError(400, 'bad_request', (e as Error).message);
      }
    }
    let limits: Limits;
    try {
      limits = mergeLimits(this.limits, b.limits, true);
    } catch (e) {
      if (e instanceof LimitsError) throw new ServiceError(400, 'bad_request', e.message);
      throw e;
    }
    const longest = longestDuration(limits.runSeconds);
    // READY_TIMEOUT ends up in the make command line: a plain number of seconds, within the run's time
    const readyTimeout = b.readyTimeout;
    if (readyTimeout !== undefined && (typeof readyTimeout !== 'number' || !Number.isFinite(readyTimeout) || readyTimeout < MIN_READY_TIMEOUT_SECONDS || readyTimeout > longest)) {
      throw new ServiceError(400, 'bad_request', `readyTimeout must be a number of seconds from ${MIN_READY_TIMEOUT_SECONDS} to ${longest} (the run's time limit, ${limits.runSeconds} s, less the room kept to stop it)`);
    }
    // the inits' time past the launcher's default comes out of the longest duration
    const longestRun = longestDuration(limits.runSeconds, readyTimeout as number | undefined);
    const duration = b.duration === undefined ? undefined : Math.min(b.duration as number, longestRun);
    const { project, projectKey } = this.parseProject(b.project);
    return {
      request: { action, project, projectKey, kind, start: b.start as string | undefined, duration, ...(duration !== undefined && duration < (b.duration as number) ? { durationAsked: b.duration as number } : {}), ...(readyTimeout !== undefined ? { readyTimeout: readyTimeout as number } : {}), ...(b.cpus !== undefined ? { cpus: b.cpus as string } : {}), ...(b.realtime === true ? { realtime: true } : {}), ...(b.werror === true ? { werror: true } : {}), ...(stdin && Object.keys(stdin).length ? { stdin } : {}), limits },
      sandbox,
    };
  }

  private parseProject(raw: unknown): { project: ProjectSource; projectKey: string | null } {
    if (!raw || typeof raw !== 'object') throw new ServiceError(400, 'bad_request', 'project must be {dir} or {files}');
    const p = raw as Record<string, unknown>;
    if ((p.dir === undefined) === (p.files === undefined)) throw new ServiceError(400, 'bad_request', 'project needs exactly one of dir, files');
    if (p.files !== undefined) {
      if (!p.files || typeof p.files !== 'object' || Array.isArray(p.files)) throw new ServiceError(400, 'bad_request', 'project.files must be an object path -> text');
      const files: Record<string, string> = {};
      const entries = Object.entries(p.files as Record<string, unknown>);
      if (entries.length > SERVICE_BOUNDS.projectFiles) throw new ServiceError(400, 'bad_request', `project.files holds ${entries.length} files: more than the ${SERVICE_BOUNDS.projectFiles} a job is given`);
      for (const [rel, text] of entries) {
        const shown = JSON.stringify(rel.slice(0, 200));
        if (typeof text !== 'string') throw new ServiceError(400, 'bad_request', `project.files[${shown}] must be a string`);
        if (Buffer.byteLength(rel) > SERVICE_BOUNDS.inlinePathBytes || rel.split('/').some((part) => Buffer.byteLength(part) > 255)) {
          throw new ServiceError(400, 'bad_request', `project.files[${shown}${rel.length > 200 ? '...' : ''}]: a path of at most ${SERVICE_BOUNDS.inlinePathBytes} bytes, each part at most 255, is given`);
        }
        const bad = INLINE_NAME_UNSAFE.exec(rel);
        if (bad) throw new ServiceError(400, 'bad_request', `project.files[${shown}]: the character U+${bad[0].charCodeAt(0).toString(16).toUpperCase().padStart(4, '0')} is refused in a path (a control or bidirectional character shows a name as another one)`);
        try {
          files[checkRelativePath(rel)] = text;
        } catch (e) {
          throw new ServiceError(400, 'bad_request', (e as UnsafePathError).message);
        }
      }
      return { project: { files }, projectKey: null };
    }
    if (typeof p.dir !== 'string' || !p.dir.startsWith('/')) throw new ServiceError(400, 'bad_request', 'project.dir must be an absolute path');
    let real: string;
    try {
      real = realpathSync(p.dir);
    } catch {
      throw new ServiceError(400, 'bad_request', `project.dir ${p.dir} does not exist`);
    }
    if (!this.projectRoots.some((root) => isInside(root, real))) {
      throw new ServiceError(403, 'forbidden_project', `project.dir ${p.dir} is outside the folders this service may build (${this.projectRoots.join(', ') || 'none: send inline files'})`);
    }
    return { project: { dir: real }, projectKey: real };
  }

  /**
   * Throws 503 `closing` or 429 `queue_full` when a job could not be taken now: the HTTP API asks
   * this before it reads a request body (docs/build-service-api.md), submit() asks it again.
   */
  checkCapacity(): void {
    if (this.closed) throw new ServiceError(503, 'closing', 'the build service is shutting down');
    if (this.running.size + this.waiting.length >= this.concurrency + this.queueSize) {
      throw new ServiceError(429, 'queue_full', `queue full: ${this.running.size} running, ${this.waiting.length} waiting (max ${this.concurrency} + ${this.queueSize}); retry later`);
    }
  }

  /** Submits a job: 400/403 bad request, 429 queue full, 503 sandbox unavailable. */
  /**
   * Queues a job. `owner`: who may list it (GET /api/jobs): a digest of the client's
   * X-Contract-Client key, or undefined (listed to nobody; its id is its only handle).
   */
  async submit(body: unknown, owner?: string): Promise<Job> {
    this.checkCapacity();
    const { request, sandbox: choice } = this.parseRequest(body);
    let resolved;
    let probeMs = 0;
    try {
      const tp = Date.now();
      resolved = await this.sandboxes.resolve(choice);
      probeMs = Date.now() - tp;
    } catch (e) {
      if (e instanceof SandboxUnavailableError) throw new ServiceError(503, 'sandbox_unavailable', e.message);
      throw e;
    }
    // re-check after the (async) probe: other submissions may have filled the queue meanwhile
    if (this.running.size + this.waiting.length >= this.concurrency + this.queueSize) {
      throw new ServiceError(429, 'queue_full', `queue full: ${this.running.size} running, ${this.waiting.length} waiting; retry later`);
    }
    // the id is the job's capability (status, log, events, artifacts, cancel): 128 random bits
    const id = `j-${randomBytes(16).toString('hex')}`;
    const job = new Job(id, request, resolved.sandbox.name);
    job.owner = owner;
    job.warnings.push(...resolved.warnings);
    // a run shortened to fit its run time limit is not a full run: said where a client reads (docs/build-service-api.md)
    const capped = request.action === 'run' ? durationCapMessage(request) : null;
    if (capped) job.warnings.push(capped);
    job.sandboxNote = resolved.note;
    job.sandboxProbeMs = probeMs;
    this.jobs.set(id, job);
    this.evictOld();
    for (const listener of this.submittedListeners) {
      try {
        listener(job);
      } catch (e) {
        this.log(`a listener of submitted jobs failed on ${job.id}: ${e instanceof Error ? e.message : String(e)}`);
      }
    }
    const start = (): void => {
      this.running.add(job);
      void job
        .execute({
          sandbox: resolved.sandbox,
          sandboxNote: resolved.note,
          runtime: this.runtime,
          generated: this.generated,
          acquireWorkspace: (j, hooks) => {
            // the host sandboxes' disk bound is a tmpfs work dir; docker bounds its own volume
            const disk = resolved.sandbox.name === 'docker' ? undefined : workDiskBytes(j.request.limits);
            return j.request.projectKey
              ? this.workspaces.acquireForProject(j.request.projectKey, resolved.sandbox.name as SandboxName, disk, hooks)
              : this.workspaces.acquireFresh(j.id, disk);
          },
        })
        // last resort (execute() handles its own faults): one job's exception never reaches the
        // process (an unhandled rejection would end the service and every other job)
        .catch((e: unknown) => {
          this.log(`internal error in job ${job.id}: ${e instanceof Error ? e.message : String(e)}`);
          job.finishUnstarted(`internal error: ${e instanceof Error ? e.message : String(e)}`, 'failed');
        })
        .finally(() => {
          this.running.delete(job);
          this.pump();
        });
    };
    if (this.running.size < this.concurrency) start();
    else this.waiting.push({ job, start });
    return job;
  }

  private pump(): void {
    while (!this.closed && this.running.size < this.concurrency && this.waiting.length) this.waiting.shift()!.start();
  }

  private evictOld(): void {
    const finished = [...this.jobs.values()].filter((j) => j.isDone);
    const excess = this.jobs.size - this.keepJobs;
    for (const j of finished.slice(0, Math.max(0, excess))) this.jobs.delete(j.id);
    // the trace records of ended jobs are the bulk of what a kept job holds: only the newest
    // ended ones keep them for replay (docs/build-service-api.md "Trace channel")
    for (const j of olderThanNewest(finished.filter((f) => this.jobs.has(f.id)), SERVICE_BOUNDS.traceReplayEndedJobs)) j.events.dropTrace();
  }

  /** Cancels a job (queued: removed at once; running: stopped within 2 s). */
  async cancel(id: string): Promise<Job | undefined> {
    const job = this.jobs.get(id);
    if (!job) return undefined;
    const i = this.waiting.findIndex((w) => w.job === job);
    if (i >= 0) {
      this.waiting.splice(i, 1);
      job.finishUnstarted('cancelled', 'cancelled');
      return job;
    }
    await job.cancel().catch(() => {});
    return job;
  }

  /** Cancels every job, waits for them to release their resources, removes all work dirs. */
  async close(): Promise<void> {
    this.closed = true;
    for (const w of this.waiting.splice(0)) w.job.finishUnstarted('cancelled: service closing', 'cancelled');
    const running = [...this.running];
    await Promise.all(running.map((j) => j.cancel()));
    await Promise.all(running.map((j) => j.finished));
    // a runtime build a cancelled job left going (job.ts): stopped before its folder is removed
    await this.runtime.close();
    await this.workspaces.removeAll();
    await this.startupSweep;
    for (const sandbox of Object.values(this.sandboxes.sandboxes)) await sandbox.close?.();
    if (this.ownsCacheDir) await removeTreeNoFollow(this.cacheDir);
    else {
      // only this service's folder: another service may share the cache folder (and its ws/)
      await removeTreeNoFollow(serviceFolder(join(this.cacheDir, 'ws')));
      await fsp.rmdir(join(this.cacheDir, 'ws')).catch(() => {});
    }
  }
}

/** The items of `list` (oldest first) but its `keep` newest: the ended jobs whose trace records are let go. */
export function olderThanNewest<T>(list: readonly T[], keep: number): T[] {
  return list.slice(0, Math.max(0, list.length - keep));
}
