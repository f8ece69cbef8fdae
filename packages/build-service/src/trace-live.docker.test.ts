/**
 * The live trace channel of the Docker sandbox (docs/build-service-api.md "Trace channel",
 * docs/sandbox.md "What the host reads while a job runs"): on a local engine the service reads
 * the run's logs at the work volume's Mountpoint, once a nonce written through the engine was read
 * back there. The report's tutorial streams its records while the run runs, in mono_ns order, the
 * same records as the collected logs; what the sandboxed program plants in its logs/ (a link to
 * /etc, a FIFO, odd names, a huge sparse file, logs/ swapped for a link mid-run) is never followed
 * and never blocks the job; when the Mountpoint is not the volume (what a remote engine, rootless
 * Docker or a VM give), the job says why in one line and runs as before. Stop mid-run asks the
 * launcher in the container to stop the architecture: every log ends with its exit record.
 * Starts dockerd and bootstraps the image when needed, or says SKIPPED loudly with the reason.
 */
import { createRequire } from 'node:module';
import { closeSync, constants, mkdtempSync, openSync, readdirSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test, vi } from 'vitest';
import { SANDBOX_UID } from '@contract-studio/conventions';
import { DEFAULT_LIMITS } from './limits.js';
import type { JobEvent, JobStatus, LineEvent, TraceEvent, TraceLine } from './pipeline/job-events.js';
import { DockerSandbox } from './sandbox/docker.js';
import { useBuildServer } from './test-support/build-server.js';
import { makeProject } from './test-support/c-projects.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { dockerUp } from './test-support/docker-env.js';
import { tutorialFiles } from './test-support/tutorial.js';
import { CSV_HEADER, parseLogFile, parseRecordLine } from './trace/parse.js';

const docker = dockerUp();

const served = useBuildServer({ concurrency: 1, sandbox: 'docker', log: () => {} }, { skip: !docker.available, afterClose: () => docker.stop(), timeoutMs: 300_000 });

afterAll(() => {
  vi.restoreAllMocks();
});

const traceLines = (events: JobEvent[]): TraceLine[] => events.filter((e): e is TraceEvent => e.type === 'trace').flatMap((e) => e.records);
const monoOf = (l: TraceLine): bigint => BigInt(/^(\d+),/.exec(l.text)![1]!);
const pct = (xs: number[], p: number): number => {
  const s = [...xs].sort((a, b) => a - b);
  return s[Math.min(s.length - 1, Math.floor((p / 100) * s.length))]!;
};

/** The dockerode Volume class the sandbox uses (loaded as it loads dockerode). */
const Volume = createRequire(import.meta.url)('dockerode/lib/volume') as { prototype: { inspect: (...a: unknown[]) => Promise<Record<string, unknown>> } };

/** Makes the engine's volume inspect name another (empty) folder, as a remote engine's path would be here. */
function mountpointElsewhere(): { dir: string; restore: () => void } {
  const dir = mkdtempSync(join(tmpdir(), 'not-the-volume-'));
  const original = Volume.prototype.inspect;
  const spy = vi.spyOn(Volume.prototype, 'inspect').mockImplementation(async function (this: unknown, ...args: unknown[]) {
    const info = await original.apply(this, args);
    return { ...info, Mountpoint: dir };
  });
  return { dir, restore: () => spy.mockRestore() };
}

async function runJob(body: Record<string, unknown>, onEvent?: (e: JobEvent) => void): Promise<{ job: Record<string, any>; events: JobEvent[]; lines: string[] }> {
  const r = await postJob(served.url, body);
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const events = await readEvents(served.url, r.json.id as string, onEvent);
  const job = await getJob(served.url, r.json.id as string);
  return { job, events, lines: events.filter((e): e is LineEvent => e.type === 'line').map((e) => e.line) };
}

async function artifactText(id: string, name: string): Promise<string> {
  return (await fetch(`${served.url}/api/jobs/${id}/artifacts/${encodeURIComponent(name)}`)).text();
}

if (!docker.available) test.skip(`docker: SKIPPED — ${docker.reason}`, () => {});

