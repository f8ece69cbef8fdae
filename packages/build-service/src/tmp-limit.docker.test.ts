/**
 * /dev/shm in Docker is the size of the job's /tmp (`tmpMiB`), as in bwrap (docs/sandbox.md
 * "Limits"): it was Docker's default 64 MiB whatever tmpMiB said. Starts dockerd and bootstraps the
 * image when needed, or says SKIPPED loudly with the reason.
 */
import { expect, test } from 'vitest';
import { useBuildServer } from './test-support/build-server.js';
import { makeProject } from './test-support/c-projects.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { dockerUp } from './test-support/docker-env.js';

const docker = dockerUp();
const served = useBuildServer({ concurrency: 1, sandbox: 'docker', log: () => {} }, { skip: !docker.available, afterClose: () => docker.stop(), timeoutMs: 300_000 });

/** Prints the sizes of /tmp and /dev/shm (statvfs), in MiB. */
const sizes = `#include <stdio.h>
#include <sys/statvfs.h>
static long mib(const char *p) { struct statvfs s; return statvfs(p, &s) == 0 ? (long)((unsigned long long)s.f_blocks * s.f_frsize >> 20) : -1; }
int main(void) { printf("tmp %ld shm %ld\\n", mib("/tmp"), mib("/dev/shm")); return 0; }
`;

if (!docker.available) test.skip(`docker: SKIPPED — ${docker.reason}`, () => {});

test.skipIf(!docker.available)('/dev/shm follows tmpMiB, as /tmp does (not Docker\'s 64 MiB)', async () => {
  for (const tmpMiB of [32, 200]) {
    const r = await postJob(served.url, { action: 'run', kind: 'make', project: { files: makeProject(sizes) }, limits: { tmpMiB } });
    expect(r.status, JSON.stringify(r.json)).toBe(201);
    const events = await readEvents(served.url, r.json.id as string);
    const job = await getJob(served.url, r.json.id as string);
    expect(job.status, job.result?.message).toBe('succeeded');
    const lines = events.filter((e) => e.type === 'line').map((e) => (e as { line: string }).line);
    expect(lines).toContain(`tmp ${tmpMiB} shm ${tmpMiB}`);
  }
}, 300_000);
