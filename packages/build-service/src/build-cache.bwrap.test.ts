/**
 * The persistent build cache (docs/getting-started.md "The build cache") with the report's tutorial
 * in bwrap, each service standing for one `contract build` process on the same cache folder:
 * - a second build of the unchanged project writes nothing into the work tree (bytes and mtimes
 *   kept) and make compiles nothing;
 * - one protected region edited in one module: make compiles that module only;
 * - two builds of one project at once (two services): both succeed, the second waited;
 * - a build stopped mid-way leaves a workspace the next build does not trust (from scratch);
 * - the host trust rule holds across processes: an executable replaced after the build is rebuilt;
 * - a runtime switched to and back (two runtime sources on one cache): the tree is built again
 *   against the runtime in use each time, though the first one's library is older than the executables.
 */
import { chmodSync, cpSync, mkdtempSync, readdirSync, readFileSync, rmSync, statSync, utimesSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { JobService } from './job-service.js';
import type { Job } from './pipeline/job.js';
import type { JobEvent } from './pipeline/job-events.js';
import { unmountWorkDisk } from './sandbox/work-disk.js';
import { listFilesNoFollow } from './util/safe-fs.js';
import { seedRuntime } from './test-support/runtime-seed.js';
import { snapshotRuntime, TUTORIAL_DIR } from './test-support/tutorial.js';

const scratch = mkdtempSync(join(tmpdir(), 'build-cache-test-'));
chmodSync(scratch, 0o711);
const cacheDir = join(scratch, 'cache');
const project = join(scratch, 'tutorial');
cpSync(TUTORIAL_DIR, project, { recursive: true, filter: (src) => !/\/(logs|run)(\/|$)/.test(src) });
const runtimeSource = snapshotRuntime();
const services: JobService[] = [];
// the test run's built runtime (the second runtime of the last test is built here)
beforeAll(() => seedRuntime(cacheDir, runtimeSource), 240_000);
afterAll(async () => {
  for (const s of services) await s.close();
  // the kept work trees are tmpfs mounts when the tests run as root: unmount them before removing
  for (const id of readdirSync(join(cacheDir, 'projects'))) await unmountWorkDisk(join(cacheDir, 'projects', id, 'work'));
  rmSync(scratch, { recursive: true, force: true });
  rmSync(runtimeSource, { recursive: true, force: true });
});

/** One "process": a service on the shared cache folder, as `contract build` makes it. */
function service(): JobService {
  const s = new JobService({ sandbox: 'bwrap', concurrency: 2, projectRoots: [scratch], cacheDir, persistentWorkspaces: true, runtimeSource, limits: { buildSeconds: 300 } });
  services.push(s);
  return s;
}

async function build(s: JobService, onJob?: (job: Job) => void): Promise<{ job: Job; lines: string[] }> {
  const job = await s.submit({ action: 'build', sandbox: 'bwrap', project: { dir: project } });
  onJob?.(job);
  const lines: string[] = [];
  job.events.subscribe(0, (e: JobEvent) => {
    if (e.type === 'line') lines.push(e.line);
  });
  await job.finished;
  return { job, lines };
}

/** The executables gcc was asked to produce in this build (`cc ... -o NAME`). */
const compiled = (lines: string[]): string[] => lines.filter((l) => /^g?cc /.test(l)).map((l) => /-o (\S+)/.exec(l)?.[1] ?? '?').sort();

function workTreeTimes(workDir: string, files: string[]): Map<string, number> {
  return new Map(files.map((f) => [f, statSync(join(workDir, f)).mtimeMs]));
}

const MSA = 'src-gen/generated/architecture/modules/MSA_mod/module.c';
let workDir = '';

describe('the build cache across services (bwrap)', () => {
  test('first build compiles everything; the next service finds the work tree as it was: nothing written, nothing compiled', async () => {
    const first = await build(service());
    expect(first.job.status, first.lines.join('\n')).toBe('succeeded');
    expect(compiled(first.lines)).toContain('MSA');
    const [id] = readdirSync(join(cacheDir, 'projects'));
    workDir = join(cacheDir, 'projects', id!, 'work');
    const files = await listFilesNoFollow(workDir, (rel, isDir) => !isDir || !/^(logs|run)$/.test(rel));
    const before = workTreeTimes(workDir, files);

    const second = await build(service());
    expect(second.job.status, second.lines.join('\n')).toBe('succeeded');
    expect(second.lines).toContain('project unchanged since the last build: generation skipped');
    expect(second.lines.some((l) => /^work tree ready: \d+ file\(s\), 0 updated \(incremental\)/.test(l))).toBe(true);
    expect(compiled(second.lines)).toEqual([]);
    expect(workTreeTimes(workDir, files)).toEqual(before);
    expect(second.lines.some((l) => /^time: sandbox start/.test(l))).toBe(true);
  });

  test('one protected region edited in MSA: only MSA is compiled', async () => {
    const path = join(project, MSA);
    const text = readFileSync(path, 'utf8');
    const edited = text.replace(/(\/\*PROTECTED REGION ID\(protect_internal_vars_MSA\) ENABLED START\*\/)/, '$1\nstatic int build_cache_test_marker = 1;\n');
    expect(edited).not.toBe(text);
    writeFileSync(path, edited.replace('build_cache_test_marker = 1;', 'build_cache_test_marker = 1; static int *const build_cache_test_use = &build_cache_test_marker;'));
    const { job, lines } = await build(service());
    expect(job.status, lines.join('\n')).toBe('succeeded');
    expect(compiled(lines)).toEqual(['MSA']);
  });

  test('two builds of the project at once (two services): both succeed, the second waits for the first', async () => {
    const [a, b] = await Promise.all([build(service()), build(service())]);
    expect(a.job.status, a.lines.join('\n')).toBe('succeeded');
    expect(b.job.status, b.lines.join('\n')).toBe('succeeded');
    const waited = [a, b].filter((r) => r.lines.some((l) => /^waiting for the other command using this project/.test(l)));
    expect(waited.length).toBe(1);
  });

  test('an executable replaced after the build is not trusted by the next service: rebuilt from scratch', async () => {
    const exe = join(workDir, 'src-gen/generated/architecture/modules/MSB_mod/MSB');
    writeFileSync(exe, '#!/bin/sh\necho planted\n');
    utimesSync(exe, new Date('2100-01-01'), new Date('2100-01-01'));
    const { job, lines } = await build(service());
    expect(job.status, lines.join('\n')).toBe('succeeded');
    expect(lines.some((l) => /^the work dir changed after the last build ended, or it was built with another runtime than runtime-[0-9a-f]{16}: its build products are not trusted, building from scratch$/.test(l)), lines.join('\n')).toBe(true);
    expect(compiled(lines)).toContain('MSB');
    expect(readFileSync(exe).subarray(0, 4).toString('latin1')).toBe('\x7fELF');
  });

  test('a build stopped mid-way is not trusted by the next service: it builds from scratch', async () => {
    // a fresh model edit, so that make has work to do when the cancel comes
    const path = join(project, MSA);
    writeFileSync(path, readFileSync(path, 'utf8').replace('build_cache_test_marker = 1;', 'build_cache_test_marker = 2;'));
    const s = service();
    const stopped = await build(s, (job) => {
      const unsubscribe = job.events.subscribe(0, (e) => {
        if (e.type === 'status' && e.status === 'building') {
          unsubscribe();
          void s.cancel(job.id);
        }
      });
    });
    expect(stopped.job.status).toBe('cancelled');
    const { job, lines } = await build(service());
    expect(job.status, lines.join('\n')).toBe('succeeded');
    expect(lines).toContain('no build ended in this workspace since it was emptied: building from scratch');
    expect(compiled(lines).length).toBeGreaterThan(5);
  });

  test('a runtime switched to and back: each build links against the runtime it uses, built from scratch', async () => {
    // a second runtime source on the same cache (a checkout or a toolchain switched to): another key
    const otherSource = snapshotRuntime();
    try {
      // built with the first runtime (built now if it was not yet): its library is older than what the other one links
      expect((await build(service())).job.status).toBe('succeeded');
      writeFileSync(join(otherSource, 'src/core.c'), `${readFileSync(join(otherSource, 'src/core.c'), 'utf8')}\n/* another runtime */\n`);
      const other = new JobService({ sandbox: 'bwrap', concurrency: 2, projectRoots: [scratch], cacheDir, persistentWorkspaces: true, runtimeSource: otherSource, limits: { buildSeconds: 300 } });
      services.push(other);
      const switched = /^the work dir changed after the last build ended, or it was built with another runtime than runtime-[0-9a-f]{16}: its build products are not trusted, building from scratch$/;
      const there = await build(other);
      expect(there.job.status, there.lines.join('\n')).toBe('succeeded');
      expect(there.lines.some((l) => switched.test(l))).toBe(true);
      expect(compiled(there.lines)).toContain('MSA');
      // back: the first runtime's library is older than the executables just linked, make alone would link nothing
      const back = await build(service());
      expect(back.job.status, back.lines.join('\n')).toBe('succeeded');
      expect(back.lines.some((l) => switched.test(l)), back.lines.join('\n')).toBe(true);
      expect(compiled(back.lines)).toContain('MSA');
      // and then the usual no-op
      const again = await build(service());
      expect(compiled(again.lines)).toEqual([]);
    } finally {
      rmSync(otherSource, { recursive: true, force: true });
    }
  });
});

