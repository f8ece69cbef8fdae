/**
 * createBuildServer(options): the build service's HTTP server (127.0.0.1 by default), usable on
 * its own (`listen()`) or mounted into another server (`handle()` + `handleUpgrade()`).
 */
import { createServer, type IncomingMessage, type Server, type ServerResponse } from 'node:http';
import type { AddressInfo } from 'node:net';
import type { Duplex } from 'node:stream';
import { afterSeq, createRouter } from './http/router.js';
import { JobWebSockets } from './http/ws.js';
import { JobService, type BuildServiceOptions } from './job-service.js';

export interface BuildServerOptions extends BuildServiceOptions {
  /** Default 127.0.0.1: the service is reachable from this machine only. */
  host?: string;
  /** Default 7391; 0 = any free port. */
  port?: number;
  /** Default '/api'. */
  basePath?: string;
}

export interface BuildServer {
  readonly service: JobService;
  /** Handles a request under basePath; resolves false when the path is not the service's. */
  handle(req: IncomingMessage, res: ServerResponse): Promise<boolean>;
  /** Handles a WebSocket upgrade for `${basePath}/jobs/:id/ws`; false when not ours. */
  handleUpgrade(req: IncomingMessage, socket: Duplex, head: Buffer): boolean;
  listen(): Promise<{ url: string; host: string; port: number }>;
  close(): Promise<void>;
}

export const DEFAULT_PORT = 7391;

export function createBuildServer(options: BuildServerOptions = {}): BuildServer {
  const basePath = (options.basePath ?? '/api').replace(/\/$/, '');
  const service = new JobService(options);
  const route = createRouter(service, basePath);
  const sockets = new JobWebSockets(service);
  let server: Server | null = null;

  const handleUpgrade = (req: IncomingMessage, socket: Duplex, head: Buffer): boolean => {
    const url = new URL(req.url ?? '/', 'http://localhost');
    const m = new RegExp(`^${basePath.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}/jobs/([^/]+)/ws$`).exec(url.pathname);
    if (!m) return false;
    if (!sockets.upgrade(m[1]!, afterSeq(req, url), req, socket, head)) {
      socket.end('HTTP/1.1 404 Not Found\r\nContent-Length: 0\r\n\r\n');
    }
    return true;
  };

  return {
    service,
    handle: route,
    handleUpgrade,
    async listen() {
      const host = options.host ?? '127.0.0.1';
      server = createServer((req, res) => {
        void route(req, res).then((handled) => {
          if (!handled) {
            res.writeHead(404, { 'Content-Type': 'application/json' });
            res.end(JSON.stringify({ error: `no route ${req.method} ${req.url}`, code: 'not_found' }));
          }
        });
      });
      server.on('upgrade', (req, socket, head) => {
        if (!handleUpgrade(req, socket, head)) socket.destroy();
      });
      await new Promise<void>((resolve, reject) => {
        server!.once('error', reject);
        server!.listen(options.port ?? DEFAULT_PORT, host, () => resolve());
      });
      const addr = server.address() as AddressInfo;
      const shown = addr.family === 'IPv6' ? `[${addr.address}]` : addr.address;
      return { url: `http://${shown}:${addr.port}`, host: addr.address, port: addr.port };
    },
    async close() {
      sockets.close();
      await service.close();
      if (server) {
        server.closeAllConnections();
        await new Promise<void>((resolve) => server!.close(() => resolve()));
      }
    },
  };
}
