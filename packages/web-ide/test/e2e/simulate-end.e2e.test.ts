/**
 * The end of a simulation in the Monitor, in headless Chromium on the real IDE server (the set-up of
 * simulate.e2e.test.ts: a copy of examples/tutorial, the real simulator behind POST /api/simulate).
 * - A simulation's trace file replayed (fixtures/simulated-flows/flows.jsonl, `contract simulate
 *   --trace`): at its end Active schemas shows schemaCommande1, which the simulation left active.
 *   Before, the end was taken for ORD's log ending with no exit record and showed `none`.
 * - The Simulate panel's session, run to 3.5 s past SECOND's activation of schemaCommande1: the
 *   Monitor shows the rows a finished run's end shows (the Deliveries' closing row of a simulation,
 *   as `contract trace` ends it) and schemaCommande1 still active; before, its records were never
 *   ended and no such row came. Then `stop SUP.action`: Active schemas says which schema ended,
 *   when and why, not a bare `none`.
 */
import { describe, it, expect } from 'vitest';
import { fileURLToPath } from 'node:url';
import { ideSession, injectStep, replayTraceFile, shot, type Session } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

/** One of the ports this test may use (E2E_SIMULATE_END_PORT to choose another). */
const PORT = Number(process.env.E2E_SIMULATE_END_PORT ?? 7101);
const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/simulated-flows/flows.jsonl', import.meta.url));

const s = ideSession({ port: PORT, buildService: false, timeout: 120_000 });

type Page = Session['page'];
const now = (page: Page) => page.locator('.sim-now').textContent();
const activeSchemaRows = (page: Page) => page.locator('.side-pane .monitor-schemas > div').allTextContents();

async function runTo(page: Page, time: string, shown: string): Promise<void> {
  await page.fill('.sim-time', time);
  await page.click('.sim-advance');
  await expect.poll(() => now(page), { timeout: 30_000 }).toBe(shown);
}

describe("a simulation's end in the Monitor", () => {
  it('a trace file replayed, and the Simulate panel\'s session, end with the schema they left active; a stop says what it ended', async () => {
    const { page } = s;
    // the simulation's trace file: its end shows schemaCommande1 active, as the simulation left it
    await replayTraceFile(s, FIXTURE, 'flows.jsonl');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 10_000 }).toMatch(/^Trace file flows\.jsonl · simulation of flows\.scenario · /);
    await page.locator('#monitor-follow').click(); // the cursor at the end
    await expect.poll(() => page.locator('.side-pane .monitor-view').getAttribute('data-t'), { timeout: 10_000 }).toBe('3500000000');
    await expect.poll(() => activeSchemaRows(page), { timeout: 10_000 }).toEqual(['● schemaCommande1 (periodic) ← SUP.action.SECOND']);
    await shot(page, 'simulate-end-trace-file');

    // the Simulate panel: SUP.action to 1.5 s, MAA's disconnection (SECOND, schemaCommande1), on to 3.5 s
    await page.locator('.panel-tab[data-panel="simulate"]').click();
    await page.waitForSelector('.sim-fn option[value="SUP.action"]', { state: 'attached', timeout: 30_000 });
    await page.selectOption('.sim-fn', 'SUP.action');
    await page.fill('.sim-params', 'consigne = {1.0, 2.0, 3.0}');
    await page.click('.sim-start');
    await expect.poll(() => now(page), { timeout: 30_000 }).toBe('0');
    await runTo(page, '1.5s', '1500ms');
    await injectStep(page, 'MAA:2 connection_status = "disconnected"');
    await expect.poll(() => page.locator('.sim-schema').allTextContents(), { timeout: 30_000 }).toContain('schemaCommande1');
    await runTo(page, '3.5s', '3500ms');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 10_000 }).toBe('Simulation: SUP.action');
    // the rows a finished run's end shows: the Deliveries' closing row (a simulation's, without ⚠)
    await expect.poll(() => page.locator('.side-pane .monitor-flow.quiet').allTextContents(), { timeout: 10_000 }).toEqual([
      expect.stringMatching(/^━ a simulation runs no module code: data values are not simulated, nor the events its modules post: what 2 data flows (and \d+ event flows? )?connected over 1 s delivered is not told$/),
    ]);
    // and the schema still active at the session's time, not ended with its last record
    await expect.poll(() => activeSchemaRows(page), { timeout: 10_000 }).toEqual(['● schemaCommande1 (periodic) ← SUP.action.SECOND']);
    await shot(page, 'simulate-end-session');

    // the session's end deactivates: said in words under Active schemas
    await injectStep(page, 'stop SUP.action');
    await expect.poll(() => activeSchemaRows(page), { timeout: 30_000 }).toEqual([
      'none · schemaCommande1 (periodic) deactivated by ORD at +3.500000 s: SUP.action.SECOND, which activated it, became inactive ← its function stopped',
    ]);
    await page.locator('.side-pane .monitor-schemas').scrollIntoViewIfNeeded();
    await shot(page, 'simulate-end-stopped');
  }, 180_000);
});
