/**
 * Limit mechanisms and workspace safety: rlimit fallback (no cgroups), the `none` sandbox's
 * warning, and a project workspace reused after its sandboxed code planted symlinks (Judge0
 * CVE-2024-28185/28189): the service never writes, reads or deletes through them.
 */
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { beforeAll, describe, expect, test } from 'vitest';
import { createBuildServer } from './server.js';
import { bigAllocation, forkBomb, honestProgram, makeProject } from './test-support/c-projects.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { useScratch } from './test-support/scratch.js';

const { temp, serve } = useScratch();

async function start(opts: Parameters<typeof createBuildServer>[0]): Promise<string> {
  const s = createBuildServer({ token: false, allowNoneSandbox: true, port: 0, cacheDir: temp('contract-cache-'), ...opts });
  serve(s);
  return (await s.listen()).url;
}

async function runJob(url: string, body: Record<string, unknown>): Promise<Record<string, any>> {
  const r = await postJob(url, body);
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const events = await readEvents(url, r.json.id as string);
  return { ...(await getJob(url, r.json.id as string)), events };
}

describe('rlimit fallback (bwrap without cgroups)', () => {
  let url: string;
  beforeAll(async () => {
    url = await start({ concurrency: 3, bwrap: { limitMechanism: 'rlimit' }, limits: { processes: 64 } });
  });

  test('fork bomb, big allocation and an honest job: each limit named with its mechanism', async () => {
    const [bomb, alloc, honest] = await Promise.all([
      runJob(url, { action: 'run', kind: 'make', sandbox: 'bwrap', project: { files: makeProject(forkBomb) }, limits: { runSeconds: 20 } }),
      runJob(url, { action: 'run', kind: 'make', sandbox: 'bwrap', project: { files: makeProject(bigAllocation) } }),
      runJob(url, { action: 'run', kind: 'make', sandbox: 'bwrap', project: { files: makeProject(honestProgram(5)) } }),
    ]);
    expect(bomb.result.message).toBe('killed: process limit 64');
    expect(bomb.result.limitHit.mechanism).toBe('rlimit-nproc');
    expect(alloc.result.message).toBe('killed: memory limit 512 MiB');
    expect(alloc.result.limitHit.mechanism).toBe('rlimit-as');
    expect(honest.status).toBe('succeeded');
    expect(honest.result.mechanisms).toMatchObject({ memory: 'rlimit-as', processes: 'rlimit-nproc', network: 'netns' });
  });
});

describe('sandbox none', () => {
  test('runs only when asked by name, with a warning naming what it cannot enforce', async () => {
    const url = await start({ concurrency: 1 });
    const job = await runJob(url, { action: 'run', kind: 'make', sandbox: 'none', project: { files: makeProject(honestProgram(2)) } });
    expect(job.status).toBe('succeeded');
    expect(job.warnings[0]).toMatch(/^sandbox none: not enforced: network isolation, read-only root .*memory limit, process limit/);
    expect(job.events.some((e: any) => e.type === 'line' && e.stream === 'system' && e.line.startsWith('warning: sandbox none'))).toBe(true);
    expect(job.result.mechanisms.memory).toBe('none');
    expect(job.result.mechanisms.user).toMatch(/^host uid \d+ \(setpriv, no new privileges\)$/);
  });
});

describe('planted symlinks in a reused project workspace', () => {
  test('the next job replaces them without following; cleanup does not follow them either', async () => {
    const projects = temp('contract-projects-');
    const host = temp('contract-host-');
    writeFileSync(join(host, 'secret.txt'), 'host data\n');
    mkdirSync(join(host, 'keep'));
    writeFileSync(join(host, 'keep', 'precious.txt'), 'keep me\n');
    const project = join(projects, 'p');
    mkdirSync(project);
    for (const [rel, text] of Object.entries(makeProject(honestProgram(1)))) writeFileSync(join(project, rel), text);
    // the "run" target plants links to host paths where the service will write/delete next time
    writeFileSync(
      join(project, 'Makefile'),
      readFileSync(join(project, 'Makefile'), 'utf8') +
        `plant:\n\trm -f main.c && ln -s ${join(host, 'secret.txt')} main.c && ln -s ${join(host, 'keep')} keepdir\n`,
    );
    const s = createBuildServer({ token: false, allowNoneSandbox: true, port: 0, cacheDir: temp('contract-cache-'), projectRoots: [projects], concurrency: 1 });
    const url = (await s.listen()).url;
    const first = await runJob(url, { action: 'build', kind: 'make', sandbox: 'bwrap', project: { dir: project } });
    expect(first.status).toBe('succeeded');
    // plant: a build of a project whose "all" target is "plant"
    writeFileSync(join(project, 'Makefile'), readFileSync(join(project, 'Makefile'), 'utf8').replace('all: prog', 'all: plant'));
    const planting = await runJob(url, { action: 'build', kind: 'make', sandbox: 'bwrap', project: { dir: project } });
    expect(planting.status).toBe('succeeded');
    // next job (honest Makefile again): prepare syncs main.c -> must not write through the link
    writeFileSync(join(project, 'Makefile'), readFileSync(join(project, 'Makefile'), 'utf8').replace('all: plant', 'all: prog'));
    const again = await runJob(url, { action: 'build', kind: 'make', sandbox: 'bwrap', project: { dir: project } });
    expect(again.status, again.result.message).toBe('succeeded');
    expect(again.events.some((e: any) => e.type === 'line' && /work tree ready: .* \(incremental\)/.test(e.line))).toBe(true);
    expect(readFileSync(join(host, 'secret.txt'), 'utf8')).toBe('host data\n');
    await s.close();
    expect(readFileSync(join(host, 'keep', 'precious.txt'), 'utf8')).toBe('keep me\n');
    expect(existsSync(join(host, 'secret.txt'))).toBe(true);
  });
});
