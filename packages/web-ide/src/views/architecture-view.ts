/**
 * Architecture diagram of a schema: modules as boxes with their ports (inputs left, outputs
 * right, parameters on top), data flows (solid, `* k` periodicity), event flows (dashed,
 * `=*` continuous / `=>` one shot) and precedence edges (dotted), laid out by elkjs in a Web
 * Worker. Loaded lazily (dynamic import): not in the page's first load; once the IDE is ready and
 * idle, main.ts loads it and warms ELK's worker up (warmUpLayout).
 */
import ELK, { type ElkNode } from 'elkjs/lib/elk-api.js';
import elkWorkerUrl from 'elkjs/lib/elk-worker.min.js?url';
import { h, debounce } from '../util/dom.js';
import type { ArchSchema, ArchLocation } from '../lsp/architecture-model.js';
import { PanZoom, type Size } from './pan-zoom.js';
import { HEAD } from './schema-graph.js';
import { layoutSchema, SMALLEST_FONT_PX, MIN_FONT_PX, type SchemaLayout } from './schema-layout.js';
import { failingOn, isLayoutFault, type LayoutFault } from './layout-faults.js';

const SVG = 'http://www.w3.org/2000/svg';
const elk = new ELK({ workerFactory: () => new Worker(elkWorkerUrl) });

/**
 * Starts ELK's worker and lays out a two-module graph in it as a schema is laid out, so that its
 * script (1.5 MB: 141 ms to compile and run, traced on the 2-core test machine) and the layered
 * algorithm's first, slowest run (220 ms, then 99, 66 and 34 ms for the next layouts) are done
 * before a diagram is needed: Build & Run opens the Monitor, whose first diagram did both while gcc
 * built the job on the same two CPUs, and the page's opening frames came late.
 */
export async function warmUpLayout(): Promise<void> {
  const t0 = performance.now();
  const module = (id: string) => ({ id, width: 120, height: 60, layoutOptions: { 'elk.portConstraints': 'FIXED_SIDE' }, ports: [{ id: `${id}.in`, width: 6, height: 6, layoutOptions: { 'elk.port.side': 'WEST' } }, { id: `${id}.out`, width: 6, height: 6, layoutOptions: { 'elk.port.side': 'EAST' } }] });
  await elk.layout({
    id: 'warm-up', layoutOptions: { 'elk.algorithm': 'layered', 'elk.edgeRouting': 'ORTHOGONAL', 'elk.edgeLabels.inline': 'true' },
    children: [module('A'), module('B')],
    edges: [{ id: 'e', sources: ['A.out'], targets: ['B.in'], labels: [{ text: ':0', width: 30, height: 14 }] }],
  }).catch(() => undefined);
  performance.measure('ide:layout-warmed', { start: t0, end: performance.now() });
}

function svg<K extends keyof SVGElementTagNameMap>(tag: K, attrs: Record<string, string | number>, text?: string): SVGElementTagNameMap[K] {
  const el = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, String(v));
  if (text !== undefined) el.textContent = text;
  return el;
}

function toSeconds(t: string | undefined): number | undefined {
  const m = t?.match(/^(-?[\d.]+)(ns|us|ms|s)$/);
  if (!m) return undefined;
  return Number(m[1]) * { ns: 1e-9, us: 1e-6, ms: 1e-3, s: 1 }[m[2] as 'ns']!;
}

/** The definition a diagram element stands for (a module, a port, a flow): a click goes there. */
export const definitionOf = new WeakMap<Element, ArchLocation>();

/** Layouts kept for schemas shown again (ArchitectureView.layoutOf). */
const LAYOUTS_KEPT = 24;

