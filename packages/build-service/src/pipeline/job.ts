/**
 * One job: prepare -> build -> run (run only for action "run"), each sandboxed step with its wall
 * time limit, output caps and live events; cancel stops everything within CANCEL_DEADLINE_MS.
 */
import { posix } from 'node:path';
import type { Readable } from 'node:stream';
import type { LimitHit, Limits } from '../limits.js';
import { describeLimitHit, formatBytes } from '../limits.js';
import type { Mechanisms, Sandbox, SandboxProcess } from '../sandbox/types.js';
import { LineSplitter } from '../util/line-splitter.js';
import { collectRunArtifacts, hostWorkDirReader, type Artifact, type RunArtifacts } from './artifacts.js';
import type { CactalProblem } from './cactal-adapter.js';
import type { GccDiagnostic } from './gcc-diagnostics.js';
import { JobEvents, type JobStatus, type JobStep, type StreamName } from './job-events.js';
import { BuildOutputRouter, routeRunLine } from './output-router.js';
import { makeDir, prepareWorkspace, treeRoot, type ProjectKind, type ProjectSource } from './prepare.js';
import type { RuntimeCache } from './runtime-cache.js';
import type { Workspace } from './workspaces.js';

export interface JobRequest {
  action: 'build' | 'run';
  project: ProjectSource;
  /** Real path of project.dir (workspace reuse key), null for inline files. */
  projectKey: string | null;
  kind: ProjectKind;
  start?: string;
  duration?: number;
  /** CPU list every module is pinned to (`make run CPUS=…`, contract-launch --cpus). */
  cpus?: string;
  limits: Limits;
}

export interface JobResult {
  ok: boolean;
  step: JobStep;
  exitCode: number | null;
  signal: string | null;
  message: string;
  limitHit: LimitHit | null;
  truncated: { stdout: boolean; stderr: boolean };
  durations_ms: Partial<Record<JobStep, number>>;
  mechanisms: Mechanisms | null;
}

export interface JobContext {
  sandbox: Sandbox;
  sandboxNote: string;
  acquireWorkspace(job: Job): Promise<Workspace>;
  runtime: RuntimeCache | null;
}

const MAX_DIAGNOSTICS = 1000;

class Cancelled extends Error {}

export class Job {
  readonly events = new JobEvents();
  readonly createdAt = Date.now();
  startedAt: number | null = null;
  finishedAt: number | null = null;
  status: JobStatus = 'queued';
  result: JobResult | null = null;
  readonly diagnostics: GccDiagnostic[] = [];
  prepareDiagnostics: CactalProblem[] = [];
  readonly warnings: string[] = [];
  /** What sandbox was picked and why ("sandbox auto: picked bwrap (...)"). */
  sandboxNote = '';
  /** The run's CSV logs (and what was left out), collected from the sandbox once the run step ended. */
  artifacts: RunArtifacts | null = null;
  /** How long collecting them took (ms). */
  artifactsCollectMs: number | null = null;

