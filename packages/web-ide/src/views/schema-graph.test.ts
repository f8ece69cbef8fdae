/**
 * The graph the architecture diagram asks ELK to lay out (schema-graph.ts), laid out by the real
 * ELK (the same elkjs the page's worker runs, here in-process) for every schema of the examples, in
 * both directions, straight and folded at the shapes the panes ask: examples/mobile-robot's
 * velocityLoop drawn top to bottom and folded (the Monitor's pane at 1366 x 768: 479 x 380 px,
 * folded at 1.26) threw in ELK ("Cannot read properties of undefined (reading 'getDefault')") while
 * its flows entered ports on the sides along the flow.
 */
import { describe, it, expect, beforeAll } from 'vitest';
import { fileURLToPath } from 'node:url';
import ELK from 'elkjs/lib/elk.bundled.js';
import type { ElkNode } from 'elkjs/lib/elk-api.js';
import { loadWorkspace } from '@contract-studio/language/node';
import { schemasOf, type ArchSchema } from '../lsp/architecture-model.js';
import { graphOf, gridOf, type FlowDirection } from './schema-graph.js';

const elk = new ELK();
const example = (name: string) => fileURLToPath(new URL(`../../../../examples/${name}`, import.meta.url));

async function schemasIn(name: string): Promise<ArchSchema[]> {
  const ws = await loadWorkspace(example(name));
  return ws.documents.flatMap((d) => schemasOf(d.document.parseResult.value as never, d.document.uri.toString()));
}

/** The sides a flow may enter or leave a module by, for a drawing running that way. */
const ACROSS: Record<FlowDirection, string[]> = { RIGHT: ['WEST', 'EAST'], DOWN: ['NORTH', 'SOUTH'] };

const boxesOverlap = (a: ElkNode, b: ElkNode) =>
  a.x! < b.x! + b.width! && b.x! < a.x! + a.width! && a.y! < b.y! + b.height! && b.y! < a.y! + a.height!;

describe('the graph of a schema given to ELK', () => {
  let schemas: ArchSchema[] = [];
  beforeAll(async () => {
    schemas = [...(await schemasIn('mobile-robot')), ...(await schemasIn('tutorial'))];
  }, 120_000);

  it('finds the schemas of both examples, velocityLoop among them', () => {
    expect(schemas.map((s) => s.name)).toContain('velocityLoop');
    expect(schemas.length).toBeGreaterThan(3);
  });

  it('puts every port a flow enters or leaves on a side across the flow, in both directions', () => {
    for (const s of schemas) for (const direction of ['RIGHT', 'DOWN'] as const) {
      const g = graphOf(s, { direction });
      const ends = new Set(g.edges!.flatMap((e) => [...e.sources, ...e.targets]));
      for (const n of g.children!) for (const p of n.ports!) {
        if (ends.has(p.id)) expect(ACROSS[direction], `${s.name} ${direction} ${p.id}`).toContain(p.layoutOptions!['port.side']);
      }
    }
  });

  it("velocityLoop top to bottom, folded as the Monitor's pane at 1366 x 768 asks (1.26), is laid out", async () => {
    const velocity = schemas.find((s) => s.name === 'velocityLoop')!;
    const g = await elk.layout(graphOf(velocity, { direction: 'DOWN', fold: 479 / 380 }));
    expect(g.children!.map((n) => n.id).sort()).toEqual(velocity.modules.map((m) => m.name).sort());
  });

  it('lays out every schema of both examples in both directions, straight and folded at the shapes the panes ask', async () => {
    const failed: string[] = [];
    // pane shapes of the Monitor, the tab and the docked pane at 1280 to 2560 px wide (1.26 and 1.56 at 1366 x 768)
    const folds = [undefined, 0.32, 0.39, 0.63, 0.78, 1.02, 1.26, 1.56, 2.0, 3.06];
    for (const s of schemas) for (const direction of ['RIGHT', 'DOWN'] as const) for (const fold of folds) {
      const asked = { direction, ...(fold ? { fold } : {}) };
      const g = await elk.layout(graphOf(s, asked)).catch((e: Error) => (failed.push(`${s.name} ${JSON.stringify(asked)}: ${e.message}`), undefined));
      if (!g) continue;
      for (const [i, a] of g.children!.entries()) for (const b of g.children!.slice(i + 1)) expect(boxesOverlap(a, b), `${s.name} ${a.id} ${b.id}`).toBe(false);
    }
    expect(failed).toEqual([]);
  }, 120_000);

  it('the grid drawn when ELK fails places every module apart and draws every flow', () => {
    for (const s of schemas) {
      const g = gridOf(s, 1.3);
      expect(g.children!.length).toBe(s.modules.length);
      for (const [i, a] of g.children!.entries()) for (const b of g.children!.slice(i + 1)) expect(boxesOverlap(a, b)).toBe(false);
      for (const n of g.children!) expect(n.x! + n.width!).toBeLessThanOrEqual(g.width! + 0.5);
      for (const e of g.edges!) expect(e.sections?.length).toBe(1);
    }
  });
});
