/**
 * A schema laid out for its pane by the real ELK (in-process: the same elkjs the page's worker runs)
 * and, when ELK fails on a layout, never left without a drawing (schema-layout.ts). The failures are
 * injected around the real ELK: the graphs that made it fail (velocityLoop folded top to bottom) are
 * no longer asked (schema-graph.test.ts).
 */
import { describe, it, expect, beforeAll } from 'vitest';
import { fileURLToPath } from 'node:url';
import ELK from 'elkjs/lib/elk.bundled.js';
import type { ElkNode } from 'elkjs/lib/elk-api.js';
import { loadWorkspace } from '@contract-studio/language/node';
import { schemasOf, type ArchSchema } from '../lsp/architecture-model.js';
import { layoutSchema, type Layouter } from './schema-layout.js';

const elk = new ELK();
const realElk: Layouter = (g) => elk.layout(g);
/** The Monitor's diagram pane at 1366 x 768 (measured in the page). */
const MONITOR_PANE = { width: 479, height: 380 };

/** The real ELK, failing as ELK did on the graphs `fails` picks. */
const failingOn = (fails: (g: ElkNode) => boolean): Layouter => (g) =>
  fails(g) ? Promise.reject(new TypeError("Cannot read properties of undefined (reading 'Qg')")) : elk.layout(g);
const folded = (g: ElkNode) => !!g.layoutOptions?.['elk.layered.wrapping.strategy'];
const withOptionsAsked = (g: ElkNode) => Object.keys(g.layoutOptions ?? {}).length > 1;

describe('a schema laid out for its pane', () => {
  let velocity: ArchSchema;
  beforeAll(async () => {
    const ws = await loadWorkspace(fileURLToPath(new URL('../../../../examples/mobile-robot', import.meta.url)));
    velocity = ws.documents.flatMap((d) => schemasOf(d.document.parseResult.value as never, d.document.uri.toString())).find((s) => s.name === 'velocityLoop')!;
  }, 120_000);

  const names = (g: ElkNode) => g.children!.map((n) => n.id).sort();

  it("velocityLoop in the Monitor's pane at 1366 x 768: top to bottom, folded, every module placed, nothing to say", async () => {
    const { graph, note } = await layoutSchema(velocity, MONITOR_PANE, realElk);
    expect(note).toBeUndefined();
    expect(graph.layoutOptions!['elk.direction']).toBe('DOWN');
    expect(graph.layoutOptions!['elk.layered.wrapping.strategy']).toBe('MULTI_EDGE');
    expect(names(graph)).toEqual(velocity.modules.map((m) => m.name).sort());
  });

  it('a fold ELK fails on: the unfolded drawing, said', async () => {
    const { graph, note } = await layoutSchema(velocity, MONITOR_PANE, failingOn(folded));
    expect(note).toBe("Folding failed (Cannot read properties of undefined (reading 'Qg')): drawn unfolded");
    expect(graph.layoutOptions!['elk.layered.wrapping.strategy']).toBeUndefined();
    expect(names(graph)).toEqual(velocity.modules.map((m) => m.name).sort());
  });

  it('a straight layout ELK fails on: ELK with its defaults, said', async () => {
    const { graph, note } = await layoutSchema(velocity, MONITOR_PANE, failingOn(withOptionsAsked));
    expect(note).toMatch(/^Layout failed \(.*'Qg'.*\): drawn with a simpler layout$/);
    expect(names(graph)).toEqual(velocity.modules.map((m) => m.name).sort());
    expect(graph.edges!.every((e) => (e.sections?.length ?? 0) > 0)).toBe(true);
  });

  it('ELK failing on everything: the modules in a grid, said', async () => {
    const { graph, note } = await layoutSchema(velocity, MONITOR_PANE, failingOn(() => true));
    expect(note).toMatch(/and the simpler layout too .*: modules drawn in a grid$/);
    expect(names(graph)).toEqual(velocity.modules.map((m) => m.name).sort());
    expect(graph.width).toBeGreaterThan(0);
  });
});
