/**
 * GET /api/log?path=P.csv -> the CSV log's bytes as text/plain (workspace-relative path, a regular
 * file named *.csv, opened without following links: workspace-fs.ts); the same for a trace file
 * P.jsonl (`contract run --trace`, `contract simulate --trace`: the records as JSON lines).
 *
 * The Monitor's and the Timeline's replay of a run's logs in the workspace (`contract run` writes
 * them to PROJECT/logs, `make run` to src-gen/generated/architecture/logs) read them here, not with
 * GET /api/file: that answer is bounded at 8 MiB for the editor's tabs, and a 1 kHz schema's ORD
 * log passes 8 MiB in about 20 s of run, so a replay of a longer run lost its scheduler records.
 * The bound here is the build service's default for a collected log (the same files, had from a
 * Build & Run job; a run with a larger work dir may keep longer logs, up to 1 GiB, which
 * `contract trace` reads as a stream): LOG_READ_BYTES. A longer log is sent up to there, its size
 * said (`x-log-bytes`, and `x-log-sent`: the bytes sent), the page keeping its whole lines and saying
 * what it left (the records after: in the file, which `contract trace` reads whole); it was refused
 * whole, and the replay missed all of it. The bytes are streamed from the file to the size seen when it was
 * opened (a log still written to stays whole up to there), never held whole in the server.
 */
import type { IncomingMessage, ServerResponse } from 'node:http';
import { pipeline } from 'node:stream/promises';
import { HttpError } from './http-error.js';
import { WorkspaceFs, type DirAt } from './workspace-fs.js';
import type { WorkspacePaths } from './workspace-paths.js';
import type { LogFolderListing } from './api-types.js';
import { isLogFileName, launcherLinesOfFile, LAUNCHER_LINES_FILE, MAX_LAUNCHER_LINES_BYTES } from '@contract-studio/build-service/trace';
import { crashFileModule, crashReportOfFile, crashSiteLines, MAX_CRASH_FILE_BYTES, MAX_CRASH_FILES } from '@contract-studio/build-service/crash-files';

/** Most bytes of a CSV log read for a replay (the build service's default ARTIFACT_BOUNDS.fileBytes: the page holds what it replays; src/views/run-logs.ts LOG_READ_BYTES). */
export const LOG_READ_BYTES = 256 * 1024 * 1024;

/** Answers GET /api/log; false for any other request. */
export async function handleLogApi(paths: WorkspacePaths, req: IncomingMessage, res: ServerResponse, url: URL): Promise<boolean> {
  if (req.method !== 'GET' || url.pathname !== '/api/log') return false;
  const rel = paths.entry(url.searchParams.get('path'));
  if (!rel.endsWith('.csv') && !rel.endsWith('.jsonl')) throw new HttpError(400, `${rel} is not a CSV log (*.csv) nor a trace file (*.jsonl): only those are read here`);
  await paths.fs.withParent(rel, false, async (dir, name) => {
    const { handle, stats: st } = await WorkspaceFs.openFile(dir, name, rel);
    try {
      if (!st.isFile()) throw new HttpError(400, `${rel} is a folder`);
      // a longer log: its first LOG_READ_BYTES (the page keeps their whole lines and says the rest is left)
      const sent = Math.min(st.size, LOG_READ_BYTES);
      res.writeHead(200, { 'content-type': 'text/plain; charset=utf-8', 'cache-control': 'no-store', 'x-log-bytes': String(st.size), 'x-log-sent': String(sent) });
      if (sent === 0) {
        res.end();
        return;
      }
      await pipeline(handle.createReadStream({ start: 0, end: sent - 1, autoClose: false }), res);
    } finally {
      await handle.close().catch(() => undefined);
    }
  });
  return true;
}

/**
 * The lines the folder's crash files tell (crash-files.ts: read bounded, regular files only, in the
 * exact format naming the module of the file's name); the frames unmapped: the IDE runs no
 * addr2line, `contract trace` does, when the executable beside the logs has the report's build-id.
 */
async function folderCrashSites(dir: DirAt, rel: string): Promise<string[]> {
  const names = (await WorkspaceFs.list(dir)).filter((d) => d.name.endsWith('.crash')).map((d) => d.name).sort().slice(0, MAX_CRASH_FILES);
  const lines: string[] = [];
  for (const name of names) {
    const module = crashFileModule(name);
    const shown = rel ? `${rel}/${name}` : name;
    let text: string | null = null;
    if (module) {
      const opened = await WorkspaceFs.openFile(dir, name, shown).catch(() => null);
      if (opened) {
        try {
          if (opened.stats.isFile() && opened.stats.size <= MAX_CRASH_FILE_BYTES) {
            const buf = Buffer.alloc(MAX_CRASH_FILE_BYTES);
            const { bytesRead } = await opened.handle.read(buf, 0, MAX_CRASH_FILE_BYTES, 0);
            text = buf.subarray(0, bytesRead).toString('latin1');
          }
        } finally {
          await opened.handle.close().catch(() => undefined);
        }
      }
    }
    const report = module && text !== null ? crashReportOfFile(text, module) : undefined;
    if (!report) {
      lines.push(`${shown}: not read (a crash file is a regular file of at most ${MAX_CRASH_FILE_BYTES} bytes holding one crash report of the module it is named after)`);
      continue;
    }
    // whether the executable that crashed is beside the logs is not known here (no build-id read): the
    // command names where the build puts it, with the build-id it must have (crashSiteLines, null)
    const beside = `${rel ? `${rel}/` : ''}../modules/${report.module}_mod/${report.module}`;
    lines.push(...crashSiteLines(report, null, null, `\`contract trace ${rel || '.'}\` maps them to files and lines when the module's executable of that build is beside the logs (${beside})`));
  }
  return lines;
}

