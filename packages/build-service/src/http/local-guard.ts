/**
 * Host / Origin checks of the standalone build service (docs/build-service-api.md, "Browsers and
 * other sites"); the web IDE, which mounts the service, applies its own (web-ide
 * server/request-guard.ts) and a session token before handing requests over.
 * - DNS rebinding: the Host header must name a loopback address or the bound address;
 * - cross-site requests: a state-changing request or a WebSocket upgrade (not covered by the
 *   same-origin policy: a foreign page may open a socket and read the job's events, or cancel it)
 *   that carries an Origin must come from our own host; an opaque `null` origin is refused.
 */
import type { IncomingMessage } from 'node:http';

const LOOPBACK = new Set(['localhost', '127.0.0.1', '[::1]', '::1']);

function hostnameOf(hostHeader: string): string {
  if (hostHeader.startsWith('[')) return hostHeader.slice(0, hostHeader.indexOf(']') + 1).toLowerCase();
  const i = hostHeader.lastIndexOf(':');
  return (i < 0 ? hostHeader : hostHeader.slice(0, i)).toLowerCase();
}

/** Why the request must be refused (403), or undefined when it may go on. */
export function foreignRequest(req: IncomingMessage, boundHost: string): string | undefined {
  const host = req.headers.host ?? '';
  const name = hostnameOf(host);
  const bound = boundHost.toLowerCase();
  if (!LOOPBACK.has(name) && name !== bound && name !== `[${bound}]`) {
    return `Host ${host || '(none)'} not allowed: use the service's own address`;
  }
  const upgrade = req.headers.upgrade !== undefined;
  if ((req.method === 'GET' || req.method === 'HEAD') && !upgrade) return undefined;
  const origin = req.headers.origin;
  if (origin === undefined) return undefined; // not a browser
  if (origin === 'null') return 'cross-site request from an opaque origin refused';
  let originHost = '';
  try {
    originHost = new URL(origin).host;
  } catch {
    /* malformed: refused below */
  }
  return originHost === host ? undefined : `cross-site request from ${origin} refused`;
}
