/**
 * The standalone build service's secret (docs/build-service-api.md, "Token"): made at each
 * `listen()` unless one is given, returned by `listen()` and optionally written to a 0600 file;
 * every request and WebSocket upgrade must present it in the X-Contract-Token header, else 401.
 * Without it any local user or program could submit jobs — and `sandbox: "none"` jobs run as the
 * service's user. A server that mounts the service (`handle()`, the IDE) applies its own guard.
 */
import { createHash, randomBytes, timingSafeEqual } from 'node:crypto';
import { closeSync, constants, openSync, renameSync, unlinkSync, writeSync } from 'node:fs';
import type { IncomingMessage } from 'node:http';

export const TOKEN_HEADER = 'X-Contract-Token';

const digest = (text: string): Buffer => createHash('sha256').update(text).digest();

export class ServiceToken {
  private readonly hash: Buffer;

  constructor(readonly value: string = randomBytes(32).toString('base64url')) {
    if (value.length < 16) throw new Error('the build service token needs at least 16 characters');
    this.hash = digest(value);
  }

  /** True when the request carries the token in X-Contract-Token (compared in constant time). */
  presented(req: IncomingMessage): boolean {
    const raw = req.headers[TOKEN_HEADER.toLowerCase()];
    const candidate = Array.isArray(raw) ? raw[0] : raw;
    return typeof candidate === 'string' && timingSafeEqual(digest(candidate), this.hash);
  }

  /**
   * Writes the token to `path`, readable by its owner only: into a new file (`O_CREAT|O_EXCL|
   * O_NOFOLLOW`, 0600) beside it, renamed over `path`. A file someone else made there beforehand
   * (and may hold open, or own and re-read) is replaced, never written into; a link there is
   * replaced, never followed. Throws a sentence naming the path when that cannot be done.
   */
  writeTo(path: string): void {
    const temp = `${path}.tmp-${process.pid}-${randomBytes(6).toString('hex')}`;
    let fd: number;
    try {
      fd = openSync(temp, constants.O_WRONLY | constants.O_CREAT | constants.O_EXCL | constants.O_NOFOLLOW, 0o600);
    } catch (e) {
      throw new Error(`cannot write the token file ${path}: ${(e as NodeJS.ErrnoException).code ?? (e as Error).message} (a folder you can write to?)`);
    }
    try {
      writeSync(fd, `${this.value}\n`);
    } finally {
      closeSync(fd);
    }
    try {
      renameSync(temp, path);
    } catch (e) {
      try {
        unlinkSync(temp);
      } catch {
        // already gone
      }
      throw new Error(`cannot write the token file ${path}: ${(e as NodeJS.ErrnoException).code ?? (e as Error).message} (a file of another user, or a folder, in its place? remove it or choose another path)`);
    }
  }
}

/** The 401 answer's body: says what is missing without telling anything else. */
export function unauthorizedBody(req: IncomingMessage): { error: string; code: 'unauthorized' } {
  const sent = req.headers[TOKEN_HEADER.toLowerCase()] !== undefined;
  return {
    error: `${sent ? 'wrong' : 'missing'} ${TOKEN_HEADER} header: this build service requires the token given when it was started (docs/build-service-api.md, "Token")`,
    code: 'unauthorized',
  };
}
