/**
 * The architecture diagram docked beside the editor (docs/ide.md "Architecture"): it follows the
 * schema at the cursor, keeps its labels readable at the docked size, zooms at the pointer, pans,
 * fits, and a click on a module, port or flow goes to its definition.
 */
import { describe, it, expect } from 'vitest';
import { ideSession, shot, placeCursor, activeTab, openFile, cursorLine, type Session } from './harness.js';
import { axeScan, seriousOf } from './axe.js';
import { writeChainSchema } from './chain-schema.js';
import type {} from '../../src/app/ide-hook.js';

let s: Session;
const pane = '.side-pane .arch-canvas';

/** The scene's translate and scale (the drawing point under pane point p is (p - t) / scale). */
const viewOf = (page: Session['page']) => page.locator(`${pane} .arch-scene`).evaluate((g) => {
  const m = g.getAttribute('transform')!.match(/translate\(([-\d.]+),([-\d.]+)\) scale\(([-\d.]+)\)/)!;
  return { x: Number(m[1]), y: Number(m[2]), scale: Number(m[3]) };
});

describe('architecture diagram docked', () => {
  s = ideSession({ buildService: false });

  it('docked beside the editor, it shows the schema at the cursor with readable labels', async () => {
    const { page } = s;
    await openFile(page, 'sschema2.contract');
    await placeCursor(page, 'MSB ();');
    await page.locator('#btn-arch').click();
    await page.locator('#arch-dock').click();
    await page.locator(`${pane} .arch-svg`).waitFor({ timeout: 20_000 });
    await expect.poll(() => page.locator(`${pane} .arch-svg`).getAttribute('data-schema')).toBe('schemaCommande2');
    // the cursor moves into another schema (another file): the diagram follows
    await openFile(page, 'sschema1.contract');
    await placeCursor(page, 'MSD ();');
    await expect.poll(() => page.locator(`${pane} .arch-svg`).getAttribute('data-schema'), { timeout: 5000 }).toBe('schemaCommande1');
    // a schema picked in the list stays while the cursor moves inside the same schema
    await page.locator('.side-pane .arch-select').selectOption('schemaReceptionMessage');
    await placeCursor(page, 'MSC (consigne');
    await page.keyboard.press('ArrowDown');
    await page.waitForTimeout(500); // past the follow debounce
    expect(await page.locator(`${pane} .arch-svg`).getAttribute('data-schema')).toBe('schemaReceptionMessage');
    await page.locator('.side-pane .arch-select').selectOption('schemaCommande1');
    await expect.poll(() => page.locator(`${pane} .arch-svg`).getAttribute('data-schema')).toBe('schemaCommande1');
    await page.waitForTimeout(400); // the relayout for the pane's size settles
    // every label is drawn at 9 px or more at the docked size
    const smallest = await page.locator(`${pane} .arch-svg text`).evaluateAll((els) => Math.min(...els.map((e) => e.getBoundingClientRect().height)));
    const fontPx = await page.locator(`${pane} .arch-svg .port-label`).first().evaluate((e) => parseFloat(getComputedStyle(e).fontSize));
    const { scale } = await viewOf(page);
    expect(fontPx * scale).toBeGreaterThanOrEqual(9);
    expect(smallest).toBeGreaterThanOrEqual(9);
    await shot(page, 'arch-01-docked-follows-cursor');
    const report = await axeScan(page, 'architecture docked beside the editor');
    expect(seriousOf(report)).toEqual([]);
  });

  it('the model read again unchanged keeps the drawing (no new layout); a change of the schema draws it again', async () => {
    const { page } = s;
    await page.locator(`${pane} .arch-svg`).waitFor({ timeout: 20_000 });
    const svgMarked = () => page.evaluate((sel) => (document.querySelector(sel) as any)?.__seen === true, `${pane} .arch-svg`);
    await page.evaluate((sel) => ((document.querySelector(sel) as any).__seen = true), `${pane} .arch-svg`);
    // read again (what an edit elsewhere, or Build & Run opening the Monitor, does): the same element stays
    await page.evaluate(() => window.__ide.views.arch!.update());
    expect(await svgMarked()).toBe(true);
    // the schema shown changes (its period): a new drawing
    await openFile(page, 'sschema1.contract');
    await placeCursor(page, 'PERIOD=1s;', 'PERIOD='.length);
    await expect.poll(() => page.locator(`${pane} .arch-svg`).getAttribute('data-schema')).toBe('schemaCommande1');
    await page.evaluate((sel) => ((document.querySelector(sel) as any).__seen = true), `${pane} .arch-svg`);
    await page.keyboard.press('Delete');
    await page.keyboard.type('2');
    await expect.poll(svgMarked, { timeout: 10_000 }).toBe(false);
    await expect.poll(() => page.locator('.side-pane .arch-info').textContent()).toMatch(/^PERIOD 2s/);
    await page.keyboard.press('Control+Z');
    await page.keyboard.press('Control+Z');
    await expect.poll(() => page.locator('.side-pane .arch-info').textContent()).toMatch(/^PERIOD 1s/);
  });

  it('wheel zooms at the pointer, a drag pans, Fit and F fit the whole diagram, + and − zoom', async () => {
    const { page } = s;
    const box = (await page.locator(pane).boundingBox())!;
    const px = box.x + box.width * 0.4;
    const py = box.y + box.height * 0.5;
    const before = await viewOf(page);
    const under = { x: (px - box.x - before.x) / before.scale, y: (py - box.y - before.y) / before.scale };
    await page.mouse.move(px, py);
    await page.mouse.wheel(0, -300);
    await expect.poll(async () => (await viewOf(page)).scale).toBeGreaterThan(before.scale * 1.2);
    const zoomed = await viewOf(page);
    // the drawing point under the pointer is still under it
    expect((px - box.x - zoomed.x) / zoomed.scale).toBeCloseTo(under.x, 0);
    expect((py - box.y - zoomed.y) / zoomed.scale).toBeCloseTo(under.y, 0);
    // drag on the background: pans by the drag, no zoom
    const empty = await page.evaluate((sel) => {
      const r = document.querySelector(sel)!.getBoundingClientRect();
      for (let y = r.top + 5; y < r.bottom; y += 7) for (let x = r.left + 5; x < r.right; x += 7) {
        const el = document.elementFromPoint(x, y);
        if (el?.classList.contains('arch-svg')) return { x, y };
      }
      return null;
    }, pane);
    expect(empty).not.toBeNull();
    await page.mouse.move(empty!.x, empty!.y);
    await page.mouse.down();
    await page.mouse.move(empty!.x + 40, empty!.y + 30, { steps: 4 });
    await page.mouse.move(empty!.x + 80, empty!.y + 50, { steps: 4 });
    await page.mouse.up();
    const panned = await viewOf(page);
    expect(panned.scale).toBeCloseTo(zoomed.scale, 5);
    expect(panned.x - zoomed.x).toBeCloseTo(80, 0);
    expect(panned.y - zoomed.y).toBeCloseTo(50, 0);
    expect(await activeTab(page)).toBe('sschema1.contract'); // the drag's click did not go anywhere
    // Fit: the whole drawing inside the pane
    await page.locator('.side-pane #arch-fit').click();
    const inside = async () => {
      const [scene, canvas] = await Promise.all([page.locator(`${pane} .arch-scene`).boundingBox(), page.locator(pane).boundingBox()]);
      return scene!.x >= canvas!.x - 1 && scene!.y >= canvas!.y - 1 && scene!.x + scene!.width <= canvas!.x + canvas!.width + 1 && scene!.y + scene!.height <= canvas!.y + canvas!.height + 1;
    };
    expect(await inside()).toBe(true);
    const fitted = await viewOf(page);
    // keys on the focused diagram: + zooms in, − out, F fits again
    await page.locator(pane).focus();
    await page.keyboard.press('+');
    expect((await viewOf(page)).scale).toBeCloseTo(fitted.scale * 1.25, 3);
    await page.keyboard.press('ArrowLeft');
    await page.keyboard.press('-');
    await page.keyboard.press('-');
    expect((await viewOf(page)).scale).toBeLessThan(fitted.scale);
    await page.keyboard.press('f');
    expect((await viewOf(page)).scale).toBeCloseTo(fitted.scale, 3);
    expect(await inside()).toBe(true);
    await shot(page, 'arch-02-fitted');
  });

  it('a click on a flow, a port or a module goes to its definition; Enter on a focused module too', async () => {
    const { page } = s;
    await page.locator('.side-pane #arch-fit').click();
    // a point on the flow's line (its first segment's middle), in page coordinates
    const onFlow = await page.locator(`${pane} [data-flow-hit="MSA:0->MSC:0"]`).first().evaluate((line) => {
      const pl = line as SVGPolylineElement;
      const a = pl.points.getItem(0);
      const b = pl.points.getItem(1);
      const m = pl.getScreenCTM()!;
      const p = new DOMPoint((a.x + b.x) / 2, (a.y + b.y) / 2).matrixTransform(m);
      return { x: p.x, y: p.y };
    });
    await page.mouse.click(onFlow.x, onFlow.y);
    await expect.poll(() => cursorLine(page)).toBe(25);
    expect(await activeTab(page)).toBe('sschema1.contract');
    // MSC's data output :1 (its declaration in smodule3.contract, line 11)
    await page.locator(`${pane} .arch-node[data-module=MSC] .port.data[data-dir=out][data-port="MSC:1"]`).click();
    await expect.poll(() => activeTab(page)).toBe('smodule3.contract');
    expect(await cursorLine(page)).toBe(11);
    // the diagram stays on its schema (the cursor is in no schema now)
    expect(await page.locator(`${pane} .arch-svg`).getAttribute('data-schema')).toBe('schemaCommande1');
    await page.locator(`${pane} .arch-node[data-module=MSA] .node-title`).click();
    await expect.poll(() => activeTab(page)).toBe('smodule1.contract');
    expect(await cursorLine(page)).toBe(3);
    await page.locator(`${pane} .arch-node[data-module=MSD]`).focus();
    await page.keyboard.press('Enter');
    await expect.poll(() => activeTab(page)).toBe('smodule4.contract');
    await shot(page, 'arch-03-went-to-definition');
  });
  it('a schema file made on disk shows up; a long loop (8 modules in a chain) is folded into rows: every module readable in the tab, none cut off', async () => {
    const { page } = s;
    writeChainSchema(s.workspace);
    // the files appear in the explorer (the workspace watcher); the cursor in the schema shows it
    await page.locator('.tree-row[data-path="chain.contract"]').waitFor({ timeout: 15_000 });
    await openFile(page, 'chain.contract');
    await placeCursor(page, 'CHA ();');

    // (a file made by another program: the diagram's list had only the schemas known at the start)
    await expect.poll(() => page.locator(`${pane} .arch-svg`).getAttribute('data-schema'), { timeout: 15_000 }).toBe('chain');
    await page.waitForTimeout(400); // the relayout for the pane's size settles
    // docked (about 530 x 470 px): folded into columns, every module whole inside the pane at a
    // readable size (with the first folded spacing, the last row's bottom needed a pan)
    const docked = (await page.locator(pane).boundingBox())!;
    const starts = await page.locator(`${pane} .arch-svg .arch-node`).evaluateAll((els) => els.map((e) => { const r = e.getBoundingClientRect(); return { x: r.left, y: r.top, right: r.right, bottom: r.bottom }; }));
    expect(starts).toHaveLength(8);
    for (const b of starts) expect(b.x >= docked.x - 1 && b.right <= docked.x + docked.width + 1 && b.y >= docked.y - 1 && b.bottom <= docked.y + docked.height + 1, JSON.stringify({ b, docked })).toBe(true);
    expect((await viewOf(page)).scale).toBeGreaterThanOrEqual(9 / 11 - 1e-3);
    await shot(page, 'arch-03b-docked-loop');
    // back in its own tab (wide): folded into rows that fit it at a readable size
    await page.locator('.side-pane #arch-dock').click();
    const tab = '.arch-canvas:visible';
    await page.locator(`${tab} .arch-svg[data-schema="chain"]`).waitFor({ timeout: 10_000 });
    await page.waitForTimeout(400); // the relayout for the pane's size settles
    const canvas = (await page.locator(tab).boundingBox())!;
    const boxes = await page.locator(`${tab} .arch-svg .arch-node`).evaluateAll((els) => els.map((e) => { const r = e.getBoundingClientRect(); return { x: r.left, y: r.top, w: r.width, h: r.height }; }));
    expect(boxes).toHaveLength(8);
    for (const b of boxes) {
      expect(b.x).toBeGreaterThanOrEqual(canvas.x - 1);
      expect(b.y).toBeGreaterThanOrEqual(canvas.y - 1);
      expect(b.x + b.w).toBeLessThanOrEqual(canvas.x + canvas.width + 1);
      expect(b.y + b.h).toBeLessThanOrEqual(canvas.y + canvas.height + 1);
    }
    const fontPx = await page.locator(`${tab} .arch-svg .port-label`).first().evaluate((e) => parseFloat(getComputedStyle(e).fontSize));
    const scale = await page.locator(`${tab} .arch-scene`).evaluate((g) => Number(/scale\(([-\d.]+)\)/.exec(g.getAttribute('transform')!)![1]));
    expect(fontPx * scale).toBeGreaterThanOrEqual(9);
    await shot(page, 'arch-04-long-loop-folded');
  });
});
