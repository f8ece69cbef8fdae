import { createServer, type IncomingMessage, type ServerResponse, type Server } from 'node:http';
import { constants } from 'node:fs';
import { open } from 'node:fs/promises';
import { listTree, flattenFiles } from './file-tree.js';
import { join, basename } from 'node:path';
import { fileURLToPath } from 'node:url';
import { WorkspacePaths } from './workspace-paths.js';
import { WorkspaceFs, type DirAt } from './workspace-fs.js';
import { handleFileApi } from './file-api.js';
import { handleLogApi, handleLogFolderApi } from './log-api.js';
import { WorkspaceWatcher } from './workspace-watcher.js';
import { serveStatic } from './static-files.js';
import { HttpError } from './http-error.js';
import { guardRequest } from './request-guard.js';
import { SessionToken } from './session-token.js';
import { readJson, sendError, sendJson } from './http-util.js';
import { PROJECT_TEMPLATES } from './project-templates.js';
import { createEmbeddedBuildServer, loadWorkspaceDocuments, runCodegen, type BuildServerLike } from './integrations.js';
import { renameEntity } from './rename-api.js';
import type { GenerateResponse } from './api-types.js';
import { GeneratedTreeLock } from './generated-tree-lock.js';
import { inProjectFolder } from './project-folder.js';
import { FileLocks } from './file-locks.js';
import { fileVersion } from './file-version.js';
import { SimulateApi } from './simulate-api.js';
import { SharedRuns } from './shared-runs.js';
import { WebSocketServer } from 'ws';
import { SRC_GEN_DIR } from '@contract-studio/conventions';
import { journalWarnings } from './journal-warnings.js';
import { withProjectTreeLock } from './guarded-write.js';
import { checkProjectRoot, unusedTreeWarnings } from './project-layout.js';

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
  /** The build service's sandbox for jobs that name none (default auto: bubblewrap where it works, else Docker). */
  sandbox?: 'auto' | 'bwrap' | 'docker';
  /** The session token (default: 32 random bytes, base64url); see session-token.ts. */
  token?: string;
  /** The build service's limits for the IDE's jobs (`contract serve --limit NAME=VALUE`; docs/sandbox.md "Limits"). */
  limits?: Record<string, number>;
  /** Those limits as written on the command line (the service quotes them, and checks a count or size exactly). */
  limitTexts?: Record<string, string>;
}

export interface IdeServer {
  url: string;
  /** The URL to open in a browser: `url` + `/?token=...` (the page load sets the session cookie). */
  openUrl: string;
  /** The session token every /api request and WebSocket upgrade must present. */
  token: string;
  workspace: string;
  server: Server;
  buildServiceNote: string;
  close(): Promise<void>;
}

/**
 * A workspace text file and its version, opened without following links (workspace-fs.ts);
 * undefined when it is larger than `maxBytes` (not read: a hostile project's huge file would
 * otherwise be read whole to be dropped).
 */
async function readWorkspaceText(fs: WorkspaceFs, rel: string, maxBytes: number): Promise<{ text: string; version: string } | undefined> {
  return fs.withParent(rel, false, async (dir, name) => {
    const { handle, stats } = await WorkspaceFs.openFile(dir, name, rel);
    try {
      if (!stats.isFile() || stats.size > maxBytes) return undefined;
      const bytes = await handle.readFile();
      return { text: bytes.toString('utf8'), version: fileVersion(bytes) };
    } finally {
      await handle.close();
    }
  });
}

/** The new-project templates, each created O_EXCL|O_NOFOLLOW in the opened folder (409 when one exists). */
async function createTemplateFiles(dir: DirAt, shown: (name: string) => string): Promise<void> {
  for (const name of Object.keys(PROJECT_TEMPLATES)) {
    if (await WorkspaceFs.entry(dir, name)) throw new HttpError(409, `${shown(name)} already exists: choose an empty folder`);
  }
  for (const [name, text] of Object.entries(PROJECT_TEMPLATES)) {
    const { O_WRONLY, O_CREAT, O_EXCL, O_NOFOLLOW } = constants;
    const handle = await open(dir.at(name), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0o644);
    try {
      await handle.writeFile(text);
    } finally {
      await handle.close();
    }
  }
}

const NO_SESSION = 'this IDE server needs its session token: open the URL `contract serve` printed (.../?token=...), or send the X-Contract-Token header';

function sendText(res: ServerResponse, status: number, text: string): void {
  res.writeHead(status, { 'content-type': 'text/plain; charset=utf-8', 'cache-control': 'no-store' });
  res.end(text);
}

