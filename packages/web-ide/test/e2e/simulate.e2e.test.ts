/**
 * End-to-end: the Simulate panel (docs/simulation.md "In the IDE") in headless Chromium on the
 * real IDE server and a copy of examples/tutorial; the steps run in the real simulator (native
 * harness on the engine cores, POST /api/simulate). The §4.7 story step by step: start
 * SUP.action, step to 1 ms (FIRST active), inject `finish MAB` (its run ends: no longer running in
 * the Monitor), inject MAA:2 "disconnected" (SECOND active, its cause
 * shown, in the panel and in the Monitor), a wrong step refused with its diagnostic, then Save as
 * scenario and `contract simulate` of the saved file passes; a reload grows the session again.
 */
import { describe, it, expect } from 'vitest';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { spawnSync } from 'node:child_process';
import { ideSession, injectStep, shot, PKG, type Session } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const s = ideSession({ buildService: false, timeout: 120_000 });

type Page = Session['page'];
const simRule = (page: Page, id: string) => page.locator(`.sim-rule[data-rule="${id}"]`);
const monitorRule = (page: Page, id: string) => page.locator(`.monitor-rule[data-rule="${id}"]`);
/** Waits for the session's re-simulation after a click: the panel's virtual time says `t`. */
const now = (page: Page) => page.locator('.sim-now').textContent();
const stepValue = (page: Page) => page.evaluate(() => window.__ide.simulate.panel.stepInput.value as string);

