/**
 * GET /api/jobs/:id/ws: the same events as the SSE stream as WebSocket JSON text frames
 * ({type, seq, t, ...}), replay included; the client may send {"type":"cancel"}.
 */
import type { IncomingMessage } from 'node:http';
import type { Duplex } from 'node:stream';
import { WebSocketServer } from 'ws';
import type { JobService } from '../job-service.js';

export class JobWebSockets {
  private readonly wss = new WebSocketServer({ noServer: true });

  constructor(private readonly service: JobService) {}

  /** Handles an upgrade for a job id; returns false when the job does not exist. */
  upgrade(id: string, after: number, req: IncomingMessage, socket: Duplex, head: Buffer): boolean {
    const job = this.service.get(id);
    if (!job) return false;
    this.wss.handleUpgrade(req, socket, head, (ws) => {
      const unsubscribe = job.events.subscribe(after, (e) => {
        ws.send(JSON.stringify(e));
        if (e.type === 'end') setImmediate(() => ws.close(1000, 'job ended'));
      });
      ws.on('message', (data) => {
        try {
          const msg = JSON.parse(String(data)) as { type?: string };
          if (msg.type === 'cancel') void this.service.cancel(id);
        } catch {
          /* ignore malformed client frames */
        }
      });
      ws.on('close', unsubscribe);
      if (job.events.isEnded) setImmediate(() => ws.close(1000, 'job ended'));
    });
    return true;
  }

  close(): void {
    for (const c of this.wss.clients) c.terminate();
    this.wss.close();
  }
}
