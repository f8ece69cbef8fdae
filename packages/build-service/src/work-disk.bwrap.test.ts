/**
 * The work dir's disk limit and the CSV logs (docs/sandbox.md "The disk limit"), on real bwrap jobs
 * of the report's tutorial with a small `workDiskMiB`:
 * - a module that floods its CSV log is capped by the runtime (CONTRACT_LOG_MAX_BYTES, which the
 *   service sets to 3/4 of the room the work dir has left when the run starts): its log ends with a
 *   `log-capped` record, the run goes on to its end, and the job is not killed for the disk;
 * - the logs an earlier run left in a kept work tree count against no later job: a build after a run
 *   the disk limit stopped succeeds, instead of being stopped and blamed for a file it never wrote.
 */
import { chmodSync, cpSync, existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, expect, test } from 'vitest';
import { JobService } from './job-service.js';
import { formatBytes } from './limits.js';
import type { Job } from './pipeline/job.js';
import type { JobEvent } from './pipeline/job-events.js';
import { artifactBytes } from './pipeline/artifacts.js';
import { unmountWorkDisk } from './sandbox/work-disk.js';
import { seedRuntime } from './test-support/runtime-seed.js';
import { snapshotRuntime, TUTORIAL_DIR, tutorialFiles, withRegion } from './test-support/tutorial.js';
import { parseLogFile } from './trace/parse.js';

const DISK_MIB = 24;
const MSC = 'src-gen/generated/architecture/modules/MSC_mod/module.c';
/** MSC's init logs 400,000 records (about 50 MB, twice the work dir) before the run starts. */
const FLOOD = '    { char d[128]; for (long i = 0; i < 400000; i++) { snprintf(d, sizeof d, "seq=%ld padding=xxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxxx", i); ContractLog("burst", "", -1, 0, d); } }';
/** MSC's init fills the logs folder with a plain file (not its CSV log) until the disk refuses. */
const FILL = '    { char p[512]; const char *dir = getenv("CONTRACT_LOG_DIR"); snprintf(p, sizeof p, "%s/fill.bin", dir ? dir : "."); FILE *f = fopen(p, "wb"); static char c[65536]; while (f && fwrite(c, 1, sizeof c, f) == sizeof c && fflush(f) == 0) {} if (f) fclose(f); }';

const scratch = mkdtempSync(join(tmpdir(), 'work-disk-test-'));
chmodSync(scratch, 0o711);
const cacheDir = join(scratch, 'cache');
const runtimeSource = snapshotRuntime();
let service: JobService;
beforeAll(async () => {
  await seedRuntime(cacheDir, runtimeSource);
  service = new JobService({ sandbox: 'bwrap', concurrency: 1, projectRoots: [scratch], cacheDir, persistentWorkspaces: true, runtimeSource, limits: { workDiskMiB: DISK_MIB } });
}, 240_000);
afterAll(async () => {
  await service?.close();
  // the kept work trees are tmpfs mounts when the tests run as root: unmount them before removing
  const projects = join(cacheDir, 'projects');
  if (existsSync(projects)) for (const id of readdirSync(projects)) await unmountWorkDisk(join(projects, id, 'work'));
  rmSync(scratch, { recursive: true, force: true });
  rmSync(runtimeSource, { recursive: true, force: true });
});

async function finished(job: Job): Promise<string[]> {
  const lines: string[] = [];
  job.events.subscribe(0, (e: JobEvent) => {
    if (e.type === 'line') lines.push(e.line);
  });
  await job.finished;
  return lines;
}

