/**
 * The temp folders and build servers of a test file (or describe block): each is removed or
 * closed after all its tests, servers first. Call it at file or describe level.
 */
import { existsSync, mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll } from 'vitest';
import type { BuildServer } from '../server.js';

export interface Scratch {
  /** A new temp folder `<tmpdir>/<prefix>XXXXXX`. */
  temp(prefix: string): string;
  /** Keeps `server` to be closed after all tests; returns it. */
  serve(server: BuildServer): BuildServer;
}

export function useScratch(): Scratch {
  const dirs: string[] = [];
  const servers: BuildServer[] = [];
  afterAll(async () => {
    for (const s of servers) await s.close();
    for (const d of dirs) rmSync(d, { recursive: true, force: true });
  });
  return {
    temp(prefix) {
      const d = mkdtempSync(join(tmpdir(), prefix));
      dirs.push(d);
      return d;
    },
    serve(server) {
      servers.push(server);
      return server;
    },
  };
}

/**
 * The fresh workspaces left in a cache folder (`ws/<service folder>/<job-…|ws-…>`), as
 * `<service folder>/<name>`: none once every job of its services ended. A service's own (empty)
 * folder stays while it lives (pipeline/dead-service-folders.ts).
 */
export function freshWorkspaces(cacheDir: string): string[] {
  const ws = join(cacheDir, 'ws');
  if (!existsSync(ws)) return [];
  return readdirSync(ws).flatMap((s) => {
    try {
      return readdirSync(join(ws, s)).map((n) => `${s}/${n}`);
    } catch {
      return [s]; // not a folder: something left
    }
  });
}
