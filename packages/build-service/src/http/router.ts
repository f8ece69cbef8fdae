/**
 * The HTTP API of docs/build-service-api.md on top of a JobService.
 * `handle(req, res)` returns false for paths outside basePath, so it can share a server.
 */
import { createHash } from 'node:crypto';
import type { IncomingMessage, ServerResponse } from 'node:http';
import type { JobService } from '../job-service.js';
import type { LineEvent } from '../pipeline/job-events.js';
import { artifactBytes } from '../pipeline/artifacts.js';
import { ServiceError } from '../service-errors.js';
import { BodyReader } from './body-reader.js';
import { streamSse } from './sse.js';
import type { StreamBudget } from './stream-budget.js';
import { SANDBOX_NAMES, visibleText } from '@contract-studio/conventions';

function send(res: ServerResponse, status: number, body: unknown, headers: Record<string, string> = {}): void {
  const text = JSON.stringify(body);
  res.writeHead(status, { 'Content-Type': 'application/json; charset=utf-8', 'Content-Length': Buffer.byteLength(text), ...headers });
  res.end(text);
}

function sendError(res: ServerResponse, e: unknown, headers: Record<string, string> = {}): void {
  if (e instanceof ServiceError) {
    send(res, e.status, { error: e.message, code: e.code }, { ...(e.status === 429 || e.code === 'busy' ? { 'Retry-After': '2' } : {}), ...headers });
  } else {
    send(res, 500, { error: `internal error: ${(e as Error).message}`, code: 'internal' });
  }
}

export function afterSeq(req: IncomingMessage, url: URL): number | null {
  const header = req.headers['last-event-id'];
  const asked = url.searchParams.getAll('after');
  // the parameter repeated with different values says no one position
  if (asked.some((a) => a !== asked[0])) return null;
  // the header (what a reconnecting EventSource sends) before the parameter
  const raw = (Array.isArray(header) ? header[0] : header) ?? asked[0] ?? '0';
  // a decimal event number as the service gives them: `abc`, `+1`, `0x10`, `1e400`, 5,000 digits are refused
  if (!/^\d{1,15}$/.test(raw)) return null;
  return Number(raw);
}

/** The refusal of a malformed `?after=` or `Last-Event-ID` (the body of its 400). */
export const AFTER_ERROR = 'after (or Last-Event-ID) must be an event number: a whole number of 1 to 15 decimal digits (0: from the start), the parameter given once';

/** The job's lines as text, one line each (visibleText): what a line carries cannot begin another (a forged service line) nor act on a terminal. */
export function logText(lines: LineEvent[]): string {
  return lines.map((l) => `${new Date(l.t).toISOString()} ${l.step} ${l.source} ${l.stream} | ${visibleText(l.line)}\n`).join('');
}

/** The header a client sends to list its own jobs: any secret of its own, 16 to 200 characters. */
export const CLIENT_HEADER = 'X-Contract-Client';

/** Digest of the request's client key, or undefined when it sent none (or an unusable one: 400). */
function clientOwner(req: IncomingMessage): string | undefined {
  const raw = req.headers[CLIENT_HEADER.toLowerCase()];
  if (raw === undefined) return undefined;
  const key = Array.isArray(raw) ? raw[0] ?? '' : raw;
  if (key.length < 16 || key.length > 200) throw new ServiceError(400, 'bad_request', `${CLIENT_HEADER} must be 16 to 200 characters`);
  return createHash('sha256').update(key).digest('hex');
}

/** What the caller of `handle()` allows; a mounting server (the IDE) keeps the default. */
export interface RoutePolicy {
  /** Accept `sandbox: "none"` jobs (no isolation). The standalone server sets it from its option. */
  allowNoneSandbox: boolean;
  /** Every job runs in this sandbox (the server's `onlySandbox`): a job naming another is refused. */
  onlySandbox?: 'bwrap' | 'docker';
}

