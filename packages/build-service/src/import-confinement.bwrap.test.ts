/**
 * A job's imports stay inside its staged project (docs/sandbox.md, "Imports stay in the project"):
 * through the real service, an inline or project-folder job importing a host `.contract` file by
 * `..` or by absolute path, a link out or a FIFO gets an error naming the import, and the host file's
 * content appears nowhere in its events or result.
 */
import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { createBuildServer } from './server.js';
import { getJob, postJob, readEvents } from './test-support/client.js';

const MARK = 'HostSecretMark7391';
const host = mkdtempSync(join(tmpdir(), 'contract-host-secret-'));
const projects = mkdtempSync(join(tmpdir(), 'contract-import-projects-'));
const secret = join(host, 'secret.contract');
const server = createBuildServer({ token: false, port: 0, concurrency: 1, projectRoots: [projects] });
let url = '';

beforeAll(async () => {
  // a host file in valid Cactal: loaded, its names and values would flow into diagnostics and code
  writeFileSync(secret, `datatype HostSecret {${MARK} a};\n`);
  url = (await server.listen()).url;
});
afterAll(async () => {
  await server.close();
  rmSync(host, { recursive: true, force: true });
  rmSync(projects, { recursive: true, force: true });
});

const importer = (path: string): string => `import "${path}";\ndatatype A {int x};\n`;

async function runJob(project: Record<string, unknown>): Promise<Record<string, any>> {
  const r = await postJob(url, { action: 'build', kind: 'cactal', sandbox: 'bwrap', project });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const events = await readEvents(url, r.json.id as string);
  const job = await getJob(url, r.json.id as string);
  expect(JSON.stringify(events)).not.toContain(MARK);
  expect(JSON.stringify(job)).not.toContain(MARK);
  expect(job.status).toBe('failed');
  expect(job.result.message).toBe('project has 1 error(s)');
  // a project with errors does not wait for the runtime: it is not built, nor looked up in the cache
  const said = events.filter((e: any) => e.type === 'line').map((e: any) => e.line as string);
  expect(said.filter((l) => /building the runtime|^runtime [0-9a-f]{16} /.test(l))).toEqual([]);
  return { ...job, events };
}

const lines = (job: Record<string, any>): string[] => job.events.filter((e: any) => e.type === 'line').map((e: any) => e.line as string);

describe('imports of a job stay in its project', () => {
  test('an inline job importing a host file by `..` is refused, named', async () => {
    const up = '../'.repeat(40) + secret.slice(1);
    const job = await runJob({ files: { 'main.contract': importer(up) } });
    expect(lines(job)).toContain(`main.contract:1:8: error: import "${up}" is refused: it leads outside the project folder (imports must stay inside the project folder)`);
  });

  test('an inline job importing /etc/passwd by `..` is refused, named', async () => {
    const job = await runJob({ files: { 'main.contract': importer('../../../../../../../../../../etc/passwd') } });
    expect(lines(job).some((l) => l.includes('import "../../../../../../../../../../etc/passwd" is refused: it leads outside the project folder'))).toBe(true);
  });

  test('an inline job importing a host file by absolute path is refused, named', async () => {
    const job = await runJob({ files: { 'sub/main.contract': importer(secret) } });
    expect(lines(job)).toContain(`sub/main.contract:1:8: error: import "${secret}" is refused: absolute import paths are not allowed here; use a path relative to the importing file (imports must stay inside the project folder)`);
  });

  test('a project folder with a link out and a FIFO: neither is staged nor read, and the job fails naming both', async () => {
    const dir = join(projects, 'linked');
    mkdirSync(dir);
    symlinkSync(secret, join(dir, 'link.contract'));
    execFileSync('mkfifo', [join(dir, 'pipe.contract')]);
    writeFileSync(join(dir, 'main.contract'), 'import "link.contract";\nimport "pipe.contract";\ndatatype A {int x};\n');
    const r = await postJob(url, { action: 'build', kind: 'cactal', sandbox: 'bwrap', project: { dir } });
    expect(r.status, JSON.stringify(r.json)).toBe(201);
    const events = await readEvents(url, r.json.id as string);
    const job = await getJob(url, r.json.id as string);
    expect(JSON.stringify(events) + JSON.stringify(job)).not.toContain(MARK);
    expect(job.status).toBe('failed');
    // refused before the model is loaded (never read, never opened: the FIFO does not block)
    expect(job.result.message).toMatch(/^prepare failed: link\.contract \(a symbolic link\), pipe\.contract \(not a regular file\): the build service never reads a project's source through a link \(nor a FIFO or device\)/);
  }, 30_000);
});
