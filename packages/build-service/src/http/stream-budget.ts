/**
 * What all the streaming clients of one server (SSE and WebSocket, http/sse.ts, http/ws.ts) may
 * leave unread in their sockets' buffers together: SERVICE_BOUNDS.streamsBufferedBytes. Each
 * client's own bound (LiveBacklog) keeps one stalled client from growing the service's memory
 * without end, but not thirty of them: each held its share of a 1 kHz run's trace (15-20 MB) and
 * the service grew by half a gigabyte. Past the budget, the client with the most unread bytes is
 * dropped (it may resume from its last event id), until the rest fit.
 */
export interface StreamShare {
  /** The client's socket holds `buffered` bytes not yet sent (after a write to it). */
  holds(buffered: number): void;
  /** The client is gone. */
  leave(): void;
}

export class StreamBudget {
  private readonly clients = new Set<{ buffered: number; drop: () => void }>();
  private total = 0;

  constructor(readonly bound: number) {}

  /** The unread bytes of all the clients, as last told. */
  get held(): number {
    return this.total;
  }

  /** A new client; `drop` disconnects it (called at most once, after which it has left). */
  join(drop: () => void): StreamShare {
    const me = { buffered: 0, drop };
    this.clients.add(me);
    const leave = (): void => {
      if (!this.clients.delete(me)) return;
      this.total -= me.buffered;
      me.buffered = 0;
    };
    return {
      holds: (buffered) => {
        if (!this.clients.has(me)) return;
        this.total += buffered - me.buffered;
        me.buffered = buffered;
        this.fit();
      },
      leave,
    };
  }

  /** Drops the clients with the most unread bytes until the others fit in the budget. */
  private fit(): void {
    while (this.total > this.bound) {
      let worst: { buffered: number; drop: () => void } | undefined;
      for (const c of this.clients) if (!worst || c.buffered > worst.buffered) worst = c;
      if (!worst || worst.buffered === 0) return;
      this.clients.delete(worst);
      this.total -= worst.buffered;
      worst.buffered = 0;
      worst.drop();
    }
  }
}
