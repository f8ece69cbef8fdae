import { h } from '../util/dom.js';
import { api } from '../api.js';
import { Emitter } from '../util/emitter.js';
import { LogStore, type LogLine } from './log-store.js';
import { LogView } from './log-view.js';
import { decodeTraceRecords, type TraceLine } from '@contract-studio/build-service/trace';

export interface GccDiagnostic {
  severity: 'error' | 'warning' | 'note';
  message: string;
  file: string;
  line: number;
  column: number;
  protectedRegion?: { id: string } | null;
}

/**
 * Build & Run: submits a job to the build service, streams its events (SSE) into the log store,
 * shows the filters (per module/source, per stream, text), follow-tail, and reports gcc
 * diagnostics and the job status to the IDE.
 */
export class BuildPanel {
  readonly store = new LogStore();
  readonly view = new LogView(this.store);
  readonly onDiagnostics = new Emitter<GccDiagnostic[]>();
  readonly onStatus = new Emitter<{ status: string; message?: string; running: boolean }>();
  /** A job's event stream ended (`ok` = succeeded); a run's CSV logs are then at GET /api/jobs/:id/artifacts. */
  readonly onFinished = new Emitter<{ jobId: string; action: 'build' | 'run'; ok: boolean }>();
  /** A job was submitted (its events follow). */
  readonly onStarted = new Emitter<{ jobId: string; action: 'build' | 'run' }>();
  /** The run's trace, live: whole CSV record lines (docs/build-service-api.md "Trace channel"; build-service job-events.ts TraceEvent). */
  readonly onTrace = new Emitter<{ jobId: string; records: TraceLine[] }>();
  readonly element: HTMLElement;
  private readonly chips: HTMLElement;
  private readonly statusEl: HTMLElement;
  private readonly followBox: HTMLInputElement;
  private jobId: string | undefined;
  private source: EventSource | undefined;
  private diagnostics: GccDiagnostic[] = [];
  private chipSources = '';

  constructor() {
    this.chips = h('div', { class: 'chips' });
    this.statusEl = h('span', { class: 'job-status muted' }, 'No build yet');
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
    this.element = h('div', { class: 'build-panel' },
      h('div', { class: 'log-toolbar' }, this.statusEl, h('span', { class: 'sep' }), this.chips, h('span', { class: 'grow' }),
        streamToggle('stdout'), streamToggle('stderr'), streamToggle('system'), search,
        h('label', { class: 'toggle' }, this.followBox, 'Follow'),
        h('button', { class: 'btn small', title: 'Clear the log', onclick: () => { this.store.clear(); this.view.schedule(); } }, 'Clear')),
      this.view.element);
  }

  get running(): boolean {
    return !!this.jobId;
  }

  /** Appends a line (also used by benchmarks/tests to feed the view). */
  append(l: LogLine): void {
    const isNew = !this.store.sources.has(l.source);
    this.store.push(l);
    if (isNew) this.renderChips();
    this.view.scheduleAppend();
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

  async start(projectDir: string, action: 'build' | 'run', duration = 10, start?: string, cpus?: string, realtime?: boolean): Promise<void> {
    if (this.jobId) await this.stop();
    this.source?.close();
    this.store.clear();
    this.chipSources = '';
    this.renderChips();
    this.diagnostics = [];
    this.onDiagnostics.fire([]);
    this.setStatus('submitting', undefined, true);
    const job = await api.submitJob({ action, project: { dir: projectDir }, kind: 'cactal', duration, ...(start ? { start } : {}), ...(cpus ? { cpus } : {}), ...(realtime ? { realtime } : {}) });
    this.jobId = job.id;
    for (const w of job.warnings ?? []) this.append({ t: Date.now(), step: 'prepare', source: 'service', stream: 'system', line: `warning: ${w}` });
    this.setStatus(job.status, job.sandbox ? `sandbox ${job.sandbox}` : undefined, true);
    this.follow(job.id, action);
  }

  /**
   * Follows a job this page submitted before it was reloaded, if the build service still runs it:
   * its events again from the first (the log, the diagnostics and the kept trace: docs/build-service-api.md
   * "Events"), then live, and Stop cancels it. False when it has finished or is unknown (a restarted service).
   */
  async resume(jobId: string): Promise<boolean> {
    let job: { id: string; status: string; action: string; finishedAt: number | null };
    try {
      job = await api.getJob(jobId);
    } catch {
      return false;
    }
    if (job.finishedAt || this.jobId || (job.action !== 'build' && job.action !== 'run')) return false;
    this.jobId = job.id;
    this.setStatus(job.status, 'followed again after a reload', true);
    this.follow(job.id, job.action);
    return true;
  }

  /** Streams a job's events (SSE, from the first) into the log, the diagnostics, the trace and the status. */
  private follow(jobId: string, action: 'build' | 'run'): void {
    const es = new EventSource(`/api/jobs/${encodeURIComponent(jobId)}/events`);
    this.source = es;
    this.onStarted.fire({ jobId, action });
    es.addEventListener('trace', (e) => {
      // the records in their columnar wire form (docs/build-service-api.md "Trace channel")
      let records: TraceLine[];
      try {
        records = decodeTraceRecords(JSON.parse((e as MessageEvent).data));
      } catch (err) {
        this.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: `trace: a trace event could not be read (${(err as Error).message}); the whole trace is in the run's collected logs` });
        return;
      }
      if (records.length) this.onTrace.fire({ jobId, records });
    });
    es.addEventListener('line', (e) => this.append(JSON.parse((e as MessageEvent).data) as LogLine));
    es.addEventListener('status', (e) => {
      const d = JSON.parse((e as MessageEvent).data) as { status: string; step?: string };
      this.setStatus(d.status, d.step, true);
    });
    es.addEventListener('diagnostic', (e) => {
      this.diagnostics.push((JSON.parse((e as MessageEvent).data) as { diagnostic: GccDiagnostic }).diagnostic);
      this.onDiagnostics.fire(this.diagnostics);
    });
    es.addEventListener('limit', (e) => {
      const d = JSON.parse((e as MessageEvent).data) as { limitHit: { name: string } };
      this.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: `limit hit: ${d.limitHit.name}` });
    });
    es.addEventListener('end', (e) => {
      const d = JSON.parse((e as MessageEvent).data) as { result: { ok: boolean; message: string } | null };
      es.close();
      this.source = undefined;
      this.jobId = undefined;
      this.setStatus(d.result?.ok ? 'succeeded' : 'failed', d.result?.message, false);
      this.onFinished.fire({ jobId, action, ok: !!d.result?.ok });
    });
    es.onerror = () => {
      if (es.readyState === EventSource.CLOSED && this.jobId) {
        this.jobId = undefined;
        this.setStatus('disconnected', 'lost the connection to the build service', false);
      }
    };
  }

  async stop(): Promise<void> {
    const id = this.jobId;
    if (!id) return;
    this.setStatus('cancelling', undefined, true);
    try {
      await api.cancelJob(id);
    } catch (e) {
      this.append({ t: Date.now(), step: 'run', source: 'service', stream: 'system', line: `cancel failed: ${(e as Error).message}` });
    }
  }

  private setStatus(status: string, message: string | undefined, running: boolean): void {
    this.statusEl.textContent = `${status}${message ? ` — ${message}` : ''}`;
    this.statusEl.className = `job-status ${status}`;
    this.onStatus.fire({ status, message, running });
  }
}
