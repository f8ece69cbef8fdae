/**
 * Architecture diagram of a schema: modules as boxes with their ports (inputs left, outputs
 * right, parameters on top), data flows (solid, `* k` periodicity), event flows (dashed,
 * `=*` continuous / `=>` one shot) and precedence edges (dotted), laid out by elkjs in a Web
 * Worker. Loaded lazily (dynamic import) so elkjs costs nothing until the view is opened.
 */
import ELK, { type ElkNode, type ElkExtendedEdge, type ElkPort } from 'elkjs/lib/elk-api.js';
import elkWorkerUrl from 'elkjs/lib/elk-worker.min.js?url';
import { h } from '../util/dom.js';
import type { ArchSchema, ArchModule } from '../lsp/architecture-model.js';

const SVG = 'http://www.w3.org/2000/svg';
const elk = new ELK({ workerFactory: () => new Worker(elkWorkerUrl) });

function svg<K extends keyof SVGElementTagNameMap>(tag: K, attrs: Record<string, string | number>, text?: string): SVGElementTagNameMap[K] {
  const el = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attrs)) el.setAttribute(k, String(v));
  if (text !== undefined) el.textContent = text;
  return el;
}

const portId = (m: string, kind: string, dir: string, index: number) => `${m}.${kind}.${dir}.${index}`;

function toSeconds(t: string | undefined): number | undefined {
  const m = t?.match(/^(-?[\d.]+)(ns|us|ms|s)$/);
  if (!m) return undefined;
  return Number(m[1]) * { ns: 1e-9, us: 1e-6, ms: 1e-3, s: 1 }[m[2] as 'ns']!;
}

const NODE_W = 210;
const HEAD = 26;
const ROW = 20;

/** A module box with fixed port positions: inputs on the left, outputs on the right, parameters on top. */
function nodeOf(m: ArchModule): ElkNode {
  const ins = m.ports.filter((p) => p.direction === 'in' && p.kind !== 'param');
  const outs = m.ports.filter((p) => p.direction === 'out');
  const params = m.ports.filter((p) => p.kind === 'param');
  const rowY = (i: number) => HEAD + 8 + i * ROW;
  const longest = (ps: typeof ins) => Math.max(0, ...ps.map((p) => `:${p.index} ${p.name}`.length));
  const width = Math.max(NODE_W, 40 + 7 * (longest(ins) + longest(outs)));
  const ports: ElkPort[] = [
    ...ins.map((p, i) => ({ id: portId(m.name, p.kind, 'in', p.index), x: -5, y: rowY(i), width: 10, height: 10, layoutOptions: { 'port.side': 'WEST' } })),
    ...outs.map((p, i) => ({ id: portId(m.name, p.kind, 'out', p.index), x: width - 5, y: rowY(i), width: 10, height: 10, layoutOptions: { 'port.side': 'EAST' } })),
    ...params.map((p, i) => ({ id: portId(m.name, 'param', 'in', p.index), x: width / 2 - 5 + i * 60, y: -5, width: 10, height: 10, layoutOptions: { 'port.side': 'NORTH' } })),
  ];
  return {
    id: m.name,
    width,
    height: HEAD + 14 + ROW * Math.max(ins.length, outs.length, 1),
    ports,
    layoutOptions: { portConstraints: 'FIXED_POS' },
  };
}

export async function layoutSchema(schema: ArchSchema): Promise<ElkNode> {
  const known = new Set(schema.modules.map((m) => m.name));
  const edges: ElkExtendedEdge[] = [];
  schema.flows.forEach((f, i) => {
    if (!known.has(f.from) || !known.has(f.to)) return;
    edges.push({ id: `f${i}`, sources: [portId(f.from, f.kind, 'out', f.fromPort)], targets: [portId(f.to, f.kind, 'in', f.toPort)], labels: [{ text: f.label, width: 30, height: 14 }] });
  });
  schema.precedences.forEach((p, i) => {
    if (known.has(p.from) && known.has(p.to)) edges.push({ id: `p${i}`, sources: [p.from], targets: [p.to] });
  });
  // Ports referenced by flows but missing on a module (errors in the model) are dropped by ELK; keep only valid ones.
  const portIds = new Set(schema.modules.flatMap((m) => nodeOf(m).ports!.map((p) => p.id)));
  const valid = edges.filter((e) => [...e.sources, ...e.targets].every((s) => portIds.has(s) || known.has(s)));
  return elk.layout({
    id: 'root',
    layoutOptions: {
      'elk.algorithm': 'layered',
      'elk.direction': 'RIGHT',
      'elk.spacing.nodeNode': '50',
      'elk.layered.spacing.nodeNodeBetweenLayers': '90',
      'elk.edgeRouting': 'ORTHOGONAL',
      'elk.edgeLabels.inline': 'true',
    },
    children: schema.modules.map(nodeOf),
    edges: valid,
  });
}

