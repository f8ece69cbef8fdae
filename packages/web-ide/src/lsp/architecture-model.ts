/**
 * Extracts the data the architecture view draws from parsed Cactal documents (runs in the
 * language worker, on the linked AST): for each schema its modules with their ports, the data and
 * event communications with periodicities, and the precedence edges of the scheduling graph.
 */
/** Where something is defined (0-based line and character, as LSP positions). */
export interface ArchLocation {
  uri: string;
  line: number;
  character: number;
}

export interface ArchRange {
  start: { line: number; character: number };
  end: { line: number; character: number };
}

export interface ArchPort {
  /** The port's declaration in its module. */
  def?: ArchLocation;
  index: number;
  name: string;
  type: string;
  direction: 'in' | 'out';
  kind: 'data' | 'event' | 'param';
}

export interface ArchModule {
  /** The module's (or supervisor's) definition. */
  def?: ArchLocation;
  name: string;
  kind: string;
  wcet?: string;
  ports: ArchPort[];
}

export interface ArchFlow {
  /** The communication in the schema. */
  def?: ArchLocation;
  from: string;
  fromPort: number;
  to: string;
  toPort: number;
  kind: 'data' | 'event';
  label: string;
}

export interface ArchSchema {
  name: string;
  kind: string;
  uri: string;
  /** The schema's text in its file (the diagram follows the cursor into it). */
  range?: ArchRange;
  period?: string;
  criticalDelay?: string;
  modules: ArchModule[];
  flows: ArchFlow[];
  precedences: Array<{ from: string; to: string }>;
}

type Node = Record<string, unknown> & { $type: string };
type Ref = { ref?: Node; $refText?: string };

const arr = (v: unknown): Node[] => (Array.isArray(v) ? (v as Node[]) : []);
const refName = (r: unknown): string => {
  const x = r as Ref | undefined;
  return (x?.ref?.name as string | undefined) ?? x?.$refText ?? '?';
};

type Located = { $cstNode?: { range?: ArchRange }; $container?: Located; $document?: { uri?: { toString(): string } } };

/** Where an AST node starts, in its own document (a module referenced by a schema lives in another file). */
function defOf(node: unknown): ArchLocation | undefined {
  const n = node as Located | undefined;
  const start = n?.$cstNode?.range?.start;
  let root = n;
  while (root?.$container) root = root.$container;
  const uri = root?.$document?.uri?.toString();
  return start && uri ? { uri, line: start.line, character: start.character } : undefined;
}

function rangeOf(node: unknown): ArchRange | undefined {
  const r = (node as Located | undefined)?.$cstNode?.range;
  return r ? { start: { line: r.start.line, character: r.start.character }, end: { line: r.end.line, character: r.end.character } } : undefined;
}

function typeName(t: unknown): string {
  const tr = t as { primitive?: string; datatype?: Ref } | undefined;
  return tr?.primitive ?? refName(tr?.datatype);
}

function timeProp(blocks: Node[], blockType: string, name: string): string | undefined {
  for (const b of blocks) {
    if (b.$type !== blockType) continue;
    for (const p of arr(b.properties)) if (p.name === name) return (p.value as { text?: string } | undefined)?.text;
  }
  return undefined;
}

export function moduleOf(node: Node | undefined): ArchModule | undefined {
  if (!node) return undefined;
  const blocks = arr(node.blocks).concat(arr(node.eventFlows));
  const ports: ArchPort[] = [];
  for (const b of blocks) {
    if (b.$type === 'ParametersBlock') {
      for (const p of arr(b.parameters)) ports.push({ def: defOf(p), index: Number(p.index), name: String(p.name), type: typeName(p.type), direction: 'in', kind: 'param' });
    } else if (b.$type === 'DataFlowsBlock' || b.$type === 'EventFlowsBlock') {
      const kind = b.$type === 'DataFlowsBlock' ? 'data' : 'event';
      for (const p of arr(b.ports)) {
        ports.push({ def: defOf(p), index: Number(p.index), name: String(p.name), type: typeName(p.type), direction: p.direction === 'out' ? 'out' : 'in', kind });
      }
    }
  }
  return {
    def: defOf(node),
    name: String(node.name),
    kind: node.$type === 'Supervisor' ? 'supervisor' : String(node.kind ?? 'module'),
    wcet: timeProp(arr(node.blocks), 'SchedulingBlock', 'C'),
    ports,
  };
}

export function schemasOf(root: Node, uri: string): ArchSchema[] {
  const out: ArchSchema[] = [];
  for (const el of arr(root.elements)) {
    if (el.$type !== 'Schema') continue;
    const blocks = arr(el.blocks);
    const schema: ArchSchema = {
      name: String(el.name),
      kind: String(el.kind),
      uri,
      range: rangeOf(el),
      period: timeProp(blocks, 'RealtimeBlock', 'PERIOD'),
      criticalDelay: timeProp(blocks, 'RealtimeBlock', 'CRITICAL_DELAY'),
      modules: [],
      flows: [],
      precedences: [],
    };
    for (const b of blocks) {
      if (b.$type === 'ModulesBlock') {
        for (const inst of arr(b.instances)) {
          const ref = inst.module as Ref;
          schema.modules.push(moduleOf(ref.ref) ?? { name: refName(ref), kind: 'unresolved', ports: [] });
        }
      } else if (b.$type === 'SchedulingGraphBlock') {
        for (const e of arr(b.edges)) schema.precedences.push({ from: refName(e.from), to: refName(e.to) });
      } else if (b.$type === 'CommunicationsBlock') {
        for (const c of arr(b.communications)) {
          const data = c.$type === 'DataCommunication';
          const k = (c.periodicity as number | undefined) ?? 1;
          schema.flows.push({
            def: defOf(c),
            from: refName(c.source),
            fromPort: Number((c.sourcePort as Ref).$refText),
            to: refName(c.target),
            toPort: Number((c.targetPort as Ref).$refText),
            kind: data ? 'data' : 'event',
            label: data ? `* ${k}` : String(c.mode).replace('==', '='),
          });
        }
      }
    }
    out.push(schema);
  }
  return out;
}
