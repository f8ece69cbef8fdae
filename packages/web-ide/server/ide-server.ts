import { createServer, type IncomingMessage, type ServerResponse, type Server } from 'node:http';
import { lstat, mkdir, writeFile, readFile } from 'node:fs/promises';
import { listTree, flattenFiles } from './file-tree.js';
import { join, basename } from 'node:path';
import { fileURLToPath } from 'node:url';
import { WorkspacePaths } from './workspace-paths.js';
import { handleFileApi } from './file-api.js';
import { WorkspaceWatcher } from './workspace-watcher.js';
import { serveStatic } from './static-files.js';
import { HttpError } from './http-error.js';
import { guardRequest } from './request-guard.js';
import { readJson, sendError, sendJson } from './http-util.js';
import { PROJECT_TEMPLATES } from './project-templates.js';
import { renameInGeneratedTree } from './rename-generated.js';
import { createEmbeddedBuildServer, loadWorkspaceDocuments, runCodegen, type BuildServerLike } from './integrations.js';
import type { GenerateResponse } from './api-types.js';
import { GeneratedTreeLock } from './generated-tree-lock.js';

export interface IdeServerOptions {
  /** The workspace folder opened by the IDE. */
  workspace: string;
  host?: string;
  /** 0 = any free port. Default 7400. */
  port?: number;
  /** Folder of the Vite production build (default: this package's dist/). */
  distDir?: string;
  /** Mount the build service API (default true). */
  buildService?: boolean;
}

export interface IdeServer {
  url: string;
  workspace: string;
  server: Server;
  buildServiceNote: string;
  close(): Promise<void>;
}

const BUILD_ROUTES = /^\/api\/(jobs|sandboxes|health)(\/|$)/;
export const DEFAULT_PORT = 7400;