  private current: SandboxProcess | null = null;
  private cancelRequested = false;
  private cancelSignal!: () => void;
  private readonly cancelled = new Promise<void>((r) => (this.cancelSignal = r));
  private readonly durations: Partial<Record<JobStep, number>> = {};
  private readonly truncated = { stdout: false, stderr: false };
  private mechanisms: Mechanisms | null = null;
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
    this.events.append({ type: 'line', step, source, stream, line });
  }

  private system(step: JobStep, line: string): void {
    this.line(step, 'service', 'system', line);
  }

  /** Ends a job that never started (cancelled while queued, or refused). */
  finishUnstarted(message: string, status: 'cancelled' | 'failed'): void {
    if (this.isDone) return;
    this.result = this.makeResult('prepare', false, null, null, message, null);
    this.finish(status);
    this.emitEnd();
    this.finishedSignal();
  }

  /** Cancels: kills the running sandbox (if any); the job ends with status "cancelled". */
  async cancel(): Promise<void> {
    if (this.isDone) return;
    this.cancelRequested = true;
    this.cancelSignal();
    if (this.current) await this.current.kill();
  }

  async execute(ctx: JobContext): Promise<void> {
    this.startedAt = Date.now();
    this.system('prepare', ctx.sandboxNote);
    for (const w of this.warnings) this.line('prepare', 'service', 'system', `warning: ${w}`);
    let ws: Workspace | null = null;
    let step: JobStep = 'prepare';
    try {
      this.setStatus('preparing', 'prepare');
      const t0 = Date.now();
      ws = await this.orCancel(ctx.acquireWorkspace(this));
      const prep = await this.orCancel(
        prepareWorkspace(ws, this.request.project, this.request.kind, (l) => this.system('prepare', l)),
      );
      this.prepareDiagnostics = prep.problems;
      // Cactal trees link against the runtime (Seam 3): prebuilt on the host for bwrap/none, in
      // the image for docker. Plain Makefile projects get the image's path and no bind.
      let runtimePath = '/opt/contract/runtime';
      let runtimeDir: string | undefined;
      if (prep.ok && this.request.kind === 'cactal' && ctx.sandbox.needsHostRuntime && ctx.runtime) {
        runtimeDir = await this.orCancel(ctx.runtime.ensure((l, s) => this.line('prepare', 'runtime', s, l)));
        runtimePath = ctx.sandbox.runtimePath(runtimeDir);
      }
      this.durations.prepare = Date.now() - t0;
      if (!prep.ok) {
        const n = prep.problems.filter((p) => p.severity === 'error').length;
        this.result = this.makeResult('prepare', false, null, null, `project has ${n} error(s)`, null);
        this.finish('failed');
        return;
      }

      step = 'build';
      this.setStatus('building', 'build');
      const work = ctx.sandbox.workPath(ws.workDir);
      const dir = makeDir(this.request.kind) || '.';
      const vars = [`CONTRACT_RUNTIME=${runtimePath}`];
      const router = new BuildOutputRouter({
        startDir: posix.join(work, makeDir(this.request.kind)),
        root: posix.join(work, treeRoot(this.request.kind)),
        regions: prep.regions,
      });
      const build = await this.runStep(ctx.sandbox, ws, runtimeDir, 'build', ['make', '-C', dir, 'all', ...vars, 'EXTRA_CFLAGS=-fdiagnostics-format=json'], this.request.limits.buildSeconds, (line, stream) => {
        const routed = router.route(line, stream);
        for (const d of routed.diagnostics) this.addDiagnostic(d);
        return routed.lines;
      });
      if (!build.ok) {
        const errors = this.diagnostics.filter((d) => d.severity === 'error').length;
        const message = build.message ?? (errors ? `build failed: ${errors} error(s) (make exit ${build.exitCode})` : `build failed (make exit ${build.exitCode})`);
        this.result = this.makeResult('build', false, build.exitCode, build.signal, message, build.limitHit);
        this.finish(this.cancelRequested ? 'cancelled' : 'failed');
        return;
      }
      if (this.request.action === 'build') {
        this.result = this.makeResult('build', true, 0, null, `build succeeded${this.diagnostics.length ? ` (${this.diagnostics.length} diagnostic(s))` : ''}`, null);
        this.finish('succeeded');
        return;
      }

      step = 'run';
      this.setStatus('running', 'run');
      const runVars = [...vars, `RUN_DIR=${posix.join(work, 'run')}`, `LOG_DIR=${posix.join(work, 'logs')}`];
      if (this.request.start !== undefined) runVars.push(`START=${this.request.start}`);
      if (this.request.duration !== undefined) runVars.push(`DURATION=${this.request.duration}`);
      if (this.request.cpus !== undefined) runVars.push(`CPUS=${this.request.cpus}`);
      const run = await this.runStep(ctx.sandbox, ws, runtimeDir, 'run', ['make', '-C', dir, 'run', ...runVars], this.request.limits.runSeconds, (line) => [routeRunLine(line)]);
      if (!this.cancelRequested) await this.collectArtifacts(ctx.sandbox, ws.workDir);
      if (!run.ok) {
        const message = run.message ?? `run failed (exit ${run.exitCode}${run.signal ? `, signal ${run.signal}` : ''})`;
        this.result = this.makeResult('run', false, run.exitCode, run.signal, message, run.limitHit);
        this.finish(this.cancelRequested ? 'cancelled' : 'failed');
        return;
      }
      this.result = this.makeResult('run', true, 0, null, 'run finished (exit 0)', null);
      this.finish('succeeded');
    } catch (e) {
      if (e instanceof Cancelled || this.cancelRequested) {
        this.result = this.makeResult(step, false, null, null, 'cancelled', null);
        this.finish('cancelled');
      } else {
        const msg = (e as Error).message;
        this.system(step, `error: ${msg}`);
        this.result = this.makeResult(step, false, null, null, `${step} failed: ${msg}`, null);
        this.finish('failed');
      }
    } finally {
      // the job's processes are all gone here (runStep awaits them), so the work dir is safe to touch
      if (ws) await ws.release().catch(() => {});
      if (!this.finalStatus) {
        this.result ??= this.makeResult(step, false, null, null, 'internal error: job ended without a result', null);
        this.finish('failed');
      }
      this.emitEnd();
      this.finishedSignal();
    }
  }

  /** Copies the run's logs out of the sandbox (its processes are gone); a failure is a warning line. */
  private async collectArtifacts(sandbox: Sandbox, workDir: string): Promise<void> {
    const t0 = Date.now();
    try {
      const reader = sandbox.readWorkDirs ? sandbox.readWorkDirs.bind(sandbox) : hostWorkDirReader;
      this.artifacts = await collectRunArtifacts(reader, workDir);
      this.artifactsCollectMs = Date.now() - t0;
      const a = this.artifacts;
      this.system('run', `collected ${a.files.length} artifact(s) in ${this.artifactsCollectMs} ms${a.skipped.length ? `; left out: ${a.skipped.map((s) => `${s.name} (${s.reason})`).join(', ')}` : ''}`);
    } catch (e) {
      this.system('run', `warning: the run's logs could not be collected: ${(e as Error).message.split('\n')[0]}`);
    }
  }

  /** One collected artifact by name (GET /api/jobs/:id/artifacts/<name>). */
  artifact(name: string): Artifact | undefined {
    return this.artifacts?.files.find((f) => f.name === name);
  }

  /** The JSON listing of the artifacts (no bytes), null when the job has not run. */
  artifactsJSON(): { files: { name: string; path: string; size: number }[]; skipped: RunArtifacts['skipped']; runDirLeftovers: string[]; collect_ms: number | null } | null {
    const a = this.artifacts;
    if (!a) return null;
    return { files: a.files.map(({ name, path, size }) => ({ name, path, size })), skipped: a.skipped, runDirLeftovers: a.runDirLeftovers, collect_ms: this.artifactsCollectMs };
  }

  private orCancel<T>(p: Promise<T>): Promise<T> {
    if (this.cancelRequested) return Promise.reject(new Cancelled());
    return Promise.race([p, this.cancelled.then(() => Promise.reject(new Cancelled()))]);
  }

  private addDiagnostic(d: GccDiagnostic): void {
    if (this.diagnostics.length >= MAX_DIAGNOSTICS) return;
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
  ): Promise<{ ok: boolean; exitCode: number | null; signal: string | null; limitHit: LimitHit | null; message: string | null }> {
    if (this.cancelRequested) throw new Cancelled();
    const t0 = Date.now();
    this.system(step, `$ ${argv.join(' ')}`);
    const proc = await sandbox.start({
      name: `${this.id}-${step}`,
      jobId: this.id,
      workDir: ws.workDir,
      cwd: '',
      argv,
      env: {},
      limits: this.request.limits,
      runtimeDir,
      owner: ws.owner,
    });
    this.current = proc;
    this.mechanisms = proc.mechanisms;
    const note = (proc as { noteLine?: (l: string) => void }).noteLine;
    let timeHit: LimitHit | null = null;
    const timer = setTimeout(() => {
      timeHit = {
        name: step === 'build' ? 'buildSeconds' : 'runSeconds',
        value: seconds,
        unit: 's',
        mechanism: 'service-timer',
      };
      this.events.append({ type: 'limit', limitHit: timeHit });
      void proc.kill();
    }, seconds * 1000);
    if (this.cancelRequested) void proc.kill();
    const pump = (stream: Readable, name: 'stdout' | 'stderr'): Promise<void> =>
      new Promise((resolve) => {
        const splitter = new LineSplitter({
          maxBytes: this.request.limits.outputBytesPerStream,
          onLine: (line) => {
            note?.(line);
            for (const r of route(line, name)) this.line(step, r.source, name, r.line);
          },
          onTruncated: () => {
            this.truncated[name] = true;
            this.system(step, `[output truncated: ${name} limit ${formatBytes(this.request.limits.outputBytesPerStream)} reached]`);
          },
        });
        stream.on('data', (chunk: Buffer) => splitter.push(chunk));
        stream.on('error', () => {});
        stream.on('close', () => {
          splitter.end();
          resolve();
        });
      });
    const pumps = Promise.all([pump(proc.stdout, 'stdout'), pump(proc.stderr, 'stderr')]);
    const exit = await proc.done;
    await Promise.race([pumps, new Promise((r) => setTimeout(r, 1500))]);
    clearTimeout(timer);
    this.current = null;
    this.durations[step] = Date.now() - t0;
    const limitHit: LimitHit | null = exit.limitHit ?? timeHit;
    if (exit.limitHit) this.events.append({ type: 'limit', limitHit: exit.limitHit });
    let message: string | null = null;
    if (this.cancelRequested) message = 'cancelled';
    else if (limitHit) message = `killed: ${describeLimitHit(limitHit)}`;
    const ok = !this.cancelRequested && !limitHit && exit.exitCode === 0;
    this.system(step, ok ? `${step} finished in ${this.durations[step]} ms` : `${step}: ${message ?? `exit ${exit.exitCode}${exit.signal ? ` (${exit.signal})` : ''}`}`);
    return { ok, exitCode: exit.exitCode, signal: exit.signal, limitHit, message };
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