export function renderSchema(schema: ArchSchema, graph: ElkNode): SVGSVGElement {
  const w = (graph.width ?? 400) + 40;
  const hgt = (graph.height ?? 200) + 40;
  // the drawing at its natural size in a scene the view zooms and pans (pan-zoom.ts)
  const root = svg('svg', { class: 'arch-svg', 'data-schema': schema.name, 'data-width': w, 'data-height': hgt });
  const scene = svg('g', { class: 'arch-scene' });
  const drawing = svg('g', { transform: 'translate(20,20)' });
  scene.append(drawing);
  const defs = svg('defs', {});
  for (const [id, color] of [['arrow-data', '#61afef'], ['arrow-event', '#e5c07b'], ['arrow-prec', '#7f8796']] as const) {
    const marker = svg('marker', { id, viewBox: '0 0 10 10', refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: 'auto-start-reverse' });
    marker.append(svg('path', { d: 'M0,0 L10,5 L0,10 z', fill: color }));
    defs.append(marker);
  }
  root.append(defs, scene);
  const byName = new Map(schema.modules.map((m) => [m.name, m]));
  for (const e of graph.edges ?? []) {
    const flow = e.id.startsWith('f') ? schema.flows[Number(e.id.slice(1))] : undefined;
    const cls = flow ? `edge ${flow.kind}` : 'edge precedence';
    for (const s of e.sections ?? []) {
      const pts = [s.startPoint, ...(s.bendPoints ?? []), s.endPoint];
      // data-flow names the flow as the trace does (monitor: `MAA:0->MAB:0`)
      const points = pts.map((p) => `${p.x},${p.y}`).join(' ');
      drawing.append(svg('polyline', { points, class: cls, 'marker-end': `url(#arrow-${flow ? flow.kind : 'prec'})`,
        ...(flow ? { 'data-flow': `${flow.from}:${flow.fromPort}->${flow.to}:${flow.toPort}` } : {}) }));
      if (flow?.def) {
        // a wide invisible twin of the line takes the clicks (the line itself is 1.6 px)
        const hit = svg('polyline', { points, class: 'edge-hit', 'data-flow-hit': `${flow.from}:${flow.fromPort}->${flow.to}:${flow.toPort}` });
        hit.append(svg('title', {}, `${flow.from}:${flow.fromPort} → ${flow.to}:${flow.toPort} (click: go to the communication)`));
        definitionOf.set(hit, flow.def);
        drawing.append(hit);
      }
    }
    for (const l of e.labels ?? []) {
      if (l.x === undefined) continue;
      drawing.append(svg('text', { x: l.x, y: (l.y ?? 0) + 11, class: `edge-label ${flow?.kind ?? ''}` }, l.text));
    }
  }
  for (const n of graph.children ?? []) {
    const m = byName.get(n.id)!;
    const g = svg('g', { transform: `translate(${n.x},${n.y})`, class: `arch-node ${m.kind}`, 'data-module': m.name,
      ...(m.def ? { tabindex: 0, role: 'button', 'aria-label': `${m.kind} module ${m.name}: go to its definition` } : {}) });
    if (m.def) definitionOf.set(g, m.def);
    g.append(svg('rect', { width: n.width!, height: n.height!, rx: 6, class: 'node-box' }));
    g.append(svg('path', { d: `M0,6 a6,6 0 0 1 6,-6 h${n.width! - 12} a6,6 0 0 1 6,6 v${HEAD - 6} h${-n.width!} z`, class: 'node-head' }));
    g.append(svg('text', { x: 10, y: 17, class: 'node-title' }, m.name));
    g.append(svg('text', { x: n.width! - 10, y: 17, class: 'node-kind', 'text-anchor': 'end' }, `${m.kind === 'synchronous' ? 'sync' : m.kind === 'asynchronous' ? 'async' : m.kind}${m.wcet ? ` · C=${m.wcet}` : ''}`));
    for (const p of n.ports ?? []) {
      const [, kind, dir, idx] = p.id.split('.');
      const port = m.ports.find((q) => q.kind === kind && q.direction === dir && q.index === Number(idx));
      // data-port names the port as scenarios and the trace do (`MAA:2`): the Simulate panel injects on a click
      const box = svg('rect', { x: p.x!, y: p.y!, width: 10, height: 10, class: `port ${kind}`, 'data-dir': dir ?? '', ...(port ? { 'data-port': `${m.name}:${port.index}` } : {}) });
      g.append(box);
      if (!port) continue;
      const label = `:${port.index} ${port.name}`;
      // a port on top or at the bottom (a drawing top to bottom: schema-graph.ts nodeOf) has its label inside the box, under the head or above the bottom edge
      const side = p.layoutOptions?.['port.side'];
      const text = kind === 'param' ? svg('text', { x: p.x! + 5, y: p.y! - 4, class: 'port-label param', 'text-anchor': 'middle' }, `param :${port.index}`)
        : side === 'NORTH' ? svg('text', { x: p.x!, y: HEAD + 13, class: `port-label ${kind}` }, label)
        : side === 'SOUTH' ? svg('text', { x: p.x!, y: p.y! - 2, class: `port-label ${kind}` }, label)
        : dir === 'in' ? svg('text', { x: p.x! + 14, y: p.y! + 9, class: `port-label ${kind}` }, label)
        : svg('text', { x: p.x! - 4, y: p.y! + 9, class: `port-label ${kind}`, 'text-anchor': 'end' }, label);
      g.append(text);
      if (port.def) for (const el of [box, text]) definitionOf.set(el, port.def);
    }
    drawing.append(g);
  }
  return root;
}

