/**
 * The graph ELK lays a schema out from (architecture-view.ts runs it in ELK's worker): a box per
 * module with its ports at fixed places, an edge per flow and per precedence, and the options of
 * the layout asked (its direction, folded or not). Plain data: no DOM, no worker.
 *
 * The ports a flow enters and leaves are on the sides the flow runs through: inputs left and
 * outputs right when the drawing runs left to right, inputs on top and outputs at the bottom when
 * it runs top to bottom. A port with a flow on a side along the flow (an input on the left of a
 * module in a top-to-bottom drawing) makes ELK's layered algorithm route the flow around the module
 * through a "north/south port" dummy, and folding (ELK's wrapping) puts "breaking point" dummies
 * in the same layers: ELK 0.12 knows no spacing between those two kinds and threw (`Cannot read
 * properties of undefined (reading 'getDefault')`, `... 'Qg'` minified) for examples/mobile-robot's
 * velocityLoop in the Monitor's pane at 1366 and 1280 px wide, which is narrow enough to be drawn
 * top to bottom and too small for its straight drawing.
 */
import type { ElkNode, ElkExtendedEdge, ElkPort } from 'elkjs/lib/elk-api.js';
import type { ArchSchema, ArchModule } from '../lsp/architecture-model.js';

/** The way a drawing runs: left to right (a wide pane) or top to bottom (a narrow one). */
export type FlowDirection = 'RIGHT' | 'DOWN';

export const portId = (m: string, kind: string, dir: string, index: number) => `${m}.${kind}.${dir}.${index}`;

export const NODE_W = 210;
export const HEAD = 26;
export const ROW = 20;
/** A row of port labels inside a box drawn top to bottom (inputs under the head, outputs above the bottom edge). */
export const LABEL_ROW = 14;
/** Width of a character of a port label (11 px monospace), for the room a label takes. */
const CHAR_W = 7;
/** Room of a parameter port on the top side (its label `param :0` is drawn above the box). */
const PARAM_SLOT = 60;

/** A module's ports by role. */
function portsOf(m: ArchModule) {
  return {
    ins: m.ports.filter((p) => p.direction === 'in' && p.kind !== 'param'),
    outs: m.ports.filter((p) => p.direction === 'out'),
    params: m.ports.filter((p) => p.kind === 'param'),
  };
}

const labelOf = (p: { index: number; name: string }) => `:${p.index} ${p.name}`;

/**
 * A module box with fixed port positions. Left to right: inputs on the left, outputs on the right,
 * one row each, parameters on top. Top to bottom: inputs then parameters on top, outputs at the
 * bottom, side by side, each labelled inside the box (inputs under the head, outputs above the
 * bottom edge).
 */
