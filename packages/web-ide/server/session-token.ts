import type { IncomingMessage } from 'node:http';
import { createHash, randomBytes, timingSafeEqual } from 'node:crypto';

/** The header a program sends the token in (the browser sends the cookie instead). */
export const TOKEN_HEADER = 'x-contract-token';

function digest(text: string): Buffer {
  return createHash('sha256').update(text).digest();
}

/**
 * The IDE server's per-session secret (docs/ide.md, "Session token"): made at start, printed by
 * `contract serve` in the URL to open (`/?token=...`). That first page load trades it for a cookie
 * (HttpOnly, SameSite=Strict: other sites' requests never carry it, page scripts never read it);
 * every /api request and WebSocket upgrade must then present it, as that cookie or in the
 * X-Contract-Token header. Without it, another local user or any local program could write the
 * workspace and run code as the IDE's user (`sandbox: "none"` jobs).
 */
export class SessionToken {
  private readonly hash: Buffer;
  /** Cookies ignore the port: one name per port, so two IDEs on one host keep their own. */
  private cookieName = 'contract_session';

  constructor(readonly value: string = randomBytes(32).toString('base64url')) {
    if (value.length < 16) throw new Error('the session token needs at least 16 characters');
    this.hash = digest(value);
  }

  bindPort(port: number): void {
    this.cookieName = `contract_session_${port}`;
  }

  /** True when `candidate` is the token (compared in constant time). */
  matches(candidate: string | undefined | null): boolean {
    return typeof candidate === 'string' && timingSafeEqual(digest(candidate), this.hash);
  }

  /** True when the request carries the token in the header or the cookie. */
  presented(req: IncomingMessage): boolean {
    const header = req.headers[TOKEN_HEADER];
    if (this.matches(Array.isArray(header) ? header[0] : header)) return true;
    return this.matches(this.cookieOf(req));
  }

  /** The Set-Cookie value that gives a browser the session. */
  setCookie(): string {
    return `${this.cookieName}=${this.value}; Path=/; HttpOnly; SameSite=Strict`;
  }

  private cookieOf(req: IncomingMessage): string | undefined {
    for (const part of (req.headers.cookie ?? '').split(';')) {
      const eq = part.indexOf('=');
      if (eq > 0 && part.slice(0, eq).trim() === this.cookieName) return part.slice(eq + 1).trim();
    }
    return undefined;
  }
}
