/**
 * End-to-end: the editor's colours in the dark theme (docs/ide.md, "Colours"). A laptop field test
 * measured the selected text at 4.0:1 (keywords on the selection's #2c3b5a), and the read-only
 * skeleton of a generated C file (its C colours at an opacity of .55) was never scanned by axe-core.
 * Here the contrast of every token shown on the selection is measured in the browser, as drawn
 * (its colour, its opacity and its ancestors', on the selection's colour), in a Cactal file and in
 * a generated C file; the selection stays told apart from the editor; axe-core scans the generated
 * file's read-only view, its notice that the skeleton is read-only shown.
 */
import { describe, expect, it } from 'vitest';
import type { Page } from 'playwright-core';
import { ideSession, openFile, placeCursor, shot } from './harness.js';
import { axeScan, seriousOf } from './axe.js';
import type {} from '../../src/app/ide-hook.js';

/** This file's own port (each browser test file has its own server on its own port). */
const PORT = 7920;
const MAA = 'src-gen/generated/architecture/modules/MAA_mod/module.c';

interface SelectionContrast {
  /** The least contrast of a token drawn on the selection, and that token. */
  min: number;
  worst: string;
  tokens: number;
  /** The selection's colour, and its contrast with the editor's background. */
  selection: string;
  onEditor: number;
}

/** Selects the whole text of the active editor (Ctrl+A) and measures every visible token on the selection. */
async function selectAllAndMeasure(page: Page, anchor: string): Promise<SelectionContrast> {
  await placeCursor(page, anchor);
  await page.keyboard.press('Control+a');
  await page.locator('.monaco-editor .view-overlays .selected-text').first().waitFor({ timeout: 10_000 });
  return page.evaluate(() => {
    type Rgba = [number, number, number, number];
    const parse = (c: string): Rgba => {
      const n = (c.match(/[\d.]+/g) ?? []).map(Number);
      return [n[0] ?? 0, n[1] ?? 0, n[2] ?? 0, n[3] ?? 1];
    };
    const over = (fg: Rgba, bg: Rgba): Rgba => [0, 1, 2].map((i) => fg[i]! * fg[3] + bg[i]! * (1 - fg[3])).concat(1) as Rgba;
    const lum = (c: Rgba) => {
      const ch = c.slice(0, 3).map((v) => { const s = v / 255; return s <= 0.04045 ? s / 12.92 : ((s + 0.055) / 1.055) ** 2.4; });
      return 0.2126 * ch[0]! + 0.7152 * ch[1]! + 0.0722 * ch[2]!;
    };
    const ratio = (a: Rgba, b: Rgba) => { const [x, y] = [lum(a), lum(b)].sort((p, q) => q - p) as [number, number]; return (x + 0.05) / (y + 0.05); };
    const editorEl = window.__ide.editors.editor.getDomNode()!;
    const editorBg = parse(getComputedStyle(editorEl.querySelector('.monaco-editor-background') as HTMLElement).backgroundColor);
    const selectedEl = editorEl.querySelector('.view-overlays .selected-text') as HTMLElement;
    const selection = over(parse(getComputedStyle(selectedEl).backgroundColor), editorBg);
    // a token as drawn: its colour with its own opacity and its ancestors' (up to the editor)
    const opacityOf = (e: Element) => { let o = 1; for (let x: Element | null = e; x && x !== editorEl; x = x.parentElement) o *= Number(getComputedStyle(x).opacity); return o; };
    let min = Infinity;
    let worst = '';
    let tokens = 0;
    for (const span of editorEl.querySelectorAll('.view-lines .view-line > span > span')) {
      const text = span.textContent ?? '';
      if (!text.trim()) continue;
      const fg = parse(getComputedStyle(span).color);
      const drawn = over([fg[0], fg[1], fg[2], fg[3] * opacityOf(span)], selection);
      const r = ratio(drawn, selection);
      tokens++;
      if (r < min) { min = r; worst = `${text.trim().slice(0, 40)} (${getComputedStyle(span).color}, ${span.className})`; }
    }
    return { min, worst, tokens, selection: `rgb(${selection.slice(0, 3).map(Math.round).join(', ')})`, onEditor: ratio(selection, editorBg) };
  });
}

describe('the editor\'s colours in the dark theme', () => {
  const s = ideSession({ buildService: false, port: PORT, viewport: { width: 1366, height: 768 }, timeout: 90_000 });

  it('selected text keeps 4.5:1 (WCAG AA) in a Cactal file and in a generated C file, and the selection stays visible', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    const cactal = await selectAllAndMeasure(page, 'import');
    console.log(`selected text, supervisor.contract: ${cactal.tokens} tokens, least contrast ${cactal.min.toFixed(2)}:1 (${cactal.worst}) on ${cactal.selection}, the selection ${cactal.onEditor.toFixed(2)}:1 on the editor`);
    await shot(page, 'editor-colours-selection-cactal');
    await openFile(page, MAA);
    const generated = await selectAllAndMeasure(page, 'PROTECTED REGION ID(protect_exec_MAA)');
    console.log(`selected text, ${MAA}: ${generated.tokens} tokens, least contrast ${generated.min.toFixed(2)}:1 (${generated.worst}) on ${generated.selection}`);
    await shot(page, 'editor-colours-selection-generated');
    for (const m of [cactal, generated]) {
      expect(m.tokens).toBeGreaterThan(50);
      expect(m.min, m.worst).toBeGreaterThanOrEqual(4.5);
      // not invisible: the selection stands out from the editor's background
      expect(m.onEditor).toBeGreaterThanOrEqual(1.3);
    }
  });

  it('the read-only view of a generated C file (its greyed skeleton, the read-only notice), axe-core: no serious or critical violation', async () => {
    const { page } = s;
    await openFile(page, MAA);
    // the cursor in the skeleton, a key typed there: the editor says it is read-only
    await placeCursor(page, 'MODULE_DESCRIPTION');
    await expect.poll(() => page.locator('.monaco-editor .gen-readonly-text').count(), { timeout: 10_000 }).toBeGreaterThan(10);
    await page.keyboard.press('x');
    await page.locator('.monaco-editor-overlaymessage').waitFor({ timeout: 10_000 }).catch(() => console.log('(no read-only notice shown)'));
    await shot(page, 'editor-colours-generated-read-only');
    const scan = await axeScan(page, 'generated C, read-only skeleton', { editor: true });
    expect(seriousOf(scan)).toEqual([]);
  });
});
