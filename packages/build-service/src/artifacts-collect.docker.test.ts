/**
 * A run's logs collected out of a Docker work volume whose logs/ a program filled (docs/build-service-api.md
 * "Artifacts"): a 1 TiB sparse file, a 300 MiB one and 1500 empty files beside the module's log.
 * The collector archived the whole logs/ when the 1024 entries find listed were small, read that
 * archive up to 2 GiB into memory (the service's RSS went from 227 MiB to 4.2 GiB), never reached
 * the module's log and ended the job `succeeded` with no artifact. Now only the files listed are
 * read, each by name and bounded, the runtime's logs first: the module's log is collected, the files
 * past the bounds are said (log-lost: the job fails), and the service's memory stays bounded.
 * Starts dockerd and bootstraps the image when needed, or says SKIPPED loudly with the reason.
 */
import { expect, test } from 'vitest';
import { useBuildServer } from './test-support/build-server.js';
import { makeProject } from './test-support/c-projects.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { dockerUp } from './test-support/docker-env.js';

const docker = dockerUp();
const served = useBuildServer({ concurrency: 1, sandbox: 'docker', log: () => {} }, { skip: !docker.available, afterClose: () => docker.stop(), timeoutMs: 300_000 });

const LOG = 'CTL_7-Dec-2026-03h00m00s.csv';
const HEADER = 'mono_ns,wall_time,module,event,a,b,c,detail';
const RECORD = '1000,2026-12-07T03:00:00.000000Z,CTL,module_started,,,0,pid=1';

/** The module's log first (as the runtime writes it at start), then what a hostile exec region plants beside it (`files` empty ones too). */
const flood = (files: number): string => String.raw`#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
int main(int argc, char **argv) {
  const char *dir = argc > 1 ? argv[1] : "logs";
  char p[4096];
  mkdir(dir, 0755);
  snprintf(p, sizeof p, "%s/${LOG}", dir);
  FILE *f = fopen(p, "w"); if (!f) return 1;
  fprintf(f, "${HEADER}\n${RECORD}\n"); fclose(f);
  snprintf(p, sizeof p, "cd %s && truncate -s 1T BIG_1.csv && truncate -s 300M MID_1.csv && i=0; while [ $i -lt ${files} ]; do : > F_$i.csv; i=$((i+1)); done; ls | wc -l", dir);
  return system(p) == 0 ? 0 : 2;
}
`;

const MiB = 1024 * 1024;

/** Runs the flood program (`files` empty files beside the sparse ones) to its end; the job, and the service's RSS before and at its peak. */
async function runWatchingMemory(files: number): Promise<{ job: Record<string, any>; before: number; peak: number }> {
  const project = makeProject(flood(files));
  project.Makefile = project.Makefile!.replace('\t./prog', '\t./prog $(LOG_DIR)');
  let peak = process.memoryUsage().rss;
  const before = peak;
  const sampler = setInterval(() => (peak = Math.max(peak, process.memoryUsage().rss)), 20);
  try {
    const r = await postJob(served.url, { action: 'run', kind: 'make', project: { files: project } });
    expect(r.status, JSON.stringify(r.json)).toBe(201);
    await readEvents(served.url, r.json.id as string);
    return { job: await getJob(served.url, r.json.id as string), before, peak };
  } finally {
    clearInterval(sampler);
  }
}

if (!docker.available) test.skip(`docker: SKIPPED — ${docker.reason}`, () => {});

