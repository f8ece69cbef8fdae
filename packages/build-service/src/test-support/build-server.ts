/**
 * The build server of a test file: on a free port, without a token, over a fresh cache folder and
 * (by default) a snapshot of the runtime, started before all tests and closed, its folders
 * removed, after them. `skip` (e.g. no Docker engine) starts nothing; `afterClose` runs once the
 * server is closed (e.g. stopping the dockerd the tests started, which the close still needs).
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll } from 'vitest';
import { createBuildServer, type BuildServer, type BuildServerOptions } from '../server.js';
import { seedRuntime } from './runtime-seed.js';
import { snapshotRuntime } from './tutorial.js';

export interface TestBuildServer {
  readonly url: string;
  readonly server: BuildServer;
  readonly cacheDir: string;
}

export interface TestBuildServerSetup {
  /** Build on a copy of runtime/ (default), so that edits of runtime/ meanwhile do not relink everything. */
  snapshotRuntime?: boolean;
  /** Start with the test run's built runtime in the cache (default; see runtime-seed.ts): false for a cold cache. */
  seedRuntime?: boolean;
  skip?: boolean;
  afterClose?: () => void;
  /** The start's timeout (a first build of the runtime, an image to bootstrap). */
  timeoutMs?: number;
}

export function useBuildServer(options: Omit<BuildServerOptions, 'cacheDir' | 'runtimeSource'>, setup: TestBuildServerSetup = {}): TestBuildServer {
  let started: { url: string; server: BuildServer; cacheDir: string } | null = null;
  const dirs: string[] = [];
  beforeAll(async () => {
    if (setup.skip) return;
    const cacheDir = mkdtempSync(join(tmpdir(), 'contract-cache-'));
    dirs.push(cacheDir);
    const runtimeSource = setup.snapshotRuntime === false ? undefined : snapshotRuntime();
    if (runtimeSource) dirs.push(runtimeSource);
    if (setup.seedRuntime !== false) await seedRuntime(cacheDir, runtimeSource);
    const server = createBuildServer({ token: false, port: 0, ...options, cacheDir, ...(runtimeSource ? { runtimeSource } : {}) });
    started = { server, cacheDir, url: (await server.listen()).url };
  }, setup.timeoutMs ?? 240_000);
  afterAll(async () => {
    await started?.server.close();
    for (const d of dirs) rmSync(d, { recursive: true, force: true });
    setup.afterClose?.();
  });
  const get = (): { url: string; server: BuildServer; cacheDir: string } => {
    if (!started) throw new Error('the test build server is not started (skipped, or used outside a test)');
    return started;
  };
  return {
    get url() { return get().url; },
    get server() { return get().server; },
    get cacheDir() { return get().cacheDir; },
  };
}
