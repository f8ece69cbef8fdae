/**
 * The private /tmp of a bwrap job is a tmpfs of `tmpMiB` (limits.ts): a job that fills it gets
 * ENOSPC at that size instead of taking the host's memory.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, expect, test } from 'vitest';
import { createBuildServer, type BuildServer } from './server.js';
import { makeProject } from './test-support/c-projects.js';
import { getJob, postJob, readEvents } from './test-support/client.js';

const fillTmp = `#include <errno.h>
#include <stdio.h>
#include <string.h>
static void fill(const char *path) {
  static char chunk[1024 * 1024];
  memset(chunk, 'x', sizeof chunk);
  FILE *f = fopen(path, "wb");
  if (!f) { printf("%s: open failed: %s\\n", path, strerror(errno)); return; }
  long mib = 0;
  while (mib < 1024 && fwrite(chunk, 1, sizeof chunk, f) == sizeof chunk && fflush(f) == 0) mib++;
  printf("%s: wrote %ld MiB: %s\\n", path, mib, mib < 1024 ? strerror(errno) : "no limit");
  fclose(f);
}
int main(void) {
  fill("/tmp/fill");
  fill("/dev/shm/fill");
  fill("/dev/fill");
  return 0;
}
`;

let server: BuildServer | undefined;
const cache = mkdtempSync(join(tmpdir(), 'contract-cache-'));
afterAll(async () => {
  await server?.close();
  rmSync(cache, { recursive: true, force: true });
});

test('a job filling /tmp or /dev/shm stops at tmpMiB with ENOSPC; /dev is read-only', async () => {
  server = createBuildServer({ token: false, port: 0, cacheDir: cache });
  const { url } = await server.listen();
  const posted = await postJob(url, { action: 'run', kind: 'make', sandbox: 'bwrap', project: { files: makeProject(fillTmp) }, limits: { tmpMiB: 8 } });
  expect(posted.status, JSON.stringify(posted.json)).toBe(201);
  const events = await readEvents(url, posted.json.id as string);
  const job = await getJob(url, posted.json.id as string);
  expect(job.status).toBe('succeeded');
  const text = events.map((e) => (e.type === 'line' ? e.line : '')).join('\n');
  for (const dir of ['/tmp', '/dev/shm']) {
    const m = new RegExp(`${dir}/fill: wrote (\\d+) MiB: (.*)`).exec(text);
    expect(m, text).not.toBeNull();
    expect(Number(m![1])).toBeLessThanOrEqual(8);
    expect(m![2]).toMatch(/No space left on device/);
  }
  // /dev itself is read-only (its tmpfs took writes bounded by the memory limit alone)
  expect(text).toContain('/dev/fill: open failed: Read-only file system');
});