test.skipIf(!docker.available)("logs/ flooded (1 TiB and 300 MiB sparse files, 1500 empty ones): the module's log is collected, the rest bounded and said, memory bounded", async () => {
  const { job, before, peak } = await runWatchingMemory(1500);
  console.info(`flooded logs/: service RSS ${Math.round(before / MiB)} MiB before, peak ${Math.round(peak / MiB)} MiB; collect ${job.artifacts.collect_ms} ms`);
  const a = job.artifacts as { files: { name: string; size: number; capped: string | null }[]; skipped: { name: string; reason: string; bound?: true }[]; collect_ms: number };
  // the module's log, whole, among the files taken
  expect(a.files.map((f) => f.name)).toContain(LOG);
  expect(await (await fetch(`${served.url}/api/jobs/${job.id}/artifacts/${LOG}`)).text()).toBe(`${HEADER}\n${RECORD}\n`);
  expect(a.files).toHaveLength(256);
  expect(a.skipped).toContainEqual({ name: 'logs/', reason: 'more than 1024 entries: the others were not looked at' });
  // the files past 256 are lost, said: the run is no success
  expect(a.skipped.filter((s) => s.bound).length).toBeGreaterThan(0);
  expect(job.status).toBe('failed');
  expect(job.result.issues.some((i: { kind: string }) => i.kind === 'log-lost')).toBe(true);
  // a read of the listed files only, each bounded (was 19-29 s and 4 GiB)
  expect(a.collect_ms).toBeLessThan(15_000);
  expect(peak - before).toBeLessThan(1024 * MiB);
}, 300_000);

test.skipIf(!docker.available)('logs/ with a 1 TiB and a 300 MiB sparse file beside the module\'s log: each read up to the file bound, cut, said; memory bounded', async () => {
  const { job, before, peak } = await runWatchingMemory(0);
  console.info(`big sparse logs: service RSS ${Math.round(before / MiB)} MiB before, peak ${Math.round(peak / MiB)} MiB; collect ${job.artifacts.collect_ms} ms`);
  const a = job.artifacts as { files: { name: string; size: number; capped: string | null }[]; collect_ms: number };
  expect(a.files.map((f) => f.name)).toEqual([LOG, 'BIG_1.csv', 'MID_1.csv']);
  expect(a.files[1]!.capped).toMatch(/^1099511627776 bytes: the first 0 kept \(the 268435456-byte file bound/);
  expect(a.files[2]!.capped).toMatch(/^314572800 bytes: the first 0 kept \(the 268435456-byte file bound/);
  expect(job.status).toBe('failed'); // logs not whole: log-capped
  // two reads of 256 MiB, one after the other, each into one buffer
  expect(peak - before).toBeLessThan(1024 * MiB);
}, 300_000);

test.skipIf(!docker.available)('a cancel while the two 256 MiB reads are under way ends the job cancelled within 2 s, the files not read said', async () => {
  const files = makeProject(flood(0));
  files.Makefile = files.Makefile!.replace('\t./prog', '\t./prog $(LOG_DIR)');
  const r = await postJob(served.url, { action: 'run', kind: 'make', project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const id = r.json.id as string;
  let cancelledAt = 0;
  let endedAt = 0;
  const after: string[] = []; // what the job said after the cancel, with the ms since it (the failure's message)
  await readEvents(served.url, id, (e) => {
    if (cancelledAt && e.type === 'line') after.push(`+${Date.now() - cancelledAt} ms ${(e as { line: string }).line}`);
    // the run's processes are gone: the collection starts (the listing, the module's log, then the
    // two 256 MiB reads, about 3 s together here): the cancel comes 300 ms into it. (It came 2 s after
    // the program's last line before: on a loaded host the container's end took longer than that,
    // the cancel came during the run, and the logs were collected whole, as they then must be.)
    if (e.type === 'line' && (e as { line: string }).line.startsWith('time: run (the sandboxed processes) ') && !cancelledAt) {
      setTimeout(() => {
        cancelledAt = Date.now();
        void fetch(`${served.url}/api/jobs/${id}`, { method: 'DELETE' });
      }, 300);
    }
    if (e.type === 'end') endedAt = Date.now();
  });
  const job = await getJob(served.url, id);
  expect(job.status).toBe('cancelled');
  expect(cancelledAt).toBeGreaterThan(0);
  expect(endedAt - cancelledAt, after.join('\n')).toBeLessThan(2000);
  const skipped = job.artifacts.skipped as { name: string; reason: string }[];
  expect(skipped.filter((s) => s.reason === 'not read: the job was cancelled during the collection').length, JSON.stringify(job.artifacts)).toBeGreaterThan(0);
}, 300_000);
