/**
 * The IDE's Build & Run shares the build cache with `contract build` (docs/getting-started.md
 * "The build cache"): after a real `contract build` of the tutorial on a cache folder, the IDE
 * server started with the same CONTRACT_CACHE_DIR builds the project through /api/jobs in bwrap
 * and compiles nothing, writing nothing into the work tree.
 */
import { spawnSync } from 'node:child_process';
import { chmodSync, cpSync, mkdtempSync, realpathSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { seedRuntime } from '@contract-studio/build-service/test-support/runtime-seed';
import { startIdeServer, type IdeServer } from './ide-server.js';

const REPO = join(dirname(fileURLToPath(import.meta.url)), '..', '..', '..');
const CLI = join(REPO, 'packages', 'cli', 'bin', 'contract.js');

let base: string;
let project: string;
let cache: string;
let ide: IdeServer;
const previous = process.env.CONTRACT_CACHE_DIR;

beforeAll(async () => {
  base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-build-cache-')));
  chmodSync(base, 0o711); // the sandboxed builds' own uids reach the cache inside
  project = join(base, 'tutorial');
  cache = join(base, 'cache');
  cpSync(join(REPO, 'examples', 'tutorial'), project, { recursive: true, filter: (src) => !/\/(logs|run)(\/|$)/.test(src) });
  process.env.CONTRACT_CACHE_DIR = cache;
  await seedRuntime(cache); // the test run's built runtime
}, 240_000);

afterAll(async () => {
  await ide?.close();
  if (previous === undefined) delete process.env.CONTRACT_CACHE_DIR;
  else process.env.CONTRACT_CACHE_DIR = previous;
  // the kept work tree is a tmpfs mount when root: `contract cache clear` unmounts and removes
  spawnSync(process.execPath, [CLI, 'cache', 'clear', '--cache-dir', cache], { stdio: 'ignore' });
  spawnSync('rm', ['-rf', '--one-file-system', base]);
});

describe('Build & Run on the shared build cache', () => {
  it('after `contract build`, the IDE builds the unchanged project compiling nothing', async () => {
    const cli = spawnSync(process.execPath, [CLI, 'build', project, '--sandbox', 'bwrap'], { env: { ...process.env, CONTRACT_CACHE_DIR: cache }, encoding: 'utf8', timeout: 300_000 });
    expect(cli.status, cli.stderr).toBe(0);

    ide = await startIdeServer({ workspace: project, port: 0, buildService: true, distDir: join(base, 'no-dist') });
    const headers = { 'x-contract-token': ide.token, 'content-type': 'application/json' };
    const post = await fetch(`${ide.url}/api/jobs`, { method: 'POST', headers, body: JSON.stringify({ action: 'build', sandbox: 'bwrap', project: { dir: project } }) });
    expect(post.status).toBe(201);
    const { id } = (await post.json()) as { id: string };
    let status = 'queued';
    for (let i = 0; i < 600 && !['succeeded', 'failed', 'cancelled'].includes(status); i++) {
      await new Promise((r) => setTimeout(r, 200));
      status = ((await (await fetch(`${ide.url}/api/jobs/${id}`, { headers })).json()) as { status: string }).status;
    }
    const log = await (await fetch(`${ide.url}/api/jobs/${id}/log`, { headers })).text();
    expect(status, log).toBe('succeeded');
    expect(log).toMatch(/\| project unchanged since the last build: generation skipped$/m);
    expect(log).toMatch(/\| work tree ready: \d+ file\(s\), 0 updated \(incremental\)/);
    expect(log).not.toMatch(/\| cc /);
  }, 300_000);
});
