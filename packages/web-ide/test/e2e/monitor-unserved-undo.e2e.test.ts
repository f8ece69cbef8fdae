/**
 * End-to-end, in headless Chromium on the real IDE server: a supervisor's undo that ORD never
 * served, shown by the Monitor in the words `contract trace` tells it. The real tutorial run of
 * src/monitor/fixtures/killed-ord-run (its README: ORD stopped during schemaCommande1's activation
 * and terminated at the run's end with no exit record, SUP's undo sent to its mailbox):
 * - replayed from its logs (a folder of the workspace), the mark on schemaCommande1's row at the
 *   run's end is said under the strip when ▶ / `]` reaches it;
 * - followed live, no undo is marked unserved while the job goes on (every record in, the undo
 *   may be in flight), and it is marked when the job's end comes.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, mkdirSync, readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { WebSocketServer } from 'ws';
import { encodeTraceRecords, parseTrace, renderStory } from '@contract-studio/build-service/trace';
import { startSession, openIde, shot, type Session, showMonitor } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/killed-ord-run', import.meta.url));
const FILES = readdirSync(FIXTURE).filter((n) => n.endsWith('.csv')).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') }));
const LINES = FILES.flatMap((f) => f.text.split('\n').map((text, i) => ({ file: f.name, line: i + 1, text })))
  .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));
/** `contract trace`'s words for it, after its time and module. */
const TOLD = renderStory(parseTrace(FILES)).find((l) => l.includes('no answer to SUP\'s undo'))!.replace(/^\S+ ORD {2}/, '');

type Page = Session['page'];
const label = (page: Page) => page.locator('.monitor-source').textContent();
const markSaid = (page: Page) => page.evaluate(() => document.querySelector('.monitor-mark-said[role=status][aria-live=polite]')?.textContent ?? null);
const unservedMarks = (page: Page) => page.evaluate(() => (window.__ide.monitor.current?.marks ?? [])
  .filter((m) => m.label.includes('no answer to SUP\'s undo')).map((m) => `${m.where}: ${m.label}`));

describe('Monitor: an undo ORD never served', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession();
    mkdirSync(join(s.workspace, 'killedord'));
    cpSync(FIXTURE, join(s.workspace, 'killedord'), { recursive: true, filter: (src) => !src.endsWith('README.md') });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('a recorded run: the mark on the schema\'s row at the run\'s end says it in contract trace\'s words', async () => {
    const { page } = s;
    expect(TOLD).toMatch(/^while the run stopped: ORD's log ends with no exit record .* schemaCommande1 may have stayed active to its end$/);
    await showMonitor(page);
    await page.locator('.monitor-sources').selectOption('dir:killedord');
    await expect.poll(() => label(page)).toBe('9 CSV log(s) in killedord');
    expect(await unservedMarks(page)).toEqual([`schemaCommande1: ${TOLD}`]);
    // End, then back a mark and on to the next: the last mark, the undo's, said under the strip
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('End');
    await page.keyboard.press('[');
    await page.keyboard.press(']');
    await expect.poll(() => markSaid(page)).toContain(`schemaCommande1: ${TOLD}`);
    await shot(page, 'monitor-unserved-undo-01-recorded');
  }, 60_000);

  it('a live run: nothing said unserved while the job goes on; marked when the job ends', async () => {
    const { page } = s;
    const server = new WebSocketServer({ port: 0, host: '127.0.0.1' });
    await new Promise((r) => server.once('listening', r));
    let socket: import('ws').WebSocket | undefined;
    server.on('connection', (ws) => {
      socket = ws;
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(LINES) }));
    });
    const url = `ws://127.0.0.1:${(server.address() as { port: number }).port}/api/jobs/undo/ws?trace=only`;
    try {
      await page.evaluate((url) => window.__ide.monitor.followLive('undo', url), url);
      await expect.poll(() => page.evaluate(() => window.__ide.monitor.current?.recordCount)).toBe(LINES.length);
      await expect.poll(() => label(page)).toBe('Build & Run job undo · live');
      // every record in, SUP's exit after its undo among them, the job still going: no undo said unserved
      await page.waitForTimeout(300);
      expect(await unservedMarks(page)).toEqual([]);
      socket!.send(JSON.stringify({ type: 'end', seq: 2, t: Date.now(), result: { ok: false, message: 'run failed' } }));
      await expect.poll(() => label(page)).toMatch(/^Build & Run job undo · ended: /);
      await expect.poll(() => unservedMarks(page)).toEqual([`schemaCommande1: ${TOLD}`]);
      await page.locator('.monitor-view').focus();
      await page.keyboard.press('End');
      await page.keyboard.press('[');
      await page.keyboard.press(']');
      await expect.poll(() => markSaid(page)).toContain(`schemaCommande1: ${TOLD}`);
      await shot(page, 'monitor-unserved-undo-02-live-ended');
    } finally {
      for (const c of server.clients) c.terminate();
      await new Promise((r) => server.close(r));
    }
  }, 60_000);
});
