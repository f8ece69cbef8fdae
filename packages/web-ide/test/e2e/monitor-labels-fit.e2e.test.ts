/**
 * The Monitor's toolbar and histogram at the widths it is used at (docked at 1366×768 and 1440×900,
 * and wide at 1920×1080), on a real 1 kHz run with CRITICAL_DELAY 800 µs (src/monitor/fixtures/
 * khz-critical-800us-run) replayed from its trace file:
 * - the run list shows the chosen run's label whole (the select as wide as its text), its tooltip
 *   the whole label, and the same label is not repeated beside it; it still takes the keyboard focus;
 * - the histogram's CRITICAL_DELAY and PERIOD labels, read from the canvas's pixels for several
 *   pairs of values (close, equal, nearly equal, far, CRITICAL_DELAY > PERIOD): no label's box meets
 *   the other's, nor the other line, and both lines are drawn whole (no label over them).
 * Before, the list was 240 px at most (`Trace file field-test/khz-critical-800u` cut, the
 * label repeated beside it, its tooltip a general sentence) and at PERIOD 1 ms / CRITICAL_DELAY 800 µs the CRITICAL_DELAY label lay over the
 * PERIOD line, right above the PERIOD label. axe-core finds no serious violation. Real IDE server,
 * headless Chromium.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { startSession, openIde, shot, SHOTS, type Session } from './harness.js';
import { axeScan, seriousOf } from './axe.js';

/** One of the ports this test may use (E2E_LABELS_FIT_PORT to choose another). */
const PORT = Number(process.env.E2E_LABELS_FIT_PORT ?? 8222);
const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/khz-critical-800us-run', import.meta.url));
const WIDTHS = [{ width: 1366, height: 768 }, { width: 1440, height: 900 }, { width: 1920, height: 1080 }];
/** Where the test puts the trace file in the workspace: a name as long as a field test's (the old 240 px list cut it). */
const TRACE = 'field-test/khz-critical-800us-run1.jsonl';
const LABEL = `Trace file ${TRACE} · 1,500 record(s)`;

interface Box { x0: number; x1: number; y0: number; y1: number }
interface Drawn { lines: { red: number[]; grey: number[] }; whole: { red: boolean; grey: boolean }; labels: { red?: Box; grey?: Box } }

