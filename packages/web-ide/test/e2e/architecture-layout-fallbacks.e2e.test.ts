/**
 * What the architecture diagram draws when ELK fails on a layout (src/views/schema-layout.ts),
 * in the real page with ELK in its worker: a failed fold keeps the unfolded drawing, a failed
 * layout is made again with ELK's defaults, and when that fails too the modules are put in a grid
 * with straight flows; a line at the bottom of the pane says which. ELK is made to fail through
 * the page's test hook (`__ide.views.arch.failLayouts`, src/views/layout-faults.ts): the graphs it
 * names are refused as ELK refused the graphs it threw on, every other one is laid out by ELK.
 * Throughout, a MutationObserver on the pane records any moment it holds no drawing.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { startSession, openIde, shot, placeCursor, openFile, type Session } from './harness.js';
import { writeChainSchema, CHAIN_MODULES } from './chain-schema.js';
import type {} from '../../src/app/ide-hook.js';
import type { LayoutFault } from '../../src/views/layout-faults.js';

let s: Session;
const pane = '.side-pane .arch-canvas';
type Page = Session['page'];

interface Drawn {
  note: string | undefined;
  /** The note's box and the pane's (the note sits at the bottom of the pane). */
  noteBox?: { top: number; bottom: number };
  paneBox: { top: number; bottom: number };
  modules: string[];
  /** The module boxes' left and top edges, in the drawing's coordinates. */
  at: Array<{ x: number; y: number }>;
  flows: string[];
}

const drawn = (page: Page): Promise<Drawn> => page.evaluate((sel) => {
  const canvas = document.querySelector(sel) as HTMLElement;
  const note = canvas.querySelector('.arch-note');
  const box = (el: Element) => { const r = el.getBoundingClientRect(); return { top: r.top, bottom: r.bottom }; };
  const nodes = [...canvas.querySelectorAll<SVGGElement>('.arch-svg .arch-node')];
  return {
    note: note?.textContent ?? undefined,
    ...(note ? { noteBox: box(note) } : {}),
    paneBox: box(canvas),
    modules: nodes.map((n) => n.dataset.module ?? '').sort(),
    at: nodes.map((n) => { const m = /translate\(([-\d.]+),([-\d.]+)\)/.exec(n.getAttribute('transform') ?? '')!; return { x: Number(m[1]), y: Number(m[2]) }; }),
    flows: [...canvas.querySelectorAll<SVGPolylineElement>('.arch-svg polyline[data-flow]')].map((p) => p.dataset.flow ?? '').sort(),
  };
}, pane);

const distinct = (values: number[]) => new Set(values.map((v) => Math.round(v))).size;
const CHAIN_FLOWS = CHAIN_MODULES.slice(1).map((n, i) => `${CHAIN_MODULES[i]}:1->${n}:0`).sort();

describe('the architecture diagram when ELK fails', () => {
  beforeAll(async () => {
    s = await startSession({ buildService: false });
    writeChainSchema(s.workspace);
    await openIde(s);
    const { page } = s;
    await openFile(page, 'chain.contract');
    await placeCursor(page, 'CHA ();');
    await page.locator('#btn-arch').click();
    await page.locator('#arch-dock').click();
    await page.waitForFunction((sel) => document.querySelector(`${sel} .arch-svg`)?.getAttribute('data-schema') === 'chain', pane, { timeout: 20_000 });
    await page.waitForTimeout(400); // the relayout for the pane's size settles
    // from here on, every change of the pane that leaves it without a module drawn is recorded
    await page.evaluate((sel) => {
      const canvas = document.querySelector(sel) as HTMLElement;
      const w = window as unknown as { __emptyPane: string[] };
      w.__emptyPane = [];
      new MutationObserver(() => {
        if (!canvas.querySelector('.arch-svg .arch-node')) w.__emptyPane.push(canvas.textContent?.slice(0, 200) || '(nothing)');
      }).observe(canvas, { childList: true, subtree: true });
    }, pane);
  }, 120_000);
  afterAll(async () => {
    await s?.close();
  });

  const failLayouts = (fault: LayoutFault | undefined) => s.page.evaluate((f) => window.__ide.views.arch!.failLayouts(f), fault);
  const emptyPane = () => s.page.evaluate(() => (window as unknown as { __emptyPane: string[] }).__emptyPane);
  /** The pane's drawing once its note says `note` (undefined: no note). */
  const drawnSaying = async (note: RegExp | undefined): Promise<Drawn> => {
    await expect.poll(async () => (await drawn(s.page)).note, { timeout: 20_000 }).toSatisfy((n: string | undefined) => (note ? !!n && note.test(n) : n === undefined));
    return drawn(s.page);
  };
  const expectWhole = (d: Drawn) => {
    expect(d.modules).toEqual([...CHAIN_MODULES].sort());
    expect(d.flows).toEqual(CHAIN_FLOWS);
    expect(d.noteBox === undefined || (d.noteBox.bottom <= d.paneBox.bottom + 0.5 && d.noteBox.top > (d.paneBox.top + d.paneBox.bottom) / 2), JSON.stringify(d)).toBe(true);
  };

  it('the chain docked is folded into columns, with nothing to say', async () => {
    const d = await drawnSaying(undefined);
    expectWhole(d);
    expect(distinct(d.at.map((p) => p.x))).toBeGreaterThan(1);
  });

  it('a fold ELK fails on: the unfolded drawing (one column), said at the bottom of the pane', async () => {
    await failLayouts('fold');
    const d = await drawnSaying(/^Folding failed \(ELK made to fail by a test \(fold\)\): drawn unfolded$/);
    expectWhole(d);
    expect(d.noteBox).toBeDefined();
    expect(distinct(d.at.map((p) => p.x))).toBe(1);
    await shot(s.page, 'arch-fallback-1-fold-failed');
    expect(await emptyPane()).toEqual([]);
  });

  it('a layout ELK fails on: made again with ELK\'s defaults, said', async () => {
    await failLayouts('asked');
    const d = await drawnSaying(/^Layout failed \(ELK made to fail by a test \(asked\)\): drawn with a simpler layout$/);
    expectWhole(d);
    expect(d.noteBox).toBeDefined();
    await shot(s.page, 'arch-fallback-2-simpler-layout');
    expect(await emptyPane()).toEqual([]);
  });

  it('ELK failing on every layout: the modules in a grid with straight flows, said', async () => {
    await failLayouts('every');
    const d = await drawnSaying(/^Layout failed \(ELK made to fail by a test \(every\)\), and the simpler layout too \(ELK made to fail by a test \(every\)\): modules drawn in a grid$/);
    expectWhole(d);
    expect(d.noteBox).toBeDefined();
    // rows and columns
    expect(distinct(d.at.map((p) => p.x))).toBeGreaterThan(1);
    expect(distinct(d.at.map((p) => p.y))).toBeGreaterThan(1);
    // each flow one straight line (two points)
    const points = await s.page.locator(`${pane} .arch-svg polyline[data-flow]`).evaluateAll((ps) => ps.map((p) => p.getAttribute('points')!.trim().split(/\s+/).length));
    expect(points.every((n) => n === 2), JSON.stringify(points)).toBe(true);
    await shot(s.page, 'arch-fallback-3-grid');
    expect(await emptyPane()).toEqual([]);
  });

  it('ELK working again: the folded drawing, the note gone; the pane was never empty', async () => {
    await failLayouts(undefined);
    const d = await drawnSaying(undefined);
    expectWhole(d);
    expect(distinct(d.at.map((p) => p.x))).toBeGreaterThan(1);
    expect(await emptyPane()).toEqual([]);
  });
});
