import { h } from '../util/dom.js';
import { api, ApiError, socketUrl } from '../api.js';
import { JobStream } from './job-stream.js';
import { Emitter } from '../util/emitter.js';
import { LogStore, type LogLine } from './log-store.js';
import { LogView } from './log-view.js';
import { jobEndStatus, goneJobText, LOST_WITH_SERVER } from './job-end.js';

/** How often the build service is asked about a job whose stream was lost, until it answers (askAfterLoss). */
const ASK_AGAIN_MS = 1000;

export interface GccDiagnostic {
  severity: 'error' | 'warning' | 'note';
  message: string;
  /** Relative to the project's src-gen; null for an error with no place (ld's `cannot find -lx`, a reference without debug information). */
  file: string | null;
  line: number | null;
  column: number | null;
  protectedRegion?: { id: string } | null;
  /** `run`: the run's, not a compiler's (a module crashed at this line); absent for gcc's and ld's. */
  origin?: 'run';
}

/** What a job is asked to do beside its action (the run settings: docs/build-service-api.md, the job request). */
export interface JobOptions {
  /** Seconds (default 10). */
  duration?: number;
  start?: string;
  cpus?: string;
  realtime?: boolean;
  readyTimeout?: number;
  /** Module -> a file of the project it reads on its stdin. */
  stdin?: Record<string, string>;
}

/** The line a job's log ends with when it was cancelled without this tab's Stop. */
export const CANCELLED_ELSEWHERE =
  'cancelled, not by this tab: by another tab (its Stop, or its Build & Run, which replaces the run it follows) or a request to the build service';

/**
 * Build & Run: submits a job to the build service, streams its events (WebSocket) into the log store,
 * shows the filters (per module/source, per stream, text), follow-tail, and reports gcc
 * diagnostics and the job status to the IDE.
 */
export class BuildPanel {
  readonly store = new LogStore();
  readonly view = new LogView(this.store);
  readonly onDiagnostics = new Emitter<GccDiagnostic[]>();
  readonly onStatus = new Emitter<{ status: string; message?: string; running: boolean }>();
  /**
   * A job's event stream ended (`ok` = succeeded); a run's CSV logs are then at GET
   * /api/jobs/:id/artifacts. `cancelledElsewhere`: it was cancelled while this tab followed it, not
   * by this tab's Stop (another tab's Stop or Build & Run, a script); false for a job that had
   * ended before the tab showed it (a reload). `gone`: its stream was lost, and the build service,
   * answering again, no longer knows the job (the IDE server was restarted): it ended with the server,
   * leaving no logs.
   */
  readonly onFinished = new Emitter<{ jobId: string; action: 'build' | 'run'; ok: boolean; message?: string; cancelledElsewhere: boolean; gone?: boolean }>();
  /** A job was submitted (its events follow). */
  readonly onStarted = new Emitter<{ jobId: string; action: 'build' | 'run' }>();
  readonly element: HTMLElement;
  private readonly chips: HTMLElement;
  private readonly statusEl: HTMLElement;
  /** Where the job followed comes from when this page did not submit it ("Build & Run of another tab"). */
  private readonly originEl: HTMLElement;
  private readonly followBox: HTMLInputElement;
  /** Says how many of the oldest lines the panel let go (its bound), with the job's whole log. */
  private readonly droppedEl: HTMLElement;
  /** The store's `dropped` count droppedEl says. */
  private droppedShown = 0;
  /** The job whose lines the log holds (the one followed, or the last one, until the next). */
  private logJobId: string | undefined;
  private jobId: string | undefined;
  /** The job this tab asked to stop (its Stop, or its own next Build & Run). */
  private stopAsked: string | undefined;
  /** A submission is on its way (no job id yet). */
  private submitting = false;
  /**
   * The last start asked: a start asked while another is submitting waits for it, then replaces
   * its job as it replaces a running one (two at once, Build & Run then Ctrl+Shift+B, submitted
   * both, and the panel followed one and Stop cancelled the other).
   */
  private starting: Promise<void> = Promise.resolve();
  /**
   * Starts asked, and how many of them a Stop came after: those not yet submitted are dropped, and
   * one that was being submitted has its job cancelled as soon as the service has it.
   */
  private startsAsked = 0;
  private stoppedStarts = 0;
  private stream: JobStream | undefined;
  private diagnostics: GccDiagnostic[] = [];
  private chipSources = '';

