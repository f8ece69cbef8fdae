import { visibleText } from '@contract-studio/conventions';
import { h } from '../util/dom.js';
import { api } from '../api.js';
import type { Workspace } from '../workspace/workspace.js';
import { inferPeriodOf, type Activation, type ModelModules } from './activation-log.js';
import { barTitle, laneBars, lanesOf, lastTime } from './timeline-bars.js';
import { endGoneActivations, goneFromLauncherLines, type GoneAt } from './gone-activations.js';
import { launcherLinesOnRecordClock } from '../monitor/job-launcher-lines.js';
import { activationsFromLogs, localLogFolders, readTraceFile, readWorkspaceLogs, type LogFile, type RunLogs } from './run-logs.js';

const SVG = 'http://www.w3.org/2000/svg';
/** Trace files of the project offered as sources. */
const MAX_TRACE_FILES = 64;
/** Lanes (modules) the Timeline draws at most: a run has tens; a forged log may name a module a line. */
export const MAX_LANES = 256;

function svg<K extends keyof SVGElementTagNameMap>(tag: K, attrs: Record<string, string | number>, text?: string): SVGElementTagNameMap[K] {
  const el = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, String(v));
  // a lane's module name, a bar's or a mark's tooltip: what the logs say, written visibly
  if (text !== undefined) el.textContent = visibleText(text, { keepNewlines: true });
  return el;
}

/**
 * Timeline of module activations (one lane per module, one bar per activation), with period
 * gridlines, over one of two sources of the runtime's CSV logs: the run that just finished in
 * Build & Run (logs collected by the build service, given through `showRun`) or the local logs:
 * `<project>/logs/` (`contract run`) or `<project>/src-gen/generated/architecture/logs/` (`make run`),
 * the first that holds some (each its own choice when both do: two runs, not one), or a trace file
 * of the project (`*.jsonl`, `contract run --trace`), read as the logs it was written from.
 */
export class TimelineView {
  readonly element: HTMLElement;
  private readonly canvas: HTMLElement;
  private readonly info: HTMLElement;
  private readonly zoom: HTMLInputElement;
  private readonly source: HTMLSelectElement;
  private last: { acts: Activation[]; files: number; errors: string[]; gone?: readonly GoneAt[] } | undefined;
  /** How many updates began: one that a later one overtook while it awaited the server draws nothing. */
  private updates = 0;
  private run: RunLogs | undefined;
  /** Redraws the bars of the part of the timeline on screen (after a scroll). */
  private drawBars: (() => void) | undefined;
  private barsPending = false;
  private redrawPending = false;
  /** The width the timeline was last fitted to (the canvas's, padding left out). */
  private fittedWidth = 0;

  /** What the project's model says of its modules, read at each update (none when the IDE does not have it). */
  private model: ModelModules | undefined;

  /**
   * `modelModules`: the project's model's supervisors and other modules (the language server's
   * symbols), undefined when it cannot say: a module's supervisor records make it an engine only
   * when it may be one (activation-log.ts activationsFromCsv).
   */
  constructor(
    private readonly project: () => string,
    private readonly workspace: Workspace,
    private readonly modelModules?: () => Promise<ModelModules | undefined>,
  ) {
    this.info = h('span', { class: 'muted' });
    this.zoom = h('input', { type: 'range', min: 0, max: 8, step: 1, value: 0, class: 'zoom', title: 'Zoom (×2 per step)', 'aria-label': 'Zoom (×2 per step)' });
    this.zoom.addEventListener('input', () => this.last && this.draw(this.last.acts, this.last.files, this.last.errors, this.last.gone));
    this.canvas = h('div', {
      class: 'timeline-canvas', tabindex: 0, role: 'group', 'data-autofocus': true,
      'aria-label': 'Timeline of module activations: arrows scroll, Home and End go to the start and the end of the run; hover a bar for its times',
    });
    this.canvas.addEventListener('keydown', (e) => {
      if (e.key !== 'Home' && e.key !== 'End') return;
      this.canvas.scrollLeft = e.key === 'Home' ? 0 : this.canvas.scrollWidth;
      e.preventDefault();
    });
    this.canvas.addEventListener('scroll', () => {
      if (this.barsPending || !this.drawBars) return;
      this.barsPending = true;
      requestAnimationFrame(() => {
        this.barsPending = false;
        this.drawBars?.();
      });
    }, { passive: true });
    this.source = h('select', { class: 'timeline-source', title: 'Which run to show', 'aria-label': 'Which run to show' });
    this.source.addEventListener('change', () => void this.update());
    // fitted to its pane: a pane that changed width (the Monitor docked beside it, a window
    // resized) gets the timeline drawn again for it
    new ResizeObserver((entries) => {
      const width = Math.round(entries[0]?.contentRect.width ?? 0);
      if (!width || !this.last || Math.abs(width - this.fittedWidth) < 8 || this.redrawPending) return;
      this.redrawPending = true;
      requestAnimationFrame(() => {
        this.redrawPending = false;
        if (this.last) this.draw(this.last.acts, this.last.files, this.last.errors, this.last.gone);
      });
    }).observe(this.canvas);
    this.renderSources('local');
    this.element = h('div', { class: 'timeline-view' },
      h('div', { class: 'arch-toolbar' }, h('span', { class: 'arch-label' }, 'Activations per period'), this.source, this.info, h('span', { class: 'grow' }),
        h('label', { class: 'toggle' }, 'Zoom ', this.zoom),
        h('button', { class: 'btn small', onclick: () => void this.update() }, '⟳ Reload logs')),
      this.canvas);
  }

