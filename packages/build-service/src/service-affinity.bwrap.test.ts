/**
 * A run pinned to CPUs (`cpus`) has them to itself: while it goes on, the service's threads keep
 * off them (pipeline/service-affinity.ts), and take back their CPUs when it has ended. The service
 * runs in this process (useBuildServer), so its mask is this process's.
 */
import { spawnSync } from 'node:child_process';
import { availableParallelism } from 'node:os';
import { describe, expect, test } from 'vitest';
import { ownCpus, parseCpuList } from './pipeline/service-affinity.js';
import { useBuildServer } from './test-support/build-server.js';
import { makeProject } from './test-support/c-projects.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import type { LineEvent } from './pipeline/job-events.js';

const served = useBuildServer({ concurrency: 2, queueSize: 2, sandbox: 'bwrap' }, { snapshotRuntime: false });
const cpus = ownCpus() ?? [];
const taskset = spawnSync('taskset', ['--version']).status === 0;
const why = cpus.length < 2 ? `one CPU here (${cpus.join(',')})` : !taskset ? 'no taskset here' : '';

/** A program that runs about 1.5 s. */
const sleeper = makeProject('#include <time.h>\nint main(void) { struct timespec t = { 1, 500000000 }; nanosleep(&t, 0); return 0; }\n');

describe('the service keeps off the CPUs of a pinned run', () => {
  test('CPU lists', () => {
    expect(parseCpuList('0-2,5')).toEqual([0, 1, 2, 5]);
    expect(parseCpuList('3')).toEqual([3]);
    expect(parseCpuList('2-1')).toBeNull();
    expect(parseCpuList('1,x')).toBeNull();
    expect(parseCpuList('0-99999')).toBeNull();
  });

  test.skipIf(why !== '')(`during the run it is off them, after it back on all it had${why ? ` (SKIPPED: ${why})` : ''}`, async () => {
    expect(availableParallelism()).toBeGreaterThanOrEqual(2);
    const before = ownCpus()!;
    const last = before[before.length - 1]!;
    const r = await postJob(served.url, { action: 'run', kind: 'make', cpus: String(last), project: { files: sleeper } });
    expect(r.status, JSON.stringify(r.json)).toBe(201);
    const id = r.json.id as string;
    const seen: number[][] = [];
    let polling = true;
    const poll = (async () => {
      while (polling) {
        seen.push(ownCpus()!);
        await new Promise((done) => setTimeout(done, 50));
      }
    })();
    const events = await readEvents(served.url, id);
    polling = false;
    await poll;
    const job = await getJob(served.url, id);
    expect(job.status, job.result?.message).toBe('succeeded');
    const lines = events.filter((e): e is LineEvent => e.type === 'line').map((e) => e.line);
    const others = before.filter((c) => c !== last).join(',');
    expect(lines).toContain(`the build service keeps off CPUs ${last} while the run is pinned there: it runs on ${others}`);
    // while the run ran, the service was off its CPU; once it ended, back on every CPU it had
    expect(seen.some((m) => m.join(',') === others)).toBe(true);
    expect(seen.every((m) => !m.includes(last) || m.join(',') === before.join(','))).toBe(true);
    expect(ownCpus()).toEqual(before);
  }, 120_000);
});
