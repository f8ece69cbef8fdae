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
import { layoutSchema, MIN_FONT_PX, SMALLEST_FONT_PX, type Layouter } from './schema-layout.js';
import { fitView } from './pan-zoom.js';

const elk = new ELK();
const realElk: Layouter = (g) => elk.layout(g);
/** The Monitor's diagram pane at 1366 x 768 (measured in the page). */
const MONITOR_PANE = { width: 479, height: 380 };
/** The diagram docked beside the editor, measured in the page at 1366 x 768 and 1440 x 900. */
const DOCKED = { '1366x768': { width: 497, height: 366 }, '1440x900': { width: 530, height: 498 } };
const READABLE = MIN_FONT_PX / SMALLEST_FONT_PX;
/** The scale *Fit* shows a layout at in `pane` (renderSchema draws 20 px around it). */
const fitOf = (g: ElkNode, pane: { width: number; height: number }) => fitView({ width: g.width! + 40, height: g.height! + 40 }, pane).scale;

/** The real ELK, failing as ELK did on the graphs `fails` picks. */
const failingOn = (fails: (g: ElkNode) => boolean): Layouter => (g) =>
  fails(g) ? Promise.reject(new TypeError("Cannot read properties of undefined (reading 'Qg')")) : elk.layout(g);
const folded = (g: ElkNode) => !!g.layoutOptions?.['elk.layered.wrapping.strategy'];
const withOptionsAsked = (g: ElkNode) => Object.keys(g.layoutOptions ?? {}).length > 1;

describe('a schema laid out for its pane', () => {
  let velocity: ArchSchema;
  let schemas: ArchSchema[] = [];
  beforeAll(async () => {
    for (const example of ['mobile-robot', 'tutorial']) {
      const ws = await loadWorkspace(fileURLToPath(new URL(`../../../../examples/${example}`, import.meta.url)));
      schemas.push(...ws.documents.flatMap((d) => schemasOf(d.document.parseResult.value as never, d.document.uri.toString())));
    }
    velocity = schemas.find((s) => s.name === 'velocityLoop')!;
  }, 120_000);

  const names = (g: ElkNode) => g.children!.map((n) => n.id).sort();

  it("velocityLoop in the Monitor's pane at 1366 x 768: folded, every module placed, nothing to say", async () => {
    const { graph, note } = await layoutSchema(velocity, MONITOR_PANE, realElk);
    expect(note).toBeUndefined();
    expect(graph.layoutOptions!['elk.layered.wrapping.strategy']).toBe('MULTI_EDGE');
    expect(names(graph)).toEqual(velocity.modules.map((m) => m.name).sort());
  });

  // shown at 0.62 by Fit at 1366 x 768 before: left to right, then its other direction as one column
  it.each(Object.entries(DOCKED))('velocityLoop docked at %s: top to bottom (at 1366 x 768 folded into two columns), its flow back from MOT to WHL, whole at the readable size', async (screen, pane) => {
    const { graph, note } = await layoutSchema(velocity, pane, realElk);
    expect(note).toBeUndefined();
    expect(fitOf(graph, pane)).toBeGreaterThanOrEqual(READABLE);
    const at = new Map(graph.children!.map((n) => [n.id, n]));
    expect(graph.layoutOptions!['elk.direction']).toBe('DOWN');
    expect(new Set(graph.children!.map((n) => Math.round(n.x!))).size).toBe(screen === '1366x768' ? 2 : 1);
    // the chain drawn in the schema's order: WHL first (ELK drew it last, its flow to ODO around the other three)
    expect(at.get('WHL')!.y).toBeLessThan(at.get('ODO')!.y!);
    expect(at.get('WHL')!.x).toBeLessThanOrEqual(at.get('VEL')!.x!);
  });

  // the smallest before: schemaReceptionMessage docked at 1366 x 768, 0.55 (its module MAA alone is
  // 341 px wide: left to right, the other direction was not tried), velocityLoop at 0.62
  it.each(Object.entries(DOCKED))('every schema of both examples docked at %s: shown whole by Fit at 0.75 or more, nothing to say', async (_, pane) => {
    const shown: string[] = [];
    for (const s of schemas) {
      const { graph, note } = await layoutSchema(s, pane, realElk);
      expect(note, s.name).toBeUndefined();
      shown.push(`${s.name} ${fitOf(graph, pane).toFixed(3)}`);
    }
    expect(shown.filter((line) => Number(line.split(' ')[1]) < 0.75)).toEqual([]);
  }, 60_000);

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