/** What the monitor (src/monitor/) highlights on the diagram: the run's state at its cursor. */
export interface LiveHighlight {
  /** Modules of an active schema. */
  active: ReadonlySet<string>;
  /** Modules running a release or an activation right now. */
  running: ReadonlySet<string>;
  /** Flows (`data-flow`) that delivered recently: they pulse. */
  pulsing: ReadonlySet<string>;
  /** Flows that delivered at least once. */
  used: ReadonlySet<string>;
}

/** A cursor in an editor (0-based, LSP style): the diagram shows the schema it is in. */
export interface CursorAt {
  uri: string;
  line: number;
  character: number;
}

const inRange = (c: CursorAt, s: ArchSchema) => {
  const r = s.range;
  if (!r || s.uri !== c.uri) return false;
  const after = c.line > r.start.line || (c.line === r.start.line && c.character >= r.start.character);
  const before = c.line < r.end.line || (c.line === r.end.line && c.character <= r.end.character);
  return after && before;
};

/**
 * The view: a schema picker, figures, zoom buttons, the diagram and a legend; `update` re-layouts.
 * The diagram zooms (wheel at the pointer, +/−), pans (drag, arrows), fits (button, F); a click on a
 * module, port or flow goes to its definition; it follows the schema at the editor's cursor.
 */
export class ArchitectureView {
  readonly element: HTMLElement;
  private readonly select: HTMLSelectElement;
  private readonly canvas: HTMLElement;
  private readonly info: HTMLElement;
  private readonly panZoom: PanZoom;
  private schemas: ArchSchema[] = [];
  private chosen: string | undefined;
  /** What the canvas shows: the schema, the pane it was laid out for, and the model it was drawn from (`source`: none after a failed layout). */
  private drawn: { schema: string; pane: Size; source?: string } | undefined;
  private seq = 0;
  private live: LiveHighlight | undefined;
  /**
   * The pane's size as the ResizeObserver last reported it (null: not on screen; undefined: not
   * reported yet). Read instead of measuring: a measure while the page is being changed (the
   * Monitor opening beside the editor) forces a layout the frame then does again.
   */
  private observed: Size | null | undefined;
  private onObserved: Array<() => void> = [];
  private cursor: CursorAt | undefined;
  private followed: string | undefined;
  /** The layouts ELK is made to fail on (failLayouts, a test hook): none but in the tests. */
  private fault: LayoutFault | undefined;

