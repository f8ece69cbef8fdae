import { socketUrl } from '../api.js';

/**
 * The IDE server's events (GET /api/events, server/workspace-watcher.ts) over a WebSocket: file
 * changes, Generate All, the runs of other tabs. A WebSocket rather than an EventSource because a
 * browser opens at most six HTTP/1.1 connections to one server for all its tabs: six tabs each
 * holding a stream would leave none for their requests (docs/ide.md "Several tabs").
 * Every (re)connection begins with `hello`; a lost connection calls the `lost` listeners, then
 * connects again, 1 s after, then up to 5 s apart.
 */
export class ServerEvents {
  private readonly listeners = new Map<string, Array<(data: unknown) => void>>();
  private readonly lostListeners: Array<() => void> = [];
  private delay = 1000;

  constructor(private readonly path = '/api/events') {
    this.connect();
  }

  /** Calls `fn` with the data of every `event` (parsed JSON). */
  on(event: string, fn: (data: unknown) => void): void {
    const list = this.listeners.get(event) ?? [];
    list.push(fn);
    this.listeners.set(event, list);
  }

  /** Calls `fn` each time the connection is lost or could not be made. */
  onLost(fn: () => void): void {
    this.lostListeners.push(fn);
  }

  private connect(): void {
    const ws = new WebSocket(socketUrl(this.path));
    ws.onopen = () => (this.delay = 1000);
    ws.onmessage = (m) => {
      let msg: { event?: unknown; data?: unknown };
      try {
        msg = JSON.parse(String(m.data));
      } catch {
        return;
      }
      if (typeof msg.event !== 'string') return;
      for (const fn of this.listeners.get(msg.event) ?? []) {
        try {
          fn(msg.data);
        } catch (e) {
          console.error(`event ${msg.event}:`, e);
        }
      }
    };
    ws.onclose = () => {
      for (const fn of this.lostListeners) fn();
      setTimeout(() => this.connect(), this.delay);
      this.delay = Math.min(5000, this.delay * 2);
    };
  }
}
