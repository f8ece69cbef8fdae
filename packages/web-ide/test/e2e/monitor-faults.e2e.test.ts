/**
 * End-to-end, in headless Chromium on the real IDE server: two faults a field tester planted, as the
 * Monitor shows them, in the real run of src/monitor/fixtures/crash-and-unheard-run (its README:
 * GCS posts "land" on its port 1 that nothing subscribes; EST dereferences NULL after 30 cycles):
 * - the event no one received: a row of its own first under Deliveries, its port's first marked on
 *   the strip in `contract trace`'s words;
 * - EST's crash: said under the strip as an alert the moment its `module_crashed` record comes
 *   (live: before the job ends), named after the modules running now, marked on the strip;
 * - the failed job's long message: its run list entry ended at a word with `…`, the whole label its
 *   tooltip and accessible name;
 * - an overrun listed under its schema: ORD's line, as the record says it, its tooltip.
 * Replayed from the logs (a folder of the workspace) and followed live (a job's trace stream).
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, mkdirSync, readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { WebSocketServer } from 'ws';
import { encodeTraceRecords, parseTrace, renderStory } from '@contract-studio/build-service/trace';
import { startSession, openIde, shot, type Session, showMonitor } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/crash-and-unheard-run', import.meta.url));
const FILES = readdirSync(FIXTURE).filter((n) => n.endsWith('.csv')).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') }));
const LINES = FILES.flatMap((f) => f.text.split('\n').map((text, i) => ({ file: f.name, line: i + 1, text })))
  .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));
const STORY = renderStory(parseTrace(FILES));
/** `contract trace`'s line that says `what`, its time kept, its module's column dropped. */
const told = (what: string) => STORY.find((l) => l.includes(what))!.replace(/^(\S+) \S+ +/, '$1 ');
const UNHEARD = told('posted with no subscriber');
const CRASH = told('crashed: signal');
/** The failed job's message, as the build service sent it for this run. */
const FAILED = 'run failed: module EST crashed (died by signal 11 (Segmentation fault)) at src-gen/generated/architecture/modules/EST_mod/module.c:251 in its protected region protect_exec_EST (_exec_module_state) (contract-launch exit 1; make exit 2) [bwrap; prepare 1.0 s, build 0.3 s, run 1.5 s]';

type Page = Session['page'];
const label = (page: Page) => page.locator('.monitor-source').textContent();
const crashed = (page: Page) => page.evaluate(() => {
  const el = document.querySelector<HTMLElement>('.monitor-crashed[role=alert]');
  return el && !el.hidden ? el.textContent : null;
});
const unheardRows = (page: Page) => page.locator('.monitor-flows .monitor-flow.unheard').allTextContents();
const modules = (page: Page) => page.locator('.monitor-modules').textContent();
const marksOf = (page: Page, kind: string) => page.evaluate((kind) => (window.__ide.monitor.current?.marks ?? [])
  .filter((m) => m.kind === kind).map((m) => `+${(m.t / 1e9).toFixed(6)}s ${m.where}: ${m.label}`), kind);

