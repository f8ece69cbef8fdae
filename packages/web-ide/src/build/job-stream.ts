/**
 * A job's event stream over a WebSocket (GET /api/jobs/:id/ws, docs/build-service-api.md
 * "Events"): each frame parsed as a JSON event, and the stream taken up again after the last event
 * seen (`?after=`) when it breaks before the job's end (a network hiccup, the server restarting),
 * RETRIES times, 300 ms more apart each time; past that it is lost (a service that forgot the job).
 * Shared by the build panel (its log, diagnostics and status, `?trace=none`) and the Monitor's
 * live-run worker (the trace, `?trace=launcher`): no DOM, it runs in a worker too.
 * A socket opened with `batch=1` in its query gets its events several to a frame, a JSON array of
 * them in order (the build service sends at most one such frame every 50 ms while they stream:
 * a module printing 10,000 lines a second was 10,000 frames, each a task of the page's thread);
 * each is handled as if it had come alone.
 * Frames are hostile: one that is not a JSON object (or an array of them) is skipped, as is an
 * element of an array that is not one; a seq counts only when it is a whole number past the last.
 */

/** What a stream needs of a WebSocket (the browser's, or the `ws` package's in tests). */
export interface SocketLike {
  onmessage: ((m: MessageEvent) => void) | null;
  onclose: ((e: CloseEvent) => void) | null;
  close(): void;
}

/** A job event as it came: its fields are the reader's to check. */
export type StreamEvent = { type?: unknown; seq?: unknown } & Record<string, unknown>;

export interface JobStreamHandlers {
  event(e: StreamEvent): void;
  /** The stream broke for good, or could not be opened (`why`); nothing more comes. */
  lost(why?: string): void;
}

/** Times a broken stream is taken up again before it is lost. */
export const RETRIES = 5;

export class JobStream {
  private socket: SocketLike | undefined;
  private last: number;
  private retries = 0;
  private done = false;

  /** `url`: the stream's URL with its query (`?trace=…`); `after`: the last event already seen. */
  constructor(
    private readonly url: string,
    private readonly on: JobStreamHandlers,
    private readonly open: (url: string) => SocketLike = (u) => new WebSocket(u),
    after = 0,
  ) {
    this.last = after;
    this.connect();
  }

  /** No more events wanted (the job ended, or its follower moved on): closed, never taken up again. */
  close(): void {
    this.done = true;
    const ws = this.socket;
    this.socket = undefined;
    ws?.close();
  }

  /** One event of a frame. */
  private take(e: unknown): void {
    if (!e || typeof e !== 'object' || Array.isArray(e)) return;
    const ev = e as StreamEvent;
    if (typeof ev.seq === 'number' && Number.isSafeInteger(ev.seq) && ev.seq > this.last) this.last = ev.seq;
    this.retries = 0;
    this.on.event(ev);
  }

  private connect(): void {
    const url = this.last ? `${this.url}${this.url.includes('?') ? '&' : '?'}after=${this.last}` : this.url;
    let ws: SocketLike;
    try {
      ws = this.open(url);
    } catch (e) {
      this.done = true;
      return this.on.lost((e as Error).message);
    }
    this.socket = ws;
    ws.onmessage = (m) => {
      if (this.done || this.socket !== ws) return;
      let data: unknown;
      try {
        data = JSON.parse(String(m.data));
      } catch {
        return; // not an event of the service
      }
      if (!Array.isArray(data)) return this.take(data);
      for (const e of data) {
        // a handler may close the stream (the end) or move on: the frame's later events go with it
        if (this.done || this.socket !== ws) return;
        this.take(e);
      }
    };
    ws.onclose = () => {
      if (this.done || this.socket !== ws) return;
      if (this.retries < RETRIES) {
        const wait = 300 * ++this.retries;
        setTimeout(() => {
          if (!this.done && this.socket === ws) this.connect();
        }, wait);
        return;
      }
      this.done = true;
      this.socket = undefined;
      this.on.lost();
    };
  }
}
