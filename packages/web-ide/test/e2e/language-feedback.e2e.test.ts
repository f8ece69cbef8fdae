/**
 * End-to-end: the language server's smaller helps reach the user in the IDE — hover on a timing
 * property gives µs and the schema's figures, completion in a rule body offers whole actions (and
 * none inside a comment), and
 * Format on a file with a syntax error says why it did nothing (docs/ide.md, "Using it").
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { startSession, openIde, placeCursor, activeValue, openFile, waitSaved, type Session } from './harness.js';

let s: Session;

describe('language server feedback in the IDE', () => {
  beforeAll(async () => {
    s = await startSession({ buildService: false });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

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
      const ed = (window as any).__ide.editors.editor;
      const pos = ed.getModel().getPositionAt(offset + 1);
      ed.setPosition(pos);
      ed.focus();
    }, at);
    await page.keyboard.press('Enter');
    await page.keyboard.press('Control+Space');
    await page.locator('.suggest-widget .monaco-list-row').first().waitFor({ timeout: 5000 });
    const labels = await page.locator('.suggest-widget .monaco-list-row .label-name').allTextContents();
    expect(labels).toEqual(expect.arrayContaining(['activate schema', 'activate supervisor', 'notify'])); // the list renders only its visible rows
    await page.keyboard.press('Escape');
    await page.evaluate((text) => (window as any).__ide.editors.editor.getModel().setValue(text), before);
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
    await page.evaluate((text) => (window as any).__ide.editors.editor.getModel().setValue(text), before);
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
