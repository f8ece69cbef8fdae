/** A request body that arrives too slowly (a byte a minute) is refused with 408, not waited for forever. */
import { describe, expect, it } from 'vitest';
import { PassThrough } from 'node:stream';
import type { IncomingMessage } from 'node:http';
import { readBodyBytes } from './http-util.js';
import { HttpError } from './http-error.js';

const request = (headers: Record<string, string> = {}) => Object.assign(new PassThrough(), { headers }) as unknown as IncomingMessage & PassThrough;

describe('readBodyBytes', () => {
  it('refuses a body that has not arrived within its time (408), the request destroyed', async () => {
    const req = request({ 'content-length': '1000' });
    req.write('x');
    const started = Date.now();
    const err = await readBodyBytes(req, 0.3).then(() => undefined, (e: unknown) => e);
    expect(err).toBeInstanceOf(HttpError);
    expect((err as HttpError).status).toBe(408);
    expect((err as HttpError).message).toBe('the request body did not arrive within 0.3 s');
    expect(Date.now() - started).toBeLessThan(2000);
    expect(req.destroyed).toBe(true);
  });

  it('reads a body that arrives in time, and refuses a declared length over the bound at once', async () => {
    const req = request();
    req.end('hello');
    expect((await readBodyBytes(req, 1)).toString()).toBe('hello');
    const big = request({ 'content-length': String(64 * 1024 * 1024) });
    const err = await readBodyBytes(big, 1).then(() => undefined, (e: unknown) => e);
    expect((err as HttpError).status).toBe(413);
  });
});
