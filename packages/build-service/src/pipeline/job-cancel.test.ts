/**
 * A job cancelled while its project's workspace was being acquired (its lock taken, its folders
 * checked): the workspace is released once acquired. It was not (the job's `ws` was still unset
 * when the cancel came), and every later job of that project waited for ever in "preparing" (an
 * IDE test cancelled a job a moment after it began; the next Build & Run never left prepare).
 */
import { describe, expect, it } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import type { Sandbox } from '../sandbox/types.js';
import { Job, type JobContext } from './job.js';
import type { Workspace } from './workspaces.js';

describe('a job cancelled while its workspace is acquired', () => {
  it('releases the workspace once it is acquired, and ends cancelled at once', async () => {
    let released = 0;
    let acquired!: (w: Workspace) => void;
    const workspace = { root: '/nonexistent', stageDir: '/nonexistent/stage', workDir: '/nonexistent/work', owner: { uid: 0, gid: 0 }, reused: false, acceptedOutputs: null,
      reset: async () => {}, release: async () => void released++ } as unknown as Workspace;
    const ctx: JobContext = {
      sandbox: { name: 'none', needsHostRuntime: false } as unknown as Sandbox,
      sandboxNote: 'sandbox: none (test)',
      runtime: null,
      acquireWorkspace: () => new Promise<Workspace>((r) => (acquired = r)),
    };
    const job = new Job('j1', { action: 'build', project: { files: {} }, projectKey: '/p', kind: 'make', limits: { ...DEFAULT_LIMITS } }, 'none');
    const done = job.execute(ctx);
    await new Promise((r) => setTimeout(r, 20));
    await job.cancel();
    await done;
    expect(job.status).toBe('cancelled');
    expect(released).toBe(0); // not acquired yet
    acquired(workspace); // the acquire ends after the job did
    await new Promise((r) => setTimeout(r, 20));
    expect(released).toBe(1);
  });

  it('a cancel between two steps of the prepare (while earlier run logs are removed) rejects nothing unhandled, and the prepare it let go of is awaited before the workspace goes', async () => {
    // the cancel comes at the timing line of the workspace's acquire: the next await (the earlier
    // run's logs removed) is no cancellable step, so the prepare that follows is asked for after the
    // cancel — its rejection ('cancelled', or here a missing folder) was left unhandled, and Node
    // ended the whole service (a Stop 60 ms into a Build & Run)
    const order: string[] = [];
    const workspace = { root: '/nonexistent', stageDir: '/nonexistent/stage', workDir: '/nonexistent/work', owner: { uid: 0, gid: 0 }, reused: false, acceptedOutputs: null,
      reset: async () => {}, release: async () => void order.push('released') } as unknown as Workspace;
    const ctx: JobContext = {
      sandbox: { name: 'none', needsHostRuntime: false } as unknown as Sandbox,
      sandboxNote: 'sandbox: none (test)',
      runtime: null,
      acquireWorkspace: async () => workspace,
    };
    const unhandled: unknown[] = [];
    const seen = (e: unknown) => unhandled.push(e);
    process.on('unhandledRejection', seen);
    try {
      const job = new Job('j2', { action: 'build', project: { files: { 'a.contract': 'datatype T {int x = 1};' } }, projectKey: '/p', kind: 'cactal', limits: { ...DEFAULT_LIMITS } }, 'none');
      job.events.subscribe(0, (e) => {
        if (e.type === 'line' && e.line.startsWith('time: workspace (lock, checks)')) void job.cancel();
      });
      await job.execute(ctx);
      expect(job.status).toBe('cancelled');
      expect(order).toEqual(['released']);
      await new Promise((r) => setTimeout(r, 50));
      expect(unhandled).toEqual([]);
    } finally {
      process.off('unhandledRejection', seen);
    }
  });
});