  constructor(
    private readonly fetchSchemas: () => Promise<ArchSchema[]>,
    onToggleDock?: () => void,
    private readonly onGoTo?: (where: ArchLocation) => void,
    /** `inScrolledPanel`: the diagram is a section of a panel that scrolls (the Monitor): a plain wheel scrolls the panel. */
    private readonly opts: { inScrolledPanel?: boolean } = {},
  ) {
    this.select = h('select', { class: 'arch-select', 'aria-label': 'Schema shown' });
    this.select.addEventListener('change', () => {
      this.chosen = this.select.value;
      this.reveal();
      void this.draw();
    });
    this.info = h('span', { class: 'arch-info muted' });
    this.canvas = h('div', {
      class: 'arch-canvas', tabindex: 0, role: 'group', 'data-autofocus': true,
      'aria-label': `Architecture diagram: ${opts.inScrolledPanel ? 'Ctrl + wheel' : 'wheel'} or + and − zoom, drag or arrows pan, F fits; click a module, port or flow to go to its definition`,
    });
    this.panZoom = new PanZoom(this.canvas, (v) => {
      this.canvas.querySelector('.arch-scene')?.setAttribute('transform', `translate(${v.x.toFixed(1)},${v.y.toFixed(1)}) scale(${v.scale.toFixed(4)})`);
      this.canvas.dataset.scale = v.scale.toFixed(4);
    }, { smallestFontPx: SMALLEST_FONT_PX, minFontPx: MIN_FONT_PX, wheelScrollsPage: !!opts.inScrolledPanel }, () => this.reveal());
    const goTo = (target: EventTarget | null) => {
      for (let el = target as Element | null; el && el !== this.canvas; el = el.parentElement) {
        const def = definitionOf.get(el);
        if (def) return this.onGoTo?.(def), true;
      }
      return false;
    };
    this.canvas.addEventListener('click', (e) => goTo(e.target));
    this.canvas.addEventListener('keydown', (e) => e.key === 'Enter' && e.target !== this.canvas && goTo(e.target) && e.preventDefault());
    const zoomBtn = (id: string, label: string, title: string, run: () => void) => h('button', { class: 'btn small', id, title, 'aria-label': title, onclick: run }, label);
    this.element = h('div', { class: 'arch-view' },
      h('div', { class: 'arch-toolbar' }, h('span', { class: 'arch-label' }, 'Schema'), this.select, this.info, h('span', { class: 'grow' }),
        zoomBtn('arch-zoom-out', '−', 'Zoom out (−)', () => this.panZoom.zoom(0.8)),
        zoomBtn('arch-zoom-in', '+', 'Zoom in (+)', () => this.panZoom.zoom(1.25)),
        zoomBtn('arch-fit', 'Fit', 'Fit the diagram to the pane (F)', () => this.panZoom.fit()), // fit() reveals the pane first
        onToggleDock ? h('button', { class: 'btn small', id: 'arch-dock', title: 'Show the diagram beside the editor (or back in a tab)', onclick: onToggleDock }, '⇆ Side by side') : null,
        h('span', { class: 'legend data' }, '━ data flow'), h('span', { class: 'legend event' }, '┅ event flow'), h('span', { class: 'legend prec' }, '┈ precedence')),
      this.canvas);
    // the layout is made for the pane: a pane that changed shape (docked, resized) gets a new one
    const relayout = debounce(() => {
      const pane = this.observed;
      if (!this.drawn || !pane) return;
      const ratio = (a: Size) => a.width / Math.max(1, a.height);
      if (Math.abs(Math.log(ratio(pane) / ratio(this.drawn.pane))) > 0.25) void this.draw();
    }, 250);
    new ResizeObserver((entries) => {
      const box = entries[entries.length - 1]?.borderBoxSize?.[0];
      const [width, height] = box ? [box.inlineSize, box.blockSize] : [this.canvas.offsetWidth, this.canvas.offsetHeight];
      this.observed = width > 0 && height > 0 ? { width, height } : null;
      for (const waiter of this.onObserved.splice(0)) waiter();
      relayout();
    }).observe(this.canvas);
  }

  /**
   * In a scrolled panel, brings the whole view (its toolbar and the diagram's pane) on screen: a pane
   * partly scrolled away (its toolbar with it: the Monitor's does not stick, monitor.css) would hide the
   * top of a diagram just fitted or just picked. Nothing to do in a view that is not scrolled.
   */
  private reveal(): void {
    if (!this.opts.inScrolledPanel) return;
    let panel = this.element.parentElement;
    while (panel && !/auto|scroll/.test(getComputedStyle(panel).overflowY)) panel = panel.parentElement;
    if (!panel) return;
    // its top when that is above the panel's (else 'nearest' leaves a view taller than the panel where it is)
    const above = this.element.getBoundingClientRect().top < panel.getBoundingClientRect().top;
    this.element.scrollIntoView({ block: above ? 'start' : 'nearest', inline: 'nearest' });
  }

