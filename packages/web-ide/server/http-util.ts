import type { IncomingMessage, ServerResponse } from 'node:http';
import { JSON_BODY_NOT_OBJECT, parseJsonBody } from '@contract-studio/conventions';
import { HttpError } from './http-error.js';

const MAX_BODY = 16 * 1024 * 1024;

/** The request body as raw bytes (at most 16 MiB). */
/** How long a request body may take to arrive (the build service's requestBodySeconds): a client that sends a byte a minute holds nothing longer. */
export const BODY_SECONDS = 30;

export async function readBodyBytes(req: IncomingMessage, seconds = BODY_SECONDS): Promise<Buffer> {
  if (Number(req.headers['content-length']) > MAX_BODY) throw new HttpError(413, 'request body larger than 16 MiB');
  const chunks: Buffer[] = [];
  let size = 0;
  let late = false;
  const timer = setTimeout(() => {
    late = true;
    req.destroy(); // ends the read below
  }, seconds * 1000);
  try {
    for await (const chunk of req) {
      size += (chunk as Buffer).length;
      if (size > MAX_BODY) throw new HttpError(413, 'request body larger than 16 MiB');
      chunks.push(chunk as Buffer);
    }
  } catch (e) {
    if (late) throw new HttpError(408, `the request body did not arrive within ${seconds} s`);
    throw e;
  } finally {
    clearTimeout(timer);
  }
  if (late) throw new HttpError(408, `the request body did not arrive within ${seconds} s`);
  return Buffer.concat(chunks);
}

export async function readBody(req: IncomingMessage): Promise<string> {
  return (await readBodyBytes(req)).toString('utf8');
}

/**
 * The request's JSON object (an empty body: {}). Text that is not JSON is a 400 naming the
 * parser's error, as the build service answers it (the one reading: conventions' parseJsonBody):
 * `{ code: "bad_request", error: "invalid JSON: ..." }`; JSON that is no object, `the body must be a JSON object`.
 */
export async function readJson(req: IncomingMessage): Promise<Record<string, unknown>> {
  const parsed = parseJsonBody((await readBody(req)) || '{}');
  if (!parsed.ok) throw new HttpError(400, parsed.error, { code: 'bad_request' });
  const v = parsed.value;
  if (v === null || typeof v !== 'object' || Array.isArray(v)) throw new HttpError(400, JSON_BODY_NOT_OBJECT, { code: 'bad_request' });
  return v as Record<string, unknown>;
}

export function sendJson(res: ServerResponse, status: number, body: unknown): void {
  const text = JSON.stringify(body);
  res.writeHead(status, { 'content-type': 'application/json; charset=utf-8', 'cache-control': 'no-store' });
  res.end(text);
}

export function sendError(res: ServerResponse, e: unknown): void {
  if (e instanceof HttpError) return sendJson(res, e.status, { ...e.details, error: e.message });
  const err = e as NodeJS.ErrnoException;
  const byCode: Record<string, [number, string]> = {
    ENOENT: [404, 'not found'],
    EEXIST: [409, 'already exists'],
    ENOTDIR: [400, 'not a folder'],
    EISDIR: [400, 'is a folder'],
    ENOTEMPTY: [409, 'folder not empty'],
    EACCES: [403, 'permission denied'],
    ENOSPC: [507, 'disk full'],
  };
  const known = err && err.code ? byCode[err.code] : undefined;
  if (known) return sendJson(res, known[0], { error: `${known[1]}${err.path ? '' : ''}` });
  sendJson(res, 500, { error: `internal error: ${err?.message ?? String(e)}` });
}
