import type { IncomingMessage } from 'node:http';
import { HttpError } from './http-error.js';

const LOOPBACK = new Set(['localhost', '127.0.0.1', '[::1]', '::1']);

function hostnameOf(hostHeader: string): string {
  if (hostHeader.startsWith('[')) return hostHeader.slice(0, hostHeader.indexOf(']') + 1);
  const i = hostHeader.lastIndexOf(':');
  return (i < 0 ? hostHeader : hostHeader.slice(0, i)).toLowerCase();
}

/**
 * Protects a localhost server from other web sites open in the same browser:
 * - DNS rebinding: the Host header must name the loopback address (or the address we bind);
 * - cross-site requests: a state-changing request or a WebSocket upgrade (which browsers do not
 *   hold to the same-origin policy: a foreign page may open a socket to us and read it) that
 *   carries an Origin must come from our own host; an opaque `null` origin is refused; JSON bodies
 *   must be sent as application/json (which a foreign page cannot do without a CORS preflight,
 *   and we answer no preflight).
 * Another local user or program is kept out by the session token (session-token.ts), not here.
 */
export function guardRequest(req: IncomingMessage, boundHost: string): void {
  const host = req.headers.host ?? '';
  const name = hostnameOf(host);
  if (!LOOPBACK.has(name) && name !== boundHost.toLowerCase() && name !== `[${boundHost.toLowerCase()}]`) {
    throw new HttpError(403, `Host ${host || '(none)'} not allowed: open the IDE through its own address`);
  }
  const upgrade = req.headers.upgrade !== undefined;
  if ((req.method === 'GET' || req.method === 'HEAD') && !upgrade) return;
  const origin = req.headers.origin;
  if (origin && origin !== 'null') {
    let originHost = '';
    try {
      originHost = new URL(origin).host;
    } catch {
      /* malformed origin: refused below */
    }
    if (originHost !== host) throw new HttpError(403, `cross-site request from ${origin} refused`);
  } else if (origin === 'null') {
    throw new HttpError(403, 'cross-site request from an opaque origin refused');
  }
  if (req.method === 'POST' && req.headers['content-length'] !== '0' && !String(req.headers['content-type'] ?? '').startsWith('application/json')) {
    throw new HttpError(415, 'POST bodies must be application/json');
  }
}
