/**
 * A sandbox whose build and run steps are scripts of the test (no process, no sandbox): each step
 * writes the lines it is given when the test says, is asked to stop (terminateNamed) as the test
 * says, and ends when the test ends it. With scratchWorkspace (a real temporary folder), a Job runs
 * through prepare, build and run on it as in the service: the order of what the job logs against
 * what its sandbox prints is then the test's, not a race.
 */
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { PassThrough } from 'node:stream';
import { afterAll } from 'vitest';
import type { Mechanisms, Sandbox, SandboxCommand, SandboxExit, SandboxProcess } from '../sandbox/types.js';
import type { LimitHit } from '../limits.js';
import type { Workspace } from '../pipeline/workspaces.js';
import type { JobContext } from '../pipeline/job.js';
import type { RuntimeCache } from '../pipeline/runtime-cache.js';

const MECHANISMS: Mechanisms = { memory: 'none', processes: 'none', network: 'none', filesystem: 'none', user: 'test', time: 'service-timer', output: 'service-cap', disk: 'none' } as unknown as Mechanisms;

/** One step's process as the script drives it. */
export class ScriptedProcess implements SandboxProcess {
  readonly stdout = new PassThrough();
  readonly stderr = new PassThrough();
  readonly mechanisms = MECHANISMS;
  private ended!: (exit: SandboxExit) => void;
  readonly done = new Promise<SandboxExit>((r) => (this.ended = r));
  private exited = false;

  constructor(
    readonly command: SandboxCommand,
    private readonly onTerminate: (p: ScriptedProcess) => Promise<boolean>,
  ) {}

  /** Writes lines on a stream (`line\n` each). */
  write(stream: 'stdout' | 'stderr', ...lines: string[]): void {
    if (!this.exited) this[stream].write(lines.map((l) => `${l}\n`).join(''));
  }

  /** Ends the step's process: its streams close, then `done` resolves (with `limitHit`: as a sandbox that saw a limit stop it). */
  exit(exitCode: number | null = 0, signal: string | null = null, limitHit: LimitHit | null = null): void {
    if (this.exited) return;
    this.exited = true;
    this.stdout.end();
    this.stderr.end();
    // the streams' close events before done, as a real process's pipes
    setImmediate(() => this.ended({ exitCode, signal, limitHit }));
  }

  kill(): Promise<void> {
    this.exit(null, 'SIGKILL');
    return this.done.then(() => undefined);
  }

  terminateNamed(): Promise<boolean> {
    return this.exited ? Promise.resolve(false) : this.onTerminate(this);
  }

  noteLine(): void {}
}

export interface ScriptedStep {
  /** Called once the step's process started. */
  start(p: ScriptedProcess): void;
  /** The stop of a run asked (cancel, the run time limit): default, no launcher to ask (false). */
  terminate?(p: ScriptedProcess): Promise<boolean>;
}

/** A sandbox ("none" to the job: a host work dir; a host runtime with `needsHostRuntime`) running the steps' scripts. */
export function scriptedSandbox(steps: Partial<Record<'build' | 'run', ScriptedStep>>, { needsHostRuntime = false } = {}): Sandbox {
  return {
    name: 'none',
    needsHostRuntime,
    unenforced: [],
    workPath: (d) => d,
    runtimePath: (d) => d,
    probe: async () => ({ available: true, detail: 'scripted (test)' }),
    realtimeSupport: async () => ({ ok: false, reason: 'scripted (test)' }) as never,
    start: async (cmd) => {
      const step = steps[cmd.name.endsWith('-run') ? 'run' : 'build'] ?? { start: (p) => p.exit(0) };
      const p = new ScriptedProcess(cmd, step.terminate ?? (async () => false));
      setImmediate(() => step.start(p));
      return p;
    },
  };
}

/** A workspace in a temporary folder of its own (removed after the test file). */
export function scratchWorkspace(): Workspace {
  const root = mkdtempSync(join(tmpdir(), 'scripted-job-'));
  afterAll(() => rmSync(root, { recursive: true, force: true }));
  const workDir = join(root, 'work');
  mkdirSync(workDir);
  mkdirSync(join(root, 'stage'));
  return {
    root,
    stageDir: join(root, 'stage'),
    workDir,
    owner: { uid: process.getuid?.() ?? 0, gid: process.getgid?.() ?? 0 },
    reused: false,
    acceptedOutputs: null,
    reset: async () => {},
    release: async () => {},
  } as unknown as Workspace;
}

/** The context of a Job run in `sandbox` on `ws` (no runtime, as for a plain Makefile project, unless given). */
export function scriptedContext(sandbox: Sandbox, ws: Workspace, runtime: RuntimeCache | null = null): JobContext {
  return { sandbox, sandboxNote: 'sandbox: scripted (test)', runtime, acquireWorkspace: async () => ws };
}
