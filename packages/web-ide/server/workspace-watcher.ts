import { watch, readdirSync, type FSWatcher } from 'node:fs';
import { RENAME_JOURNAL_NAME, TREE_LOCK_NAME } from '@contract-studio/conventions';
import { basename, join } from 'node:path';
import type { ServerResponse } from 'node:http';
import type { WebSocket } from 'ws';
import { isAtomicTempFile } from './atomic-write.js';

const SKIPPED = new Set(['node_modules', '.git', '.vite', TREE_LOCK_NAME, RENAME_JOURNAL_NAME]);

/**
 * Watches the workspace folder and pushes changed paths to every connected client, batched over
 * 60 ms: `change` with `{"paths":[...]}` (and the events others broadcast), as Server-Sent Events
 * (GET /api/events: `event: change`) or WebSocket text frames (`{"event":"change","data":{...}}`,
 * what the IDE page uses: docs/ide.md "Several tabs").
 * One non-recursive watcher per folder: a folder watch keeps reporting a file that is replaced
 * by rename (atomic writes), which Node's recursive mode on Linux (one watch per file inode) loses.
 */
export class WorkspaceWatcher {
  private readonly clients = new Set<ServerResponse>();
  private readonly sockets = new Set<WebSocket>();
  private readonly watchers = new Map<string, FSWatcher>();
  private pending = new Set<string>();
  private timer: NodeJS.Timeout | undefined;
  private readonly heartbeat: NodeJS.Timeout;
  private closed = false;

  constructor(private readonly root: string) {
    this.watchTree('');
    this.heartbeat = setInterval(() => {
      for (const c of this.clients) c.write(': ping\n\n');
      for (const ws of this.sockets) ws.ping();
    }, 15000);
    this.heartbeat.unref();
  }

  /**
   * Watches folder `rel` and the folders under it. `announce`: a folder that appeared since the
   * last flush — what was made in it before its watcher was set (a run's `logs/` and its first
   * CSV files, made within a few ms) is told as changed too, at the next flush.
   */
  private watchTree(rel: string, announce = false): void {
    if (this.closed || this.watchers.has(rel)) return;
    const abs = rel ? join(this.root, rel) : this.root;
    let entries;
    try {
      entries = readdirSync(abs, { withFileTypes: true });
      const w = watch(abs, (_event, name) => this.onEvent(rel, name?.toString()));
      w.on('error', () => this.unwatch(rel));
      this.watchers.set(rel, w);
    } catch {
      return; // folder gone or unreadable: nothing to watch
    }
    for (const e of entries) {
      if (SKIPPED.has(e.name) || isAtomicTempFile(e.name)) continue;
      const child = rel ? `${rel}/${e.name}` : e.name;
      if (announce) this.pending.add(child);
      if (e.isDirectory()) this.watchTree(child, announce);
    }
    if (announce && this.pending.size) this.timer ??= setTimeout(() => this.flush(), 60);
  }

  private unwatch(rel: string): void {
    for (const [k, w] of this.watchers) {
      if (k === rel || k.startsWith(rel + '/')) {
        w.close();
        this.watchers.delete(k);
      }
    }
  }

  private onEvent(dirRel: string, name: string | undefined): void {
    if (!name || isAtomicTempFile(basename(name)) || SKIPPED.has(name)) return;
    const rel = dirRel ? `${dirRel}/${name}` : name;
    this.pending.add(rel);
    this.timer ??= setTimeout(() => this.flush(), 60);
  }

  /** Registers an SSE client on a GET /api/events response; `greeting`: events it gets first, after `hello`. */
  attach(res: ServerResponse, greeting: Array<{ event: string; data: unknown }> = []): void {
    res.writeHead(200, { 'content-type': 'text/event-stream', 'cache-control': 'no-store', connection: 'keep-alive' });
    res.write('event: hello\ndata: {}\n\n');
    for (const g of greeting) res.write(`event: ${g.event}\ndata: ${JSON.stringify(g.data)}\n\n`);
    this.clients.add(res);
    res.on('close', () => this.clients.delete(res));
  }

  /** Registers a WebSocket client (GET /api/events upgraded); `greeting` as for attach(). */
  attachSocket(ws: WebSocket, greeting: Array<{ event: string; data: unknown }> = []): void {
    // a client's protocol error is emitted as 'error': without a listener it would end the server
    ws.on('error', () => ws.terminate());
    ws.on('close', () => this.sockets.delete(ws));
    for (const g of [{ event: 'hello', data: {} }, ...greeting]) ws.send(JSON.stringify(g));
    this.sockets.add(ws);
  }

  /** Sends a custom event to every client (e.g. after Generate All). */
  broadcast(event: string, data: unknown): void {
    const json = JSON.stringify(data);
    const msg = `event: ${event}\ndata: ${json}\n\n`;
    for (const c of this.clients) c.write(msg);
    const frame = `{"event":${JSON.stringify(event)},"data":${json}}`;
    for (const ws of this.sockets) ws.send(frame, () => {}); // a send on a closing socket reports here
  }

  private flush(): void {
    this.timer = undefined;
    // new folders get a watcher, removed ones lose theirs
    const changed = [...this.pending];
    this.pending.clear();
    for (const rel of changed) {
      this.unwatchIfGone(rel);
      this.watchTree(rel, true);
    }
    // what new folders held when their watchers were set is told with them
    const paths = [...new Set([...changed, ...this.pending])];
    this.pending.clear();
    if (this.timer) {
      clearTimeout(this.timer);
      this.timer = undefined;
    }
    if (paths.length) this.broadcast('change', { paths });
  }

  private unwatchIfGone(rel: string): void {
    if (!this.watchers.has(rel)) return;
    try {
      readdirSync(join(this.root, rel));
    } catch {
      this.unwatch(rel);
    }
  }

  close(): void {
    this.closed = true;
    for (const w of this.watchers.values()) w.close();
    this.watchers.clear();
    clearInterval(this.heartbeat);
    for (const ws of this.sockets) ws.terminate();
    this.sockets.clear();
    if (this.timer) clearTimeout(this.timer);
    for (const c of this.clients) c.end();
    this.clients.clear();
  }
}