export function renderSchema(schema: ArchSchema, graph: ElkNode): SVGSVGElement {
  const w = (graph.width ?? 400) + 40;
  const hgt = (graph.height ?? 200) + 40;
  const root = svg('svg', { viewBox: `-20 -20 ${w} ${hgt}`, width: w, height: hgt, class: 'arch-svg', 'data-schema': schema.name });
  const defs = svg('defs', {});
  for (const [id, color] of [['arrow-data', '#61afef'], ['arrow-event', '#e5c07b'], ['arrow-prec', '#7f8796']] as const) {
    const marker = svg('marker', { id, viewBox: '0 0 10 10', refX: 9, refY: 5, markerWidth: 7, markerHeight: 7, orient: 'auto-start-reverse' });
    marker.append(svg('path', { d: 'M0,0 L10,5 L0,10 z', fill: color }));
    defs.append(marker);
  }
  root.append(defs);
  const byName = new Map(schema.modules.map((m) => [m.name, m]));
  for (const e of graph.edges ?? []) {
    const flow = e.id.startsWith('f') ? schema.flows[Number(e.id.slice(1))] : undefined;
    const cls = flow ? `edge ${flow.kind}` : 'edge precedence';
    for (const s of e.sections ?? []) {
      const pts = [s.startPoint, ...(s.bendPoints ?? []), s.endPoint];
      // data-flow names the flow as the trace does (monitor: `MAA:0->MAB:0`)
      root.append(svg('polyline', { points: pts.map((p) => `${p.x},${p.y}`).join(' '), class: cls, 'marker-end': `url(#arrow-${flow ? flow.kind : 'prec'})`,
        ...(flow ? { 'data-flow': `${flow.from}:${flow.fromPort}->${flow.to}:${flow.toPort}` } : {}) }));
    }
    for (const l of e.labels ?? []) {
      if (l.x === undefined) continue;
      root.append(svg('text', { x: l.x, y: (l.y ?? 0) + 11, class: `edge-label ${flow?.kind ?? ''}` }, l.text));
    }
  }
  for (const n of graph.children ?? []) {
    const m = byName.get(n.id)!;
    const g = svg('g', { transform: `translate(${n.x},${n.y})`, class: `arch-node ${m.kind}`, 'data-module': m.name });
    g.append(svg('rect', { width: n.width!, height: n.height!, rx: 6, class: 'node-box' }));
    g.append(svg('path', { d: `M0,6 a6,6 0 0 1 6,-6 h${n.width! - 12} a6,6 0 0 1 6,6 v${HEAD - 6} h${-n.width!} z`, class: 'node-head' }));
    g.append(svg('text', { x: 10, y: 17, class: 'node-title' }, m.name));
    g.append(svg('text', { x: n.width! - 10, y: 17, class: 'node-kind', 'text-anchor': 'end' }, `${m.kind === 'synchronous' ? 'sync' : m.kind === 'asynchronous' ? 'async' : m.kind}${m.wcet ? ` · C=${m.wcet}` : ''}`));
    for (const p of n.ports ?? []) {
      const [, kind, dir, idx] = p.id.split('.');
      const port = m.ports.find((q) => q.kind === kind && q.direction === dir && q.index === Number(idx));
      // data-port names the port as scenarios and the trace do (`MAA:2`): the Simulate panel injects on a click
      g.append(svg('rect', { x: p.x!, y: p.y!, width: 10, height: 10, class: `port ${kind}`, 'data-dir': dir ?? '', ...(port ? { 'data-port': `${m.name}:${port.index}` } : {}) }));
      if (!port) continue;
      const label = `:${port.index} ${port.name}`;
      if (kind === 'param') g.append(svg('text', { x: p.x! + 5, y: p.y! - 4, class: 'port-label param', 'text-anchor': 'middle' }, `param :${port.index}`));
      else if (dir === 'in') g.append(svg('text', { x: p.x! + 14, y: p.y! + 9, class: `port-label ${kind}` }, label));
      else g.append(svg('text', { x: p.x! - 4, y: p.y! + 9, class: `port-label ${kind}`, 'text-anchor': 'end' }, label));
    }
    root.append(g);
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

/** The view: a schema picker, figures, the diagram and a legend; `update` re-layouts. */
export class ArchitectureView {
  readonly element: HTMLElement;
  private readonly select: HTMLSelectElement;
  private readonly canvas: HTMLElement;
  private readonly info: HTMLElement;
  private schemas: ArchSchema[] = [];
  private chosen: string | undefined;
  private seq = 0;
  private live: LiveHighlight | undefined;

  constructor(
    private readonly fetchSchemas: () => Promise<ArchSchema[]>,
    onToggleDock?: () => void,
  ) {
    this.select = h('select', { class: 'arch-select' });
    this.select.addEventListener('change', () => {
      this.chosen = this.select.value;
      void this.draw();
    });
    this.info = h('span', { class: 'arch-info muted' });
    this.canvas = h('div', { class: 'arch-canvas' });
    this.element = h('div', { class: 'arch-view' },
      h('div', { class: 'arch-toolbar' }, h('span', { class: 'arch-label' }, 'Schema'), this.select, this.info, h('span', { class: 'grow' }),
        onToggleDock ? h('button', { class: 'btn small', id: 'arch-dock', title: 'Show the diagram beside the editor (or back in a tab)', onclick: onToggleDock }, '⇆ Side by side') : null,
        h('span', { class: 'legend data' }, '━ data flow'), h('span', { class: 'legend event' }, '┅ event flow'), h('span', { class: 'legend prec' }, '┈ precedence')),
      this.canvas);
  }

  /** The schema shown, when one is. */
  get schema(): string | undefined {
    return this.chosen;
  }

  /** Shows schema `name` (no-op when it is shown or unknown). */
  async choose(name: string): Promise<void> {
    if (name === this.chosen || !this.schemas.some((s) => s.name === name)) return;
    this.chosen = name;
    this.select.value = name;
    await this.draw();
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
      return;
    }
    const names = this.schemas.map((s) => s.name);
    if (!this.chosen || !names.includes(this.chosen)) this.chosen = names[0];
    this.select.replaceChildren(...this.schemas.map((s) => h('option', { value: s.name, selected: s.name === this.chosen }, `${s.name} (${s.kind})`)));
    await this.draw();
  }

  private async draw(): Promise<void> {
    const schema = this.schemas.find((s) => s.name === this.chosen);
    if (!schema) {
      this.canvas.replaceChildren(h('div', { class: 'muted pad' }, 'No schema in the workspace'));
      this.info.textContent = '';
      return;
    }
    const seq = ++this.seq;
    const period = toSeconds(schema.period);
    const sumC = schema.modules.reduce((a, m) => a + (toSeconds(m.wcet) ?? 0), 0);
    this.info.textContent = schema.kind === 'periodic'
      ? `PERIOD ${schema.period ?? '?'} · CRITICAL_DELAY ${schema.criticalDelay ?? '?'} · ΣC ${(sumC * 1000).toFixed(2)} ms${period ? ` · utilisation ${((sumC / period) * 100).toFixed(1)} %` : ''}`
      : 'event schema (asynchronous modules)';
    try {
      const graph = await layoutSchema(schema);
      if (seq !== this.seq) return;
      this.canvas.replaceChildren(renderSchema(schema, graph));
      if (this.live) this.highlight(this.live);
    } catch (e) {
      this.canvas.replaceChildren(h('div', { class: 'pad gen-error' }, `Layout failed: ${(e as Error).message}`));
    }
  }
}
