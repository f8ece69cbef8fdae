/**
 * The Web Worker side of a live run (live-follow.worker.ts is its entry): opens the job's trace
 * stream itself (GET /api/jobs/:id/ws?trace=launcher, docs/build-service-api.md "Trace channel":
 * the trace and the launcher's own lines), decodes its batches and folds every record into a
 * MonitorModel, off the page's main thread; a launcher's line saying a module ended shows it gone
 * (MonitorModel.launcherLine).
 * The page gets a snapshot of the live state (and the new marks) at most every `snapshotMs`,
 * and the state at an earlier time when it asks for one (remote-model.ts).
 *
 * Everything read from the stream is hostile: a frame that is not JSON is skipped, a batch that
 * does not decode is skipped and said (problems), lines and batches are bounded.
 * A broken stream is taken up again after the last event seen (job-stream.ts, as for the build panel).
 */
import { NOT_A_LOG_WHY, forEachTraceLine, moduleOfLog } from '@contract-studio/build-service/trace';
import { JobStream, type SocketLike, type StreamEvent } from '../build/job-stream.js';
import { MonitorModel } from './monitor-model.js';
import { jobOutcome, CONNECTION_LOST, LOST_TRACE, type FromFollower, type Snapshot, type ToFollower } from './live-follow-protocol.js';

/** Bounds on what one trace event may bring (the producer sends far less per event). */
export const MAX_LINES_PER_EVENT = 100_000;
export const MAX_LINE = 4096;
const MAX_FILE_NAME = 200;
/** Least time between two snapshots to the page (one per frame at most). */
export const SNAPSHOT_MS = 16;
const MAX_PROBLEMS = 20;
/** Logs whose line numbers are followed for gaps (the service tails at most 256). */
const MAX_GAP_FILES = 1024;
/** A log's first record line: line 1 is its header (counted by the service, never sent). */
const FIRST_RECORD_LINE = 2;

export type { SocketLike };

export class LiveFollower {
  readonly model = new MonitorModel();
  private stream: JobStream | undefined;
  private ended = false;
  private stopped = false;
  private measure = false;
  private marksSent = 0;
  private postedVersion = -1;
  private lastPost = -Infinity;
  private postTimer: ReturnType<typeof setTimeout> | undefined;
  private readonly problems: string[] = [];
  private problemsSent = 0;
  /** measure only: each record's wall time and arrival since the last snapshot (buffers kept from one to the next) */
  private walls = new Float64Array(1024);
  private arrived = new Float64Array(1024);
  private measured = 0;
  /** How the job ended (its `end` event's result), or why the stream stopped. */
  private outcome: string | undefined;
  private foldMs = 0;
  /** Wall-clock parse cache (measure only): the second of the last record. */
  private second = '';
  private secondMs = NaN;
  /** Trace events folded: the id of each event's text in the model (its lines are ranges of it). */
  private events = 0;
  /**
   * Lines of the logs that never came: each log's lines arrive in order, numbered as in the file
   * (docs/build-service-api.md "Trace channel"), so a number past the next one expected is a gap —
   * records the service sent before this stream attached (or while it was broken) and did not keep
   * past its traceLinesKept bound. The log followed last is kept out of the map (the common case: a
   * run of lines of one log).
   */
  private missed = 0;
  /** The logs seen, and each module's first (noteLogFile). */
  private readonly logFiles = new Set<string>();
  private readonly logOf = new Map<string, string>();
  private readonly nextLines = new Map<string, number>();
  private gapFile: string | undefined;
  private gapNext = FIRST_RECORD_LINE;

  constructor(
    private readonly post: (m: FromFollower) => void,
    private readonly openSocket: (url: string) => SocketLike,
    private readonly snapshotMs = SNAPSHOT_MS,
  ) {}

