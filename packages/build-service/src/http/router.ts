/**
 * The HTTP API of docs/build-service-api.md on top of a JobService.
 * `handle(req, res)` returns false for paths outside basePath, so it can share a server.
 */
import { createHash } from 'node:crypto';
import type { IncomingMessage, ServerResponse } from 'node:http';
import type { JobService } from '../job-service.js';
import type { LineEvent } from '../pipeline/job-events.js';
import { ServiceError } from '../service-errors.js';
import { streamSse } from './sse.js';

const MAX_BODY_BYTES = 80 * 1024 * 1024;

function send(res: ServerResponse, status: number, body: unknown, headers: Record<string, string> = {}): void {
  const text = JSON.stringify(body);
  res.writeHead(status, { 'Content-Type': 'application/json; charset=utf-8', 'Content-Length': Buffer.byteLength(text), ...headers });
  res.end(text);
}

function sendError(res: ServerResponse, e: unknown): void {
  if (e instanceof ServiceError) {
    send(res, e.status, { error: e.message, code: e.code }, e.status === 429 ? { 'Retry-After': '2' } : {});
  } else {
    send(res, 500, { error: `internal error: ${(e as Error).message}`, code: 'internal' });
  }
}

function readJson(req: IncomingMessage): Promise<unknown> {
  return new Promise((resolve, reject) => {
    const chunks: Buffer[] = [];
    let size = 0;
    req.on('data', (c: Buffer) => {
      size += c.length;
      if (size > MAX_BODY_BYTES) {
        reject(new ServiceError(413, 'too_large', `request body above ${MAX_BODY_BYTES} bytes`));
        req.destroy();
        return;
      }
      chunks.push(c);
    });
    req.on('end', () => {
      try {
        resolve(JSON.parse(Buffer.concat(chunks).toString('utf8') || 'null'));
      } catch (e) {
        reject(new ServiceError(400, 'bad_request', `invalid JSON: ${(e as Error).message}`));
      }
    });
    req.on('error', reject);
  });
}

export function afterSeq(req: IncomingMessage, url: URL): number {
  const raw = req.headers['last-event-id'] ?? url.searchParams.get('after') ?? '0';
  const n = Number(Array.isArray(raw) ? raw[0] : raw);
  return Number.isInteger(n) && n > 0 ? n : 0;
}

function logText(lines: LineEvent[]): string {
  return lines.map((l) => `${new Date(l.t).toISOString()} ${l.step} ${l.source} ${l.stream} | ${l.line}\n`).join('');
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

export function createRouter(service: JobService, basePath: string) {
  return async function handle(req: IncomingMessage, res: ServerResponse): Promise<boolean> {
    const url = new URL(req.url ?? '/', 'http://localhost');
    if (url.pathname !== basePath && !url.pathname.startsWith(`${basePath}/`)) return false;
    const path = url.pathname.slice(basePath.length) || '/';
    const parts = path.split('/').filter(Boolean);
    const method = req.method ?? 'GET';
    try {
      if (parts[0] === 'health' && parts.length === 1 && method === 'GET') {
        send(res, 200, { ok: true, ...service.stats });
      } else if (parts[0] === 'sandboxes' && parts.length === 1 && method === 'GET') {
        const sandboxes = [];
        for (const name of ['bwrap', 'docker', 'none'] as const) sandboxes.push({ name, ...(await service.sandboxes.probe(name)) });
        let auto: string | null = null;
        try {
          auto = (await service.sandboxes.resolve('auto')).sandbox.name;
        } catch {
          auto = null;
        }
        send(res, 200, { default: service.defaultSandbox, auto, sandboxes, limits: service.limits });
      } else if (parts[0] === 'jobs' && parts.length === 1 && method === 'POST') {
        const job = await service.submit(await readJson(req), clientOwner(req));
        send(
          res,
          201,
          { id: job.id, status: job.status, sandbox: job.sandboxName, sandboxNote: job.sandboxNote, warnings: job.warnings },
          { Location: `${basePath}/jobs/${job.id}` },
        );
      } else if (parts[0] === 'jobs' && parts.length === 1 && method === 'GET') {
        // one client never sees another's jobs (SPEC §5): only those submitted with the same key
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
            void service.cancel(job.id);
            send(res, 202, { id: job.id, status: 'cancelling' });
          }
        } else if (sub === 'events' && parts.length === 3 && method === 'GET') streamSse(job, req, res, afterSeq(req, url));
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
          const file = job.artifact(name);
          if (!file) throw new ServiceError(404, 'not_found', `job ${job.id} has no artifact "${name}"${job.isDone ? '' : ' (yet: the job has not finished)'}`);
          res.writeHead(200, {
            'Content-Type': name.endsWith('.csv') ? 'text/csv; charset=utf-8' : 'application/octet-stream',
            'Content-Length': file.data.length,
            'Content-Disposition': `attachment; filename="${file.name}"`,
            'X-Content-Type-Options': 'nosniff',
          });
          res.end(file.data);
        } else throw new ServiceError(404, 'not_found', `no route ${method} ${url.pathname}`);
      } else {
        throw new ServiceError(404, 'not_found', `no route ${method} ${url.pathname}`);
      }
    } catch (e) {
      if (!res.headersSent) sendError(res, e);
      else res.end();
    }
    return true;
  };
}
