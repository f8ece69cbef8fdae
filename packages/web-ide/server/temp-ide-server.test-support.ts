/**
 * For the server's tests: the real IDE server (no build service, no front end) on a workspace in
 * a fresh temp folder (empty, or filled by the test before the server starts), and its removal.
 * Not part of the server (excluded from its build like the tests).
 */
import { mkdirSync, mkdtempSync, realpathSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { startIdeServer, type IdeServer } from './ide-server.js';

export interface TempIdeServer {
  /** The temp folder (the workspace is `ws` inside it; other test folders may go beside it). */
  base: string;
  /** The workspace the server serves. */
  ws: string;
  ide: IdeServer;
  /** Stops the server and removes the temp folder. */
  close(): Promise<void>;
}

export interface TempIdeServerOptions {
  /** The workspace folder's name in the temp folder (default `ws`). */
  workspace?: string;
  /** Fills the temp folder before the server starts (the workspace folder exists then). */
  prepare?: (base: string, ws: string) => void;
}

export async function startTempIdeServer(prefix: string, options: TempIdeServerOptions = {}): Promise<TempIdeServer> {
  const base = realpathSync(mkdtempSync(join(tmpdir(), prefix)));
  const ws = join(base, options.workspace ?? 'ws');
  mkdirSync(ws);
  options.prepare?.(base, ws);
  const ide = await startIdeServer({ workspace: ws, port: 0, buildService: false, distDir: join(base, 'no-dist') });
  return {
    base, ws, ide,
    async close() {
      await ide.close();
      rmSync(base, { recursive: true, force: true });
    },
  };
}
