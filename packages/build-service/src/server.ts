/**
 * createBuildServer(options): the build service's HTTP server (127.0.0.1 by default), usable on
 * its own (`listen()`) or mounted into another server (`handle()` + `handleUpgrade()`). `listen()`
 * refuses foreign Hosts and cross-site Origins (http/local-guard.ts), requires the service token
 * on every request and upgrade (http/service-token.ts) and refuses `sandbox: "none"` jobs unless
 * `allowNoneSandbox`; a server that mounts the service applies its own checks before calling
 * `handle()` / `handleUpgrade()` (docs/build-service-api.md, "Token").
 */
import { createServer, type IncomingMessage, type Server, type ServerResponse } from 'node:http';
import type { AddressInfo } from 'node:net';
import type { Duplex } from 'node:stream';
import { AFTER_ERROR, afterSeq, createRouter } from './http/router.js';
import { StreamBudget } from './http/stream-budget.js';
import { SERVICE_BOUNDS } from './limits.js';
import { BATCH_ERROR, JobWebSockets, TRACE_FILTER_ERROR, batchParam, traceFilter } from './http/ws.js';
import { foreignRequest } from './http/local-guard.js';
import { ServiceToken, unauthorizedBody } from './http/service-token.js';
import { JobService, type BuildServiceOptions } from './job-service.js';

export interface BuildServerOptions extends BuildServiceOptions {
  /** Default 127.0.0.1: the service is reachable from this machine only. */
  host?: string;
  /** Default 7391; 0 = any free port. */
  port?: number;
  /** Default '/api'. */
  basePath?: string;
  /**
   * `listen()` only: the token every request and WebSocket upgrade must send in X-Contract-Token
   * (at least 16 characters). Default: a random one per start, returned by `listen()`.
   * `false` turns the check off (tests, or a front that guards the service itself).
   */
  token?: string | false;
  /** `listen()` only: a file to write the token to, mode 0600 (e.g. in $XDG_RUNTIME_DIR). */
  tokenFile?: string;
  /**
   * `listen()` only: accept `sandbox: "none"` jobs (no isolation: they run as the service's user).
   * Default false: such jobs are refused with 403. Mounted (`handle()`), the caller decides.
   */
  allowNoneSandbox?: boolean;
  /**
   * Every job runs in this sandbox (`contract serve --sandbox bwrap|docker`, the IDE's choice made
   * for all its jobs): a job naming another one (`none` and `auto` too) is refused with 403, one
   * naming none gets it (as the default `sandbox`, which it should be). Both `handle()` and `listen()`.
   */
  onlySandbox?: 'bwrap' | 'docker';
}

export interface BuildServer {
  readonly service: JobService;
  /** Handles a request under basePath; resolves false when the path is not the service's. */
  handle(req: IncomingMessage, res: ServerResponse): Promise<boolean>;
  /** Handles a WebSocket upgrade for `${basePath}/jobs/:id/ws`; false when not ours. */
  handleUpgrade(req: IncomingMessage, socket: Duplex, head: Buffer): boolean;
  /** Resolves the URL and the token clients must send (null when started with `token: false`). */
  listen(): Promise<{ url: string; host: string; port: number; token: string | null }>;
  close(): Promise<void>;
}

/** A 400 before the upgrade, its body `why` (text): the socket is closed; true (the request was ours). */
function refuseUpgrade(socket: Duplex, why: string): true {
  const body = `${why}\n`;
  socket.end(`HTTP/1.1 400 Bad Request\r\nConnection: close\r\nContent-Type: text/plain; charset=utf-8\r\nContent-Length: ${Buffer.byteLength(body)}\r\n\r\n${body}`);
  return true;
}

export const DEFAULT_PORT = 7391;

/**
 * The answer to a request the HTTP parser refused ('clientError'): Node's own status (431 headers
 * too large, 408 request timeout, else 400) with a JSON body {error, code} where the socket can
 * still be written to; the connection is closed. Exported for a server that mounts the service.
 */
export function answerClientError(err: NodeJS.ErrnoException, socket: Duplex): void {
  if (err.code === 'ECONNRESET' || !socket.writable) {
    socket.destroy();
    return;
  }
  const [status, reason, code] =
    err.code === 'HPE_HEADER_OVERFLOW'
      ? [431, 'Request Header Fields Too Large', 'bad_request']
      : err.code === 'ERR_HTTP_REQUEST_TIMEOUT'
        ? [408, 'Request Timeout', 'timeout']
        : [400, 'Bad Request', 'bad_request'];
  const what = (err as { reason?: string }).reason ?? err.message;
  const body = JSON.stringify({ error: `malformed HTTP request: ${String(what).slice(0, 200)}${err.code ? ` (${err.code})` : ''}`, code });
  socket.end(`HTTP/1.1 ${status} ${reason}\r\nConnection: close\r\nContent-Type: application/json; charset=utf-8\r\nContent-Length: ${Buffer.byteLength(body)}\r\n\r\n${body}`);
}