test('a module flooding its CSV log is capped to fit the work dir: log-capped, the run goes on, no disk limit hit', async () => {
  const files = withRegion(await tutorialFiles(), MSC, 'protect_init_MSC', FLOOD, true);
  const job = await service.submit({ action: 'run', sandbox: 'bwrap', duration: 2, project: { files } });
  const lines = await finished(job);
  const result = job.result!;
  const tail = lines.slice(-30).join('\n');
  expect(result.limitHit, `${result.message}\n${tail}`).toBeNull();
  expect(result.step).toBe('run');
  expect(result.issues.map((i) => i.kind), tail).toEqual(['log-capped']);
  const msc = job.artifacts!.files.find((f) => f.name.startsWith('MSC_'))!;
  expect(result.issues[0]!.file).toBe(msc.name);

  // the bound: 3/4 of what the build left free of the disk limit, said in the log
  const records = parseLogFile({ name: msc.name, text: artifactBytes(msc).toString('utf8') });
  const capped = records.filter((r) => r.kind === 'log-capped');
  expect(capped).toHaveLength(2);
  const bound = Number(/log reached its (\d+)-byte bound/.exec((capped[0] as { detail: string }).detail)?.[1]);
  // 3/4 of what the log line says the work dir had left (in MiB, 2 decimals), and that is most of the disk
  // (the tutorial's build, executables with their debug information, takes about a third of it)
  const leftMiB = Number(/3\/4 of the ([\d.]+) MiB the work dir has left/.exec(lines.find((l) => l.startsWith('CSV logs capped at ')) ?? '')?.[1]);
  expect(leftMiB).toBeGreaterThan(DISK_MIB * 0.5);
  expect(Math.abs(bound - 0.75 * leftMiB * 1024 * 1024)).toBeLessThanOrEqual(0.75 * 0.005 * 1024 * 1024);
  expect(bound).toBeLessThanOrEqual(DISK_MIB * 1024 * 1024 * 0.75);
  expect(msc.size).toBeLessThanOrEqual(bound);
  expect(result.message).toBe(`run finished with 1 problem(s): log ${msc.name} is not whole: the module reached its CSV log bound of ${formatBytes(bound)} (CONTRACT_LOG_MAX_BYTES): later records were not written`);
  expect(lines.find((l) => l.startsWith('CSV logs capped at '))).toMatch(
    new RegExp(`^CSV logs capped at ${formatBytes(bound).replace('.', '\\.')} per module \\(CONTRACT_LOG_MAX_BYTES: 3/4 of the [\\d.]+ MiB the work dir has left of its ${DISK_MIB} MiB disk limit\\)`),
  );
  // the run went on to its end: MSC's last record says how many records were not written, every other log ends with its exit record
  expect((capped[1] as { detail: string }).detail).toMatch(/\d+ records not written after the log reached its \d+-byte bound/);
  expect(lines, tail).toContain('all modules stopped cleanly');
  // the launcher's own lines file (contract-launch.log) is no module's log
  for (const f of job.artifacts!.files.filter((x) => x !== msc && x.name.endsWith('.csv'))) {
    expect(parseLogFile({ name: f.name, text: artifactBytes(f).toString('utf8') }).at(-1)?.kind, f.name).toBe('module_exit');
  }
}, 240_000);

test.skipIf(process.getuid?.() !== 0)('a build after a run the disk limit stopped is not stopped by that run\'s logs, nor blamed for them', async () => {
  const project = join(scratch, 'tutorial');
  cpSync(TUTORIAL_DIR, project, { recursive: true, filter: (src) => !/\/(logs|run)(\/|$)/.test(src) });
  const file = join(project, MSC);
  const source = readFileSync(file, 'utf8');
  const filling = withRegion(withRegion({ [MSC]: source }, MSC, 'protect_init_MSC', FILL, true), MSC, 'protect_additional_import_MSC', '#include <stdlib.h>', true)[MSC]!;
  expect(filling).not.toBe(source);
  writeFileSync(file, filling);

  const run = await service.submit({ action: 'run', sandbox: 'bwrap', duration: 2, project: { dir: project } });
  const runLines = await finished(run);
  expect(run.result!.limitHit?.name, runLines.slice(-20).join('\n')).toBe('workDiskMiB');
  expect(run.result!.message).toMatch(/^killed: disk limit 24 MiB \(work dir\): filled by logs\/fill\.bin /);

  // the next job of the project: a build (the IDE's Build, `contract build`) on the kept work tree
  const build = await service.submit({ action: 'build', sandbox: 'bwrap', project: { dir: project } });
  const lines = await finished(build);
  expect(build.status, `${build.result!.message}\n${lines.slice(-20).join('\n')}`).toBe('succeeded');
  expect(build.result!.limitHit).toBeNull();
  expect(lines.join('\n')).not.toContain('fill.bin');
  const [id] = readdirSync(join(cacheDir, 'projects'));
  expect(existsSync(join(cacheDir, 'projects', id!, 'work', 'logs'))).toBe(false);
}, 240_000);

/** MSC's init fills the work dir with a plain file beside logs/ (not a log) until the disk refuses. */
const BIGFILE = FILL.replace('"%s/fill.bin"', '"%s/../bigfile"');

test.skipIf(process.getuid?.() !== 0)('a log the disk reserve stopped says what filled the work dir (a module\'s bigfile), not the run\'s logs', async () => {
  const files = withRegion(withRegion(await tutorialFiles(), MSC, 'protect_init_MSC', BIGFILE, true), MSC, 'protect_additional_import_MSC', '#include <stdlib.h>', true);
  const job = await service.submit({ action: 'run', sandbox: 'bwrap', duration: 2, project: { files } });
  const lines = await finished(job);
  const result = job.result!;
  const tail = lines.slice(-30).join('\n');
  expect(result.limitHit?.name, `${result.message}\n${tail}`).toBe('workDiskMiB');
  const filledBy = /: filled by (bigfile [\d.]+ MiB.* \(of .*\))$/.exec(result.message ?? '')?.[1];
  expect(filledBy, result.message ?? '').toBeDefined();
  const reserve = result.issues.filter((i) => i.kind === 'log-capped' && i.message.includes('its module stopped writing at'));
  expect(reserve.length, JSON.stringify(result.issues, null, 1)).toBeGreaterThan(0);
  // the same measure as the FAILED line's, not a guess that the logs filled it
  for (const i of reserve) {
    expect(i.message).toContain(`the work dir was nearly full, filled by ${filledBy}`);
    expect(i.message).not.toContain('of the run\'s logs');
  }
}, 240_000);
