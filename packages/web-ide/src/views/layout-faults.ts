/**
 * ELK failing on purpose, for the tests of what the diagram draws when ELK fails (schema-layout.ts:
 * a failed fold keeps the drawing made before it, a failed layout is made again with ELK's defaults,
 * then a grid). The graphs a fault names are refused before they reach ELK, as ELK refused the
 * graphs it threw on (schema-graph.ts); every other graph is laid out by ELK itself. The page
 * exposes it as `__ide.views.arch.failLayouts(fault)` (architecture-view.ts) for the browser tests.
 */
import type { ElkNode } from 'elkjs/lib/elk-api.js';
import type { Layouter } from './schema-layout.js';

/**
 * `fold`: the folded layouts (ELK's wrapping); `asked`: every layout with the options the diagram
 * asks (all but one made with ELK's defaults); `every`: every layout.
 */
export type LayoutFault = 'fold' | 'asked' | 'every';

export const LAYOUT_FAULTS: Record<LayoutFault, (graph: ElkNode) => boolean> = {
  fold: (g) => !!g.layoutOptions?.['elk.layered.wrapping.strategy'],
  asked: (g) => Object.keys(g.layoutOptions ?? {}).length > 1,
  every: () => true,
};

export const isLayoutFault = (v: unknown): v is LayoutFault => typeof v === 'string' && Object.hasOwn(LAYOUT_FAULTS, v);

/** `elk`, failing on the graphs `fault` names (as ELK does: the promise rejects); `elk` itself when there is no fault. */
export function failingOn(fault: LayoutFault | undefined, elk: Layouter): Layouter {
  if (!fault) return elk;
  const fails = LAYOUT_FAULTS[fault];
  return (graph) => (fails(graph) ? Promise.reject(new Error(`ELK made to fail by a test (${fault})`)) : elk(graph));
}