describe('Monitor: an event no one received, a module that crashed', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession();
    mkdirSync(join(s.workspace, 'faults'));
    cpSync(FIXTURE, join(s.workspace, 'faults'), { recursive: true, filter: (src) => !src.endsWith('README.md') });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('a recorded run: Deliveries lists the event no one received first, EST is said crashed, both marked in contract trace\'s words', async () => {
    const { page } = s;
    expect(UNHEARD).toBe('+0.336166s event GCS:1 posted with no subscriber: no one received it (no supervisor or module subscribed to GCS:1 then); its later ones are counted at the end');
    expect(CRASH).toBe('+0.432425s crashed: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array');
    await showMonitor(page);
    await page.locator('.monitor-sources').selectOption('dir:faults');
    await expect.poll(() => label(page)).toBe('8 CSV log(s) in faults');
    expect(await marksOf(page, 'unheard')).toEqual([UNHEARD.replace('+0.336166s ', '+0.336166s GCS: ').replace('its later ones are counted at the end', 'Deliveries counts its later ones')]);
    expect(await marksOf(page, 'crash')).toEqual(['+0.432425s EST: crashed: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array']);
    await expect.poll(() => crashed(page)).toBe('⚠ EST crashed at +0.432425 s: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array');
    // drawn with the diagram, once it is made
    await expect.poll(() => modules(page)).toMatch(/^Running now: .*· crashed: EST/);
    await expect.poll(() => unheardRows(page)).toEqual(['┅ GCS:1 → no subscriber ×1 · no one received it · last +0.336166 s']);
    // the row comes first under Deliveries, its tooltip in contract trace's words
    expect(await page.locator('.monitor-flows > :first-child').getAttribute('title')).toBe('event GCS:1 posted with no subscriber: no one received it (no supervisor or module subscribed to GCS:1 then)');
    // an overrun listed under its schema: its tooltip is ORD's line, as the record says it
    expect(await page.locator('.monitor-pschema[data-periodic=altHold] .overrun').last().getAttribute('title')).toBe('overrun: altHold cycle still running, release skipped (click: the cursor goes there)');
    await page.locator('.monitor-flows').scrollIntoViewIfNeeded();
    await shot(page, 'monitor-faults-01-recorded');
    // from the start, ] steps mark by mark to the event no one received, then on to the crash: each said under the strip
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('Home');
    await expect.poll(() => crashed(page)).toBeNull();
    const said: string[] = [];
    for (let i = 0; i < 300 && !said.some((x) => x.includes('crashed')); i++) {
      await page.keyboard.press(']');
      said.push((await page.locator('.monitor-mark-said').textContent()) ?? '');
    }
    expect(said).toContainEqual(expect.stringContaining('+0.336166 s GCS: event GCS:1 posted with no subscriber: no one received it'));
    expect(said.at(-1)).toContain('+0.432425 s EST: crashed: signal 11 (SIGSEGV)');
    await expect.poll(() => crashed(page)).toBe('⚠ EST crashed at +0.432425 s: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array');
  }, 90_000);

  it('a live run: EST is said crashed as its record comes, before the job ends; the ended job\'s long message is shortened at a word in the run list', async () => {
    const { page } = s;
    const server = new WebSocketServer({ port: 0, host: '127.0.0.1' });
    await new Promise((r) => server.once('listening', r));
    let socket: import('ws').WebSocket | undefined;
    const crash = LINES.findIndex((l) => l.text.includes(',EST,module_crashed,'));
    server.on('connection', (ws) => {
      socket = ws;
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(LINES.slice(0, crash)) }));
    });
    const url = `ws://127.0.0.1:${(server.address() as { port: number }).port}/api/jobs/faults/ws?trace=only`;
    try {
      await page.evaluate((url) => window.__ide.monitor.followLive('faults', url), url);
      await expect.poll(() => page.evaluate(() => window.__ide.monitor.current?.recordCount)).toBe(crash);
      await expect.poll(() => label(page)).toBe('Build & Run job faults · live');
      expect(await crashed(page)).toBeNull();
      await expect.poll(() => unheardRows(page)).toEqual(['┅ GCS:1 → no subscriber ×1 · no one received it · last +0.336166 s']);
      // the crash record comes: said at once (an alert), the job still going
      const sent = Date.now();
      socket!.send(JSON.stringify({ type: 'trace', seq: 2, t: Date.now(), ...encodeTraceRecords(LINES.slice(crash, crash + 1)) }));
      await expect.poll(() => crashed(page), { interval: 10 }).toBe('⚠ EST crashed at +0.432425 s: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array');
      console.log(`crash record sent → said by the Monitor: ${Date.now() - sent} ms`);
      await expect.poll(() => modules(page)).toMatch(/^Running now: .*· crashed: EST/);
      expect(await label(page)).toBe('Build & Run job faults · live');
      await shot(page, 'monitor-faults-02-live-crash');
      socket!.send(JSON.stringify({ type: 'trace', seq: 3, t: Date.now(), ...encodeTraceRecords(LINES.slice(crash + 1)) }));
      socket!.send(JSON.stringify({ type: 'end', seq: 4, t: Date.now(), result: { ok: false, message: FAILED } }));
      const whole = `Build & Run job faults · ended: failed: ${FAILED}`;
      await expect.poll(() => label(page)).toBe(whole);
      // the run list: ended at a word with an ellipsis, the whole label its tooltip and accessible name
      const option = page.locator('.monitor-sources option[value="live:faults"]');
      const text = (await option.textContent())!;
      expect(text.length).toBeLessThanOrEqual(240);
      expect(text).toMatch(/ [^ ]+…$/);
      expect(whole.startsWith(text.slice(0, -1))).toBe(true);
      expect(whole[text.length - 1]).toBe(' '); // the word before the ellipsis is whole
      expect(await option.getAttribute('title')).toBe(whole);
      expect(await option.getAttribute('aria-label')).toBe(whole);
    } finally {
      for (const c of server.clients) c.terminate();
      await new Promise((r) => server.close(r));
    }
  }, 60_000);
});