  /** The logs of the run that just finished in Build & Run: selected, and drawn if the view is shown. */
  showRun(logs: RunLogs): void {
    this.run = logs;
    this.renderSources('run');
    if (this.element.isConnected) void this.update();
  }

  /**
   * `local` is the first local logs folder that holds logs (`held`: those that do); when both do,
   * the other is offered as `local:<folder>`.
   */
  private renderSources(selected: string, held: string[] = [], traces: string[] = []): void {
    const options = [h('option', { value: 'local', selected: selected === 'local' }, held[0] ? visibleText(`Local logs: ${held[0]}/`) : 'Local logs (contract run / make run)')];
    for (const folder of held.slice(1)) options.push(h('option', { value: `local:${folder}`, selected: selected === `local:${folder}` }, visibleText(`Local logs: ${folder}/`)));
    for (const path of traces) options.push(h('option', { value: `file:${path}`, selected: selected === `file:${path}` }, visibleText(`Trace file: ${path}`)));
    if (this.run) options.unshift(h('option', { value: 'run', selected: selected === 'run' }, visibleText(`Last Build & Run (${this.run.label.replace(/^Build & Run /, '')})`)));
    this.source.replaceChildren(...options);
    this.source.value = selected === 'run' && this.run ? 'run' : held.includes(selected.slice(6)) || traces.includes(selected.slice(5)) ? selected : 'local';
  }

  async update(): Promise<void> {
    // an update that awaits the server (the model, the local logs) and ends after a later one began
    // (the job's logs shown when it ended) draws nothing: the later one's drawing stands
    const seq = ++this.updates;
    const superseded = (): boolean => seq !== this.updates;
    const model = await this.modelModules?.().catch(() => undefined);
    if (superseded()) return;
    this.model = model;
    if (this.source.value === 'run' && this.run) {
      // the launcher's lines of the job's log, put on the records' clock as the Monitor's replay of the job puts them
      const lines = launcherLinesOnRecordClock(this.run.files, this.run.launcherLines);
      return this.drawLogs(this.run.files, this.run.problems, `${this.run.label} left no CSV logs.`, lines);
    }
    await this.workspace.refreshTree();
    if (superseded()) return;
    const folders = localLogFolders(this.project(), this.workspace.allFiles());
    const held = folders.filter((f) => f.csvs.length);
    // trace files of the project (`contract run --trace`): the logs they were written from (build-service trace/jsonl.ts)
    const pre = this.project() ? `${this.project()}/` : '';
    const traces = this.workspace.allFiles().filter((f) => f.endsWith('.jsonl') && f.startsWith(pre)).sort().slice(0, MAX_TRACE_FILES);
    this.renderSources(this.source.value || 'local', held.map((f) => f.folder), traces);
    if (this.source.value.startsWith('file:')) {
      // its launcher_line items (`contract run --trace`): a module killed from outside ended at the line's time, as in a folder's replay
      const { files, problems, launcherLines } = await readTraceFile(this.source.value.slice(5), (f) => f);
      if (superseded()) return;
      return this.drawLogs(files, problems, `${this.source.value.slice(5)} holds no record.`, launcherLines);
    }
    const csvs = (held.find((f) => `local:${f.folder}` === this.source.value) ?? held[0])?.csvs ?? [];
    if (!csvs.length) {
      this.info.textContent = '';
      this.last = undefined;
      const [cli, make] = folders.map((f) => `${f.folder}/`);
      this.canvas.replaceChildren(h('div', { class: 'pad muted' }, `No CSV logs in ${cli} nor in ${make} yet. \`contract run\` writes a run's logs to ${cli} (or the folder its --logs names: open it in the Monitor), \`make -C src-gen/generated/architecture run\` to ${make}; a Build & Run shows its own run here when it ends.`));
      return;
    }
    // the folder as the server lists it (its links and FIFOs too, which the Explorer's tree does
    // not show), as the Monitor reads it: a log left out is named with why
    const folder = (held.find((f) => `local:${f.folder}` === this.source.value) ?? held[0])!.folder;
    const listing = await api.logFolder(folder).catch((e: Error) => ({ logs: csvs, more: 0, max: 0, notRead: [`${folder} could not be listed (${e.message}): its logs the Explorer shows are read`], notReadCount: 1 }));
    if (superseded()) return;
    // past the bound, ORD's log (the schemas' activations) is read first, not left out by name order
    const { files, problems: unread, partly } = await readWorkspaceLogs(listing.logs, (f) => f, undefined, { supervisors: new Set() });
    if (superseded()) return;
    const problems = [...unread, ...partly];
    const notRead = [...listing.notRead];
    if (listing.notReadCount > listing.notRead.length) notRead.push(`${listing.notReadCount - listing.notRead.length} more entries that are no regular file`);
    if (listing.more) notRead.push(`${listing.more} more CSV log(s) past the first ${listing.max}`);
    // the folder's contract-launch.log (its end lines, each with its time on the records' clock)
    this.drawLogs(files, [...problems, ...notRead], '', 'launcherLines' in listing ? listing.launcherLines : undefined);
  }