  /** A message of the page. */
  handle(m: ToFollower): void {
    switch (m?.type) {
      case 'follow':
        this.measure = !!m.measure;
        if (typeof m.url === 'string' && !this.stream) {
          this.stream = new JobStream(m.url, {
            event: (e) => this.receive(e),
            lost: (why) => this.finish(why === undefined ? LOST_TRACE : `the trace stream could not be opened (${why})`, why === undefined ? CONNECTION_LOST : undefined),
          }, this.openSocket);
        }
        return;
      case 'feed':
        if (Array.isArray(m.records)) this.fold(() => {
          const arrival = Date.now();
          let n = 0;
          for (const r of m.records) {
            if (!r || typeof r.text !== 'string' || typeof r.file !== 'string' || n++ >= MAX_LINES_PER_EVENT) continue;
            const line = Number.isInteger(r.line) ? r.line : 0;
            if (Number.isSafeInteger(r.unsent) && r.unsent! > 0) this.pushUnsent(r.file, line, r.unsent!);
            else this.pushLine(r.file, line, r.text, 0, r.text.length, arrival);
          }
        });
        return;
      case 'stateAt': {
        const t = Number(m.t);
        if (!Number.isFinite(t)) return;
        this.post({ type: 'state', t, state: this.model.stateAt(t), exact: this.model.exactAt(t) });
        return;
      }
      case 'stop':
        this.stopped = true;
        clearTimeout(this.postTimer);
        this.stream?.close();
        return;
    }
  }

  /** An event of the job's stream (parsed and seq-tracked by job-stream.ts). */
  private receive(e: StreamEvent): void {
    if (this.ended || this.stopped) return;
    const arrival = Date.now();
    if (e.type === 'trace') {
      const textId = this.events++;
      this.fold(() => {
        let n = 0;
        try {
          forEachTraceLine(e, (file, line, text, from, to, cut, unsent) => {
            if (n++ >= MAX_LINES_PER_EVENT) return;
            if (unsent) this.pushUnsent(file, line, unsent);
            else this.pushLine(file, line, text, from, to, arrival, textId, cut);
          });
        } catch (err) {
          this.problem(`a trace event could not be read (${(err as Error).message}); the whole trace is in the run's collected logs`);
        }
      });
    } else if (e.type === 'line') {
      // the launcher's own line (its stderr, the run step: a module's output is tagged with its name, never `launcher`)
      const l = e as { step?: unknown; source?: unknown; stream?: unknown; line?: unknown };
      if (l.step === 'run' && l.source === 'launcher' && l.stream === 'stderr' && typeof l.line === 'string' && l.line.length <= MAX_LINE) {
        const line = l.line;
        this.fold(() => this.model.launcherLine(line));
      }
    } else if (e.type === 'end') this.finish(undefined, jobOutcome((e as { result?: unknown }).result));
  }

  /** The line text.slice(from, to) (read in place: the model keeps its range of the event's text, `textId`). */
  private pushLine(file: string, line: number, text: string, from: number, to: number, arrival: number, textId?: number, cut = false): void {
    const name = boundedName(file);
    if (line === 1) {
      // the service sends a log's line 1 only when it is not the runtime's header, and nothing of
      // that file after it (build-service pipeline/trace-lines.ts): no log, said, none of it read
      this.problem(`${name}: ${NOT_A_LOG_WHY}`);
      this.model.countUnsent(1); // its one unreadable line, as a replay and `contract trace` count it
      return;
    }
    if (name !== this.gapFile) this.noteLogFile(name);
    this.followLines(name, line);
    this.model.pushLineIn(name, line, text, from, Math.min(to, from + MAX_LINE + 1), textId, cut);
    if (this.measure) {
      if (this.measured === this.walls.length) {
        const walls = new Float64Array(this.measured * 2);
        const arrived = new Float64Array(this.measured * 2);
        walls.set(this.walls);
        arrived.set(this.arrived);
        this.walls = walls;
        this.arrived = arrived;
      }
      this.walls[this.measured] = this.wallOf(text, from);
      this.arrived[this.measured++] = arrival;
    }
  }

  /**
   * `count` lines of `file` from `line` on that are no record, which the service counted without
   * sending them (trace/wire.ts `unsent`): counted unreadable, and not missed (they were not lost).
   */
  private pushUnsent(file: string, line: number, count: number): void {
    const name = boundedName(file);
    this.followLines(name, line);
    if (line + count > this.gapNext) this.gapNext = Math.min(Number.MAX_SAFE_INTEGER, line + count);
    this.model.countUnsent(count);
  }