export function nodeOf(m: ArchModule, direction: FlowDirection = 'RIGHT'): ElkNode {
  const { ins, outs, params } = portsOf(m);
  if (direction === 'DOWN') {
    const slot = (p: { index: number; name: string }) => 16 + CHAR_W * labelOf(p).length;
    const along = (ps: typeof ins, first = 12) => {
      const xs: number[] = [];
      let x = first;
      for (const p of ps) xs.push(x), (x += slot(p));
      return { xs, end: x };
    };
    const top = along(ins);
    const paramXs = params.map((_, i) => top.end + i * PARAM_SLOT);
    const bottom = along(outs);
    const width = Math.max(NODE_W, top.end + params.length * PARAM_SLOT + 6, bottom.end + 6);
    // a row of labels each (14 px): as tall as a box drawn left to right, so that a loop of 8 folded into columns fits the docked pane
    const height = HEAD + 10 + LABEL_ROW * ((ins.length ? 1 : 0) + (outs.length ? 1 : 0) || 1);
    const ports: ElkPort[] = [
      ...ins.map((p, i) => ({ id: portId(m.name, p.kind, 'in', p.index), x: top.xs[i]!, y: -5, width: 10, height: 10, layoutOptions: { 'port.side': 'NORTH' } })),
      ...params.map((p, i) => ({ id: portId(m.name, 'param', 'in', p.index), x: paramXs[i]!, y: -5, width: 10, height: 10, layoutOptions: { 'port.side': 'NORTH' } })),
      ...outs.map((p, i) => ({ id: portId(m.name, p.kind, 'out', p.index), x: bottom.xs[i]!, y: height - 5, width: 10, height: 10, layoutOptions: { 'port.side': 'SOUTH' } })),
    ];
    return { id: m.name, width, height, ports, layoutOptions: { portConstraints: 'FIXED_POS' } };
  }
  const rowY = (i: number) => HEAD + 8 + i * ROW;
  const longest = (ps: typeof ins) => Math.max(0, ...ps.map((p) => labelOf(p).length));
  const width = Math.max(NODE_W, 40 + CHAR_W * (longest(ins) + longest(outs)));
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

/**
 * A folded drawing is tighter, so that more of the schema fits the pane at a readable size: an
 * 8-module loop docked beside the editor (about 530 x 470 px) fits whole at the readable scale
 * (modules 20 px apart, edges 5 px from modules and each other, a 4 px border).
 */
const FOLDED_SPACING = {
  'elk.layered.spacing.edgeNodeBetweenLayers': '5',
  'elk.layered.spacing.edgeEdgeBetweenLayers': '5',
  'elk.spacing.edgeNode': '5',
  'elk.spacing.edgeEdge': '5',
  'elk.padding': '[top=4,left=4,bottom=4,right=4]',
  // no extra room around the flows that run from one row (column) to the next: the 4-module loop
  // docked at 1366 x 768, folded into two columns, was 20 px too wide for the readable size
  'elk.layered.wrapping.additionalEdgeSpacing': '0',
};

/** The flows and precedences between modules of the schema whose ports exist (a model with errors may name others: ELK would refuse them). */
function edgesOf(schema: ArchSchema, nodes: ElkNode[]): ElkExtendedEdge[] {
  const known = new Set(schema.modules.map((m) => m.name));
  const edges: ElkExtendedEdge[] = [];
  schema.flows.forEach((f, i) => {
    if (!known.has(f.from) || !known.has(f.to)) return;
    edges.push({ id: `f${i}`, sources: [portId(f.from, f.kind, 'out', f.fromPort)], targets: [portId(f.to, f.kind, 'in', f.toPort)], labels: [{ text: f.label, width: 30, height: 14 }] });
  });
  schema.precedences.forEach((p, i) => {
    if (known.has(p.from) && known.has(p.to)) edges.push({ id: `p${i}`, sources: [p.from], targets: [p.to] });
  });
  const portIds = new Set(nodes.flatMap((n) => n.ports!.map((p) => p.id)));
  return edges.filter((e) => [...e.sources, ...e.targets].every((s) => portIds.has(s) || known.has(s)));
}

/** What is asked of ELK: the way the drawing runs, folded into rows or columns shaped `fold` (width / height) or not. */
export interface LayoutAsked {
  direction: FlowDirection;
  fold?: number;
}

/** The graph ELK lays `schema` out from, fresh each time (ELK writes its results into it). */
export function graphOf(schema: ArchSchema, asked: LayoutAsked): ElkNode {
  const { direction, fold } = asked;
  const children = schema.modules.map((m) => nodeOf(m, direction));
  const down = direction === 'DOWN';
  return {
    id: 'root',
    layoutOptions: {
      'elk.algorithm': 'layered',
      'elk.direction': direction,
      'elk.spacing.nodeNode': fold ? '20' : '50',
      'elk.layered.spacing.nodeNodeBetweenLayers': down ? (fold ? '20' : '50') : '90',
      'elk.edgeRouting': 'ORTHOGONAL',
      'elk.edgeLabels.inline': 'true',
      // a loop's flow back is the one back in the schema's order of modules (velocityLoop: MOT -> WHL, WHL
      // drawn first), not one ELK picks (it drew WHL last, its flow to ODO around the other three)
      'elk.layered.cycleBreaking.strategy': 'MODEL_ORDER',
      // a long chain (a periodic loop of 8 modules) folded into rows (columns) shaped like the pane
      ...(fold ? { 'elk.layered.wrapping.strategy': 'MULTI_EDGE', 'elk.aspectRatio': fold.toFixed(2), ...FOLDED_SPACING } : {}),
    },
    children,
    edges: edgesOf(schema, children),
  };
}

/**
 * The last resort when ELK fails on a schema: its modules in a grid shaped like the pane (in the
 * order of the schema), each flow a straight line from its output port to its input port, no ELK
 * involved. Never as readable as a layout, but every module and flow is there.
 */
export function gridOf(schema: ArchSchema, paneRatio = 1.6): ElkNode {
  const graph = graphOf(schema, { direction: 'RIGHT' });
  const nodes = graph.children!;
  const columns = Math.max(1, Math.min(nodes.length, Math.round(Math.sqrt(nodes.length * paneRatio))));
  const gapX = 90;
  const gapY = 50;
  const colW = Math.max(...nodes.map((n) => n.width!), 1);
  const rows: number[] = [];
  nodes.forEach((n, i) => {
    const r = Math.floor(i / columns);
    rows[r] = Math.max(rows[r] ?? 0, n.height!);
  });
  const rowTop = (r: number) => rows.slice(0, r).reduce((a, hgt) => a + hgt + gapY, 0);
  const at = new Map<string, { x: number; y: number }>();
  nodes.forEach((n, i) => {
    n.x = (i % columns) * (colW + gapX);
    n.y = rowTop(Math.floor(i / columns));
    for (const p of n.ports ?? []) at.set(p.id, { x: n.x + p.x! + 5, y: n.y + p.y! + 5 });
    at.set(n.id, { x: n.x + n.width! / 2, y: n.y + n.height! / 2 });
  });
  for (const e of graph.edges ?? []) {
    const from = at.get(e.sources[0]!)!;
    const to = at.get(e.targets[0]!)!;
    e.sections = [{ id: `${e.id}s`, startPoint: from, endPoint: to }];
    for (const l of e.labels ?? []) Object.assign(l, { x: (from.x + to.x) / 2 - l.width! / 2, y: (from.y + to.y) / 2 - l.height! });
  }
  graph.width = columns * colW + (columns - 1) * gapX;
  graph.height = Math.max(0, rowTop(rows.length) - gapY);
  return graph;
}