describe('the Monitor\'s run list and histogram labels fit', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession({ port: PORT, buildService: false, viewport: WIDTHS[0], example: join(FIXTURE, 'robot') });
    cpSync(join(FIXTURE, 'run1.jsonl'), join(s.workspace, TRACE));
    await openIde(s);
    const { page } = s;
    await page.locator('#btn-monitor').click();
    await page.locator('.side-pane .monitor-view').waitFor();
    await page.waitForSelector(`.monitor-sources option[value="file:${TRACE}"]`, { state: 'attached', timeout: 20_000 });
    await page.locator('.monitor-sources').selectOption(`file:${TRACE}`);
    await page.waitForFunction(() => document.querySelector('.monitor-pschema[data-periodic="goTo"] .monitor-pname')?.textContent === 'goTo · PERIOD 1ms · CRITICAL_DELAY 800us', undefined, { timeout: 30_000 });
  }, 90_000);
  afterAll(async () => {
    await s?.close();
  });

  it('the run list shows the chosen run whole, its tooltip the label, no copy beside it, at each width', async () => {
    const { page } = s;
    for (const size of WIDTHS) {
      await page.setViewportSize(size);
      await page.waitForTimeout(300);
      const m = await page.evaluate(() => {
        const sel = document.querySelector('.monitor-sources') as HTMLSelectElement;
        const cs = getComputedStyle(sel);
        const ctx = document.createElement('canvas').getContext('2d')!;
        ctx.font = cs.font;
        const text = sel.selectedOptions[0]?.textContent ?? '';
        const beside = document.querySelector('.monitor-source') as HTMLElement;
        return {
          text, title: sel.title, textPx: ctx.measureText(text).width,
          // the room the text has: the box less its paddings and borders and the arrow (16 px)
          roomPx: sel.getBoundingClientRect().width - parseFloat(cs.paddingLeft) - parseFloat(cs.paddingRight) - parseFloat(cs.borderLeftWidth) - parseFloat(cs.borderRightWidth) - 16,
          besideShown: beside.getClientRects().length > 0, besideText: beside.textContent,
        };
      });
      console.log(`${size.width}x${size.height}: run list text ${Math.round(m.textPx)} px in ${Math.round(m.roomPx)} px; label beside shown: ${m.besideShown}`);
      expect(m.text).toBe(LABEL);
      expect(m.title).toBe(LABEL);
      expect(m.textPx, `${size.width}x${size.height}`).toBeLessThanOrEqual(m.roomPx);
      expect(m.besideText).toBe(LABEL); // kept for what reads it, not shown twice
      expect(m.besideShown).toBe(false);
      await page.locator('.monitor-toolbar').screenshot({ path: join(SHOTS, `monitor-labels-fit-toolbar-${size.width}.png`) });
    }
    // the keyboard reaches it as before
    await page.locator('.monitor-sources').focus();
    expect(await page.evaluate(() => document.activeElement?.className)).toBe('monitor-sources');
    await page.setViewportSize(WIDTHS[0]!);
  }, 60_000);

  it('the histogram\'s labels meet neither each other nor the other line, for several pairs of values', async () => {
    const { page } = s;
    const pairs: Array<[string, string]> = [['1ms', '800us'], ['1ms', '1ms'], ['1ms', '990us'], ['1ms', '900us'], ['800us', '1ms'], ['10ms', '100us'], ['1ms', '10us'], ['100us', '1ms'], ['5ms', '800us']];
    for (const [period, cd] of pairs) {
      writeFileSync(join(s.workspace, 'schema.contract'), `import "datatype.contract";\nimport "module1.contract";\nimport "module2.contract";\n\nperiodic schema goTo(Position goal = {0.0, 0.0, 0.0}) {\n    realtime { PERIOD=${period}; CRITICAL_DELAY=${cd}; }\n    modules { LOC (); CTL (goal:0); }\n    scheduling graph { LOC -> CTL; }\n    communications { LOC:0 -> CTL:0 * 1; }\n}\n`);
      await expect.poll(() => page.locator('.monitor-pschema[data-periodic="goTo"] .monitor-pname').textContent(), { timeout: 30_000 }).toBe(`goTo · PERIOD ${period} · CRITICAL_DELAY ${cd}`);
      await page.waitForTimeout(200);
      const d: Drawn = await page.evaluate(() => {
        const c = document.querySelector('.monitor-pschema[data-periodic="goTo"] canvas') as HTMLCanvasElement;
        const { width: w, height: h } = c;
        const px = c.getContext('2d')!.getImageData(0, 0, w, h).data;
        const base = h - 14; // under it: the axis' times
        const kind = (x: number, y: number) => {
          const i = (y * w + x) * 4;
          const [r, g, b] = [px[i]!, px[i + 1]!, px[i + 2]!];
          // near the lines' colours (#e06c75, #9aa3b2): a line's or its label's text, not the bars (#61afef)
          if (Math.abs(r - 0xe0) + Math.abs(g - 0x6c) + Math.abs(b - 0x75) < 100) return 'red';
          if (Math.abs(r - 0x9a) + Math.abs(g - 0xa3) + Math.abs(b - 0xb2) < 100 && Math.max(r, g, b) - Math.min(r, g, b) < 40) return 'grey';
          return '';
        };
        const out = { lines: { red: [] as number[], grey: [] as number[] }, whole: { red: true, grey: true }, labels: {} as Record<string, { x0: number; x1: number; y0: number; y1: number }> };
        for (const col of ['red', 'grey'] as const) {
          const counts = Array.from({ length: w }, (_, x) => Array.from({ length: base }, (_, y) => kind(x, y)).filter((k) => k === col).length);
          out.lines[col] = counts.flatMap((n, x) => (n >= base * 0.6 ? [x] : []));
          // a line is whole: its strongest column has its colour from the top to the bars' base
          if (out.lines[col].length) out.whole[col] = Math.max(...out.lines[col].map((x) => counts[x]!)) >= base - 1;
        }
        for (const col of ['red', 'grey'] as const) {
          let box: { x0: number; x1: number; y0: number; y1: number } | undefined;
          for (let y = 0; y < 32; y++) for (let x = 0; x < w; x++) {
            if (kind(x, y) !== col || out.lines[col].some((l) => Math.abs(l - x) <= 2)) continue;
            box = box ? { x0: Math.min(box.x0, x), x1: Math.max(box.x1, x), y0: Math.min(box.y0, y), y1: Math.max(box.y1, y) } : { x0: x, x1: x, y0: y, y1: y };
          }
          if (box) out.labels[col] = box;
        }
        return out as Drawn;
      });
      const what = `PERIOD ${period} / CRITICAL_DELAY ${cd}: ${JSON.stringify(d)}`;
      console.log(what);
      await page.locator('.monitor-pschema[data-periodic="goTo"] canvas').screenshot({ path: join(SHOTS, `monitor-labels-fit-hist-${period}-${cd}.png`) });
      expect(d.lines.red.length, what).toBeGreaterThan(0);
      expect(d.labels.red, what).toBeDefined();
      expect(d.whole, what).toEqual({ red: true, grey: true });
      const meets = (a: Box, b: Box) => a.x0 <= b.x1 && b.x0 <= a.x1 && a.y0 <= b.y1 && b.y0 <= a.y1;
      if (d.lines.grey.length) {
        expect(d.labels.grey, what).toBeDefined();
        expect(meets(d.labels.red!, d.labels.grey!), what).toBe(false);
        for (const x of d.lines.grey) expect(x < d.labels.red!.x0 - 1 || x > d.labels.red!.x1 + 1, what).toBe(true);
        for (const x of d.lines.red) expect(x < d.labels.grey!.x0 - 1 || x > d.labels.grey!.x1 + 1, what).toBe(true);
      }
    }
    await shot(page, 'monitor-labels-fit');
    expect(seriousOf(await axeScan(page, 'Monitor, a 1 kHz run replayed'))).toEqual([]);
  }, 240_000);
});
