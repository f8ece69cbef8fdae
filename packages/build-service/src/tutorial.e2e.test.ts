/**
 * End to end on the report's tutorial (examples/tutorial): load + check + generate (language and
 * codegen packages), build with gcc/make against the runtime, run with the launcher, in bwrap and
 * in Docker; no-op rebuild; gcc diagnostics inside a protected region; adversarial code placed in
 * a module's protected region while an honest run completes.
 */
import { join } from 'node:path';
import { describe, expect, test } from 'vitest';
import type { LineEvent } from './pipeline/job-events.js';
import { useBuildServer } from './test-support/build-server.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { dockerUp } from './test-support/docker-env.js';
import { MAA_MODULE, TUTORIAL_DIR, tutorialFiles, withRegion } from './test-support/tutorial.js';

const docker = dockerUp();

const served = useBuildServer({ concurrency: 3, projectRoots: [join(TUTORIAL_DIR, '..')] }, { afterClose: () => docker.stop(), timeoutMs: 240_000 });

async function runJob(body: Record<string, unknown>): Promise<{ job: Record<string, any>; lines: LineEvent[] }> {
  const r = await postJob(served.url, body);
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const events = await readEvents(served.url, r.json.id as string);
  return { job: await getJob(served.url, r.json.id as string), lines: events.filter((e): e is LineEvent => e.type === 'line') };
}

function expectTutorialRan(job: Record<string, any>, lines: LineEvent[]): void {
  expect(job.status, `${job.result?.message}\n${lines.slice(-30).map((l) => `${l.source}: ${l.line}`).join('\n')}`).toBe('succeeded');
  const run = lines.filter((l) => l.step === 'run');
  expect(run.some((l) => l.source === 'MAA' && l.line === 'initialization of MAA')).toBe(true);
  expect(run.some((l) => l.source === 'GLB' && /function mission\(consigne = \{i=0\.0,j=0\.0,k=0\.0\}\) started/.test(l.line))).toBe(true);
  expect(run.some((l) => l.source === 'MSC')).toBe(true);
  expect(lines.filter((l) => l.step === 'build' && /^g?cc .* -o MAA /.test(l.line))).toHaveLength(1);
}

interface ArtifactListing {
  files: { name: string; path: string; size: number }[];
  skipped: { name: string; reason: string }[];
  runDirLeftovers: string[];
}

async function artifacts(id: string): Promise<ArtifactListing> {
  const res = await fetch(`${served.url}/api/jobs/${id}/artifacts`);
  expect(res.status).toBe(200);
  return ((await res.json()) as { artifacts: ArtifactListing }).artifacts;
}

async function artifactText(id: string, name: string): Promise<{ status: number; text: string }> {
  const res = await fetch(`${served.url}/api/jobs/${id}/artifacts/${encodeURIComponent(name)}`);
  return { status: res.status, text: await res.text() };
}

/** The tutorial's 9 module processes each write one CSV log (docs/runtime-api.md naming). */
async function expectTutorialLogs(id: string): Promise<ArtifactListing> {
  const list = await artifacts(id);
  const modules = list.files.filter((f) => f.name.endsWith('.csv')).map((f) => /^([A-Z]+)_.*\.csv$/.exec(f.name)?.[1]).sort();
  // beside them, the launcher's own lines (docs/runtime-api.md "contract-launch")
  expect(list.files.map((f) => f.name)).toContain('contract-launch.log');
  expect(modules).toEqual(['GLB', 'MAA', 'MAB', 'MSA', 'MSB', 'MSC', 'MSD', 'ORD', 'SUP']);
  expect(list.runDirLeftovers).toEqual([]);
  const glb = list.files.find((f) => f.name.startsWith('GLB_'))!;
  const body = await artifactText(id, glb.name);
  expect(body.status).toBe(200);
  expect(Buffer.byteLength(body.text)).toBe(glb.size);
  expect(body.text).toMatch(/function mission\(consigne = \{i=0\.0,j=0\.0,k=0\.0\}\) started/);
  return list;
}

