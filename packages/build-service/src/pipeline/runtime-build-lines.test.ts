/**
 * The lines of a shared runtime build go to the jobs waiting for it (runtime-build-lines.ts), with
 * the real make on a small runtime whose build takes a while: a job that stops waiting (cancelled
 * during the first job's build) gets no line after that, and a job that joins the build in
 * progress gets the lines so far, then the later ones. The cancelled job got every later line of
 * the build (its log went on after its cancel), and the joining one only `already built`, while
 * nothing was built yet, and none of the build's lines (nor, had it failed, why).
 */
import { chmodSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { RuntimeCache } from './runtime-cache.js';
import { RuntimeBuildLines } from './runtime-build-lines.js';
import { DEFAULT_LIMITS } from '../limits.js';
import { scratchWorkspace, scriptedContext, scriptedSandbox } from '../test-support/scripted-sandbox.js';
import type { LineEvent } from './job-events.js';
import { Job } from './job.js';

const scratch = mkdtempSync(join(tmpdir(), 'runtime-build-lines-test-'));
chmodSync(scratch, 0o711);
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

/** A runtime whose build prints `step one`, waits `seconds`, prints `step two` (or fails there), then builds. */
function slowRuntime(dir: string, seconds: number, fail = false): void {
  mkdirSync(join(dir, 'src'), { recursive: true });
  writeFileSync(join(dir, 'src', 'lib.c'), 'int contract_value(void) { return 1; }\n');
  writeFileSync(
    join(dir, 'Makefile'),
    'all: build/libmodule.a build/contract-launch\n' +
      `build/libmodule.a: src/lib.c\n\t@echo step one; sleep ${seconds}; echo step two${fail ? '; echo "lib.c: error: the reason" >&2; false' : ''}\n\tmkdir -p build && cc -c -o build/lib.o src/lib.c && ar rcs $@ build/lib.o\n` +
      'build/contract-launch: build/libmodule.a\n\tprintf "int main(void){return 0;}" > build/l.c && cc -o $@ build/l.c\n',
  );
}

describe('the lines of a shared runtime build', () => {
  test('a job that stops waiting gets no later line; a job joining the build in progress gets the lines so far, then the later ones', async () => {
    const source = join(scratch, 'slow');
    slowRuntime(source, 0.6);
    const cache = new RuntimeCache(source, join(scratch, 'cache-slow'));
    const s = await cache.sources();
    let cancelFirst!: () => void;
    const firstCancelled = new Promise<void>((r) => (cancelFirst = r));
    const first: string[] = [];
    const firstDone = cache.ensureBuilt(s, (l) => {
      first.push(l);
      if (l === 'step one') cancelFirst();
    }, firstCancelled);
    await firstCancelled;
    const second: string[] = [];
    const dir = await cache.ensureBuilt(s, (l) => second.push(l));
    expect(await firstDone).toBe(dir);
    expect(first.at(-1)).toBe('step one');
    expect(first).not.toContain('step two');
    expect(second[0]).toBe(`runtime ${s.key} is being built for another job: its lines follow`);
    expect(second[1]).toMatch(/^building the runtime \(make -C /);
    expect(second.slice(2)).toEqual(['step one', 'step two']);
    // a job after the build: told it is built, no replay
    const third: string[] = [];
    expect(await cache.ensureBuilt(s, (l) => third.push(l))).toBe(dir);
    expect(third).toEqual([`runtime ${s.key} already built`]);
    await cache.close();
  }, 60_000);

  test('a job joining a build that fails gets why (the compiler\'s line), though the job that started it was cancelled', async () => {
    const source = join(scratch, 'failing');
    slowRuntime(source, 0.4, true);
    const cache = new RuntimeCache(source, join(scratch, 'cache-failing'));
    const s = await cache.sources();
    let cancelFirst!: () => void;
    const firstCancelled = new Promise<void>((r) => (cancelFirst = r));
    const firstDone = cache.ensureBuilt(s, (l) => void (l === 'step one' && cancelFirst()), firstCancelled);
    firstDone.catch(() => {});
    await firstCancelled;
    const second: [string, string][] = [];
    await expect(cache.ensureBuilt(s, (l, stream) => second.push([l, stream]))).rejects.toThrow(/runtime build failed \(make exit 2\)/);
    expect(second).toContainEqual(['lib.c: error: the reason', 'stderr']);
    await cache.close();
  }, 60_000);
});

describe('RuntimeBuildLines', () => {
  test('a follower that throws costs the others nothing; no line is told after the end', () => {
    const lines = new RuntimeBuildLines();
    const got: string[] = [];
    lines.follow(() => {
      throw new Error('a job log failing');
    });
    lines.follow((l) => got.push(l));
    lines.line('a', 'stdout');
    lines.end();
    lines.line('b', 'stdout');
    expect(got).toEqual(['a']);
  });
});

describe('two jobs and one runtime build', () => {
  test('the job cancelled during the build logs none of its later lines, before or after its end; the next job logs the whole build', async () => {
    const source = join(scratch, 'jobs');
    // long enough for the second job's prepare (its generation) to end while the build still runs
    slowRuntime(source, 4);
    const runtime = new RuntimeCache(source, join(scratch, 'cache-jobs'));
    const project = { files: { 'a.contract': 'datatype T {int x = 1};\n' } };
    const newJob = (id: string) => new Job(id, { action: 'build', project, projectKey: null, kind: 'cactal', limits: { ...DEFAULT_LIMITS } }, 'none');
    const sandbox = scriptedSandbox({}, { needsHostRuntime: true });
    const first = newJob('j-first');
    const second = newJob('j-second');
    const firstWs = scratchWorkspace();
    const secondWs = scratchWorkspace();
    let cancelledAt = 0;
    let secondDone: Promise<void> | undefined;
    first.events.subscribe(0, (e) => {
      if (e.type === 'line' && e.source === 'runtime' && e.line === 'step one' && !cancelledAt) {
        cancelledAt = e.seq;
        void first.cancel();
        // the next Build & Run, at once
        secondDone = second.execute(scriptedContext(sandbox, secondWs, runtime));
      }
    });
    await first.execute(scriptedContext(sandbox, firstWs, runtime));
    expect(first.status).toBe('cancelled');
    await secondDone;
    expect(second.status).toBe('succeeded');
    const runtimeLines = (job: Job) => job.events.all.filter((e): e is LineEvent => e.type === 'line' && e.source === 'runtime');
    expect(cancelledAt).toBeGreaterThan(0);
    expect(runtimeLines(first).filter((e) => e.seq > cancelledAt)).toEqual([]);
    expect(first.events.all.at(-1)!.type).toBe('end');
    expect(runtimeLines(second).map((e) => e.line)).toEqual([
      `runtime ${(await runtime.sources()).key} is being built for another job: its lines follow`,
      expect.stringMatching(/^building the runtime/),
      'step one',
      'step two',
    ]);
    await runtime.close();
  }, 60_000);
});