/**
 * The end lines of the folder's launcher lines file (contract-launch.log: a regular file, no link
 * followed, its first MAX_LAUNCHER_LINES_BYTES read), or why it was not read; none when it is not there.
 */
async function folderLauncherLines(dir: DirAt, rel: string): Promise<{ lines: { monoNs: string; line: string }[]; problem?: string }> {
  const shown = rel ? `${rel}/${LAUNCHER_LINES_FILE}` : LAUNCHER_LINES_FILE;
  if (!(await WorkspaceFs.entry(dir, LAUNCHER_LINES_FILE).catch(() => undefined))) return { lines: [] };
  let opened: Awaited<ReturnType<typeof WorkspaceFs.openFile>>;
  try {
    opened = await WorkspaceFs.openFile(dir, LAUNCHER_LINES_FILE, shown);
  } catch (e) {
    return { lines: [], problem: `${shown}: not read (${(e as Error).message})` };
  }
  try {
    if (!opened.stats.isFile()) return { lines: [], problem: `${shown}: not a regular file, not read` };
    const buf = Buffer.alloc(Math.min(MAX_LAUNCHER_LINES_BYTES, opened.stats.size));
    const { bytesRead } = await opened.handle.read(buf, 0, buf.length, 0);
    const lines = launcherLinesOfFile(buf.subarray(0, bytesRead).toString('utf8')).map((l) => ({ monoNs: String(l.monoNs), line: l.line }));
    return opened.stats.size > MAX_LAUNCHER_LINES_BYTES ? { lines, problem: `${shown}: only its first ${MAX_LAUNCHER_LINES_BYTES} bytes read` } : { lines };
  } finally {
    await opened.handle.close().catch(() => undefined);
  }
}

/** Logs of one folder a replay reads at most (the Monitor's bound: its run list, its model). */
export const FOLDER_LOGS_MAX = 256;
/** Entries of a folder's listing named as not read, at most (the others counted). */
const NOT_READ_NAMED = 20;

/** Why a `*.csv` entry of a log folder is not read (contract trace's words), or '' for a regular file. */
function notReadWhy(d: import('node:fs').Dirent): string {
  if (d.isFile()) return '';
  if (d.isSymbolicLink()) return 'a symbolic link, not read (logs are never read through a link)';
  const kind = d.isFIFO() ? 'a FIFO' : d.isSocket() ? 'a socket' : d.isCharacterDevice() || d.isBlockDevice() ? 'a device' : d.isDirectory() ? 'a folder' : 'not a regular file';
  return `${kind}, not read`;
}

/**
 * GET /api/log-folder?path=F -> the `*.csv` logs of workspace folder F ('' = the root) a replay
 * reads, and those it does not read, said (LogFolderListing): the Explorer's tree lists no link nor
 * FIFO, so a replay built from it alone would miss them without a word. The folder is opened from
 * the root without following links (workspace-fs.ts).
 */
export async function handleLogFolderApi(paths: WorkspacePaths, req: IncomingMessage, res: ServerResponse, url: URL): Promise<boolean> {
  if (req.method !== 'GET' || url.pathname !== '/api/log-folder') return false;
  paths.resolve(url.searchParams.get('path')); // the clear 400/403 answers
  const rel = paths.normalise(url.searchParams.get('path'));
  const listing = await paths.fs.withDir(rel ? rel.split('/') : [], false, async (dir) => {
    const entries = (await WorkspaceFs.list(dir)).filter((d) => isLogFileName(d.name)).sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0));
    const regular = entries.filter((d) => d.isFile());
    const odd = entries.filter((d) => !d.isFile());
    const listed = regular.slice(0, FOLDER_LOGS_MAX);
    // their sizes (lstat: no link followed): the replay reads the small logs first under its bound
    const sizes = await Promise.all(listed.map(async (d) => (await WorkspaceFs.entry(dir, d.name).catch(() => undefined))?.size ?? 0));
    const crashSites = await folderCrashSites(dir, rel);
    const launcher = await folderLauncherLines(dir, rel);
    return {
      ...(crashSites.length ? { crashSites } : {}),
      ...(launcher.lines.length ? { launcherLines: launcher.lines } : {}),
      ...(launcher.problem ? { launcherLinesProblem: launcher.problem } : {}),
      logs: listed.map((d) => (rel ? `${rel}/${d.name}` : d.name)),
      sizes,
      more: Math.max(0, regular.length - FOLDER_LOGS_MAX),
      max: FOLDER_LOGS_MAX,
      notRead: odd.slice(0, NOT_READ_NAMED).map((d) => `${d.name}: ${notReadWhy(d)}`),
      notReadCount: odd.length,
    } satisfies LogFolderListing;
  });
  res.writeHead(200, { 'content-type': 'application/json; charset=utf-8', 'cache-control': 'no-store' });
  res.end(JSON.stringify(listing));
  return true;
}