describe.each(['bwrap', ...(docker.available ? ['docker'] : [])])('the tutorial in %s', (sandbox) => {
  test('generates, builds and runs; a second build is a no-op', async () => {
    const first = await runJob({ action: 'run', sandbox, duration: 2, project: { dir: TUTORIAL_DIR } });
    expectTutorialRan(first.job, first.lines);
    expect(first.lines.some((l) => /modules pinned to CPUs/.test(l.line))).toBe(false); // no CPUS: the system places them
    await expectTutorialLogs(first.job.id);
    expect(first.job.artifacts.files.length).toBe(10); // 9 module logs and the launcher's own lines
    const again = await runJob({ action: 'build', sandbox, project: { dir: TUTORIAL_DIR } });
    expect(again.job.status).toBe('succeeded');
    expect(again.lines.some((l) => l.line === 'project unchanged since the last build: generation skipped')).toBe(true);
    expect(again.lines.filter((l) => l.step === 'build' && /^g?cc /.test(l.line))).toEqual([]);
  });

  test('the CSV logs come out through the API; a link planted in logs/ is not followed', async () => {
    const plant = [
      '    { const char *d = getenv("CONTRACT_LOG_DIR"); char p[4096];',
      '      if (d) { snprintf(p, sizeof p, "%s/planted.csv", d); if (symlink("/etc/passwd", p) != 0) perror("symlink"); } }',
    ].join('\n');
    const files = withRegion(
      withRegion(await tutorialFiles(), MAA_MODULE, 'protect_init_MAA', plant, true),
      MAA_MODULE,
      'protect_additional_import_MAA',
      '#include <unistd.h>\n#include <stdlib.h>\n#include <stdio.h>',
      true,
    );
    // pinned to CPU 0 (contract-launch --cpus through `make run CPUS=0`)
    const { job, lines } = await runJob({ action: 'run', sandbox, duration: 2, cpus: '0', project: { files } });
    expectTutorialRan(job, lines);
    expect(lines.some((l) => /modules pinned to CPUs 0$/.test(l.line))).toBe(true);
    const list = await expectTutorialLogs(job.id);
    expect(list.skipped).toEqual([{ name: 'planted.csv', reason: 'not a regular file (symlink): not followed' }]);
    expect((await artifactText(job.id, 'planted.csv')).status).toBe(404);
    for (const f of list.files) expect((await artifactText(job.id, f.name)).text).not.toMatch(/^root:/m);
  });
});

if (!docker.available) {
  test.skip(`docker: SKIPPED — ${docker.reason}`, () => {});
}

