/**
 * Reading JSON request bodies with bounded memory (docs/build-service-api.md, POST /api/jobs):
 * everything that can refuse a request (content type, declared length, a full service) is checked
 * from the headers, BEFORE any byte of the body is read; the body is then streamed with a running
 * cap, and at most SERVICE_BOUNDS.requestBodiesAtOnce bodies are held at once, so the memory the
 * service spends on bodies stays below that many times SERVICE_BOUNDS.requestBodyBytes.
 */
import type { IncomingMessage } from 'node:http';
import { SERVICE_BOUNDS } from '../limits.js';
import { ServiceError } from '../service-errors.js';
import { parseJsonBody } from '@contract-studio/conventions';

/** `Content-Type: application/json` (any parameters): a browser cannot send it cross-site without a preflight. */
function isJson(req: IncomingMessage): boolean {
  const type = (req.headers['content-type'] ?? '').split(';')[0]!.trim().toLowerCase();
  return type === 'application/json';
}

/** The declared length, null when the body is chunked; 400 on a malformed header. */
function declaredLength(req: IncomingMessage): number | null {
  const raw = req.headers['content-length'];
  if (raw === undefined) return null;
  if (!/^\d{1,16}$/.test(raw)) throw new ServiceError(400, 'bad_request', `bad Content-Length "${raw.slice(0, 40)}"`);
  return Number(raw);
}

export class BodyReader {
  private reading = 0;

  constructor(
    private readonly maxBytes = SERVICE_BOUNDS.requestBodyBytes,
    private readonly atOnce = SERVICE_BOUNDS.requestBodiesAtOnce,
    private readonly seconds = SERVICE_BOUNDS.requestBodySeconds,
  ) {}

  /** Bodies being read now (for tests and /api/health). */
  get active(): number {
    return this.reading;
  }

  /**
   * Checks the headers (415, 413, 503 `busy`) and takes one of the reading slots; `read()` then
   * streams the body and frees the slot. Throws ServiceError before anything is read.
   */
  admit(req: IncomingMessage): { read(): Promise<unknown> } {
    if (!isJson(req)) throw new ServiceError(415, 'unsupported_media_type', 'the body must be JSON with the header Content-Type: application/json');
    const length = declaredLength(req);
    if (length !== null && length > this.maxBytes) {
      throw new ServiceError(413, 'too_large', `request body of ${length} bytes is above the ${this.maxBytes}-byte limit`);
    }
    if (this.reading >= this.atOnce) {
      throw new ServiceError(503, 'busy', `${this.reading} request bodies are being read already (at most ${this.atOnce} at once); retry later`);
    }
    this.reading++;
    let released = false;
    const release = (): void => {
      if (!released) {
        released = true;
        this.reading--;
      }
    };
    return {
      read: () => readJson(req, length, this.maxBytes, this.seconds).finally(release),
    };
  }
}

function readJson(req: IncomingMessage, length: number | null, maxBytes: number, seconds: number): Promise<unknown> {
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => fail(new ServiceError(408, 'timeout', `the request body did not arrive within ${seconds} s`)), seconds * 1000);
    // one buffer of the declared size (no copies of every chunk), else chunks under the running cap
    const whole = length !== null ? Buffer.allocUnsafe(length) : null;
    const chunks: Buffer[] = [];
    let size = 0;
    let done = false;
    const fail = (e: Error): void => {
      if (done) return;
      done = true;
      clearTimeout(timer);
      reject(e);
      // a refused body is not read further: the answer goes out, then the connection closes
      req.pause();
    };
    req.on('data', (c: Buffer) => {
      if (done) return;
      const limit = length ?? maxBytes;
      if (size + c.length > limit) {
        fail(new ServiceError(length !== null ? 400 : 413, length !== null ? 'bad_request' : 'too_large', length !== null ? 'request body longer than its Content-Length' : `request body above ${maxBytes} bytes`));
        return;
      }
      if (whole) c.copy(whole, size);
      else chunks.push(c);
      size += c.length;
    });
    req.on('end', () => {
      if (done) return;
      done = true;
      clearTimeout(timer);
      const body = whole ? whole.subarray(0, size) : Buffer.concat(chunks, size);
      chunks.length = 0;
      const parsed = parseJsonBody(body.toString('utf8') || 'null');
      if (parsed.ok) resolve(parsed.value);
      else reject(new ServiceError(400, 'bad_request', parsed.error));
    });
    req.on('error', (e) => fail(e));
    req.on('close', () => fail(new ServiceError(400, 'bad_request', 'the request ended before its body')));
  });
}