  constructor() {
    this.chips = h('div', { class: 'chips', title: 'Show or hide a source\'s lines (more sources: scroll, or the wheel)' });
    // a run of 30 modules has more chips than the row shows: the wheel scrolls them sideways
    this.chips.addEventListener('wheel', (e) => {
      if (this.chips.scrollWidth <= this.chips.clientWidth || Math.abs(e.deltaX) > Math.abs(e.deltaY)) return;
      e.preventDefault();
      this.chips.scrollLeft += e.deltaY;
    }, { passive: false });
    this.statusEl = h('span', { class: 'job-status muted' }, 'No build yet');
    this.originEl = h('span', { class: 'job-origin muted' });
    this.followBox = h('input', { type: 'checkbox', checked: true, id: 'follow-tail' });
    this.followBox.addEventListener('change', () => this.view.setFollow(this.followBox.checked));
    this.view.onFollowChange = (f) => (this.followBox.checked = f);
    const streamToggle = (stream: string) => {
      const box = h('input', { type: 'checkbox', checked: true, 'data-stream': stream });
      box.addEventListener('change', () => {
        const hidden = new Set(this.store.filter.hiddenStreams);
        if (box.checked) hidden.delete(stream);
        else hidden.add(stream);
        this.store.setFilter({ hiddenStreams: hidden });
        this.view.schedule();
      });
      return h('label', { class: 'toggle' }, box, stream);
    };
    const search = h('input', { class: 'log-search', placeholder: 'Filter text…', spellcheck: 'false' });
    search.addEventListener('input', () => {
      this.store.setFilter({ text: search.value });
      this.view.schedule();
    });
    this.droppedEl = h('div', { class: 'log-dropped', role: 'status', hidden: true });
    this.element = h('div', { class: 'build-panel' },
      h('div', { class: 'log-toolbar' }, this.statusEl, this.originEl, h('span', { class: 'sep' }), this.chips, h('span', { class: 'grow' }),
        streamToggle('stdout'), streamToggle('stderr'), streamToggle('system'), search,
        h('label', { class: 'toggle' }, this.followBox, 'Follow'),
        h('button', { class: 'btn small', title: 'Clear the log', onclick: () => { this.store.clear(); this.showDropped(); this.view.schedule(); } }, 'Clear')),
      this.droppedEl,
      this.view.element);
  }

  get running(): boolean {
    return !!this.jobId;
  }

  /** Following a job, or submitting one. */
  get busy(): boolean {
    return !!this.jobId || this.submitting;
  }

  /** Appends a line (also used by benchmarks/tests to feed the view). */
  append(l: LogLine): void {
    const isNew = !this.store.sources.has(l.source);
    this.store.push(l);
    if (isNew) this.renderChips();
    if (this.store.dropped !== this.droppedShown) this.showDropped();
    this.view.scheduleAppend();
  }

  /**
   * Says how many of the oldest lines the panel let go (it keeps the last `capacity`, a quarter
   * more at most): never silently. The job's whole log stays in the build service, as text at GET
   * /api/jobs/:id/log (as long as the service keeps the job: its last 50), linked here.
   */
  private showDropped(): void {
    const n = this.store.dropped;
    this.droppedShown = n;
    this.droppedEl.hidden = n === 0;
    if (n === 0) return this.droppedEl.replaceChildren();
    const id = this.logJobId;
    const text = `${n.toLocaleString('en-US')} earlier line(s) not shown: this panel keeps the last ${this.store.capacity.toLocaleString('en-US')}`;
    this.droppedEl.replaceChildren(...(id
      ? [`${text}; the whole log: `, h('a', { href: `/api/jobs/${encodeURIComponent(id)}/log`, download: `job-${id}.log`, target: '_blank', rel: 'noopener' }, 'download it')]
      : [`${text}.`]));
  }

