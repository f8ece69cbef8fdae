import type { GccDiagnostic } from './gcc-diagnostics.js';
import type { LimitHit } from '../limits.js';

export type JobStep = 'prepare' | 'build' | 'run';
export type JobStatus = 'queued' | 'preparing' | 'building' | 'running' | 'succeeded' | 'failed' | 'cancelled';
export type StreamName = 'stdout' | 'stderr' | 'system';

export interface LineEvent {
  type: 'line';
  seq: number;
  t: number;
  step: JobStep;
  /** 'service' | 'build' | '<MODULE>' | 'run' */
  source: string;
  stream: StreamName;
  line: string;
}
export interface StatusEvent {
  type: 'status';
  seq: number;
  t: number;
  status: JobStatus;
  step?: JobStep;
}
export interface DiagnosticEvent {
  type: 'diagnostic';
  seq: number;
  t: number;
  diagnostic: GccDiagnostic;
}
export interface LimitEvent {
  type: 'limit';
  seq: number;
  t: number;
  limitHit: LimitHit;
}
export interface EndEvent {
  type: 'end';
  seq: number;
  t: number;
  result: unknown;
}
export type JobEvent = LineEvent | StatusEvent | DiagnosticEvent | LimitEvent | EndEvent;
type Payload<E> = E extends JobEvent ? Omit<E, 'seq' | 't'> : never;

export type Subscriber = (event: JobEvent) => void;

/**
 * The append-only event log of one job: numbers events (seq from 1, no gaps), keeps all of them
 * (a finished job keeps its full log) and delivers them to subscribers, replaying the past first.
 */
export class JobEvents {
  private readonly events: JobEvent[] = [];
  private readonly subscribers = new Set<Subscriber>();
  private ended = false;

  get isEnded(): boolean {
    return this.ended;
  }

  get all(): readonly JobEvent[] {
    return this.events;
  }

  append(payload: Payload<JobEvent>): JobEvent {
    if (this.ended) throw new Error('job event log already ended');
    const event = { ...payload, seq: this.events.length + 1, t: Date.now() } as JobEvent;
    this.events.push(event);
    if (event.type === 'end') this.ended = true;
    for (const s of [...this.subscribers]) {
      try {
        s(event);
      } catch {
        this.subscribers.delete(s);
      }
    }
    if (this.ended) this.subscribers.clear();
    return event;
  }

  /**
   * Replays every event with seq > afterSeq, then delivers live ones. Returns an unsubscribe
   * function. Replay and live delivery are synchronous, so no event is missed or doubled.
   */
  subscribe(afterSeq: number, subscriber: Subscriber): () => void {
    for (const e of this.events.slice(Math.max(0, afterSeq))) subscriber(e);
    if (this.ended) return () => {};
    this.subscribers.add(subscriber);
    return () => this.subscribers.delete(subscriber);
  }
}
