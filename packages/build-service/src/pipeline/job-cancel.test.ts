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
});