  private renderChips(): void {
    const names = [...this.store.sources.keys()].sort();
    const key = names.join(',');
    if (key === this.chipSources) return;
    this.chipSources = key;
    this.chips.replaceChildren(...names.map((name) => {
      const off = this.store.filter.hiddenSources.has(name);
      return h('button', {
        class: `chip${off ? ' off' : ''}`, 'data-source': name, title: `Show/hide ${name}`,
        onclick: () => {
          const hidden = new Set(this.store.filter.hiddenSources);
          if (hidden.has(name)) hidden.delete(name);
          else hidden.add(name);
          this.store.setFilter({ hiddenSources: hidden });
          this.chipSources = '';
          this.renderChips();
          this.view.schedule();
        },
      }, name);
    }));
  }

  /**
   * Submits a job and follows it; a job this panel follows is cancelled first (replaced). Starts
   * asked one after the other are submitted one after the other; a Stop asked after a start that
   * is not submitted yet drops it.
   */
  start(projectDir: string, action: 'build' | 'run', opts: JobOptions = {}): Promise<void> {
    const asked = ++this.startsAsked;
    const next = this.starting.catch(() => undefined).then(() => (asked <= this.stoppedStarts ? undefined : this.submitAndFollow(asked, projectDir, action, opts)));
    this.starting = next;
    return next;
  }

  private async submitAndFollow(asked: number, projectDir: string, action: 'build' | 'run', opts: JobOptions): Promise<void> {
    if (this.jobId) await this.cancelFollowed();
    this.clear();
    this.setStatus('submitting', undefined, true);
    this.submitting = true;
    let job;
    try {
      const { duration = 10, start, readyTimeout, cpus, realtime, stdin } = opts;
      job = await api.submitJob({
        action, project: { dir: projectDir }, kind: 'cactal', duration, ...(start ? { start } : {}), ...(readyTimeout ? { readyTimeout } : {}), ...(cpus ? { cpus } : {}),
        ...(realtime ? { realtime } : {}), ...(stdin && Object.keys(stdin).length ? { stdin } : {}),
      });
    } finally {
      this.submitting = false;
    }
    this.jobId = job.id;
    // its warnings (job.warnings) come as the service's `warning:` lines of the stream: not added here too (they were shown twice, once only after a reload)
    this.setStatus(job.status, job.sandbox ? `sandbox ${job.sandbox}` : undefined, true);
    this.follow(job.id, action);
    // a Stop came while it was on its way
    if (asked <= this.stoppedStarts) await this.cancelFollowed();
  }

  /** Empties the log, the source chips and the diagnostics (a new job is followed). */
  private clear(): void {
    const stream = this.stream;
    this.stream = undefined;
    stream?.close();
    this.store.clear();
    this.logJobId = undefined;
    this.showDropped();
    this.chipSources = '';
    this.renderChips();
    this.diagnostics = [];
    this.onDiagnostics.fire([]);
    this.setOrigin('');
  }