export function createBuildServer(options: BuildServerOptions = {}): BuildServer {
  const basePath = (options.basePath ?? '/api').replace(/\/$/, '');
  const service = new JobService(options);
  // what all the streaming clients of this server may leave unread together (http/stream-budget.ts)
  const budget = new StreamBudget(SERVICE_BOUNDS.streamsBufferedBytes);
  const route = createRouter(service, basePath, budget);
  const sockets = new JobWebSockets(service, budget);
  let server: Server | null = null;
  const token = options.token === false ? null : new ServiceToken(options.token);
  const only = options.onlySandbox ? { onlySandbox: options.onlySandbox } : {};
  const standalone = { allowNoneSandbox: options.allowNoneSandbox === true, ...only };
  const mounted = { allowNoneSandbox: true, ...only };

  const handleUpgrade = (req: IncomingMessage, socket: Duplex, head: Buffer): boolean => {
    const url = new URL(req.url ?? '/', 'http://localhost');
    const m = new RegExp(`^${basePath.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}/jobs/([^/]+)/ws$`).exec(url.pathname);
    if (!m) return false;
    const trace = traceFilter(url);
    if (!trace) return refuseUpgrade(socket, TRACE_FILTER_ERROR);
    const batch = batchParam(url);
    if (batch === null) return refuseUpgrade(socket, BATCH_ERROR);
    const after = afterSeq(req, url);
    if (after === null) return refuseUpgrade(socket, AFTER_ERROR);
    if (!sockets.upgrade(m[1]!, after, req, socket, head, trace, batch)) {
      socket.end('HTTP/1.1 404 Not Found\r\nConnection: close\r\nContent-Length: 0\r\n\r\n');
    }
    return true;
  };

  return {
    service,
    handle: (req, res) => route(req, res, mounted),
    handleUpgrade,
    async listen() {
      const host = options.host ?? '127.0.0.1';
      server = createServer((req, res) => {
        const refused = foreignRequest(req, host);
        if (refused) {
          res.writeHead(403, { 'Content-Type': 'application/json' });
          res.end(JSON.stringify({ error: refused, code: 'forbidden' }));
          return;
        }
        if (token && !token.presented(req)) {
          res.writeHead(401, { 'Content-Type': 'application/json', Connection: 'close' });
          res.end(JSON.stringify(unauthorizedBody(req)));
          return;
        }
        route(req, res, standalone)
          .then((handled) => {
            if (!handled) {
              res.writeHead(404, { 'Content-Type': 'application/json' });
              res.end(JSON.stringify({ error: `no route ${req.method} ${req.url}`, code: 'not_found' }));
            }
          })
          // a request's failure ends that request only, never the service
          .catch(() => res.destroy());
      });
      // a request Node's parser refuses (a malformed Content-Length, a bad header): a JSON
      // {error, code} as every other error (docs/build-service-api.md), not Node's empty 400
      server.on('clientError', (err: NodeJS.ErrnoException, socket: Duplex) => answerClientError(err, socket));
      server.on('upgrade', (req, socket, head) => {
        if (foreignRequest(req, host)) {
          socket.end('HTTP/1.1 403 Forbidden\r\nConnection: close\r\nContent-Length: 0\r\n\r\n');
          return;
        }
        if (token && !token.presented(req)) {
          socket.end('HTTP/1.1 401 Unauthorized\r\nConnection: close\r\nContent-Length: 0\r\n\r\n');
          return;
        }
        if (!handleUpgrade(req, socket, head)) socket.destroy();
      });
      await new Promise<void>((resolve, reject) => {
        server!.once('error', reject);
        server!.listen(options.port ?? DEFAULT_PORT, host, () => resolve());
      });
      const addr = server.address() as AddressInfo;
      const shown = addr.family === 'IPv6' ? `[${addr.address}]` : addr.address;
      if (token && options.tokenFile) token.writeTo(options.tokenFile);
      return { url: `http://${shown}:${addr.port}`, host: addr.address, port: addr.port, token: token?.value ?? null };
    },
    async close() {
      // the jobs end first (cancelled), so that every stream, SSE and WebSocket alike, gets its
      // job's `end` before its socket closes (1001 going away for a WebSocket still open)
      await service.close();
      await sockets.shutdown();
      if (server) {
        server.closeAllConnections();
        await new Promise<void>((resolve) => server!.close(() => resolve()));
      }
    },
  };
}
