/** Typed client of the IDE server's HTTP API (see server/file-api.ts and server/ide-server.ts). */
import type { FileReadResponse, FolderContents, RecentRun, FileWriteResponse, GenerateResponse, LogFolderListing, RenameEntityResponse, SimulateResponse, StaleSaveDetails, TreeEntry } from '../server/api-types.js';

export type { TreeEntry, FileWriteResponse, FileReadResponse, StaleSaveDetails };
/** What POST /api/generate answers: codegen's report, the src-gen folder and the time taken. */
export type GenerateReport = GenerateResponse;

export class ApiError extends Error {
  constructor(
    readonly status: number,
    message: string,
    /** The other fields of the JSON error answer (e.g. `region`, `line` of a refused save). */
    readonly details: Record<string, unknown> = {},
  ) {
    super(message);
  }
}

async function call<T>(method: string, url: string, body?: unknown, raw = false, extraHeaders: Record<string, string> = {}): Promise<T> {
  let res: Response;
  try {
    res = await fetch(url, {
      method,
      headers: { ...(body === undefined ? {} : { 'content-type': raw ? 'text/plain; charset=utf-8' : 'application/json' }), ...extraHeaders },
      body: body === undefined ? undefined : raw ? (body as string) : JSON.stringify(body),
    });
  } catch {
    throw new ApiError(0, 'server unreachable');
  }
  const text = await res.text();
  const data = answerOf(text);
  if (!res.ok) throw errorOf(res.status, data);
  return data as T;
}

/** A JSON answer's value; text that is not JSON is taken as the error it says. */
function answerOf(text: string): unknown {
  try {
    return text ? JSON.parse(text) : {};
  } catch {
    return { error: text };
  }
}

/** The ApiError of a failed request's answer (`{error, ...details}`). */
function errorOf(status: number, data: unknown): ApiError {
  return new ApiError(status, (data as { error?: string }).error ?? `HTTP ${status}`, data as Record<string, unknown>);
}

const q = (p: string) => encodeURIComponent(p);

/**
 * GET `url` (through `fetchFn`, a test's own) when the answer is a success; else an ApiError whose
 * message names the URL and the status: `<url>: HTTP 404 <the answer's error>`.
 */
export async function getOk(url: string, fetchFn: typeof fetch = fetch): Promise<Response> {
  let res: Response;
  try {
    res = await fetchFn(url);
  } catch {
    throw new ApiError(0, `${url}: server unreachable`);
  }
  if (res.ok) return res;
  const data = answerOf(await res.text().catch(() => '')) as { error?: unknown };
  const said = typeof data.error === 'string' && data.error ? ` ${data.error}` : '';
  throw new ApiError(res.status, `${url}: HTTP ${res.status}${said}`, data as Record<string, unknown>);
}

/** Characters a piece of a downloaded text holds at least before it is cut (after a line end). */
export const PIECE_CHARS = 1 << 20;

/**
 * A response's body as text in pieces of whole lines (UTF-8, as Response.text()), decoded as its
 * chunks come. A log of hundreds of MB read with text() is decoded in one task at the end, which
 * held the page's frames for 150–450 ms on a 200 MB log; decoded chunk by chunk and joined once,
 * the join (one copy of 100 MB) still held them up to 380 ms. Here no string is longer than a piece
 * of about PIECE_CHARS (1 Mi characters), each ending at a line end (the last one: where the text
 * ends), but for a line longer than that, which is one piece: joining them gives the text, byte for
 * byte (a character split across chunks included). None for an empty body.
 */
export async function responsePieces(res: Response): Promise<string[]> {
  if (!res.body) {
    const text = await res.text();
    return text ? [text] : [];
  }
  const reader = res.body.getReader();
  const decoder = new TextDecoder();
  const pieces: string[] = [];
  let pending: string[] = []; // decoded chunks not in a piece yet (the first may start inside a line)
  let pendingChars = 0;
  const add = (chunk: string): void => {
    if (!chunk) return;
    if (pendingChars + chunk.length >= PIECE_CHARS) {
      // cut after the chunk's last line end: only the chunk is searched, so a line without end is never searched again
      const nl = chunk.lastIndexOf('\n');
      if (nl >= 0) {
        pending.push(chunk.slice(0, nl + 1));
        pieces.push(pending.join(''));
        pending = nl + 1 < chunk.length ? [chunk.slice(nl + 1)] : [];
        pendingChars = pending[0]?.length ?? 0;
        return;
      }
    }
    pending.push(chunk);
    pendingChars += chunk.length;
  };
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    add(decoder.decode(value, { stream: true }));
  }
  add(decoder.decode());
  if (pending.length) pieces.push(pending.join(''));
  return pieces;
}

/**
 * A log read for a replay: its text in pieces of whole lines, its size, and the bytes read of it
 * (less than its size: the server sends a log's first LOG_READ_BYTES, of which the last line, cut, is
 * left out too).
 */
export interface ReadLog {
  pieces: string[];
  size: number;
  read: number;
  /** The bytes the server sent (its bound on one log, when less than `size`). */
  sent: number;
}

/**
 * A CSV log of the workspace as text in pieces of whole lines (responsePieces; GET /api/log: bounded
 * for logs, not for the editor's tabs: a longer log's first bytes, whole lines). `maxBytes`: a log
 * whose bytes sent are more than that (the server says them first) is not downloaded: 413.
 */
