/**
 * Memory and process limits in Docker end the job as in bwrap (docs/sandbox.md "Memory and process
 * limits in Docker", docker-cgroup.ts): a program that forks past the pids limit and hides every
 * failure, and one whose child is OOM-killed while the program goes on, are both stopped at the hit
 * with `killed: ...` and `limitHit` — not at the end of the run, not as a success. Read from the
 * container's cgroup (this host's cgroup v1), and the memory kill also from the engine's oom events
 * alone (`limitWatch: 'engine'`, what a remote engine gives), and the hidden forks from the engine's
 * process count alone. Starts dockerd and bootstraps the
 * image when needed, or says SKIPPED loudly with the reason.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { createBuildServer, type BuildServer } from '../server.js';
import { makeProject } from '../test-support/c-projects.js';
import { getJob, postJob, readEvents } from '../test-support/client.js';
import { dockerUp } from '../test-support/docker-env.js';

const HEAD = '#define _GNU_SOURCE\n#include <stdio.h>\n#include <stdlib.h>\n#include <string.h>\n#include <unistd.h>\n#include <sys/wait.h>\n';

/** Forks 64 sleeping children, hides every refused fork, then lives on for 20 s. */
const silentForks = `${HEAD}
int main(void) {
  int made = 0, refused = 0;
  for (int i = 0; i < 64; i++) {
    pid_t p = fork();
    if (p == 0) { sleep(30); _exit(0); }
    if (p > 0) made++; else refused++;
  }
  printf("children: %d made, %d refused\\n", made, refused); fflush(stdout);
  sleep(20);
  return 0;
}
`;

/** A child allocates until the kernel kills it; the program goes on for 20 s (a module OOM-killed in a run that continues). */
const childOutOfMemory = `${HEAD}
int main(void) {
  pid_t p = fork();
  if (p == 0) {
    for (;;) { char *m = malloc(1 << 20); if (!m) _exit(3); memset(m, 1, 1 << 20); }
  }
  int st = 0;
  waitpid(p, &st, 0);
  printf("child ended, signal %d\\n", WIFSIGNALED(st) ? WTERMSIG(st) : 0); fflush(stdout);
  sleep(20);
  return 0;
}
`;

/** A child writes a file in the job's /tmp (a tmpfs), 1 MiB per 20 ms, until the kernel kills it; the program goes on for 20 s (a run's logs filling its tmpfs). */
const childFillsTmpfs = `${HEAD}
int main(void) {
  pid_t p = fork();
  if (p == 0) {
    /* the child is the one the kernel kills (a process may raise its own score): were it the parent,
       the container's init, the container would end and its tmpfs go with it before it is read */
    FILE *adj = fopen("/proc/self/oom_score_adj", "w");
    if (adj) { fputs("1000", adj); fclose(adj); }
    static char block[1 << 20];
    memset(block, 1, sizeof block);
    FILE *f = fopen("/tmp/fill", "w");
    if (!f) _exit(3);
    for (;;) {
      if (fwrite(block, 1, sizeof block, f) != sizeof block || fflush(f) != 0) _exit(4);
      usleep(20000);
    }
  }
  int st = 0;
  waitpid(p, &st, 0);
  printf("child ended, signal %d\\n", WIFSIGNALED(st) ? WTERMSIG(st) : 0); fflush(stdout);
  sleep(20);
  return 0;
}
`;

const env = dockerUp();
const servers: BuildServer[] = [];
let cacheDir: string;

async function serve(docker: Record<string, unknown> = {}): Promise<string> {
  const server = createBuildServer({ token: false, port: 0, concurrency: 2, cacheDir, sandbox: 'docker', docker, log: () => {} });
  servers.push(server);
  return (await server.listen()).url;
}

async function run(url: string, main: string, limits: Record<string, number>): Promise<Record<string, any>> {
  const r = await postJob(url, { action: 'run', kind: 'make', project: { files: makeProject(main) }, limits });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  await readEvents(url, r.json.id as string);
  return getJob(url, r.json.id as string);
}

