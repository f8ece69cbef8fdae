/**
 * What of a job's memory its files in tmpfs mounts hold (memory.stat `shmem`), read from a real
 * cgroup v1 job cgroup where this machine has one (root, v1 memory and pids writable): the service
 * says it at a memory limit hit, where the kernel's OOM killer kills processes that are not the cause.
 */
import { spawn } from 'node:child_process';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, test } from 'vitest';
import { DEFAULT_LIMITS, memoryBytes, memoryHeldByFiles } from '../limits.js';
import { readShmemBytes } from './cgroup-procs.js';
import { JobCgroup } from './cgroup.js';
import { startHostProcess } from './host-process.js';
import type { Mechanisms } from './types.js';

const MiB = 1024 * 1024;

describe('readShmemBytes', () => {
  test('v1 counts its subtree (total_shmem) before its own (shmem); v2 has shmem; none said: null', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'shmem-'));
    try {
      writeFileSync(join(dir, 'memory.stat'), 'cache 12763136\nrss 4096\nshmem 10465280\nmapped_file 0\ntotal_cache 20000000\ntotal_shmem 441409536\n');
      expect(await readShmemBytes(dir)).toBe(441409536);
      writeFileSync(join(dir, 'memory.stat'), 'anon 4096\nfile 20000000\nkernel 1\nshmem 10465280\nfile_mapped 0\n');
      expect(await readShmemBytes(dir)).toBe(10465280);
      writeFileSync(join(dir, 'memory.stat'), 'anon 4096\n');
      expect(await readShmemBytes(dir)).toBeNull();
      rmSync(join(dir, 'memory.stat'));
      expect(await readShmemBytes(dir)).toBeNull();
    } finally {
      rmSync(dir, { recursive: true, force: true });
    }
  });
});

describe.skipIf(JobCgroup.unavailableReason() !== null)('JobCgroup.memoryFiles on this machine\'s cgroup v1', () => {
  test('a file a process of the job writes to a tmpfs counts in it; the process\'s own memory does not', async () => {
    const cg = await JobCgroup.create(`shmem-test-${process.pid}`, 256 * MiB, 16);
    const shm = `/dev/shm/contract-shmem-test-${process.pid}`;
    try {
      const before = (await cg.memoryFiles()) ?? -1;
      expect(before).toBeGreaterThanOrEqual(0);
      expect(before).toBeLessThan(MiB);
      // the process joins the job's cgroup, then writes 24 MiB to a tmpfs file and exits
      const child = spawn('sh', ['-c', `read go; head -c ${24 * MiB} /dev/zero > ${shm}`], { stdio: ['pipe', 'ignore', 'inherit'] });
      for (const f of cg.procsFiles) writeFileSync(f, String(child.pid));
      child.stdin!.end('go\n');
      await new Promise((r) => child.on('exit', r));
      const after = (await cg.memoryFiles()) ?? -1;
      expect(after - before).toBeGreaterThanOrEqual(24 * MiB);
      expect(after - before).toBeLessThan(26 * MiB);
    } finally {
      rmSync(shm, { force: true });
      await cg.destroy();
    }
  });
});

describe.skipIf(JobCgroup.unavailableReason() !== null)('a job stopped by its memory limit with its memory in a tmpfs (this machine\'s cgroup v1)', () => {
  test('the limit hit comes from the cgroup\'s OOM kill count and says what the tmpfs files held', async () => {
    const limits = { ...DEFAULT_LIMITS, memoryMiB: 48 };
    const cg = await JobCgroup.create(`shmem-oom-test-${process.pid}`, memoryBytes(limits), 16);
    const shm = `/dev/shm/contract-shmem-oom-test-${process.pid}`;
    try {
      // as a run's logs filling its tmpfs work dir: the writer is killed, its file stays
      const proc = startHostProcess({
        argv: ['/bin/sh', '-c', `head -c ${200 * MiB} /dev/zero > ${shm}`],
        cwd: tmpdir(),
        env: { PATH: '/usr/bin:/bin' },
        limits,
        mechanisms: { memory: 'cgroup-v1' } as unknown as Mechanisms,
        cgroup: cg,
        guessLimitsFromOutput: false,
      });
      const exit = await proc.done;
      expect(exit.limitHit).toMatchObject({ name: 'memory', value: 48 * MiB, mechanism: 'cgroup-v1' });
      expect(exit.limitHit!.memoryFilesBytes).toBeGreaterThan(40 * MiB);
      expect(memoryHeldByFiles(exit.limitHit!)).toBe(exit.limitHit!.memoryFilesBytes);
    } finally {
      rmSync(shm, { force: true });
      await cg.destroy();
    }
  }, 20_000);
});
