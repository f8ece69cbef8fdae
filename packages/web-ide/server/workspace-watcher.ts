import { watch, type FSWatcher } from 'node:fs';
import { basename } from 'node:path';
import type { ServerResponse } from 'node:http';
import { isAtomicTempFile } from './atomic-write.js';

/**
 * Watches the workspace folder recursively and pushes changed paths to every connected client as
 * Server-Sent Events (`event: change`, data `{"paths":[...]}`), batched over 60 ms.
 */
export class WorkspaceWatcher {
  private readonly clients = new Set<ServerResponse>();
  private watcher: FSWatcher | undefined;
  private pending = new Set<string>();
  private timer: NodeJS.Timeout | undefined;
  private readonly heartbeat: NodeJS.Timeout;

  constructor(root: string) {
    try {
      this.watcher = watch(root, { recursive: true }, (_event, name) => {
        if (!name) return;
        const rel = name.toString().split('\\').join('/');
        if (isAtomicTempFile(basename(rel)) || rel.split('/').some((p) => p === 'node_modules' || p === '.git')) return;
        this.pending.add(rel);
        this.timer ??= setTimeout(() => this.flush(), 60);
      });
      this.watcher.on('error', () => undefined);
    } catch {
      this.watcher = undefined; // watching unsupported: the IDE still works, without live updates
    }
    this.heartbeat = setInterval(() => {
      for (const c of this.clients) c.write(': ping\n\n');
    }, 15000);
    this.heartbeat.unref();
  }

  /** Registers an SSE client on a GET /api/events response. */
  attach(res: ServerResponse): void {
    res.writeHead(200, { 'content-type': 'text/event-stream', 'cache-control': 'no-store', connection: 'keep-alive' });
    res.write('event: hello\ndata: {}\n\n');
    this.clients.add(res);
    res.on('close', () => this.clients.delete(res));
  }

  /** Sends a custom event to every client (e.g. after Generate All). */
  broadcast(event: string, data: unknown): void {
    const msg = `event: ${event}\ndata: ${JSON.stringify(data)}\n\n`;
    for (const c of this.clients) c.write(msg);
  }

  private flush(): void {
    this.timer = undefined;
    const paths = [...this.pending];
    this.pending.clear();
    if (paths.length) this.broadcast('change', { paths });
  }

  close(): void {
    this.watcher?.close();
    clearInterval(this.heartbeat);
    if (this.timer) clearTimeout(this.timer);
    for (const c of this.clients) c.end();
    this.clients.clear();
  }
}