/**
 * 403 for a job naming a sandbox other than the policy's only one, and for a `sandbox: "none"`
 * job (named, or the service's default) the policy does not allow.
 */
function checkSandboxPolicy(service: JobService, body: unknown, policy: RoutePolicy): void {
  const named = body && typeof body === 'object' ? (body as { sandbox?: unknown }).sandbox : undefined;
  if (policy.onlySandbox && named !== undefined && named !== policy.onlySandbox) {
    throw new ServiceError(403, 'forbidden', `sandbox ${JSON.stringify(String(named).slice(0, 40))} refused: this server runs every job in ${policy.onlySandbox} (it was started so, e.g. \`contract serve --sandbox ${policy.onlySandbox}\`); name ${policy.onlySandbox} or no sandbox`);
  }
  if (policy.allowNoneSandbox) return;
  if ((named ?? service.defaultSandbox) === 'none') {
    throw new ServiceError(403, 'forbidden', 'sandbox "none" jobs (no isolation: they run as the service\'s user) are refused: this service was not started with allowNoneSandbox: true; use "bwrap", "docker" or "auto"');
  }
}

export function createRouter(service: JobService, basePath: string, budget?: StreamBudget) {
  const bodies = new BodyReader();
  return async function handle(req: IncomingMessage, res: ServerResponse, policy: RoutePolicy = { allowNoneSandbox: true }): Promise<boolean> {
    const url = new URL(req.url ?? '/', 'http://localhost');
    if (url.pathname !== basePath && !url.pathname.startsWith(`${basePath}/`)) return false;
    const path = url.pathname.slice(basePath.length) || '/';
    const parts = path.split('/').filter(Boolean);
    const method = req.method ?? 'GET';
    /** A body left unread is not drained: the answer closes the connection instead. */
    let bodyUnread = method === 'POST' || method === 'PUT' || method === 'PATCH';
    try {
      if (parts[0] === 'health' && parts.length === 1 && method === 'GET') {
        // a service shutting down takes no job (503 closing): said here too, not ok
        if (service.closing) send(res, 503, { ok: false, closing: true, ...service.stats });
        else send(res, 200, { ok: true, closing: false, ...service.stats });
      } else if (parts[0] === 'sandboxes' && parts.length === 1 && method === 'GET') {
        const sandboxes = [];
        for (const name of SANDBOX_NAMES) sandboxes.push({ name, ...(await service.sandboxes.probe(name)) });
        let auto: string | null = null;
        try {
          auto = (await service.sandboxes.resolve('auto')).sandbox.name;
        } catch {
          auto = null;
        }
        send(res, 200, { default: service.defaultSandbox, auto, sandboxes, limits: service.limits });
      } else if (parts[0] === 'jobs' && parts.length === 1 && method === 'POST') {
        // every refusal that needs no body comes before reading it (docs/build-service-api.md)
        const owner = clientOwner(req);
        service.checkCapacity();
        const body = await bodies.admit(req).read();
        bodyUnread = false;
        checkSandboxPolicy(service, body, policy);
        const job = await service.submit(body, owner);
        send(
          res,
          201,
          { id: job.id, status: job.status, sandbox: job.sandboxName, sandboxNote: job.sandboxNote, warnings: job.warnings },
          { Location: `${basePath}/jobs/${job.id}` },
        );
      } else if (parts[0] === 'jobs' && parts.length === 1 && method === 'GET') {
        // one client never sees another's jobs (docs/build-service-api.md "GET /api/jobs"): only those submitted with the same key
        const owner = clientOwner(req);
        send(res, 200, {
          jobs: owner === undefined ? [] : service.list(owner).map((j) => ({ id: j.id, status: j.status, action: j.request.action, sandbox: j.sandboxName, createdAt: j.createdAt, finishedAt: j.finishedAt, message: j.result?.message ?? null })),
          ...(owner === undefined ? { note: `send the header ${CLIENT_HEADER} (16 to 200 characters of your own) with POST /api/jobs and here to list your jobs; a job id is the only handle on its job` } : {}),
        });
      } else if (parts[0] === 'jobs' && parts.length >= 2) {
        const job = service.get(parts[1]!);
        if (!job) throw new ServiceError(404, 'not_found', `no job ${parts[1]}`);
        const sub = parts[2];
        if (parts.length === 2 && method === 'GET') send(res, 200, job.toJSON());
        else if (parts.length === 2 && method === 'DELETE') {
          if (job.isDone) send(res, 200, { id: job.id, status: job.status });
          else {
            service.cancel(job.id).catch(() => {});
            send(res, 202, { id: job.id, status: 'cancelling' });
          }
        } else if (sub === 'events' && parts.length === 3 && method === 'GET') {
          const after = afterSeq(req, url);
          if (after === null) throw new ServiceError(400, 'bad_request', AFTER_ERROR);
          // nothing will ever follow: 204 No Content, which stops an EventSource (WHATWG HTML
          // "Server-sent events": a 200 stream closed at once made it reconnect every 3 s for ever)
          if (job.events.isEnded && after >= job.events.all.length) {
            res.writeHead(204, { 'Cache-Control': 'no-cache' });
            res.end();
          } else streamSse(job, req, res, after, budget);
        }
        else if (sub === 'log' && parts.length === 3 && method === 'GET') {
          const text = logText(job.events.all.filter((e): e is LineEvent => e.type === 'line'));
          res.writeHead(200, { 'Content-Type': 'text/plain; charset=utf-8' });
          res.end(text);
        } else if (sub === 'artifacts' && parts.length === 3 && method === 'GET') {
          send(res, 200, { id: job.id, status: job.status, artifacts: job.artifactsJSON() ?? { files: [], skipped: [], runDirLeftovers: [], collect_ms: null } });
        } else if (sub === 'artifacts' && parts.length === 4 && method === 'GET') {
          let name: string;
          try {
            name = decodeURIComponent(parts[3]!);
          } catch {
            throw new ServiceError(400, 'bad_request', `bad artifact name "${parts[3]}"`);
          }
          // a log's name is one file name: no folder part, no control character, not . or ..
          // eslint-disable-next-line no-control-regex
          if (name === '' || name === '.' || name === '..' || name.length > 255 || /[/\\\u0000-\u001f\u007f]/.test(name)) {
            throw new ServiceError(400, 'bad_request', `bad artifact name ${JSON.stringify(name)}: a file name (no folder, no control character)`);
          }
          const file = job.artifact(name);
          if (!file) throw new ServiceError(404, 'not_found', `job ${job.id} has no artifact "${name}"${job.isDone ? '' : ' (yet: the job has not finished)'}`);
          // kept gzip-compressed (artifacts.ts): sent as is to a client that takes gzip
          const gz = /\bgzip\b/.test(String(req.headers['accept-encoding'] ?? ''));
          const body = gz ? file.gzip : artifactBytes(file);
          res.writeHead(200, {
            'Content-Type': name.endsWith('.csv') ? 'text/csv; charset=utf-8' : 'application/octet-stream',
            'Content-Length': body.length,
            ...(gz ? { 'Content-Encoding': 'gzip' } : {}),
            Vary: 'Accept-Encoding',
            'Content-Disposition': `attachment; filename="${file.name}"`,
            'X-Content-Type-Options': 'nosniff',
          });
          res.end(body);
        } else throw new ServiceError(404, 'not_found', `no route ${method} ${url.pathname}`);
      } else {
        throw new ServiceError(404, 'not_found', `no route ${method} ${url.pathname}`);
      }
    } catch (e) {
      if (!res.headersSent) sendError(res, e, bodyUnread ? { Connection: 'close' } : {});
      else res.end();
    }
    return true;
  };
}