async function readLog(path: string, maxBytes = Infinity): Promise<ReadLog> {
  let res: Response;
  try {
    res = await fetch(`/api/log?path=${q(path)}`);
  } catch {
    throw new ApiError(0, 'server unreachable');
  }
  const size = Number(res.headers.get('x-log-bytes') ?? 0);
  const sent = Number(res.headers.get('x-log-sent') ?? size);
  if (res.ok && sent > maxBytes) {
    await res.body?.cancel().catch(() => undefined);
    throw new ApiError(413, `${sent} bytes, past the ${maxBytes} bytes left of the replay's bound`);
  }
  if (res.ok) {
    const pieces = await responsePieces(res);
    return sent < size ? withoutCutLine(pieces, sent, size) : { pieces, size, read: sent, sent };
  }
  throw errorOf(res.status, answerOf(await res.text().catch(() => '')));
}

/** The first bytes of a longer log (`size` bytes): their whole lines (the last one, cut where the bytes stop, is no record). */
function withoutCutLine(pieces: string[], sent: number, size: number): ReadLog {
  const last = pieces.pop() ?? '';
  const end = last.lastIndexOf('\n') + 1;
  if (end) pieces.push(last.slice(0, end));
  return { pieces, size, read: sent - new TextEncoder().encode(last.slice(end)).length, sent };
}

/** The WebSocket URL of a path of this server (ws:, or wss: when the page came over https). */
export function socketUrl(path: string): string {
  return `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}${path}`;
}

export interface Snapshot {
  name: string;
  root: string;
  entries: TreeEntry[];
  files: Record<string, string>;
  /** The version of each file in `files` (the base of the tab's saves). */
  versions?: Record<string, string>;
}

/** The disk's text and version when a save was refused because its base is stale (409). */
export function staleDetails(e: unknown): StaleSaveDetails | undefined {
  if (!(e instanceof ApiError) || e.status !== 409 || e.details.stale !== true) return undefined;
  const { content, version } = e.details;
  return typeof content === 'string' && typeof version === 'string' ? { stale: true, content, version } : undefined;
}

export const api = {
  snapshot: () => call<Snapshot>('GET', '/api/snapshot'),
  info: () => call<{ workspace: string; name: string; buildService: string; buildAvailable: boolean }>('GET', '/api/info'),
  tree: () => call<{ root: string; entries: TreeEntry[] }>('GET', '/api/tree'),
  /** The workspace's last Build & Run jobs the build service keeps, newest first (the Monitor's run list). */
  recentRuns: () => call<{ jobs: RecentRun[] }>('GET', '/api/recent-runs'),
  read: (path: string) => call<FileReadResponse>('GET', `/api/file?path=${q(path)}`),
  /** A run's CSV log in the workspace, for a replay (up to 256 MiB, where `read` stops at 8 MiB; `maxBytes`: not downloaded beyond). */
  readLog,
  /** The `*.csv` logs of a workspace folder a replay reads, and the entries it does not read (links, FIFOs), said. */
  logFolder: (path: string) => call<LogFolderListing>('GET', `/api/log-folder?path=${q(path)}`),
  /**
   * Saves a file edited from version `base` (If-Match; 409 + staleDetails when the disk moved on;
   * no base = a blind write). For a generated file the answer may be `merged` (the text now on disk is in `content`).
   */
  write: (path: string, content: string, base?: string) =>
    call<FileWriteResponse>('PUT', `/api/file?path=${q(path)}`, content, true, base ? { 'if-match': `"${base}"` } : {}),
  create: (path: string, type: 'file' | 'dir', content = '') => call<{ path: string }>('POST', '/api/create', { path, type, content }),
  rename: (from: string, to: string) => call<{ from: string; to: string }>('POST', '/api/rename', { from, to }),
  remove: (path: string) => call<{ path: string }>('DELETE', `/api/file?path=${q(path)}`),
  /** A generated file's protected regions holding user code, and whether the next generation restores them if it is deleted. */
  userCode: (path: string) => call<{ regions: string[]; restorable: boolean }>('GET', `/api/user-code?path=${q(path)}`),
  /** What deleting a folder deletes: how many files, and its generated files holding user code (docs/ide.md "Deleting a folder"). */
  folderContents: (path: string) => call<FolderContents>('GET', `/api/folder-contents?path=${q(path)}`),
  newProject: (folder: string) => call<{ folder: string; files: string[] }>('POST', '/api/new-project', { folder }),
  generate: (project: string) => call<GenerateReport>('POST', '/api/generate', { project }),
  renameEntity: (project: string, from: string, to: string, what: { kind?: string; owner?: string; members?: string[]; files?: Array<{ path: string; text: string; base: string }> } = {}) =>
    call<RenameEntityResponse>('POST', '/api/rename-entity', { project, from, to, ...what }),
  submitJob: (body: unknown) => call<{ id: string; status: string; sandbox?: string; warnings?: string[] }>('POST', '/api/jobs', body),
  /** Runs a scenario text on a project in virtual time (422 with `diagnostics` when it has errors). */
  simulate: (project: string, scenario: string) => call<SimulateResponse>('POST', '/api/simulate', { project, scenario }),
  /** A job's status (404 once the build service no longer knows it). */
  getJob: (id: string) => call<{ id: string; status: string; action: string; finishedAt: number | null }>('GET', `/api/jobs/${q(id)}`),
  cancelJob: (id: string) => call<{ id: string; status: string }>('DELETE', `/api/jobs/${q(id)}`),
};
