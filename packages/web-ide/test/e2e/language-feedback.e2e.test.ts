/**
 * End-to-end: the language server's smaller helps reach the user in the IDE — hover on a timing
 * property gives µs and the schema's figures, completion in a rule body offers whole actions (and
 * none inside a comment), and
 * Format on a file with a syntax error says why it did nothing (docs/ide.md, "Using it").
 */
import { describe, it, expect } from 'vitest';
import { ideSession, placeCursor, activeValue, openFile, waitSaved, shot, type Session } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

let s: Session;

describe('language server feedback in the IDE', () => {
  s = ideSession({ buildService: false });

  it('hover on PERIOD= shows µs, utilisation and critical path', async () => {
    const { page } = s;
    await openFile(page, 'sschema1.contract');
    await placeCursor(page, 'PERIOD', 2);
    await page.keyboard.press('Control+k');
    await page.keyboard.press('Control+i');
    const hover = page.locator('.monaco-hover-content', { hasText: 'µs' }).first();
    await hover.waitFor({ timeout: 5000 });
    const text = await hover.textContent();
    expect(text).toMatch(/utilisation of/);
    expect(text).toMatch(/critical path: [\d,.]+ µs/);
    await page.keyboard.press('Escape');
  });

  it('completion on an empty line of a rule body offers whole actions', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    const before = await activeValue(page);
    // an empty line right after a rule's precondition
    const at = before.search(/\]\s*\n/);
    expect(at).toBeGreaterThan(0);
    await page.evaluate((offset) => {
      const ed = window.__ide.editors.editor;
      const pos = ed.getModel()!.getPositionAt(offset + 1);
      ed.setPosition(pos);
      ed.focus();
    }, at);
    await page.keyboard.press('Enter');
    await page.keyboard.press('Control+Space');
    await page.locator('.suggest-widget .monaco-list-row').first().waitFor({ timeout: 5000 });
    const labels = await page.locator('.suggest-widget .monaco-list-row .label-name').allTextContents();
    expect(labels).toEqual(expect.arrayContaining(['activate schema', 'activate supervisor', 'notify'])); // the list renders only its visible rows
    await page.keyboard.press('Escape');
    await page.evaluate((text) => window.__ide.editors.editor.getModel()!.setValue(text), before);
    await waitSaved(page);
  });

  it('completion lists the language server\'s candidates only, never the file\'s words (Monaco\'s word-based suggestions off for Cactal)', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    const before = await activeValue(page);
    // words of the file that name nothing a module reference can take
    await placeCursor(page, 'temp_consigne = consigne;', 'temp_consigne = consigne;'.length);
    await page.keyboard.type(' // r1 rx');
    /** The list Monaco shows once it has its answer: its rows, or none when it says "No suggestions." (an explicit Ctrl+Space). */
    const shown = async () => {
      await page.waitForFunction(() => {
        const widget = document.querySelector('.suggest-widget.visible');
        const message = widget?.querySelector<HTMLElement>('.message');
        return !!widget && (!!widget.querySelector('.monaco-list-row') || (!!message && message.offsetParent !== null && /No suggestions/.test(message.textContent ?? '')));
      }, undefined, { timeout: 10_000 });
      return page.locator('.suggest-widget.visible .monaco-list-row').evaluateAll((rows) => rows.map((r) => ({
        label: r.querySelector('.label-name')?.textContent ?? '',
        word: !!r.querySelector('.suggest-icon.codicon-symbol-text'), // Monaco's word-based items are of kind Text
      })));
    };
    // a module reference: the modules in scope, and nothing else
    await placeCursor(page, 'activate resttime module MAA', 'activate resttime module '.length);
    for (let i = 0; i < 3; i++) await page.keyboard.press('Delete');
    await page.keyboard.type('M');
    await page.keyboard.press('Control+Space');
    await expect.poll(async () => (await shown()).map((r) => r.label), { timeout: 10_000 }).toEqual(['MAA', 'MAB', 'MSA', 'MSB', 'MSC', 'MSD']);
    await page.keyboard.press('Escape');
    await page.keyboard.press('Backspace');
    // a letter no module starts with: the server has no candidate, and no word of the file is offered in its place
    await page.keyboard.type('r');
    await page.keyboard.press('Control+Space');
    const words = await shown();
    expect(words, JSON.stringify(words)).toEqual([]);
    await shot(page, 'completion-no-words');
    await page.keyboard.press('Escape');
    // a rule label in a condition: the rules, no words
    await placeCursor(page, 'started(THIRD)', 'started('.length);
    for (let i = 0; i < 5; i++) await page.keyboard.press('Delete');
    await page.keyboard.type('R');
    await page.keyboard.press('Control+Space');
    await expect.poll(async () => (await shown()).map((r) => r.label), { timeout: 10_000 }).toEqual(['RECEPTION']);
    await page.keyboard.press('Escape');
    await page.evaluate((text) => window.__ide.editors.editor.getModel()!.setValue(text), before);
    await waitSaved(page);
  });

  it('a comment typed word by word brings up no completion list, and Enter starts a new line', async () => {
    const { page } = s;
    await openFile(page, 'smodule4.contract');
    const before = await activeValue(page);
    await placeCursor(page, 'synchronous module MSD');
    // a space is a trigger character: in code it asks the server, in a comment it must not list keywords
    for (const word of ['// the', 'server', 'was', 'down', 'async']) {
      await page.keyboard.type(`${word} `, { delay: 20 });
      await page.waitForTimeout(300); // the time a list would take to come from the worker
      expect(await page.locator('.suggest-widget.visible').count(), `after "${word} "`).toBe(0);
    }
    await page.keyboard.press('Enter');
    expect(await activeValue(page)).toContain('// the server was down async \nsynchronous module MSD');
    await page.evaluate((text) => window.__ide.editors.editor.getModel()!.setValue(text), before);
    await waitSaved(page);
  });

  it('Format on a file with a syntax error changes nothing and says why', async () => {
    const { page } = s;
    await openFile(page, 'smodule3.contract');
    await placeCursor(page, 'C=1ms;', 5);
    await page.keyboard.press('Delete'); // drops the ';'
    const broken = await activeValue(page);
    await page.keyboard.press('Control+Shift+i');
    const notice = page.locator('.toast', { hasText: 'Not formatted: line' }).first();
    await notice.waitFor({ timeout: 5000 });
    expect(await notice.textContent()).toMatch(/Fix the syntax error first/);
    expect(await activeValue(page)).toBe(broken);
    await page.keyboard.type(';');
    await waitSaved(page);
  });
});