  /**
   * Follows a job submitted elsewhere — by this page before it was reloaded, or by another tab —
   * if the build service still runs it and this panel follows none: its events from the first
   * (the log and the diagnostics: docs/build-service-api.md "Events"; the Monitor follows the trace), then live,
   * and Stop cancels it. False when it has finished (unless `ended`: this tab's own last job, shown
   * again after a reload, its log whole and its end, the Monitor and its logs too), is unknown (a
   * restarted service: said when `sayIfGone`), or this panel is busy with a job of its own. `why`
   * is shown beside the status.
   */
  /**
   * Follows job `jobId` in the panel (again): `followed`; `gone` when the build service no longer
   * knows it (said when `sayIfGone`), or it is no build nor run; `not now` when the panel is busy
   * with another job, the job ended and `ended` is not set, or the service could not be asked (a
   * reload's job is then kept for the next one).
   */
  async resume(jobId: string, opts: { why?: string; sayIfGone?: boolean; ended?: boolean; stoppedHere?: boolean } = {}): Promise<'followed' | 'gone' | 'not now'> {
    const why = opts.why ?? 'followed again after a reload';
    const sayIfGone = opts.sayIfGone ?? why === 'followed again after a reload';
    if (this.busy) return 'not now';
    let job: { id: string; status: string; action: string; finishedAt: number | null };
    try {
      job = await api.getJob(jobId);
    } catch (e) {
      if (!(e instanceof ApiError && e.status === 404)) return 'not now';
      // the job this tab followed before a reload is gone: the IDE server (and its build service)
      // was restarted, which ends its jobs. Said, rather than an empty panel as if nothing had run.
      if (sayIfGone && !this.busy) {
        this.clear();
        this.setOrigin(`(${why})`);
        this.setStatus('gone', goneJobText(jobId), false);
      }
      return 'gone';
    }
    if (job.action !== 'build' && job.action !== 'run') return 'gone';
    if ((job.finishedAt && !opts.ended) || this.busy) return 'not now';
    this.clear();
    this.jobId = job.id;
    this.setOrigin(job.finishedAt ? '(shown again after a reload: it had ended)' : `(${why})`);
    this.setStatus(job.status, undefined, !job.finishedAt);
    // this tab's Stop before the reload is still its own
    this.stopAsked = opts.stoppedHere ? job.id : undefined;
    this.follow(job.id, job.action, { hadEnded: !!job.finishedAt });
    return 'followed';
  }

