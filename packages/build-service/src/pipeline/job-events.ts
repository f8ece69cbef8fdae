import type { GccDiagnostic } from './gcc-diagnostics.js';
import type { LimitHit } from '../limits.js';
import type { TraceLine } from '../trace/wire.js';

/** One whole record line of a module's CSV log: defined with its wire form (trace/wire.ts, browser-safe). */
export type { TraceLine };

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
/**
 * The run-time trace, live (docs/build-service-api.md "Trace channel"): the records the run's
 * modules wrote since the previous trace event, in mono_ns order across files; none lost, none
 * doubled, replayable from the start like the log lines.
 */
export interface TraceEvent {
  type: 'trace';
  seq: number;
  t: number;
  records: TraceLine[];
  /**
   * On the first trace event of an ended job whose trace records were let go (JobEvents.dropTrace:
   * older than the service's traceReplayEndedJobs newest ended jobs): how many records its trace
   * events held. They are in the job's collected CSV logs; its other events are kept.
   */
  dropped?: number;
}
export type JobEvent = LineEvent | StatusEvent | DiagnosticEvent | LimitEvent | TraceEvent | EndEvent;
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
  /** Told the number of subscribers when it changes (the live trace's flush delay follows it). */
  onSubscribers: ((count: number) => void) | null = null;

  private changed(): void {
    try {
      this.onSubscribers?.(this.subscribers.size);
    } catch {
      /* a listener's fault is not the stream's */
    }
  }

  get isEnded(): boolean {
    return this.ended;
  }

  /** Clients attached now. */
  get subscriberCount(): number {
    return this.subscribers.size;
  }

  get all(): readonly JobEvent[] {
    return this.events;
  }

  /**
   * Lets the trace records of an ended job go (the server's memory: a 1 kHz run keeps 50,000 of
   * them, about 20 MB): its trace events stay, with their seq, but empty; the first says how many
   * records were let go (`dropped`). Every other event is kept. Returns that number (0: nothing to
   * let go, or the job has not ended).
   */
  dropTrace(): number {
    if (!this.ended) return 0;
    let dropped = 0;
    let first = -1;
    for (let i = 0; i < this.events.length; i++) {
      const e = this.events[i]!;
      if (e.type !== 'trace' || e.records.length === 0) continue;
      dropped += e.records.length;
      if (first < 0) first = i;
      this.events[i] = { type: 'trace', seq: e.seq, t: e.t, records: [] };
    }
    if (first >= 0) (this.events[first] as TraceEvent).dropped = dropped + ((this.events[first] as TraceEvent).dropped ?? 0);
    return dropped;
  }

  append(payload: Payload<JobEvent>): JobEvent {
    if (this.ended) throw new Error('job event log already ended');
    const event = { ...payload, seq: this.events.length + 1, t: Date.now() } as JobEvent;
    this.events.push(event);
    if (event.type === 'end') this.ended = true;
    this.deliver(event);
    if (this.ended && this.subscribers.size) {
      this.subscribers.clear();
      this.changed();
    }
    return event;
  }

  /** Hands `event` to every subscriber; one that throws is dropped (a gone client). */
  private deliver(event: JobEvent): void {
    for (const s of [...this.subscribers]) {
      try {
        s(event);
      } catch {
        this.subscribers.delete(s);
        this.changed();
      }
    }
  }

  /**
   * Delivers an event to the subscribers attached now without keeping it (the live trace beyond
   * the service's traceLinesKept bound, docs/build-service-api.md "Trace channel"): it carries the
   * seq of the last kept event, so a client resuming from it gets the kept events only.
   */
  broadcast(payload: Payload<JobEvent>): void {
    if (this.ended || this.subscribers.size === 0) return;
    const event = { ...payload, seq: this.events.length, t: Date.now() } as JobEvent;
    this.deliver(event);
  }

  /**
   * Replays every event with seq > afterSeq, then delivers live ones. Returns an unsubscribe
   * function. Replay and live delivery are synchronous, so no event is missed or doubled.
   */
  subscribe(afterSeq: number, subscriber: Subscriber): () => void {
    // a subscriber that throws (a client stream gone bad) is dropped, in replay as when live
    try {
      for (const e of this.events.slice(Math.max(0, afterSeq))) subscriber(e);
    } catch {
      return () => {};
    }
    if (this.ended) return () => {};
    this.subscribers.add(subscriber);
    this.changed();
    return () => {
      if (this.subscribers.delete(subscriber)) this.changed();
    };
  }
}