const BUILD_ROUTES = /^\/api\/(jobs|sandboxes|health)(\/|$)/;
export const DEFAULT_PORT = 7400;

/** Starts the IDE server: static front end + file API + watcher + generate + build service. */
export async function startIdeServer(options: IdeServerOptions): Promise<IdeServer> {
  const paths = new WorkspacePaths(options.workspace);
  const host = options.host ?? '127.0.0.1';
  const distDir = options.distDir ?? fileURLToPath(new URL('../dist', import.meta.url));
  // Generate All, the rename carry-over and guarded saves of generated files run one at a time.
  const treeLock = new GeneratedTreeLock();
  // the saves of one file run one at a time (version compare + write: docs/ide.md)
  const fileLocks = new FileLocks();
  let build: BuildServerLike | undefined;
  let buildServiceNote = 'build service disabled';
  // first: limits the service refuses (BuildLimitsRefused) stop the start before anything runs
  if (options.buildService !== false) {
    const b = await createEmbeddedBuildServer(paths.root, undefined, options.sandbox, options.limits, options.limitTexts);
    if (typeof b === 'string') buildServiceNote = b;
    else {
      build = b;
      buildServiceNote = 'build service mounted at /api/jobs';
    }
  }
  const watcher = new WorkspaceWatcher(paths.root);
  // every tab hears of the runs the others start (docs/ide.md "Several tabs")
  const runs = build ? new SharedRuns(build.service, paths.root, (job) => watcher.broadcast('job', job)) : undefined;
  /** What a client of /api/events is told first: the runs going on. */
  const greeting = () => (runs ? [{ event: 'jobs', data: { jobs: runs.going() } }] : []);
  // /api/events as a WebSocket (what the page uses): clients send nothing, so frames stay tiny
  const eventSockets = new WebSocketServer({ noServer: true, maxPayload: 1024 });

  const token = new SessionToken(options.token);
  const simulate = new SimulateApi(paths);

  const handle = async (req: IncomingMessage, res: ServerResponse): Promise<void> => {
    const url = new URL(req.url ?? '/', 'http://localhost');
    try {
      guardRequest(req, host);
      if (url.pathname.startsWith('/api/')) {
        if (!token.presented(req)) throw new HttpError(401, NO_SESSION, { code: 'unauthorized' });
        if (BUILD_ROUTES.test(url.pathname)) {
          if (!build) throw new HttpError(503, buildServiceNote);
          runs?.claim(req, url.pathname); // a job submitted through the IDE is listed by /api/recent-runs
          if (await build.handle(req, res)) return;
          throw new HttpError(404, `no such build service route: ${url.pathname}`);
        }
        if (req.method === 'GET' && url.pathname === '/api/events') return watcher.attach(res, greeting());
        if (await handleFileApi(paths, req, res, url, treeLock, fileLocks)) return;
        if (await handleLogApi(paths, req, res, url)) return;
        if (await handleLogFolderApi(paths, req, res, url)) return;
        if (await handleProjectApi(req, res, url)) return;
        if (await simulate.handle(req, res, url)) return;
        throw new HttpError(404, `no such API route: ${req.method} ${url.pathname}`);
      }
      if (req.method !== 'GET' && req.method !== 'HEAD') throw new HttpError(405, 'method not allowed');
      if (url.searchParams.has('token')) return openSession(req, res, url);
      // the page itself only with the session (the built assets hold no workspace data)
      if (!/\.\w+$/.test(url.pathname) || url.pathname.endsWith('.html')) {
        if (!token.presented(req)) return sendText(res, 401, `${NO_SESSION}\n`);
      }
      await serveStatic(distDir, req, res, url);
    } catch (e) {
      if (!res.headersSent) sendError(res, e);
      else res.end();
    }
  };

  /** `/?token=T`: a right token becomes the session cookie, and the address bar loses the token. */
  const openSession = (req: IncomingMessage, res: ServerResponse, url: URL): void => {
    if (!token.matches(url.searchParams.get('token'))) return sendText(res, 401, `wrong session token. ${NO_SESSION}\n`);
    url.searchParams.delete('token');
    res.writeHead(303, { location: url.pathname + url.search, 'set-cookie': token.setCookie(), 'cache-control': 'no-store', 'referrer-policy': 'no-referrer' });
    res.end();
  };

  const handleProjectApi = async (req: IncomingMessage, res: ServerResponse, url: URL): Promise<boolean> => {
    const route = `${req.method} ${url.pathname}`;
    if (route === 'GET /api/snapshot') {
      // Everything the first paint needs in one response: tree + every .contract text (<= 4 MiB).
      const entries = await listTree(paths.fs);
      const files: Record<string, string> = {};
      const versions: Record<string, string> = {};
      let budget = 4 * 1024 * 1024;
      for (const p of flattenFiles(entries).filter((f) => f.endsWith('.contract'))) {
        const read = await readWorkspaceText(paths.fs, p, budget).catch(() => undefined);
        if (read === undefined || (budget -= read.text.length) < 0) continue;
        files[p] = read.text;
        versions[p] = read.version;
      }
      sendJson(res, 200, { workspace: paths.root, name: basename(paths.root), root: paths.root, entries, files, versions });
      return true;
    }
    if (route === 'GET /api/recent-runs') {
      // the Monitor's run list in every tab: this workspace's last Build & Run jobs the build service keeps
      sendJson(res, 200, { jobs: runs ? runs.recent() : [] });
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
      // the tree's write lock before the model is read: a terminal's rename, whose .contract files
      // and tree change together, is seen whole or not at all
      const project = paths.toRelative(projectDir);
      // a folder inside a project (the Eclipse layout's src/) would get a second tree without the user's code
      checkProjectRoot(paths.root, project);
      let layoutWarnings: string[] = [];
      const report = await treeLock.run(() => inProjectFolder(paths, projectDir, (dir) => withProjectTreeLock(dir, async (journal) => {
        const { documents } = await loadWorkspaceDocuments(dir);
        layoutWarnings = unusedTreeWarnings(dir, project, documents.map((d) => d.file));
        const generated = await runCodegen(documents, join(dir, SRC_GEN_DIR));
        // an interrupted terminal rename finished first: said in the Generate panel, first
        generated.warnings.unshift(...journalWarnings(journal));
        return generated;
      }, (f) => (project ? `${project}/${f}` : f))));
      const srcGen = paths.toRelative(join(projectDir, SRC_GEN_DIR));
      const answer: GenerateResponse = { ...report, srcGen, layoutWarnings, ms: Date.now() - t0 };
      sendJson(res, 200, answer);
      watcher.broadcast('generated', { srcGen });
      return true;
    }
    if (route === 'POST /api/new-project') {
      const body = await readJson(req);
      const folder = paths.toRelative(paths.resolve(body.folder ?? ''));
      const inFolder = (name: string) => (folder ? `${folder}/${name}` : name);
      await paths.fs.withDir(folder.split('/').filter(Boolean), true, (dir) => createTemplateFiles(dir, inFolder));
      sendJson(res, 201, { folder, files: Object.keys(PROJECT_TEMPLATES).map(inFolder) });
      return true;
    }
    if (route === 'POST /api/rename-entity') {
      sendJson(res, 200, await renameEntity(paths, treeLock, fileLocks, await readJson(req)));
      return true;
    }
    return false;
  };

  const server = createServer((req, res) => void handle(req, res));
  // WebSockets: /api/events (the workspace's events) and the build service's job streams (GET /api/jobs/:id/ws).
  server.on('upgrade', (req, socket, head) => {
    // same Host/Origin checks and session token as the HTTP API: a socket is read cross-origin
    try {
      guardRequest(req, host);
      if (!token.presented(req)) throw new HttpError(401, NO_SESSION, { code: 'unauthorized' });
    } catch (e) {
      const status = e instanceof HttpError ? e.status : 400;
      socket.end(`HTTP/1.1 ${status} ${status === 401 ? 'Unauthorized' : 'Forbidden'}\r\nConnection: close\r\nContent-Length: 0\r\n\r\n`);
      return;
    }
    if (new URL(req.url ?? '/', 'http://localhost').pathname === '/api/events') {
      eventSockets.handleUpgrade(req, socket, head, (ws) => watcher.attachSocket(ws, greeting()));
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
    eventSockets.close();
    runs?.close();
    await build?.close().catch(() => undefined);
    throw e;
  }
  const addr = server.address();
  const port = typeof addr === 'object' && addr ? addr.port : options.port;
  token.bindPort(port ?? DEFAULT_PORT);
  const url = `http://${host.includes(':') ? `[${host}]` : host}:${port}`;
  return {
    url,
    openUrl: `${url}/?token=${token.value}`,
    token: token.value,
    workspace: paths.root,
    server,
    buildServiceNote,
    async close() {
      watcher.close();
      eventSockets.close();
      runs?.close();
      await build?.close().catch(() => undefined);
      server.closeAllConnections();
      await new Promise<void>((r) => server.close(() => r()));
      simulate.close();
    },
  };
}
