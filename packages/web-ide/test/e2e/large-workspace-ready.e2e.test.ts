/**
 * The ready mark (`body[data-ready=true]`, performance mark `ide:ready`: what users and the e2e
 * tests wait for) on a very large workspace: the language bench's synthetic architecture of 1,000
 * modules (1,231 files). At the moment the mark is set, the language server's first full
 * validation of the workspace has been published and the Problems counts in the status bar are
 * the ones `contract check` finds (the language package's loadWorkspace, in Node). It came once each
 * file had its first diagnostics (or after 15 s): some came from builds made before the files they
 * import were opened (75 to 80 errors shown at the mark, 1 about 12 s later).
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { startSession, shot, type Session } from './harness.js';
import { writeSyntheticArchitecture } from '../../../language/bench/synthetic-architecture.js';

let s: Session;

describe('the ready mark on a very large workspace', () => {
  beforeAll(async () => {
    s = await startSession({ buildService: false, empty: true });
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('set once the first full validation is published and shown: the status bar counts those of contract check', async () => {
    const { page } = s;
    const files = writeSyntheticArchitecture(s.workspace) as number;
    expect(files).toBeGreaterThan(1000);
    const { loadWorkspace } = await import('@contract-studio/language/node');
    const model = await loadWorkspace(s.workspace);
    const expected = {
      errors: model.diagnostics.filter((d) => d.severity === 'error').length,
      warnings: model.diagnostics.filter((d) => d.severity === 'warning').length,
    };
    expect(expected.errors + expected.warnings).toBeGreaterThan(0);
    // what the page shows at the very moment the mark is set
    await page.addInitScript(() => {
      new MutationObserver((_m, observer) => {
        if (document.body?.dataset.ready !== 'true') return;
        const status = document.getElementById('status-problems');
        (window as unknown as { __atReady: unknown }).__atReady = { errors: Number(status?.dataset.errors ?? 0), warnings: Number(status?.dataset.warnings ?? 0) };
        observer.disconnect();
      }).observe(document, { attributes: true, subtree: true, attributeFilter: ['data-ready'] });
    });
    await page.goto(s.server.openUrl);
    await page.waitForSelector('body[data-ready=true]', { timeout: 240_000 });
    const atReady = await page.evaluate(() => (window as unknown as { __atReady: unknown }).__atReady);
    await shot(page, 'large-workspace-ready');
    expect(atReady).toEqual(expected);
  }, 300_000);
});
