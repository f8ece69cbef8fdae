/**
 * How a schema is laid out for the pane it is shown in (the architecture diagram,
 * architecture-view.ts): the direction, the folded tries kept while they show the schema larger, and
 * what is drawn when ELK fails on a layout. `elk` runs a layout: ELK in its worker on the page, ELK
 * in-process in the tests.
 */
import type { ElkNode } from 'elkjs/lib/elk-api.js';
import type { ArchSchema } from '../lsp/architecture-model.js';
import type { Size } from './pan-zoom.js';
import { graphOf, gridOf } from './schema-graph.js';

/** Lays a graph out (ELK's `layout`). */
export type Layouter = (graph: ElkNode) => Promise<ElkNode>;

/** The smallest text of the drawing (port and flow labels, CSS .port-label/.edge-label) and the smallest size it is shown at automatically. */
export const SMALLEST_FONT_PX = 11;
export const MIN_FONT_PX = 9;
/** A fold that shows the schema less than this much larger than the drawing before it ends the folded tries (layoutSchema). */
const FOLD_GAIN = 1.05;

/** A layout and, when ELK failed on the one asked and a simpler one was made instead, what was said. */
export interface SchemaLayout {
  graph: ElkNode;
  /** Shown with the drawing: which layout failed and what was drawn instead. */
  note?: string;
}

const reason = (e: unknown) => (e instanceof Error ? e.message : String(e));

/**
 * Lays the schema out for the pane it is shown in: left to right in a wide pane, top to bottom in a
 * narrow one; folded into rows (or columns) when it would not fit the pane at a readable size. A
 * layout ELK fails on never leaves the pane without a drawing: a failed fold keeps the best drawing
 * made so far, a failed straight layout is made left to right with ELK's defaults, and if that fails
 * too the modules are put in a grid (schema-graph.ts gridOf); the note says which.
 */
export async function layoutSchema(schema: ArchSchema, pane: Size | undefined, elk: Layouter): Promise<SchemaLayout> {
  const down = !!pane && pane.width / Math.max(1, pane.height) < 1.3;
  const direction = down ? 'DOWN' : 'RIGHT';
  const layout = (fold?: number) => elk(graphOf(schema, { direction, ...(fold ? { fold } : {}) }));
  let straight: ElkNode;
  try {
    straight = await layout();
  } catch (e) {
    return simplerLayout(schema, pane, elk, `Layout failed (${reason(e)})`);
  }
  if (!pane) return { graph: straight };
  // folded only when the straight drawing does not fit the pane at a readable size: into rows shaped
  // like the pane, then (ELK's folding only approaches the shape asked) twice and four times as many,
  // keeping the one that shows most of the schema. A try that shows hardly more of it (FOLD_GAIN) than
  // the best so far ends the tries: ELK could not fold the graph (two modules flowing both ways: the same drawing
  // at every shape asked), or folded it as far as it goes (each further try is as tall or taller).
  // Every try was made whatever it gave, and the Monitor's first diagram of the tutorial was laid out
  // four times in ELK's worker while gcc built the job (straight, then three folds giving one drawing).
  const readable = MIN_FONT_PX / SMALLEST_FONT_PX;
  // as *Fit* shows it (pan-zoom.ts fitView: 16 px from the pane's edges; renderSchema: 20 px around the drawing)
  const fitScale = (g: ElkNode) => Math.min((pane.width - 32) / Math.max(1, (g.width ?? 1) + 40), (pane.height - 32) / Math.max(1, (g.height ?? 1) + 40));
  let best = straight;
  let folding = false;
  for (const k of [1, 2, 4]) {
    if (fitScale(best) >= readable) break;
    let folded: ElkNode;
    try {
      folded = await layout(pane.width / Math.max(1, pane.height) / k);
    } catch (e) {
      return { graph: best, note: `Folding failed (${reason(e)}): drawn ${best === straight ? 'unfolded' : 'less folded'}` };
    }
    const gain = fitScale(folded) / fitScale(best);
    if (gain > 1) best = folded;
    if (gain <= FOLD_GAIN) break;
    folding = true;
  }
  // still not all of it readable: the other direction, folded like the pane, is tried once, kept when
  // it shows the schema larger; an error there keeps what was made. Tried after a fold that showed more,
  // or when the drawing is held back by its length along the way it runs (too wide left to right, too
  // tall top to bottom), which the other direction lays across; not for a drawing held back across it
  // (two modules whose flows go both ways top to bottom in the Monitor: one layout more, the same size).
  // Docked at 1366 x 768 (497 x 366 px, drawn left to right), a loop of 4 modules with a flow back
  // (velocityLoop) is folded into two columns top to bottom and shown whole at 0.83 (0.62 before: left
  // to right, then its other direction as one column); two modules whose flows go both ways, which
  // folding does nothing for (schemaReceptionMessage), are drawn top to bottom at 0.78 (0.55 before)
  const along = (g: ElkNode) => {
    const byWidth = (pane.width - 32) / Math.max(1, (g.width ?? 1) + 40);
    const byHeight = (pane.height - 32) / Math.max(1, (g.height ?? 1) + 40);
    return direction === 'DOWN' ? byHeight < byWidth : byWidth < byHeight;
  };
  if (fitScale(best) < readable && (folding || along(best))) {
    const other = direction === 'DOWN' ? 'RIGHT' : 'DOWN';
    const turned = await elk(graphOf(schema, { direction: other, fold: pane.width / Math.max(1, pane.height) })).catch(() => undefined);
    if (turned && fitScale(turned) > fitScale(best) * FOLD_GAIN) best = turned;
  }
  return { graph: best };
}

/** The layout after ELK failed on the one asked: left to right with ELK's defaults, else a grid of the modules. */
async function simplerLayout(schema: ArchSchema, pane: Size | undefined, elk: Layouter, failed: string): Promise<SchemaLayout> {
  try {
    const graph = graphOf(schema, { direction: 'RIGHT' });
    graph.layoutOptions = { 'elk.algorithm': 'layered' };
    return { graph: await elk(graph), note: `${failed}: drawn with a simpler layout` };
  } catch (e) {
    const ratio = pane ? pane.width / Math.max(1, pane.height) : undefined;
    return { graph: gridOf(schema, ratio), note: `${failed}, and the simpler layout too (${reason(e)}): modules drawn in a grid` };
  }
}
