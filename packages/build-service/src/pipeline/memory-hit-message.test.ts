/**
 * A run the memory limit stopped, counted by the job's cgroup: when its files in tmpfs mounts (the
 * work dir's logs) held most of the memory, the job's end message says so and names them, instead of
 * leaving the kernel's choice of a process to kill to read as the cause.
 */
import { mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { DEFAULT_LIMITS, type LimitHit } from '../limits.js';
import { scratchWorkspace, scriptedContext, scriptedSandbox } from '../test-support/scripted-sandbox.js';
import { Job } from './job.js';

const MiB = 1024 * 1024;

async function runStoppedBy(hit: LimitHit): Promise<string | undefined> {
  const ws = scratchWorkspace();
  const job = new Job(`j-${hit.memoryFilesBytes ?? 0}`, { action: 'run', project: { files: { Makefile: 'all:\n\ttrue\nrun:\n\ttrue\n' } }, projectKey: null, kind: 'make', limits: { ...DEFAULT_LIMITS } } as never, 'none');
  // the run writes its log, then the kernel's OOM killer ends it
  const sandbox = scriptedSandbox({ run: { start: (p) => {
    mkdirSync(join(ws.workDir, 'logs'), { recursive: true });
    writeFileSync(join(ws.workDir, 'logs', 'ORD_7-Dec-2026-08h00m00s.csv'), Buffer.alloc(3 * MiB, 'x'));
    p.exit(null, 'SIGKILL', hit);
  } } });
  await job.execute(scriptedContext(sandbox, ws));
  return job.result?.message;
}

describe('the end message of a job the memory limit stopped', () => {
  const hit: LimitHit = { name: 'memory', value: 512 * MiB, unit: 'bytes', mechanism: 'cgroup-v1' };
  it('says how much of the memory the job\'s tmpfs files held, and which files the work dir held, when they held half of it or more', async () => {
    const message = await runStoppedBy({ ...hit, memoryFilesBytes: 480 * MiB });
    expect(message).toMatch(/^killed: memory limit 512 MiB: 480 MiB of it were the job's files in its tmpfs mounts \(the work dir, \/tmp, \/dev\/shm\), which no kill frees; the work dir held logs\/ORD_7-Dec-2026-08h00m00s\.csv 3 MiB/);
  });

  it('is the limit alone when the processes held it (a memory hog), or the cgroup did not say', async () => {
    expect(await runStoppedBy({ ...hit, memoryFilesBytes: 4 * MiB })).toBe('killed: memory limit 512 MiB');
    expect(await runStoppedBy(hit)).toBe('killed: memory limit 512 MiB');
  });
});
