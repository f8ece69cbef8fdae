import { h } from '../util/dom.js';
import type { Workspace } from '../workspace/workspace.js';
import { inferPeriod, type Activation } from './activation-log.js';
import { activationsFromLogs, readWorkspaceLogs, type LogFile, type RunLogs } from './run-logs.js';

const SVG = 'http://www.w3.org/2000/svg';

function svg<K extends keyof SVGElementTagNameMap>(tag: K, attrs: Record<string, string | number>, text?: string): SVGElementTagNameMap[K] {
  const el = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, String(v));
  if (text !== undefined) el.textContent = text;
  return el;
}

/**
 * Timeline of module activations (one lane per module, one bar per activation), with period
 * gridlines, over one of two sources of the runtime's CSV logs: the run that just finished in
 * Build & Run (logs collected by the build service, given through `showRun`) or the local logs
 * under `<project>/src-gen/generated/architecture/logs/` (`make run` / `contract run`).
 */
export class TimelineView {
  readonly element: HTMLElement;
  private readonly canvas: HTMLElement;
  private readonly info: HTMLElement;
  private readonly zoom: HTMLInputElement;
  private readonly source: HTMLSelectElement;
  private last: { acts: Activation[]; files: number; errors: string[] } | undefined;
  private run: RunLogs | undefined;

  constructor(
    private readonly project: () => string,
    private readonly workspace: Workspace,
  ) {
    this.info = h('span', { class: 'muted' });
    this.zoom = h('input', { type: 'range', min: 0, max: 8, step: 1, value: 0, class: 'zoom', title: 'Zoom (×2 per step)', 'aria-label': 'Zoom (×2 per step)' });
    this.zoom.addEventListener('input', () => this.last && this.draw(this.last.acts, this.last.files, this.last.errors));
    this.canvas = h('div', { class: 'timeline-canvas' });
    this.source = h('select', { class: 'timeline-source', title: 'Which run to show', 'aria-label': 'Which run to show' });
    this.source.addEventListener('change', () => void this.update());
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

  private renderSources(selected: 'run' | 'local'): void {
    const options = [h('option', { value: 'local', selected: selected === 'local' }, 'Local logs (make run / contract run)')];
    if (this.run) options.unshift(h('option', { value: 'run', selected: selected === 'run' }, `Last Build & Run (${this.run.label.replace(/^Build & Run /, '')})`));
    this.source.replaceChildren(...options);
    this.source.value = selected === 'run' && this.run ? 'run' : 'local';
  }

  async update(): Promise<void> {
    if (this.source.value === 'run' && this.run) return this.drawLogs(this.run.files, this.run.problems, `${this.run.label} left no CSV logs.`);
    const p = this.project();
    const logDir = `${p ? `${p}/` : ''}src-gen/generated/architecture/logs`;
    await this.workspace.refreshTree();
    const csvs = this.workspace.allFiles().filter((f) => f.startsWith(logDir + '/') && f.endsWith('.csv'));
    if (!csvs.length) {
      this.info.textContent = '';
      this.canvas.replaceChildren(h('div', { class: 'pad muted' }, `No CSV logs in ${logDir}/ yet. Runs of \`make -C src-gen/generated/architecture run\` (or \`contract run\`) write them there; a Build & Run shows its own run here when it ends.`));
      return;
    }
    const { files, problems } = await readWorkspaceLogs(csvs, (f) => f, Infinity);
    this.drawLogs(files, problems, '');
  }

  private drawLogs(files: LogFile[], problems: string[], emptyText: string): void {
    if (!files.length && emptyText) {
      this.info.textContent = '';
      this.last = undefined;
      this.canvas.replaceChildren(h('div', { class: 'pad muted' }, `${emptyText} ${problems.join(' ')}`.trim()));
      return;
    }
    const { acts, errors } = activationsFromLogs(files);
    this.draw(acts, files.length + problems.length, [...problems, ...errors]);
  }

  private draw(acts: Activation[], files: number, errors: string[]): void {
    this.last = { acts, files, errors };
    if (!acts.length) {
      this.canvas.replaceChildren(h('div', { class: 'pad muted' }, `No activations in ${files} log file(s). ${errors.join(' ')}`));
      return;
    }
    const t0 = acts[0]!.start;
    const tEnd = Math.max(...acts.map((a) => a.end ?? a.start));
    const span = Math.max(1, tEnd - t0);
    const modules = [...new Set(acts.map((a) => a.module))].sort();
    const period = inferPeriod(acts);
    const lane = 26;
    const left = 70;
    // fit the visible width (hover a bar for exact times)
    const width = Math.max(600, (this.canvas.clientWidth || 1000) - 40) * 2 ** Number(this.zoom.value);
    const height = modules.length * lane + 30;
    const x = (t: number) => left + ((t - t0) / span) * (width - left - 10);
    const axis = svg('text', { x: width - 10, y: height - 6, class: 'period-label', 'text-anchor': 'end' }, `${(span / 1e6).toFixed(1)} ms`);
    const root = svg('svg', { width, height, class: 'timeline-svg' });
    if (period) {
      let k = 0;
      for (let t = t0; t <= tEnd && k < 2000; t += period, k++) {
        root.append(svg('line', { x1: x(t), x2: x(t), y1: 0, y2: height - 20, class: 'period-line' }));
        if (k % Math.max(1, Math.ceil(2000 / 40 / 50)) === 0) root.append(svg('text', { x: x(t) + 2, y: height - 6, class: 'period-label' }, `#${k}`));
      }
    }
    modules.forEach((m, i) => {
      root.append(svg('text', { x: 6, y: i * lane + 17, class: 'lane-label' }, m));
      root.append(svg('line', { x1: left, x2: width, y1: (i + 1) * lane, y2: (i + 1) * lane, class: 'lane-sep' }));
    });
    for (const a of acts) {
      const i = modules.indexOf(a.module);
      const x1 = x(a.start);
      const x2 = Math.max(x1 + 2, x(a.end ?? tEnd));
      const bar = svg('rect', { x: x1, y: i * lane + 5, width: x2 - x1, height: lane - 10, rx: 2, class: `act-bar${a.end === undefined ? ' open' : ''}` });
      bar.append(svg('title', {}, `${a.module} ${((a.start - t0) / 1e6).toFixed(3)} ms → ${a.end ? `${((a.end - a.start) / 1e6).toFixed(3)} ms` : 'running'} ${a.detail}`));
      root.append(bar);
    }
    root.append(axis);
    this.info.textContent = `${acts.length} activations · ${modules.length} modules · ${(span / 1e6).toFixed(1)} ms${period ? ` · period ≈ ${(period / 1e6).toFixed(2)} ms` : ''}${errors.length ? ` · ${errors.length} unreadable log(s)` : ''}`;
    this.canvas.replaceChildren(root);
  }
}
