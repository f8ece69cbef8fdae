/**
 * How far behind a streaming client may fall (http/sse.ts, http/ws.ts): its replay (the events up
 * to now, sent at once when it attaches) may sit in its socket's buffer whole; beyond that, at most
 * `bound` bytes of live events (SERVICE_BOUNDS.streamBufferedBytes). A client past it is dropped:
 * the live trace of a 1 kHz schema is megabytes a second, and a stalled monitor must not grow the
 * service's memory without end (it may resume from its last event).
 */
export class LiveBacklog {
  /** Bytes sent during the replay; null while the replay runs. */
  private replayed: number | null = null;
  private written = 0;

  constructor(private readonly bound: number) {}

  /** A frame of `bytes` was handed to the socket. */
  sent(bytes: number): void {
    if (this.replayed === null) this.written += bytes;
  }

  /** The replay is over: from now on the socket's buffer may hold it plus `bound`. */
  replayDone(): void {
    this.replayed = this.written;
  }

  /** Whether a client with `buffered` bytes still unsent in its socket is too far behind. */
  tooFarBehind(buffered: number): boolean {
    return this.replayed !== null && buffered > this.replayed + this.bound;
  }
}