  /** `launcherLines`: the launcher's end lines of a logs folder, a trace file or a job, on the records' clock (gone-activations.ts). */
  private drawLogs(files: LogFile[], problems: string[], emptyText: string, launcherLines?: readonly { monoNs: string; line: string }[]): void {
    if (!files.length && emptyText) {
      this.info.textContent = '';
      this.last = undefined;
      this.canvas.replaceChildren(h('div', { class: 'pad muted' }, visibleText(`${emptyText} ${problems.join(' ')}`.trim())));
      return;
    }
    const { acts, errors } = activationsFromLogs(files, this.model);
    const gone = goneFromLauncherLines(files, launcherLines);
    endGoneActivations(acts, gone);
    this.draw(acts, files.length + problems.length, [...problems, ...errors], gone);
  }

  /** `gone`: the modules the launcher's end lines say ended, marked in their lanes at that time (gone-activations.ts). */
  private draw(acts: Activation[], files: number, errors: string[], gone: readonly GoneAt[] = []): void {
    this.last = { acts, files, errors, gone };
    this.drawBars = undefined;
    if (!acts.length) {
      this.canvas.replaceChildren(h('div', { class: 'pad muted' }, visibleText(`No activations in ${files} log file(s). ${errors.join(' ')}`)));
      return;
    }
    // a lane per module, MAX_LANES at most (by name): a log a module's code wrote may name a new
    // module on each line; the activations of the others are left out, and the header says so
    const { modules, lanes, leftOutModules, leftOutActs } = lanesOf(acts, MAX_LANES);
    if (leftOutActs) {
      const drawn = new Set(modules);
      acts = acts.filter((a) => drawn.has(a.module)); // still in start order
    }
    const t0 = acts[0]!.start;
    const tEnd = lastTime(acts);
    const span = Math.max(1, tEnd - t0);
    const periodOf = inferPeriodOf(acts);
    const period = periodOf?.ns;
    const lane = 26;
    const left = 70;
    // fit the visible width (hover a bar for exact times)
    const visible = this.canvas.clientWidth;
    this.fittedWidth = Math.round(visible - 40);
    const fit = Math.max(300, (visible || 1000) - 40);
    // zoom in far enough to see each period (8 px apart) of a long run: 2^8 at least, 2^16 at most
    this.zoom.max = String(period ? Math.min(16, Math.max(8, Math.ceil(Math.log2(((span / period) * 8) / fit)))) : 8);
    const width = fit * 2 ** Number(this.zoom.value);
    // under the lanes: a row of period numbers (#k), then the run's length on a row of its own (on
    // one row, the last #k and the length overlapped)
    const height = modules.length * lane + 44;
    const x = (t: number) => left + ((t - t0) / span) * (width - left - 10);
    const invX = (px: number) => t0 + ((px - left) / (width - left - 10)) * span;
    const axis = svg('text', { x: width - 10, y: height - 6, class: 'period-label', 'text-anchor': 'end' }, `${(span / 1e6).toFixed(1)} ms`);
    const root = svg('svg', { width, height, class: 'timeline-svg' });
    const grid = svg('g', { class: 'period-grid' });
    root.append(grid);
    // a line every `step` periods, at least 8 px apart, and a label at least 60 px apart
    const periodPx = period ? x(t0 + period) - x(t0) : 0;
    const step = period ? Math.max(1, Math.ceil(8 / periodPx)) : 0;
    // labels as far apart as the widest one takes (10 px text: about 7 px a character) and 60 px at least
    const labelPx = period ? Math.max(60, (String(Math.floor(span / period)).length + 1) * 7 + 14) : 60;
    const labelEvery = step * Math.max(1, Math.ceil(labelPx / (step * periodPx)));
    const drawGrid = (from: number, to: number): SVGElement[] => {
      if (!period) return [];
      const made: SVGElement[] = [];
      const last = Math.floor((tEnd - t0) / period);
      const first = Math.max(0, Math.floor((invX(from) - t0) / period / step) * step);
      for (let k = first; k <= last && x(t0 + k * period) <= to; k += step) {
        const px = x(t0 + k * period);
        made.push(svg('line', { x1: px, x2: px, y1: 0, y2: height - 34, class: 'period-line' }));
        // a label that would pass the right edge is left out (it was cut)
        if (k % labelEvery === 0 && px + 2 + (String(k).length + 1) * 7 <= width) made.push(svg('text', { x: px + 2, y: height - 20, class: 'period-label' }, `#${k}`));
      }
      return made;
    };
    modules.forEach((m, i) => {
      root.append(svg('text', { x: 6, y: i * lane + 17, class: 'lane-label' }, m));
      root.append(svg('line', { x1: left, x2: width, y1: (i + 1) * lane, y2: (i + 1) * lane, class: 'lane-sep' }));
    });
    const bars = svg('g', { class: 'act-bars' });
    root.append(bars);
    // a module the launcher's own line says ended (killed from outside, crashed): a mark in its lane at the line's time
    const drawnGone = gone.filter((g) => modules.includes(g.module));
    for (const g of drawnGone) {
      const i = modules.indexOf(g.module);
      const px = x(Math.min(Math.max(g.at, t0), t0 + span));
      const mark = svg('line', { x1: px, x2: px, y1: i * lane + 2, y2: (i + 1) * lane - 2, class: 'gone-mark', 'data-module': g.module });
      mark.append(svg('title', {}, `${g.module} gone at ${((g.at - t0) / 1e6).toFixed(3)} ms: ${g.words}`));
      root.append(mark);
    }
    const drawBars = () => {
      // only what is on screen, and a screen's width either side of it (pixels of the svg): the
      // period lines and the bars
      const view = this.canvas.clientWidth || 1000;
      const from = this.canvas.scrollLeft - view;
      const to = this.canvas.scrollLeft + 2 * view;
      const made: SVGElement[] = [];
      lanes.forEach((laneActs, i) => {
        for (const b of laneBars(laneActs, x, invX, tEnd, from, to)) {
          const bar = svg('rect', { x: b.x1, y: i * lane + 5, width: b.x2 - b.x1, height: lane - 10, rx: 2, class: `act-bar${b.open ? ' open' : ''}${b.last.gone ? ' gone' : ''}${b.count > 1 ? ' many' : ''}${b.first.event && b.last.event ? ' event' : ''}` });
          bar.append(svg('title', {}, barTitle(b, t0)));
          made.push(bar);
        }
      });
      bars.replaceChildren(...made);
      grid.replaceChildren(...drawGrid(from, to));
    };
    root.append(axis);
    const leftOut = leftOutModules ? ` · ${leftOutModules} more modules named in the logs, past the ${MAX_LANES} lanes shown (${leftOutActs} activations left out: did a module's code write into its log?)` : '';
    const events = acts.reduce((n, a) => n + (a.event ? 1 : 0), 0);
    this.info.textContent = visibleText(`${acts.length - events} activations · ${modules.length} modules${events ? ` · ${events} events handled` : ''}${leftOut}${drawnGone.length ? ` · gone: ${drawnGone.map((g) => `${g.module} at ${((g.at - t0) / 1e6).toFixed(3)} ms (${g.words})`).join(', ')}` : ''} · ${(span / 1e6).toFixed(1)} ms${periodOf ? ` · period ≈ ${(periodOf.ns / 1e6).toFixed(2)} ms (of ${periodOf.module}: the grid's #k)` : ''}${errors.length ? ` · left out or not whole: ${errors.slice(0, 8).join('; ')}${errors.length > 8 ? `; ${errors.length - 8} more` : ''}` : ''}`);
    this.canvas.replaceChildren(root);
    // drawn once the svg is in place: a zoom keeps the scroll position, clamped to the new width
    drawBars();
    this.drawBars = drawBars;
  }
}