if (env.available) {
  let cgroupUrl: string;
  let engineUrl: string;
  beforeAll(async () => {
    cacheDir = mkdtempSync(join(tmpdir(), 'contract-cache-'));
    cgroupUrl = await serve();
    engineUrl = await serve({ limitWatch: 'engine' });
  });

  afterAll(async () => {
    for (const s of servers) await s.close();
    rmSync(cacheDir, { recursive: true, force: true });
    env.stop();
  });

  describe('docker: limit hits end the job at once, as in bwrap', () => {
    /** A job of silentForks at `processes: 24`: stopped at the hit (the program would have lived 20 s more), the forking program named. */
    const stoppedByProcessLimit = async (url: string): Promise<void> => {
      const job = await run(url, silentForks, { processes: 24 });
      expect(job.status).toBe('failed');
      expect(job.result.step).toBe('run');
      expect(job.result.message).toBe('killed: process limit 24');
      expect(job.result.limitHit).toMatchObject({ name: 'processes', value: 24, unit: 'count', mechanism: 'docker', module: 'prog' });
      expect(job.result.durations_ms.run).toBeLessThan(10_000);
    };

    test('a memory limit under the minimum (1 MiB; the engine takes 6 MiB at least) is refused at submit, 400, naming the minimum', async () => {
      const r = await postJob(cgroupUrl, { action: 'run', kind: 'make', project: { files: makeProject(silentForks) }, limits: { memoryMiB: 1 } });
      expect(r.status).toBe(400);
      expect(r.json.error).toMatch(/^limit memoryMiB must be at least 32 MiB/);
    });

    test('forks refused by the pids limit, every failure hidden: killed: process limit, at the hit', async () => {
      await stoppedByProcessLimit(cgroupUrl);
    });

    test("a child OOM-killed while the program goes on: the whole job is killed: memory limit, at the kill", async () => {
      const job = await run(cgroupUrl, childOutOfMemory, { memoryMiB: 96 });
      expect(job.status).toBe('failed');
      expect(job.result.step).toBe('run');
      expect(job.result.message).toBe('killed: memory limit 96 MiB');
      expect(job.result.limitHit).toMatchObject({ name: 'memory', value: 96 * 1024 * 1024, unit: 'bytes', mechanism: 'docker' });
      expect(job.result.durations_ms.run).toBeLessThan(10_000);
    });

    /** A job of childFillsTmpfs at `memoryMiB: 64` (its /tmp larger): the message says how much of the limit its tmpfs files held, as bwrap's does. */
    const stoppedByTmpfsFiles = async (url: string): Promise<void> => {
      const job = await run(url, childFillsTmpfs, { memoryMiB: 64, tmpMiB: 256 });
      expect(job.status).toBe('failed');
      expect(job.result.message).toMatch(/^killed: memory limit 64 MiB: [\d.]+ MiB of it were the job's files in its tmpfs mounts \(the work dir, \/tmp, \/dev\/shm\), which no kill frees/);
      expect(job.result.limitHit).toMatchObject({ name: 'memory', value: 64 * 1024 * 1024, unit: 'bytes', mechanism: 'docker' });
      expect(job.result.limitHit.memoryFilesBytes).toBeGreaterThan(40 * 1024 * 1024);
      expect(job.result.durations_ms.run).toBeLessThan(10_000);
    };

    test('a child filling the job\'s tmpfs /tmp up to the memory limit: the message says what its files held (from the container\'s cgroup)', async () => {
      await stoppedByTmpfsFiles(cgroupUrl);
    });

    test("without the cgroup (limitWatch: 'engine', as a remote engine): what the tmpfs files held, from the engine's stats", async () => {
      await stoppedByTmpfsFiles(engineUrl);
    });

    test("without the cgroup (limitWatch: 'engine', as a remote engine): forks refused and hidden are seen from the engine's process count, at the hit, the forking program named from the engine's process list", async () => {
      await stoppedByProcessLimit(engineUrl);
    });

    test("without the cgroup (limitWatch: 'engine', as a remote engine): the engine's oom event ends the job at the kill", async () => {
      const job = await run(engineUrl, childOutOfMemory, { memoryMiB: 96 });
      expect(job.status).toBe('failed');
      expect(job.result.message).toBe('killed: memory limit 96 MiB');
      expect(job.result.limitHit).toMatchObject({ name: 'memory', value: 96 * 1024 * 1024, unit: 'bytes', mechanism: 'docker' });
      expect(job.result.durations_ms.run).toBeLessThan(10_000);
    });
  });
} else {
  describe('docker limits', () => {
    test.skip(`SKIPPED: ${env.reason}`, () => {});
  });
}
