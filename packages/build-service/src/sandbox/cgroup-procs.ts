/**
 * What cgroup v1 (cgroup.ts) and v2 (cgroup-v2.ts) do alike with a job's cgroup folder: list its
 * processes, SIGKILL them until none is left, and remove the folder once the kernel has reaped them
 * (docs/sandbox.md "Memory and process limits in bwrap").
 */
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

/**
 * Bytes of tmpfs and shared-memory pages charged to a memory cgroup folder (its memory.stat: v1
 * `total_shmem`, its whole subtree, else `shmem`; v2 `shmem`); null when the file does not say. At
 * the memory limit they are the job's files in its tmpfs mounts (the work dir, /tmp, /dev/shm):
 * memory no kill frees.
 */
export async function readShmemBytes(memoryDir: string): Promise<number | null> {
  const text = await readSmallFile(join(memoryDir, 'memory.stat'), 16384);
  const m = /^total_shmem (\d{1,19})$/m.exec(text) ?? /^shmem (\d{1,19})$/m.exec(text);
  return m ? Number(m[1]) : null;
}

/**
 * The first `maxBytes` of a small cgroup file (a counter file: memory.events, pids.events, ...), ''
 * when it is gone or unreadable: one bounded read, whatever the file claims to hold.
 */
export async function readSmallFile(path: string, maxBytes = 4096): Promise<string> {
  let fh: fsp.FileHandle | undefined;
  try {
    fh = await fsp.open(path, 'r');
    const buf = Buffer.alloc(maxBytes);
    const { bytesRead } = await fh.read(buf, 0, maxBytes, 0);
    return buf.subarray(0, bytesRead).toString('utf8');
  } catch {
    return '';
  } finally {
    await fh?.close().catch(() => {});
  }
}

/** The pids in `<dir>/cgroup.procs` (none when the folder is gone or unreadable). */
export async function cgroupPids(dir: string): Promise<number[]> {
  const text = await fsp.readFile(join(dir, 'cgroup.procs'), 'utf8').catch(() => '');
  return text
    .split('\n')
    .filter(Boolean)
    .map(Number)
    .filter((n) => Number.isInteger(n) && n > 0);
}

/** SIGKILLs every process `pids()` lists until none is left; false when the deadline passed first. */
export async function killUntilEmpty(pids: () => Promise<number[]>, deadlineMs: number): Promise<boolean> {
  const end = Date.now() + deadlineMs;
  for (;;) {
    const left = await pids();
    if (left.length === 0) return true;
    for (const pid of left) {
      try {
        process.kill(pid, 'SIGKILL');
      } catch {
        /* already gone */
      }
    }
    if (Date.now() > end) return false;
    await sleep(20);
  }
}

/** Removes an emptied cgroup folder: rmdir fails for a short while until the killed processes are reaped. */
export async function removeCgroupDir(dir: string): Promise<void> {
  for (let i = 0; i < 50; i++) {
    try {
      await fsp.rmdir(dir);
      return;
    } catch (e) {
      if ((e as NodeJS.ErrnoException).code === 'ENOENT') return;
      await sleep(20);
    }
  }
}