  /**
   * A second log of one module in the run's logs folder (named as the runtime names a log): said
   * while the run goes on, as a replay and `contract trace` say it — a run writes one log per
   * module, so it was written by some module's code under that name (forged deadline misses, rules).
   */
  private noteLogFile(name: string): void {
    if (this.logFiles.has(name) || this.logFiles.size >= MAX_GAP_FILES) return;
    this.logFiles.add(name);
    const module = moduleOfLog(name);
    if (module === undefined) return;
    const first = this.logOf.get(module);
    if (first === undefined) this.logOf.set(module, name);
    else this.problem(`${module}: a second log of it in the run's logs folder (${name}, beside ${first}), read with the first: a run writes one log per module (a file named as its log that is not one)`);
  }

  /** Counts the lines of `file` skipped before `line` (missed). */
  private followLines(file: string, line: number): void {
    if (file !== this.gapFile) {
      if (this.gapFile !== undefined && (this.nextLines.has(this.gapFile) || this.nextLines.size < MAX_GAP_FILES)) this.nextLines.set(this.gapFile, this.gapNext);
      this.gapFile = file;
      this.gapNext = this.nextLines.get(file) ?? FIRST_RECORD_LINE;
    }
    if (line > this.gapNext) this.missed = Math.min(Number.MAX_SAFE_INTEGER, this.missed + (line - this.gapNext));
    if (line >= this.gapNext) this.gapNext = line + 1;
  }

  private fold(work: () => void): void {
    const start = performance.now();
    work();
    this.foldMs += performance.now() - start;
    this.schedule();
  }

  private problem(text: string): void {
    if (this.problems.length < MAX_PROBLEMS) this.problems.push(text);
    this.schedule();
  }

  private finish(problem?: string, outcome?: string): void {
    if (this.ended) return;
    this.ended = true;
    this.outcome = outcome ?? 'the trace stream could not be opened';
    // the job's end (not a stream lost): its undos to ORD that ORD's log never answered are marked now, never before
    if (outcome !== undefined && outcome !== CONNECTION_LOST) this.model.recordsEnded();
    if (problem) this.problems.push(problem);
    this.stream?.close();
    clearTimeout(this.postTimer);
    this.postTimer = undefined;
    this.snapshot();
  }

  /** A snapshot now, or when `snapshotMs` has passed since the last. */
  private schedule(): void {
    if (this.postTimer || this.stopped) return;
    const wait = this.snapshotMs - (performance.now() - this.lastPost);
    if (wait <= 0) this.snapshot();
    else this.postTimer = setTimeout(() => {
      this.postTimer = undefined;
      this.snapshot();
    }, wait);
  }

  private snapshot(): void {
    const m = this.model;
    if (m.version === this.postedVersion && !this.ended && this.problems.length === this.problemsSent) return;
    this.lastPost = performance.now();
    this.postedVersion = m.version;
    const s: Snapshot = {
      type: 'snapshot', live: m.live, end: m.end, count: m.recordCount, missed: this.missed, marks: m.marks.slice(this.marksSent),
      ended: this.ended, ...(this.ended ? { outcome: this.outcome } : {}), problems: this.problems.slice(this.problemsSent), foldMs: this.foldMs,
    };
    this.marksSent = m.marks.length;
    this.problemsSent = this.problems.length;
    if (this.measure) {
      s.walls = this.walls.slice(0, this.measured);
      s.arrived = this.arrived.slice(0, this.measured);
      this.measured = 0;
    }
    this.post(s);
  }

  /**
   * A record's wall_time column (ms since the epoch, µs precision), for the benchmark's latency.
   * Read in place (the second is cut out only when it changes): the measure must not add its own
   * garbage to the worker it measures.
   */
  private wallOf(text: string, from: number): number {
    const c = text.indexOf(',', from) + 1; // 2026-11-28T13:58:13.785123
    if (!text.startsWith(this.second, c) || this.second === '') {
      this.second = text.slice(c, c + 19);
      this.secondMs = Date.parse(`${this.second}Z`);
    }
    let us = 0;
    for (let i = c + 20; i < c + 26; i++) us = us * 10 + (text.charCodeAt(i) - 48);
    return this.secondMs + us / 1000;
  }
}

/** A log's name as the follower keeps it (a hostile stream's file names are bounded). */
function boundedName(file: string): string {
  return file.length > MAX_FILE_NAME ? file.slice(0, MAX_FILE_NAME) : file;
}