describe('Simulate panel', () => {
  it('steps the tutorial story, shows rules with causes in the panel and the Monitor, saves a scenario that contract simulate passes', async () => {
    const { page } = s;
    await page.locator('.panel-tab[data-panel="simulate"]').click();
    await page.waitForSelector('.sim-fn option[value="SUP.action"]', { state: 'attached', timeout: 30_000 });
    await page.selectOption('.sim-fn', 'SUP.action');
    // the function's parameters, from the outline's symbols, are the parameters' hint
    expect(await page.locator('.sim-fn option[value="SUP.action"]').textContent()).toBe('SUP.action(TypeA consigne)');
    expect(await page.locator('.sim-params').getAttribute('placeholder')).toBe('consigne = value   (empty: the defaults)');
    await page.fill('.sim-params', 'consigne = {1.0, 2.0, 3.0}');
    await page.click('.sim-start');
    await expect.poll(() => now(page), { timeout: 30_000 }).toBe('0');

    // Next: to the engines' next change, FIRST's elapsed=1ms timer
    await page.click('.sim-next');
    await expect.poll(() => now(page), { timeout: 30_000 }).toBe('1ms');
    await expect.poll(() => simRule(page, 'SUP.action.FIRST').getAttribute('class')).toContain('active');
    expect(await simRule(page, 'SUP.action.FIRST').textContent()).toContain('← elapsed=1ms at 1ms');
    await expect.poll(() => page.locator('.sim-schema').allTextContents()).toEqual(['schemaReceptionMessage']);
    await expect.poll(() => monitorRule(page, 'SUP.action.FIRST').getAttribute('data-active'), { timeout: 10_000 }).toBe('true');

    // a wrong step: refused with the checker's diagnostic, the session unchanged
    // the step field completes with the scenario language: MAA's out event ports after `MAA:`
    await page.locator('.sim-step .view-lines').click();
    await page.keyboard.type('MAA:');
    await page.keyboard.press('Control+Space');
    await expect.poll(() => page.locator('.suggest-widget .monaco-list-row').allTextContents(), { timeout: 15_000 }).toEqual(expect.arrayContaining([expect.stringMatching(/^2/)]));
    await page.keyboard.press('Escape');
    await injectStep(page, 'MAA:2 3');
    await expect.poll(() => page.locator('.sim-message').textContent(), { timeout: 30_000 }).toMatch(/error\(s\).*line 4:\d+: .*MAA:2 3/s);
    expect(await page.evaluate(() => window.__ide.simulate.session.lines.length)).toBe(0);

    // a click on MAA's out event port :2 in the Monitor's diagram starts that step, with its values offered
    await expect.poll(() => page.locator('.monitor-view .arch-svg').getAttribute('data-schema'), { timeout: 15_000 }).toBe('schemaReceptionMessage');
    await page.locator('.monitor-diagram rect.port[data-port="MAA:2"]').click();
    await expect.poll(() => stepValue(page)).toBe('MAA:2 ');
    await expect.poll(() => page.locator('.suggest-widget .monaco-list-row').allTextContents(), { timeout: 15_000 }).toEqual(expect.arrayContaining([expect.stringContaining('"disconnected"')]));
    await page.keyboard.press('Escape');

    // MAB's own code ends its run (the tutorial's MAB does so at once): the Monitor no longer lists it as running
    await expect.poll(() => page.locator('.monitor-modules').textContent(), { timeout: 10_000 }).toBe('Running now: MAA, MAB');
    await injectStep(page, 'finish MAB');
    await expect.poll(() => page.locator('.monitor-modules').textContent(), { timeout: 30_000 }).toBe('Running now: MAA');
    expect(await page.evaluate(() => window.__ide.simulate.session.lines.length)).toBe(1);

    // inject the disconnection: SECOND active, caused by it; FIRST inactive
    await injectStep(page, 'MAA:2 connection_status = "disconnected"');
    await expect.poll(() => simRule(page, 'SUP.action.SECOND').getAttribute('class'), { timeout: 30_000 }).toBe('sim-rule active');
    expect(await simRule(page, 'SUP.action.SECOND').textContent()).toContain('← MAA:2 = "disconnected" at 1ms');
    expect(await simRule(page, 'SUP.action.FIRST').getAttribute('class')).toBe('sim-rule inactive');
    expect(await page.locator('.sim-schema').allTextContents()).toContain('schemaCommande1');
    expect(await page.locator('.sim-local').count()).toBeGreaterThan(0);
    const actions = await page.locator('.sim-step-row').filter({ hasText: 'MAA:2 connection_status' }).locator('.sim-action').allTextContents();
    // FIRST's undo in a run's words (as `contract trace` and `simulate --verbose` say it), not the harness's bare `stop module MAA`
    expect(actions).toContain('SUP: undo: stop module MAA');
    expect(actions.filter((a) => /^SUP: (stop|disconnect|unsubscribe|release) /.test(a))).toEqual([]);
    await expect.poll(() => monitorRule(page, 'SUP.action.SECOND').getAttribute('data-active'), { timeout: 10_000 }).toBe('true');
    expect(await monitorRule(page, 'SUP.action.SECOND').getAttribute('data-cause')).toBe('MAA:2 value="disconnected"');
    expect(await stepValue(page)).toBe('');
    await shot(page, 'simulate-panel');

    // save as scenario: a workspace file that contract simulate runs and passes
    await page.fill('.sim-save-path', 'scenarios/session.scenario');
    await page.click('.sim-save');
    await expect.poll(() => page.locator('.sim-message').textContent(), { timeout: 10_000 }).toContain('saved scenarios/session.scenario');
    const saved = readFileSync(join(s.workspace, 'scenarios/session.scenario'), 'utf8');
    expect(saved).toContain('start SUP.action(consigne = {1.0, 2.0, 3.0})');
    expect(saved).toContain('t=1ms finish MAB');
    expect(saved).toContain('t=1ms MAA:2 connection_status = "disconnected"');
    expect(saved).toContain('expect at 1ms rule SUP.action.SECOND active');
    expect(saved).toContain('expect at 1ms rule SUP.action.FIRST inactive');
    // the periodic schema released by then: its deadline misses and overruns pinned (none)
    expect(saved).toContain('expect at 1ms deadline misses schemaCommande1 == 0\nexpect at 1ms overruns schemaCommande1 == 0\n');
    // stepping on by a time: the session runs on, the saved file is unchanged
    await page.fill('.sim-time', '+5ms');
    await page.click('.sim-advance');
    await expect.poll(() => now(page), { timeout: 30_000 }).toBe('6ms');
    expect(await simRule(page, 'SUP.action.SECOND').getAttribute('class')).toBe('sim-rule active');
    // the Monitor shows what the virtual modules did: schemaCommande1's first cycle (MSA 0.5 ms, then
    // MSC and MSD 1 ms each, from 1 ms) complete with its response time, from the harness's typed records
    const cycle = page.locator('.monitor-pschema[data-periodic="schemaCommande1"] .monitor-pstats');
    await expect.poll(() => cycle.textContent(), { timeout: 10_000 }).toMatch(/^3 module release\(s\) · last cycle 0 · 1 cycle\(s\) complete · response last 2\.5 ms, mean 2\.5 ms, max 2\.5 ms · 0 deadline miss/);
    await shot(page, 'simulate-monitor-cycle');
    const cli = spawnSync(process.execPath, [join(PKG, '../cli/bin/contract.js'), 'simulate', s.workspace, join(s.workspace, 'scenarios/session.scenario')], { encoding: 'utf8', timeout: 60_000 });
    expect(cli.status, cli.stdout + cli.stderr).toBe(0);
    expect(cli.stdout).toMatch(/1 passed, 0 failed/);

    // a reload keeps the session: the panel is shown again with its functions, and the session is
    // grown again and simulated (its function, parameters, steps and time; the rules as before)
    await page.reload();
    await page.waitForSelector('body[data-ready=true]', { timeout: 60_000 });
    await expect.poll(() => now(page), { timeout: 30_000 }).toBe('6ms');
    expect(await page.locator('.sim-fn').inputValue()).toBe('SUP.action');
    expect(await page.locator('.sim-params').inputValue()).toBe('consigne = {1.0, 2.0, 3.0}');
    // the time is shown before the restored session is simulated again, the message after: waited for
    await expect.poll(() => page.locator('.sim-message').textContent(), { timeout: 30_000 }).toBe('restored the session of SUP.action from before the reload: 2 step(s), at 6ms');
    expect(await page.evaluate(() => window.__ide.simulate.session.lines.map((l: { text: string }) => l.text))).toEqual(['finish MAB', 'MAA:2 connection_status = "disconnected"']);
    await expect.poll(() => simRule(page, 'SUP.action.SECOND').getAttribute('class'), { timeout: 30_000 }).toBe('sim-rule active');
    await expect.poll(() => monitorRule(page, 'SUP.action.SECOND').getAttribute('data-active'), { timeout: 10_000 }).toBe('true');
    // the session goes on from there
    await page.fill('.sim-time', '+1ms');
    await page.click('.sim-advance');
    await expect.poll(() => now(page), { timeout: 30_000 }).toBe('7ms');

    // Save as scenario onto a file that exists replaces it only when asked twice
    const before = readFileSync(join(s.workspace, 'scenarios/session.scenario'), 'utf8');
    await page.fill('.sim-save-path', 'scenarios/session.scenario');
    await page.click('.sim-save');
    await expect.poll(() => page.locator('.sim-message').textContent(), { timeout: 10_000 }).toMatch(/^scenarios\/session\.scenario exists: Save as scenario again to replace it/);
    expect(readFileSync(join(s.workspace, 'scenarios/session.scenario'), 'utf8')).toBe(before);
    await page.click('.sim-save');
    await expect.poll(() => page.locator('.sim-message').textContent(), { timeout: 10_000 }).toContain('saved scenarios/session.scenario');
    expect(readFileSync(join(s.workspace, 'scenarios/session.scenario'), 'utf8')).toContain('expect at 7ms rule SUP.action.SECOND active');

    // the step field's keys are its own: Tab and Shift+Tab leave it for the controls around it,
    // Escape goes back to the code editor, where Enter makes a new line (it injected a step there,
    // for every editor of the page, once the panel had been shown)
    const focused = () => page.evaluate(() => (document.activeElement?.closest('.sim-step') ? 'step' : document.activeElement?.className ?? ''));
    await page.locator('.sim-step .view-lines').click();
    await page.keyboard.press('Tab');
    await expect.poll(focused).toContain('sim-inject');
    await page.keyboard.press('Shift+Tab');
    await expect.poll(focused).toBe('step');
    await page.keyboard.press('Shift+Tab');
    await expect.poll(focused).toContain('sim-advance');
    expect(await stepValue(page)).toBe(''); // no tab character typed into it
    await page.locator('.sim-step .view-lines').click();
    await page.keyboard.press('Escape');
    await expect.poll(() => page.evaluate(() => !!document.activeElement?.closest('.simulate-panel'))).toBe(false);
    const lines = () => page.evaluate(() => window.__ide.editors.editor.getModel()!.getLineCount() as number);
    const before2 = await lines();
    await page.keyboard.press('End');
    await page.keyboard.press('Enter');
    await expect.poll(lines).toBe(before2 + 1);
    expect(await page.evaluate(() => window.__ide.simulate.session.lines.length)).toBe(2);
    await page.keyboard.press('ControlOrMeta+Z');
    await expect.poll(lines).toBe(before2);
  }, 180_000);
});