/** A job's collected module logs (its CSV files), the launcher's own lines file among the artifacts too. */
function moduleLogs(artifacts: { files: { name: string }[] }): { files: { name: string }[] } {
  expect(artifacts.files.map((f) => f.name)).toContain('contract-launch.log');
  return { files: artifacts.files.filter((f) => f.name.endsWith('.csv')) };
}

describe.skipIf(!docker.available)('live trace in docker', () => {
  test('the tutorial: records arrive while the run runs, in mono_ns order, equal to the collected logs', async () => {
    const files = await tutorialFiles();
    let status: JobStatus = 'queued';
    const arrivals: { at: bigint; status: JobStatus; records: TraceLine[] }[] = [];
    const { job, events, lines } = await runJob({ action: 'run', duration: 4, project: { files } }, (e) => {
      if (e.type === 'status') status = e.status;
      if (e.type === 'trace') arrivals.push({ at: process.hrtime.bigint(), status, records: e.records });
    });
    expect(job.status, `${job.result?.message}\n${lines.slice(-20).join('\n')}`).toBe('succeeded');
    expect(job.sandbox).toBe('docker');
    expect(lines.filter((l) => l.startsWith('trace:'))).toEqual([]);

    // the trace came while the job was running, before the run step ended, the artifacts and the end
    const running = arrivals.filter((a) => a.status === 'running');
    expect(running.length).toBeGreaterThan(3);
    const kinds = events.map((e) => e.type);
    const runEnded = events.findIndex((e) => e.type === 'line' && /^run finished in/.test(e.line));
    expect(kinds.indexOf('trace')).toBeLessThan(runEnded);
    expect(kinds.slice(0, runEnded).filter((k) => k === 'trace').length).toBeGreaterThan(3);
    expect(kinds.lastIndexOf('trace')).toBeLessThan(events.findIndex((e) => e.type === 'line' && /^collected \d+ artifact/.test(e.line)));

    // per file: exactly the collected log's records, in file order
    const trace = traceLines(events);
    const listing = moduleLogs(job.artifacts as { files: { name: string }[] });
    expect(listing.files).toHaveLength(9);
    let total = 0;
    for (const f of listing.files) {
      const want = parseLogFile({ name: f.name, text: await artifactText(job.id, f.name) });
      const got = trace.filter((l) => l.file === f.name).map((l) => parseRecordLine(l.file, l.line, l.text));
      expect(got, f.name).toEqual(want);
      total += want.length;
    }
    expect(trace).toHaveLength(total);
    expect(total).toBeGreaterThan(100);

    // mono_ns never goes back across the stream
    const monos = trace.map(monoOf);
    for (let i = 1; i < monos.length; i++) expect(monos[i]! >= monos[i - 1]!, `record ${i}: ${trace[i]!.text} after ${trace[i - 1]!.text}`).toBe(true);

    // the containers' CLOCK_MONOTONIC is this host's: every record was written before it arrived
    // (a clock of its own would put mono_ns anywhere), and the live ones within the run's seconds
    const latencyMs = running.flatMap((a) => a.records.map((l) => Number(a.at - monoOf(l)) / 1e6));
    for (const ms of latencyMs) expect(ms).toBeGreaterThanOrEqual(0);
    expect(pct(latencyMs, 50)).toBeLessThan(10_000);
    console.info(`docker live trace: ${latencyMs.length} records while running; write -> SSE client latency p50 ${pct(latencyMs, 50).toFixed(1)} ms, p99 ${pct(latencyMs, 99).toFixed(1)} ms`);
  }, 300_000);

  test('Stop mid-run: the launcher in the container is asked (SIGTERM from this host, the cancel queued as its reason) and stops the tutorial; every log ends with its exit record saying why', async () => {
    await stopMidRun(served.url);
  }, 300_000);

  test('the proof leaves nothing in the work tree, is kept per volume, and says why when the Mountpoint is not the volume', async () => {
    const sb = new DockerSandbox({ log: () => {} });
    const work = mkdtempSync(join(tmpdir(), 'contract-live-root-'));
    writeFileSync(join(work, 'a.txt'), 'a\n');
    const step = async (name: string, argv = ['true']): Promise<void> => {
      const proc = await sb.start({ name: `${name}-${process.pid}-${Date.now()}`, workDir: work, cwd: '', argv, env: {}, limits: DEFAULT_LIMITS });
      proc.stdout.resume();
      proc.stderr.resume();
      expect((await proc.done).exitCode).toBe(0);
    };
    try {
      expect(await sb.liveWorkRoot(work)).toEqual({ ok: false, reason: 'the job has no work volume yet' });
      await step('live-root');
      const before = await sb.workTreeDigest(work);
      expect(before).not.toBeNull();
      const t0 = process.hrtime.bigint();
      const live = await sb.liveWorkRoot(work);
      console.info(`docker volume proof (first call for a volume): ${Number(process.hrtime.bigint() - t0) / 1e6} ms`);
      expect(live).toEqual({ ok: true, root: expect.stringMatching(/^\/.+/) });
      if (!live.ok) return;
      expect(readdirSync(live.root)).toEqual(['a.txt']);
      expect(await sb.workTreeDigest(work)).toBe(before);
      expect(await sb.liveWorkRoot(work)).toBe(live); // kept: no second proof

      // a flush mark as a module makes it (its user, 0644): this service (root here) opens it for
      // writing too, as the tail does for the watched flush delay (trace-tail.ts openMark)
      await step('live-root-mark', ['sh', '-c', 'mkdir logs && head -c 16 /dev/zero > logs/M.csv.mark']);
      const mark = join(live.root, 'logs', 'M.csv.mark');
      expect(statSync(mark).uid).toBe(SANDBOX_UID);
      if (process.getuid?.() === 0) closeSync(openSync(mark, constants.O_RDWR | constants.O_NOFOLLOW | constants.O_NONBLOCK));

      // a new volume (the old one released), whose Mountpoint is some other folder: refused, and
      // the nonce is removed from the volume through the engine
      await sb.release(work);
      const elsewhere = mountpointElsewhere();
      try {
        await step('live-root-2');
        const again = await sb.workTreeDigest(work);
        const refused = await sb.liveWorkRoot(work);
        expect(refused).toEqual({ ok: false, reason: `the folder the engine names for the volume (${elsewhere.dir}) does not hold the nonce written into the volume through the engine (ENOENT): it is not the containers' volume` });
        expect(readdirSync(elsewhere.dir)).toEqual([]);
        expect(await sb.workTreeDigest(work)).toBe(again);
      } finally {
        elsewhere.restore();
        rmSync(elsewhere.dir, { recursive: true, force: true });
      }
    } finally {
      await sb.release(work);
      await sb.close();
      rmSync(work, { recursive: true, force: true });
    }
  }, 120_000);

  test('fallback: the Mountpoint is not the volume -> one line says why, the job still succeeds with its logs', async () => {
    const elsewhere = mountpointElsewhere();
    let result;
    try {
      result = await runJob({ action: 'run', kind: 'make', project: { files: loggerProject('plain') } });
    } finally {
      elsewhere.restore();
      rmSync(elsewhere.dir, { recursive: true, force: true });
    }
    const { job, events, lines } = result;
    expect(job.status, `${job.result?.message}\n${lines.slice(-20).join('\n')}`).toBe('succeeded');
    expect(lines.filter((l) => l.startsWith('trace:'))).toEqual([
      `trace: no live trace channel in the docker sandbox: the folder the engine names for the volume (${elsewhere.dir}) does not hold the nonce written into the volume through the engine (ENOENT): it is not the containers' volume; the records are in the collected logs`,
    ]);
    expect(traceLines(events)).toEqual([]);
    expect((job.artifacts as { files: { name: string }[] }).files.map((f) => f.name)).toEqual(['A.csv']);
    expect(parseLogFile({ name: 'A.csv', text: await artifactText(job.id, 'A.csv') }).length).toBeGreaterThan(50);
  }, 180_000);

  test('planted in logs/: a link to /etc/passwd, a FIFO, odd names, a 1 TiB sparse file: not followed, no hang, A.csv exactly', async () => {
    const t0 = Date.now();
    const { job, events, lines } = await runJob({ action: 'run', kind: 'make', project: { files: loggerProject('plant') } });
    // the program ran to its end; the sparse log is the run's one problem (a log cut at the file bound is not whole)
    expect(job.result?.exitCode, `${job.result?.message}\n${lines.slice(-20).join('\n')}`).toBe(0);
    expect(job.result?.message).toMatch(/^run finished with 1 problem\(s\): log H\.csv is not whole: 1099511627776 bytes: the first 0 kept/);
    const trace = traceLines(events);
    expect(trace.some((l) => /root:/.test(l.text))).toBe(false);
    expect(new Set(trace.map((l) => l.file))).toEqual(new Set(['A.csv', 'H.csv']));
    const want = parseLogFile({ name: 'A.csv', text: await artifactText(job.id, 'A.csv') });
    expect(trace.filter((l) => l.file === 'A.csv').map((l) => parseRecordLine(l.file, l.line, l.text))).toEqual(want);
    expect(want.length).toBeGreaterThan(50);
    // the sparse file is read only as far as the file bound (its size known first), never streamed whole
    const files = (job.artifacts as { files: { name: string; capped: string | null }[] }).files;
    expect(files.find((f) => f.name === 'H.csv')?.capped).toMatch(/^1099511627776 bytes: the first 0 kept \(the 268435456-byte file bound/);
    console.info(`planted logs/: job ended in ${Date.now() - t0} ms; ${trace.filter((l) => l.file === 'H.csv').length} record(s) from the sparse H.csv; lines: ${lines.filter((l) => l.startsWith('trace:')).join(' | ')}`);
  }, 300_000);

  test('logs/ a link to /etc from the start: not followed, one line; the job ends', async () => {
    const { job, events, lines } = await runJob({ action: 'run', kind: 'make', project: { files: loggerProject('etc') } });
    expect(job.status, job.result?.message).not.toBe('running');
    expect(traceLines(events)).toEqual([]);
    expect(lines.filter((l) => l.startsWith('trace:'))).toEqual([expect.stringMatching(/^trace: logs\/ is not a directory \((ELOOP|ENOTDIR)\): no live trace$/)]);
  }, 180_000);

  test('logs/ swapped for a link to /etc mid-run: the folder opened is read on, nothing of /etc', async () => {
    const { job, events, lines } = await runJob({ action: 'run', kind: 'make', project: { files: loggerProject('swap') } });
    expect(job.status, job.result?.message).not.toBe('running');
    const trace = traceLines(events);
    expect(trace.some((l) => /root:/.test(l.text))).toBe(false);
    expect(new Set(trace.map((l) => l.file))).toEqual(new Set(['A.csv']));
    // every record A.csv got, through the descriptor kept after the swap, came live
    const records = trace.map((l) => parseRecordLine(l.file, l.line, l.text));
    expect(records.length).toBe(200);
    expect(records.every((r) => r.kind === 'module_started')).toBe(true);
    expect(lines.some((l) => /logs\/ is not a directory/.test(l))).toBe(false);
  }, 180_000);
});

/**
 * A plain Makefile project whose program writes 200 records to $(LOG_DIR)/A.csv over about 2 s
 * with the host's clock (CLOCK_MONOTONIC), after planting what `mode` says:
 * plain: nothing; plant: X.csv a link to /etc/passwd, F.csv a FIFO, odd names, H.csv a 1 TiB
 * sparse file; etc: logs/ a link to /etc; swap: logs/ renamed and replaced by a link to /etc
 * after 100 records (the program goes on writing through its open file).
 */
function loggerProject(mode: 'plain' | 'plant' | 'etc' | 'swap'): Record<string, string> {
  const main = String.raw`#define _GNU_SOURCE
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
static const char *mode = "${mode}";
int main(int argc, char **argv) {
  const char *dir = argc > 1 ? argv[1] : "logs";
  char path[4096];
  if (!strcmp(mode, "etc")) { symlink("/etc", dir); }
  else mkdir(dir, 0755);
  if (!strcmp(mode, "plant")) {
    snprintf(path, sizeof path, "%s/X.csv", dir); symlink("/etc/passwd", path);
    snprintf(path, sizeof path, "%s/F.csv", dir); mkfifo(path, 0644);
    snprintf(path, sizeof path, "%s/odd name.csv", dir); FILE *o = fopen(path, "w"); if (o) { fputs("${CSV_HEADER}\n1,2026-01-01T00:00:00Z,O,module_started,,,0,pid=1\n", o); fclose(o); }
    snprintf(path, sizeof path, "%s/nl\nname.csv", dir); o = fopen(path, "w"); if (o) { fputs("x\n", o); fclose(o); }
    snprintf(path, sizeof path, "%s/H.csv", dir); int h = open(path, O_WRONLY | O_CREAT, 0644); if (h >= 0) { ftruncate(h, 1LL << 40); close(h); }
  }
  snprintf(path, sizeof path, "%s/A.csv", dir);
  FILE *f = fopen(path, "w");
  if (!f) { if (!strcmp(mode, "etc")) return 0; perror(path); return 1; }
  fprintf(f, "${CSV_HEADER}\n"); fflush(f);
  for (int i = 0; i < 200; i++) {
    struct timespec m, w; clock_gettime(CLOCK_MONOTONIC, &m); clock_gettime(CLOCK_REALTIME, &w);
    struct tm tm; gmtime_r(&w.tv_sec, &tm); char ts[32]; strftime(ts, sizeof ts, "%Y-%m-%dT%H:%M:%S", &tm);
    fprintf(f, "%lld,%s.%06ldZ,A,module_started,,,0,pid=%d seq=%d\n", (long long)m.tv_sec * 1000000000LL + m.tv_nsec, ts, w.tv_nsec / 1000, (int)getpid(), i);
    fflush(f);
    if (i == 100 && !strcmp(mode, "swap")) {
      char old[4096]; snprintf(old, sizeof old, "%s.old", dir);
      rename(dir, old); symlink("/etc", dir);
    }
    usleep(10000);
  }
  fclose(f);
  return 0;
}
`;
  const files = makeProject(main);
  files.Makefile = files.Makefile!.replace('\t./prog', '\t./prog $(LOG_DIR)');
  return files;
}

describe.skipIf(!docker.available)("live trace in docker, the container's cgroup not read here (limitWatch: 'engine', as a remote engine)", () => {
  const remote = useBuildServer({ concurrency: 1, sandbox: 'docker', docker: { limitWatch: 'engine' }, log: () => {} }, { skip: !docker.available, timeoutMs: 300_000 });

  test('Stop mid-run: the launcher is asked inside the container (contract-launch --term-why: the image has no kill that queues), and says why as from the host', async () => {
    await stopMidRun(remote.url);
  }, 300_000);
});

/**
 * The tutorial stopped (DELETE) half a second after SUP's rule SECOND became active: cancelled, every
 * module stopped cleanly, the launcher says the cancel's reason, and every log ends with its exit
 * record after a KILL saying it (whether the service signals from this host or inside the container).
 */
async function stopMidRun(url: string): Promise<void> {
  const files = await tutorialFiles();
  const r = await postJob(url, { action: 'run', duration: 60, project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const id = r.json.id as string;
  let asked = false;
  const events = await readEvents(url, id, (e) => {
    if (asked || e.type !== 'trace' || !e.records.some((l) => l.text.includes(',SUP,sup_rule,') && l.text.includes('action.SECOND active'))) return;
    asked = true;
    setTimeout(() => void fetch(`${url}/api/jobs/${id}`, { method: 'DELETE' }), 500);
  });
  const job = await getJob(url, id);
  const lines = events.filter((e): e is LineEvent => e.type === 'line').map((e) => e.line);
  expect(job.status, lines.slice(-20).join('\n')).toBe('cancelled');
  expect(lines.some((l) => l.startsWith('stopping the architecture as at the end of a run'))).toBe(true);
  expect(lines, lines.slice(-30).join('\n')).toContain('all modules stopped cleanly');
  // the cancel queued as the stop's reason
  expect(lines).toContain('stopping: the job was cancelled');
  const trace = traceLines(events);
  const listing = moduleLogs(job.artifacts as { files: { name: string }[] });
  expect(listing.files).toHaveLength(9);
  for (const f of listing.files) {
    const text = await (await fetch(`${url}/api/jobs/${id}/artifacts/${encodeURIComponent(f.name)}`)).text();
    const want = parseLogFile({ name: f.name, text });
    expect(want.at(-1)?.kind, f.name).toBe('module_exit');
    expect(text, f.name).toContain(',request_received,contract-launch,,22,KILL (the job was cancelled)\n');
    expect(trace.filter((l) => l.file === f.name).map((l) => parseRecordLine(l.file, l.line, l.text)), f.name).toEqual(want);
  }
}