  /** The schema shown, when one is. */
  get schema(): string | undefined {
    return this.chosen;
  }

  /** Zoom scale of the drawing (1 = natural size). */
  get scale(): number {
    return this.panZoom.view.scale;
  }

  /**
   * Test hook (`__ide.views.arch.failLayouts('fold')` in the browser tests): from now on ELK fails on
   * the layouts `fault` names (layout-faults.ts; undefined: none), and the schema shown is drawn
   * again, so that what is drawn when ELK fails can be seen in the page.
   */
  async failLayouts(fault: LayoutFault | undefined): Promise<void> {
    if (fault !== undefined && !isLayoutFault(fault)) throw new Error(`Unknown layout fault ${JSON.stringify(fault)}: fold, asked or every`);
    this.fault = fault;
    if (this.drawn) this.drawn.source = undefined;
    await this.draw();
  }

  /** Shows schema `name` (no-op when it is shown or unknown). */
  async choose(name: string): Promise<void> {
    if (name === this.chosen || !this.schemas.some((s) => s.name === name)) return;
    this.chosen = name;
    this.select.value = name;
    await this.draw();
  }

  /**
   * The editor's cursor moved: when it went into a schema, that schema is shown (moving inside the
   * same schema keeps a schema picked in the list meanwhile).
   */
  follow(cursor: CursorAt | undefined): void {
    this.cursor = cursor;
    const at = cursor && this.schemas.find((s) => inRange(cursor, s));
    const entered = at && at.name !== this.followed;
    this.followed = at?.name;
    if (entered) void this.choose(at.name);
  }
  /** Marks the run's state on the diagram (classes only: no re-layout), or clears it. */
  highlight(live: LiveHighlight | undefined): void {
    this.live = live;
    const svgEl = this.canvas.querySelector('svg');
    if (!svgEl) return;
    // called every frame while a run is watched: touch the DOM only when something changed
    const key = live ? [live.active, live.running, live.pulsing, live.used].map((s) => [...s].sort().join(',')).join('|') : '';
    if (svgEl.dataset.live === key) return;
    svgEl.dataset.live = key;
    svgEl.classList.toggle('live', !!live);
    for (const g of svgEl.querySelectorAll<SVGGElement>('.arch-node')) {
      const m = g.dataset.module ?? '';
      g.classList.toggle('live-active', !!live?.active.has(m));
      g.classList.toggle('live-running', !!live?.running.has(m));
    }
    for (const e of svgEl.querySelectorAll<SVGPolylineElement>('polyline[data-flow]')) {
      const f = e.dataset.flow ?? '';
      e.classList.toggle('pulse', !!live?.pulsing.has(f));
      e.classList.toggle('used', !!live?.used.has(f));
    }
  }

  async update(): Promise<void> {
    try {
      this.schemas = await this.fetchSchemas();
    } catch (e) {
      this.canvas.replaceChildren(h('div', { class: 'pad gen-error' }, `Cannot read the model: ${(e as Error).message}`));
      if (this.drawn) this.drawn.source = undefined;
      return;
    }
    const names = this.schemas.map((s) => s.name);
    const atCursor = this.cursor && this.schemas.find((s) => inRange(this.cursor!, s));
    if (atCursor && atCursor.name !== this.followed) this.chosen = atCursor.name; // the cursor went into a schema since
    this.followed = atCursor?.name;
    if (!this.chosen || !names.includes(this.chosen)) this.chosen = names[0];
    this.select.replaceChildren(...this.schemas.map((s) => h('option', { value: s.name, selected: s.name === this.chosen }, `${s.name} (${s.kind})`)));
    await this.draw();
  }