/** Starts the IDE server: static front end + file API + watcher + generate + build service. */
export async function startIdeServer(options: IdeServerOptions): Promise<IdeServer> {
  const paths = new WorkspacePaths(options.workspace);
  const host = options.host ?? '127.0.0.1';
  const distDir = options.distDir ?? fileURLToPath(new URL('../dist', import.meta.url));
  const watcher = new WorkspaceWatcher(paths.root);
  // Generate All, the rename carry-over and guarded saves of generated files run one at a time.
  const treeLock = new GeneratedTreeLock();
  let build: BuildServerLike | undefined;
  let buildServiceNote = 'build service disabled';
  if (options.buildService !== false) {
    const b = await createEmbeddedBuildServer(paths.root);
    if (typeof b === 'string') buildServiceNote = b;
    else {
      build = b;
      buildServiceNote = 'build service mounted at /api/jobs';
    }
  }

  const handle = async (req: IncomingMessage, res: ServerResponse): Promise<void> => {
    const url = new URL(req.url ?? '/', 'http://localhost');
    try {
      guardRequest(req, host);
      if (url.pathname.startsWith('/api/')) {
        if (BUILD_ROUTES.test(url.pathname)) {
          if (!build) throw new HttpError(503, buildServiceNote);
          if (await build.handle(req, res)) return;
          throw new HttpError(404, `no such build service route: ${url.pathname}`);
        }
        if (req.method === 'GET' && url.pathname === '/api/events') return watcher.attach(res);
        if (await handleFileApi(paths, req, res, url, treeLock)) return;
        if (await handleProjectApi(req, res, url)) return;
        throw new HttpError(404, `no such API route: ${req.method} ${url.pathname}`);
      }
      if (req.method !== 'GET' && req.method !== 'HEAD') throw new HttpError(405, 'method not allowed');
      await serveStatic(distDir, req, res, url);
    } catch (e) {
      if (!res.headersSent) sendError(res, e);
      else res.end();
    }
  };

  const handleProjectApi = async (req: IncomingMessage, res: ServerResponse, url: URL): Promise<boolean> => {
    const route = `${req.method} ${url.pathname}`;
    if (route === 'GET /api/snapshot') {
      // Everything the first paint needs in one response: tree + every .contract text (<= 4 MiB).
      const entries = await listTree(paths.root);
      const files: Record<string, string> = {};
      let budget = 4 * 1024 * 1024;
      for (const p of flattenFiles(entries).filter((f) => f.endsWith('.contract'))) {
        const text = await readFile(join(paths.root, ...p.split('/')), 'utf8').catch(() => undefined);
        if (text === undefined || (budget -= text.length) < 0) continue;
        files[p] = text;
      }
      sendJson(res, 200, { workspace: paths.root, name: basename(paths.root), root: paths.root, entries, files });
      return true;
    }
    if (route === 'GET /api/info') {
      sendJson(res, 200, { workspace: paths.root, name: basename(paths.root), buildService: buildServiceNote, buildAvailable: !!build });
      return true;
    }
    if (route === 'POST /api/generate') {
      const body = await readJson(req);
      const projectDir = paths.resolve(body.project ?? '');
      const t0 = Date.now();
      const report = await treeLock.run(async () => {
        const { documents } = await loadWorkspaceDocuments(projectDir);
        return runCodegen(documents, join(projectDir, 'src-gen'), {});
      });
      const srcGen = paths.toRelative(join(projectDir, 'src-gen'));
      const answer: GenerateResponse = { ...report, srcGen, ms: Date.now() - t0 };
      sendJson(res, 200, answer);
      watcher.broadcast('generated', { srcGen });
      return true;
    }
    if (route === 'POST /api/new-project') {
      const body = await readJson(req);
      const dir = paths.resolve(body.folder ?? '');
      for (const name of Object.keys(PROJECT_TEMPLATES)) {
        if (await lstat(join(dir, name)).catch(() => undefined)) {
          throw new HttpError(409, `${paths.toRelative(join(dir, name))} already exists: choose an empty folder`);
        }
      }
      await mkdir(dir, { recursive: true });
      for (const [name, text] of Object.entries(PROJECT_TEMPLATES)) await writeFile(join(dir, name), text, { flag: 'wx' });
      sendJson(res, 201, { folder: paths.toRelative(dir), files: Object.keys(PROJECT_TEMPLATES).map((n) => paths.toRelative(join(dir, n))) });
      return true;
    }
    if (route === 'POST /api/rename-entity') {
      const body = await readJson(req);
      const projectDir = paths.resolve(body.project ?? '');
      if (typeof body.from !== 'string' || typeof body.to !== 'string') throw new HttpError(400, 'from and to are required');
      const { from, to } = body;
      try {
        const report = await treeLock.run(() => renameInGeneratedTree(join(projectDir, 'src-gen'), from, to));
        sendJson(res, 200, report);
      } catch (e) {
        throw new HttpError(409, (e as Error).message);
      }
      return true;
    }
    return false;
  };

  const server = createServer((req, res) => void handle(req, res));
  // The build service's WebSocket event stream (GET /api/jobs/:id/ws) needs the upgrade too.
  server.on('upgrade', (req, socket, head) => {
    try {
      guardRequest(req, host);
    } catch {
      socket.destroy();
      return;
    }
    if (!build?.handleUpgrade?.(req, socket, head)) socket.destroy();
  });
  try {
    await new Promise<void>((resolve, reject) => {
      server.once('error', reject);
      server.listen(options.port ?? DEFAULT_PORT, host, () => resolve());
    });
  } catch (e) {
    // port in use, bad address: release what was started so the process can exit
    watcher.close();
    await build?.close().catch(() => undefined);
    throw e;
  }
  const addr = server.address();
  const port = typeof addr === 'object' && addr ? addr.port : options.port;
  return {
    url: `http://${host.includes(':') ? `[${host}]` : host}:${port}`,
    workspace: paths.root,
    server,
    buildServiceNote,
    async close() {
      watcher.close();
      await build?.close().catch(() => undefined);
      server.closeAllConnections();
      await new Promise<void>((r) => server.close(() => r()));
    },
  };
}
