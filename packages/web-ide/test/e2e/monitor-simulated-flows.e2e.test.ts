/**
 * A simulation's trace file (`contract simulate --trace` of the tutorial: fixtures/simulated-flows)
 * replayed in the Monitor: its Deliveries rows tell no flow that delivered nothing (its modules ran
 * no code) but one row without ⚠ that says why. Before, the replay showed three ⚠ rows blaming
 * code that never ran (`MSC never read its input :0`, `MAA posted none on its output :0`). Real IDE
 * server, headless Chromium.
 */
import { describe, it, expect } from 'vitest';
import { fileURLToPath } from 'node:url';
import { ideSession, replayTraceFile, shot } from './harness.js';

/** One of the ports this test may use (E2E_SIMULATED_FLOWS_PORT to choose another). */
const PORT = Number(process.env.E2E_SIMULATED_FLOWS_PORT ?? 8211);
const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/simulated-flows/flows.jsonl', import.meta.url));

describe("a simulation's trace file, replayed", () => {
  const s = ideSession({ port: PORT, buildService: false });

  it('shows no ⚠ row of a silent flow, one row saying a simulation runs no module code', async () => {
    const { page } = s;
    await replayTraceFile(s, FIXTURE, 'flows.jsonl');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 10_000 }).toMatch(/^Trace file flows\.jsonl · simulation of flows\.scenario · /);
    await expect.poll(() => page.locator('.monitor-flow.quiet').allTextContents(), { timeout: 10_000 }).toEqual([
      '━ a simulation runs no module code: data values are not simulated, nor the events its modules post: what 2 data flows and 1 event flow connected over 1 s delivered is not told',
    ]);
    // in the flows' own colour, not the warning's
    const colours = await page.locator('.monitor-flow.quiet').evaluate((el) => {
      const probe = document.createElement('span');
      probe.style.color = 'var(--warn)';
      el.parentElement!.appendChild(probe);
      const warn = getComputedStyle(probe).color;
      probe.remove();
      return { row: getComputedStyle(el).color, flows: getComputedStyle(el.parentElement!).color, warn };
    });
    expect(colours.row).toBe(colours.flows);
    expect(colours.row).not.toBe(colours.warn);
    await page.locator('.monitor-flow.quiet').scrollIntoViewIfNeeded();
    await shot(page, 'monitor-simulated-flows');
  }, 120_000);
});