describe('the start request (bwrap)', () => {
  test('one naming no supervisor of the project (another project\'s) fails the run with a start-refused issue, not a success', async () => {
    const { job, lines } = await runJob({ action: 'run', sandbox: 'bwrap', duration: 1, start: 'MIS.mission()', project: { dir: TUTORIAL_DIR } });
    expect(lines.some((l) => l.source === 'launcher' && /^error: START request to MIS: /.test(l.line))).toBe(true);
    expect(job.status, JSON.stringify(job.result)).not.toBe('succeeded');
    expect(job.result.issues).toEqual([expect.objectContaining({ kind: 'start-refused', module: 'MIS', message: expect.stringMatching(/^the run's start request names MIS, which the launcher could not reach: .*is MIS a supervisor of this project\?\)$/) })]);
  });
});

describe('user code in protected regions (bwrap)', () => {
  test('a compile error in MAA init is reported on module.c, inside protect_init_MAA', async () => {
    const files = withRegion(await tutorialFiles(), MAA_MODULE, 'protect_init_MAA', '    return undeclared_in_region;');
    const { job } = await runJob({ action: 'build', sandbox: 'bwrap', project: { files } });
    expect(job.status).toBe('failed');
    const err = job.diagnostics.find((d: any) => d.severity === 'error');
    expect(err).toMatchObject({ file: 'generated/architecture/modules/MAA_mod/module.c', protectedRegion: { id: 'protect_init_MAA' } });
    expect(err.message).toMatch(/undeclared_in_region/);
    expect(err.line).toBeGreaterThan(err.protectedRegion.startLine);
    expect(err.line).toBeLessThan(err.protectedRegion.endLine);
  });

  test('src-gen/ older than the model: an error in a region is told at the line of the user\'s own file', async () => {
    const broken = withRegion(await tutorialFiles(), MAA_MODULE, 'protect_init_MAA', '    return undeclared_in_region;');
    // the user's module.c is not the file the build generates (here: 3 lines fewer above the
    // regions, as a port added to the model since the last generate shifts them): its region's lines move
    const generatedLines = broken[MAA_MODULE]!.split('\n');
    expect(generatedLines.slice(0, 3).every((l) => l.startsWith('//'))).toBe(true);
    const mine = generatedLines.slice(3).join('\n');
    // the manifest of that older generation recorded that file's own skeleton, not this one's: here
    // it records none of it (as a manifest of a version before the skeleton check), so the file is
    // compared with the regenerated one: generated lines missing lose none of the user's code
    const manifest = JSON.parse(broken['src-gen/.contract-manifest.json']!) as { skeletons: Record<string, string>; skeletonLines: Record<string, string> };
    const inManifest = MAA_MODULE.replace(/^src-gen\//, '');
    expect(manifest.skeletons[inManifest]).toBeDefined();
    delete manifest.skeletons[inManifest];
    delete manifest.skeletonLines[inManifest];
    const older = { ...broken, [MAA_MODULE]: mine, 'src-gen/.contract-manifest.json': JSON.stringify(manifest, null, 2) };
    const { job } = await runJob({ action: 'build', sandbox: 'bwrap', project: { files: older } });
    expect(job.status).toBe('failed');
    const err = job.diagnostics.find((d: any) => d.severity === 'error');
    const userLine = mine.split('\n').findIndex((l) => l.includes('undeclared_in_region')) + 1;
    expect(err).toMatchObject({ file: 'generated/architecture/modules/MAA_mod/module.c', line: userLine, protectedRegion: { id: 'protect_init_MAA' } });
    expect(mine.split('\n')[err.protectedRegion.startLine - 1]).toContain('protect_init_MAA');
    expect(err.message).not.toMatch(/as this build generated it/);
    // the same project with its src-gen/ up to date: the lines are the file's, 3 more
    const { job: fresh } = await runJob({ action: 'build', sandbox: 'bwrap', project: { files: broken } });
    expect(fresh.diagnostics.find((d: any) => d.severity === 'error').line).toBe(userLine + 3);
  });

  test('a fork bomb and a 4 GiB allocation in MAA init are stopped while an honest run completes', async () => {
    const base = await tutorialFiles();
    // each child execs another program (`sleep`): it no longer bears MAA's name
    const bomb = withRegion(base, MAA_MODULE, 'protect_init_MAA', '    for (;;) { pid_t p = fork(); if (p == 0) { execl("/bin/sleep", "sleep", "60", (char *)0); _exit(127); } if (p < 0) { perror("fork"); sleep(1); } }');
    const alloc = withRegion(
      base,
      MAA_MODULE,
      'protect_init_MAA',
      '    for (size_t got = 0; got < ((size_t)4 << 30); got += (size_t)64 << 20) { char *p = malloc((size_t)64 << 20); if (!p) return 0; memset(p, 1, (size_t)64 << 20); }\n    return 1;',
    );
    const withHeaders = (f: Record<string, string>) =>
      withRegion(f, MAA_MODULE, 'protect_additional_import_MAA', '#include <unistd.h>\n#include <stdlib.h>\n#include <string.h>\n#include <stdio.h>', true);
    const [b, a, honest] = await Promise.all([
      runJob({ action: 'run', sandbox: 'bwrap', duration: 10, project: { files: withHeaders(bomb) } }),
      runJob({ action: 'run', sandbox: 'bwrap', duration: 10, project: { files: withHeaders(alloc) } }),
      runJob({ action: 'run', sandbox: 'bwrap', duration: 3, project: { files: base } }),
    ]);
    expect(b.job.result.message).toBe('killed: process limit 256');
    // the sleeps descend from MAA: the limit's issue names the module whose code forks
    expect(b.job.result.issues).toEqual(expect.arrayContaining([expect.objectContaining({ kind: 'limit', module: 'MAA', message: expect.stringMatching(/\(MAA had \d+ of the job's processes: its code forks\)$/) })]));
    expect(a.job.result.message).toBe('killed: memory limit 512 MiB');
    expectTutorialRan(honest.job, honest.lines);
  });
});