  private async draw(): Promise<void> {
    const schema = this.schemas.find((s) => s.name === this.chosen);
    if (!schema) {
      this.canvas.replaceChildren(h('div', { class: 'muted pad' }, 'No schema in the workspace'));
      if (this.drawn) this.drawn.source = undefined;
      this.info.textContent = '';
      return;
    }
    const seq = ++this.seq;
    const period = toSeconds(schema.period);
    const sumC = schema.modules.reduce((a, m) => a + (toSeconds(m.wcet) ?? 0), 0);
    this.info.textContent = schema.kind === 'periodic'
      ? `PERIOD ${schema.period ?? '?'} · CRITICAL_DELAY ${schema.criticalDelay ?? '?'} · ΣC ${(sumC * 1000).toFixed(2)} ms${period ? ` · utilisation ${((sumC / period) * 100).toFixed(1)} %` : ''}`
      : 'event schema (asynchronous modules)';
    this.info.title = this.info.textContent;
    try {
      const pane = await this.paneSize();
      if (seq !== this.seq) return;
      // the same schema of the same model in a pane of the same size (a model re-read after a save that
      // changed another file, the Monitor opened again by Build & Run): the drawing is already right
      const source = JSON.stringify(schema);
      const d = this.drawn;
      if (d?.source === source && d.schema === schema.name && pane && d.pane.width === pane.width && d.pane.height === pane.height) return;
      const { graph, note } = await this.layoutOf(schema, source, pane);
      if (seq !== this.seq) return;
      const drawing = renderSchema(schema, graph);
      this.canvas.replaceChildren(drawing, ...(note ? [h('div', { class: 'arch-note', role: 'status' }, note)] : []));
      const size = { width: Number(drawing.dataset.width), height: Number(drawing.dataset.height) };
      // the same schema re-drawn after an edit keeps the user's zoom and pan; a new one starts readable
      const keepView = this.drawn?.schema === schema.name && pane && this.drawn.pane.width === pane.width && this.drawn.pane.height === pane.height;
      this.panZoom.setContent(size, !keepView);
      this.drawn = { schema: schema.name, pane: pane ?? { width: 0, height: 0 }, source };
      if (this.live) this.highlight(this.live);
    } catch (e) {
      if (this.drawn) this.drawn.source = undefined; // the error replaced the drawing: the next draw makes one
      this.canvas.replaceChildren(h('div', { class: 'pad gen-error' }, `Layout failed: ${(e as Error).message}`));
    }
  }

  /**
   * The layouts made, by schema model and pane size (and the fault failLayouts asked; the last LAYOUTS_KEPT): the Monitor shows the
   * schema active at its cursor, and a run whose schemas take turns switched the diagram back and
   * forth several times a second, each time laying the schema out again in ELK's worker (up to four
   * layouts with the folded tries), competing for the CPU with the run. A layout depends on nothing
   * else; the drawing is still made anew from it (renderSchema), fresh for its highlight. A layout
   * still being made is kept too: a draw asked meanwhile (the model read again, the schema chosen
   * while the Monitor opens) waits for it instead of asking ELK for the same one; a failed one is
   * let go, so the next draw tries again.
   */
  private readonly layouts = new Map<string, Promise<SchemaLayout>>();

  private layoutOf(schema: ArchSchema, source: string, pane: Size | undefined): Promise<SchemaLayout> {
    const key = `${pane ? `${pane.width}x${pane.height}` : '-'} ${this.fault ?? ''} ${source}`;
    const kept = this.layouts.get(key);
    if (kept) {
      this.layouts.delete(key);
      this.layouts.set(key, kept); // the most recent last
      return kept;
    }
    const graph = layoutSchema(schema, pane, failingOn(this.fault, (g) => elk.layout(g)));
    this.layouts.set(key, graph);
    graph.catch(() => this.layouts.get(key) === graph && this.layouts.delete(key));
    for (const old of this.layouts.keys()) if (this.layouts.size > LAYOUTS_KEPT) this.layouts.delete(old);
    return graph;
  }

  /**
   * The pane's size, when it is on screen: the observer's, after its first report (it comes with the
   * next layout); a pane that is not laid out (not in the page, hidden) gets no report, so after
   * 100 ms it is measured.
   */
  private async paneSize(): Promise<Size | undefined> {
    if (this.observed === undefined) {
      await new Promise<void>((done) => {
        const timer = setTimeout(done, 100);
        this.onObserved.push(() => (clearTimeout(timer), done()));
      });
    }
    if (this.observed !== undefined) return this.observed ?? undefined;
    const r = this.canvas.getBoundingClientRect();
    return r.width > 0 && r.height > 0 ? { width: r.width, height: r.height } : undefined;
  }
}
