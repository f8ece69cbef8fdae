/**
 * The work disk's inodes in Docker (docs/sandbox.md "The disk limit"): a program that creates empty
 * files in /work until `open` fails with ENOSPC (no byte used, every inode) is stopped as in bwrap,
 * `killed: disk limit N MiB (work dir)` with `limitHit` workDiskMiB. The volume's statfs was read
 * with `%f` (free blocks) where the free inodes are `%d`, and such a job ended `ok`, `limitHit: null`.
 * Starts dockerd and bootstraps the image when needed, or says SKIPPED loudly with the reason.
 */
import { expect, test } from 'vitest';
import { useBuildServer } from './test-support/build-server.js';
import { makeProject } from './test-support/c-projects.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { dockerUp } from './test-support/docker-env.js';

const docker = dockerUp();
const served = useBuildServer({ concurrency: 1, sandbox: 'docker', log: () => {} }, { skip: !docker.available, afterClose: () => docker.stop(), timeoutMs: 300_000 });

/** Empty files in the work dir until one cannot be created, then 20 s of sleep (the job should not last that long). */
const inodeFlood = `#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include <sys/stat.h>
int main(void) {
  mkdir("many", 0755);
  char p[64]; int n = 0;
  for (;; n++) {
    snprintf(p, sizeof p, "many/f%d", n);
    int fd = open(p, O_WRONLY | O_CREAT, 0644);
    if (fd < 0) { printf("open failed after %d files: %s\\n", n, strerror(errno)); break; }
    close(fd);
  }
  fflush(stdout);
  sleep(20);
  return 0;
}
`;

if (!docker.available) test.skip(`docker: SKIPPED — ${docker.reason}`, () => {});

test.skipIf(!docker.available)('out of inodes in /work (empty files until ENOSPC): killed: disk limit (work dir), as in bwrap', async () => {
  const r = await postJob(served.url, { action: 'run', kind: 'make', project: { files: makeProject(inodeFlood) }, limits: { workDiskMiB: 16 } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const events = await readEvents(served.url, r.json.id as string);
  const job = await getJob(served.url, r.json.id as string);
  const lines = events.filter((e) => e.type === 'line').map((e) => (e as { line: string }).line);
  expect(lines.some((l) => /^open failed after \d+ files: No space left on device$/.test(l)), lines.slice(-20).join('\n')).toBe(true);
  expect(job.status).toBe('failed');
  expect(job.result.limitHit).toMatchObject({ name: 'workDiskMiB', value: 16 * 1024 * 1024, unit: 'bytes', mechanism: 'docker-tmpfs-volume' });
  expect(job.result.message).toMatch(/^killed: disk limit 16 MiB \(work dir\)/);
  // stopped at the hit (the disk watch), not at the program's end 20 s later
  expect(job.result.durations_ms.run).toBeLessThan(15_000);
}, 300_000);