  /**
   * Streams a job's events into the log, the diagnostics and the status (not the trace: the Monitor's own socket), from the
   * first (a broken stream is taken up again after the last event seen: job-stream.ts). A
   * WebSocket (GET /api/jobs/:id/ws, docs/build-service-api.md "Events"), not an EventSource:
   * a browser opens at most six HTTP/1.1 connections to a server for all its tabs, and streams
   * held on them by tabs following a run would leave none for their saves (as for /api/events,
   * app/server-events.ts).
   */
  private follow(jobId: string, action: 'build' | 'run', opts: { hadEnded?: boolean } = {}): void {
    // the run's trace goes to the Monitor's worker on a socket of its own (monitor/live-follower.ts);
    // a broken stream is taken up again after the last event seen (job-stream.ts)
    let lastStatus: string | undefined;
    this.logJobId = jobId;
    // batch=1: the events several to a frame, one frame every 50 ms at most while they stream (a
    // module printing 10,000 lines a second was as many frames, each a task of the page: job-stream.ts)
    const stream: JobStream = new JobStream(socketUrl(`/api/jobs/${encodeURIComponent(jobId)}/ws?trace=none&batch=1`), {
      event: (e) => {
        switch (e.type) {
          case 'line':
            return this.append(e as unknown as LogLine);
          case 'status': {
            const d = e as unknown as { status: string; step?: string };
            lastStatus = d.status;
            return this.setStatus(d.status, d.step, true);
          }
          case 'diagnostic':
            this.diagnostics.push((e as unknown as { diagnostic: GccDiagnostic }).diagnostic);
            return this.onDiagnostics.fire(this.diagnostics);
          case 'limit':
            return this.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: `limit hit: ${(e as unknown as { limitHit: { name: string } }).limitHit.name}` });
          case 'end': {
            const d = e as unknown as { result: { ok: boolean; message: string } | null };
            stream.close();
            if (this.stream === stream) this.stream = undefined;
            this.jobId = undefined;
            const end = jobEndStatus(d.result, lastStatus);
            const cancelledElsewhere = end.status === 'cancelled' && this.stopAsked !== jobId;
            if (cancelledElsewhere) {
              this.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: CANCELLED_ELSEWHERE });
            }
            this.setStatus(end.status, cancelledElsewhere ? 'from another tab or a script' : end.message, false);
            this.onFinished.fire({ jobId, action, ok: !!d.result?.ok, message: d.result?.message, cancelledElsewhere: cancelledElsewhere && !opts.hadEnded });
            return;
          }
        }
      },
      lost: () => {
        if (this.stream !== stream || this.jobId !== jobId) return;
        this.stream = undefined;
        this.jobId = undefined;
        this.setStatus('disconnected', 'lost the connection to the build service: asking it about the job until it answers', false);
        void this.askAfterLoss(jobId, action);
      },
    });
    this.stream = stream;
    this.onStarted.fire({ jobId, action });
  }

  /**
   * After job `jobId`'s stream was lost for good: asks the build service about the job every
   * ASK_AGAIN_MS until it answers, while the log still holds that job and the panel follows no other.
   * It no longer knows it (the IDE server was restarted, ending its jobs): said in the log and the
   * status, and the job ends (`gone`: the Monitor says so too) — every tab that followed it comes to
   * the same, instead of "disconnected" for ever beside a reloaded tab's "gone". It still knows it
   * (the connection broke, not the server): followed again, or its end shown.
   */
  private async askAfterLoss(jobId: string, action: 'build' | 'run'): Promise<void> {
    const movedOn = () => this.logJobId !== jobId || this.busy;
    for (;;) {
      await new Promise((r) => setTimeout(r, ASK_AGAIN_MS));
      if (movedOn()) return;
      try {
        await api.getJob(jobId);
      } catch (e) {
        // no answer (the server still down) or a refused session (401: restarted with a new token,
        // until the tab has its session back): asked again
        if (!(e instanceof ApiError && e.status === 404)) continue;
        if (movedOn()) return;
        const text = goneJobText(jobId);
        this.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: text });
        this.setStatus('gone', text, false);
        this.onFinished.fire({ jobId, action, ok: false, message: LOST_WITH_SERVER, cancelledElsewhere: false, gone: true });
        return;
      }
      if (movedOn()) return;
      const origin = this.originEl.textContent?.replace(/^\((.*)\)$/, '$1');
      await this.resume(jobId, { ended: true, why: origin || 'followed again once the build service answered' });
      return;
    }
  }

  async stop(): Promise<void> {
    // the starts asked until now and not yet submitted are dropped; one being submitted is cancelled once it is
    this.stoppedStarts = this.startsAsked;
    if (this.submitting) {
      this.setStatus('cancelling', 'once the build service has the job', true); // submitAndFollow cancels it
      return;
    }
    await this.cancelFollowed();
  }

  /** Cancels the job this panel follows (Stop, or a new start replacing it). */
  private async cancelFollowed(): Promise<void> {
    const id = this.jobId;
    if (!id) return;
    this.stopAsked = id;
    this.setStatus('cancelling', undefined, true);
    try {
      await api.cancelJob(id);
    } catch (e) {
      this.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: `cancel failed: ${(e as Error).message}` });
    }
  }

  /** Where the job followed comes from (whole in its tooltip: a narrow panel cuts it; the browser tests set it). */
  setOrigin(text: string): void {
    this.originEl.textContent = text;
    this.originEl.title = text;
  }

  /** The job's status line (the browser tests set it too). */
  setStatus(status: string, message: string | undefined, running: boolean): void {
    this.statusEl.textContent = `${status}${message ? ` — ${message}` : ''}`;
    this.statusEl.title = this.statusEl.textContent; // whole, when the row cuts it
    this.statusEl.className = `job-status ${status}`;
    this.onStatus.fire({ status, message, running });
  }
}
