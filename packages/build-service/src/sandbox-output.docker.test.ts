/**
 * The output of a sandbox is hostile, in Docker (sandbox-output.bwrap.test.ts for the reasons):
 * a JSON line of the wrong shape (children 5), and an exception of the service's own output
 * handling; the job's container and volume never stay behind. Starts dockerd and bootstraps the
 * image when needed, or says SKIPPED loudly with the reason.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import Docker from 'dockerode';
import { afterAll, beforeAll, describe, expect, test, vi } from 'vitest';
import { freshWorkspaces } from './test-support/scratch.js';
import type { LineEvent } from './pipeline/job-events.js';
import { BuildOutputRouter } from './pipeline/output-router.js';
import { LABEL_JOB } from './sandbox/docker-owner.js';
import { createBuildServer, type BuildServer } from './server.js';
import { honestProgram, makeProject } from './test-support/c-projects.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { dockerUp } from './test-support/docker-env.js';

const env = dockerUp();
let server: BuildServer;
let url: string;
let cacheDir: string;

async function runJob(body: Record<string, unknown>): Promise<{ job: Record<string, any>; lines: LineEvent[] }> {
  const r = await postJob(url, body);
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const events = await readEvents(url, r.json.id as string);
  return { job: await getJob(url, r.json.id as string), lines: events.filter((e): e is LineEvent => e.type === 'line') };
}

async function expectNothingLeft(id: string): Promise<void> {
  const docker = new Docker();
  const label = [`${LABEL_JOB}=${id}`];
  expect(await docker.listContainers({ all: true, filters: { label } })).toEqual([]);
  expect((await docker.listVolumes({ filters: { label } })).Volumes ?? []).toEqual([]);
  expect(freshWorkspaces(cacheDir)).toEqual([]);
}

if (env.available) {
  beforeAll(async () => {
    cacheDir = mkdtempSync(join(tmpdir(), 'contract-cache-'));
    server = createBuildServer({ token: false, port: 0, concurrency: 2, cacheDir, sandbox: 'docker', log: () => {} });
    url = (await server.listen()).url;
  });

  afterAll(async () => {
    await server?.close();
    rmSync(cacheDir, { recursive: true, force: true });
    env.stop();
  });

  describe('hostile output in docker', () => {
    test('a JSON line with children 5 stays a text line; the service goes on', async () => {
      const main = `${String.raw`__asm__(".warning \"x\\n[{\\\"kind\\\":\\\"error\\\",\\\"children\\\":5}]\"");`}\nint main(void) { return 0; }\n`;
      const { job, lines } = await runJob({ action: 'build', kind: 'make', project: { files: makeProject(main) } });
      expect(job.status, job.result?.message).toBe('succeeded');
      expect(lines.some((l) => l.stream === 'stderr' && l.line === '[{"kind":"error","children":5}]')).toBe(true);
      expect((await fetch(`${url}/api/health`)).status).toBe(200);
      await expectNothingLeft(job.id);
    });

    test('an exception of the output handling fails the job only; its container and volume are removed', async () => {
      const spy = vi.spyOn(BuildOutputRouter.prototype, 'route').mockImplementation(() => {
        throw new TypeError('(d.children ?? []).map is not a function');
      });
      let broken;
      try {
        broken = await runJob({ action: 'build', kind: 'make', project: { files: makeProject(honestProgram()) } });
      } finally {
        spy.mockRestore();
      }
      expect(broken.job.status).toBe('failed');
      expect(broken.job.result.message).toMatch(/^internal error: build std(out|err): /);
      await expectNothingLeft(broken.job.id);
      const honest = await runJob({ action: 'run', kind: 'make', project: { files: makeProject(honestProgram(5)) } });
      expect(honest.job.status, honest.job.result?.message).toBe('succeeded');
      await expectNothingLeft(honest.job.id);
    });
  });
} else {
  describe('docker sandbox', () => {
    test.skip(`SKIPPED: ${env.reason}`, () => {});
  });
}
