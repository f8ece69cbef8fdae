/**
 * The architecture diagram at common laptop sizes (1366 x 768, and 1280 x 720 at 200 %): every
 * schema of examples/mobile-robot drawn in the Monitor's diagram and docked beside the editor, with
 * no "Layout failed" and, after Fit, every module's box inside the pane. velocityLoop's diagram
 * failed in the Monitor at these widths (`Layout failed: Cannot read properties of undefined
 * (reading 'Qg')`): its pane there is narrow enough to draw top to bottom, and ELK threw on the
 * folded layout (src/views/schema-graph.ts). Real server, headless Chromium, a recorded run of
 * the example (src/monitor/fixtures/mobile-robot-run) in the workspace's logs folder.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, mkdirSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadWorkspace } from '@contract-studio/language/node';
import { schemasOf } from '../../src/lsp/architecture-model.js';
import { startSession, openIde, shot, MOBILE_ROBOT, type Session } from './harness.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/mobile-robot-run', import.meta.url));
type Page = Session['page'];

interface Drawn {
  schema: string;
  errors: string[];
  canvas: { left: number; top: number; right: number; bottom: number };
  modules: Array<{ name: string; left: number; top: number; right: number; bottom: number }>;
}

const drawnIn = (page: Page, canvasSelector: string): Promise<Drawn> => page.evaluate((sel) => {
  const canvas = document.querySelector(sel) as HTMLElement;
  const c = canvas.getBoundingClientRect();
  const svg = canvas.querySelector('svg.arch-svg') as SVGSVGElement | null;
  return {
    schema: svg?.dataset.schema ?? '',
    errors: [...canvas.querySelectorAll('.gen-error, .arch-note')].map((e) => e.textContent ?? ''),
    canvas: { left: c.left, top: c.top, right: c.right, bottom: c.bottom },
    modules: [...canvas.querySelectorAll<SVGGElement>('.arch-node')].map((n) => {
      const r = n.getBoundingClientRect();
      return { name: n.dataset.module ?? '', left: r.left, top: r.top, right: r.right, bottom: r.bottom };
    }),
  };
}, canvasSelector);

const expectInside = (d: Drawn, schema: string) => {
  for (const m of d.modules) {
    const where = `${schema} ${m.name} ${JSON.stringify(m)} in ${JSON.stringify(d.canvas)}`;
    expect(m.left, where).toBeGreaterThanOrEqual(d.canvas.left - 0.5);
    expect(m.right, where).toBeLessThanOrEqual(d.canvas.right + 0.5);
    expect(m.top, where).toBeGreaterThanOrEqual(d.canvas.top - 0.5);
    expect(m.bottom, where).toBeLessThanOrEqual(d.canvas.bottom + 0.5);
  }
};

/**
 * Picks each schema in the view's list: drawn with no error, all its modules, each inside the pane
 * after Fit; `wholeAtFirst`: the schemas whose first view (labels at 9 px or more) shows them whole.
 */
async function expectEverySchemaDrawnWhole(page: Page, view: string, modulesOf: Map<string, string[]>, name: string, wholeAtFirst: string[] = []): Promise<void> {
  const select = page.locator(`${view} select.arch-select`);
  const schemas = await select.locator('option').evaluateAll((os) => os.map((o) => (o as HTMLOptionElement).value));
  expect(schemas.sort()).toEqual([...modulesOf.keys()].sort());
  for (const schema of schemas) {
    await select.selectOption(schema);
    await expect.poll(async () => {
      const d = await drawnIn(page, `${view} .arch-canvas`);
      return d.errors.length ? d.errors.join(' | ') : d.schema;
    }, { timeout: 20_000 }).toBe(schema);
    await page.waitForTimeout(300); // the first view set
    if (wholeAtFirst.includes(schema)) expectInside(await drawnIn(page, `${view} .arch-canvas`), `${schema} (first view)`);
    await page.locator(`${view} #arch-fit`).click();
    await page.waitForTimeout(300);
    const d = await drawnIn(page, `${view} .arch-canvas`);
    expect(d.errors, schema).toEqual([]);
    expect(d.modules.map((m) => m.name).sort(), schema).toEqual([...modulesOf.get(schema)!].sort());
    expectInside(d, schema);
    await page.locator(`${view} .arch-view`).scrollIntoViewIfNeeded();
    await shot(page, `laptop-${name}-${view.includes('monitor') ? 'monitor' : 'docked'}-${schema}`);
  }
}

const SCREENS = [
  { name: '1366x768', viewport: { width: 1366, height: 768 }, deviceScaleFactor: 1 },
  { name: '1280x720@2x', viewport: { width: 1280, height: 720 }, deviceScaleFactor: 2 },
];

describe.each(SCREENS)('the architecture diagram of examples/mobile-robot at $name', ({ name, viewport, deviceScaleFactor }) => {
  let s: Session;
  const modulesOf = new Map<string, string[]>();
  beforeAll(async () => {
    const ws = await loadWorkspace(MOBILE_ROBOT);
    for (const d of ws.documents) for (const schema of schemasOf(d.document.parseResult.value as never, d.document.uri.toString())) modulesOf.set(schema.name, schema.modules.map((m) => m.name));
    s = await startSession({ example: MOBILE_ROBOT, buildService: false, viewport, deviceScaleFactor });
    mkdirSync(join(s.workspace, 'logs'));
    cpSync(FIXTURE, join(s.workspace, 'logs'), { recursive: true, filter: (src) => !src.endsWith('README.md') });
    await openIde(s);
  }, 120_000);
  afterAll(async () => {
    await s?.close();
  });

  it("in the Monitor, replaying the workspace's logs: every schema drawn, each module inside the pane after Fit", async () => {
    const { page } = s;
    await page.locator('#btn-monitor').click();
    await page.locator('.side-pane .monitor-view').waitFor();
    await page.locator('.monitor-sources').selectOption('dir:logs');
    await expect.poll(() => page.locator('.monitor-view .arch-svg, .monitor-view .gen-error').first().count(), { timeout: 20_000 }).toBe(1);
    await expectEverySchemaDrawnWhole(page, '.monitor-view', modulesOf, name);
  }, 120_000);

  // localisationLoop (LOC, NAV) showed NAV off the pane at 1366 x 768 (drawn left to right only)
  it('docked beside the editor: every schema drawn, each module inside the pane after Fit; the schemas of one or two modules whole at first', async () => {
    const { page } = s;
    await page.locator('#btn-arch').click();
    await page.locator('.arch-view #arch-dock').first().click();
    await page.locator('.side-pane .arch-view').waitFor();
    const small = [...modulesOf].filter(([, modules]) => modules.length <= 2).map(([schema]) => schema);
    expect(small).toContain('localisationLoop');
    await expectEverySchemaDrawnWhole(page, '.side-pane', modulesOf, name, small);
  }, 120_000);
});
