/**
 * End-to-end, in headless Chromium on the real IDE server: an event flood as the Monitor shows it,
 * in the real run of src/monitor/fixtures/event-flood-run (its README: PSH posts an event every
 * 1 ms, BIN takes 20 ms an event: PSH's posts wait for room in BIN's full mailbox, 24 waits in six
 * `event_waited` records, one per streak). PSH:0 -> BIN:0's Deliveries row has the totals over
 * every streak so far (waits, their time in all, the longest), its title `contract trace`'s closing
 * line for the flow; replayed from the logs (a folder of the workspace) and followed live (a job's
 * trace stream), where the row's totals grow streak by streak.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, mkdirSync, readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { WebSocketServer } from 'ws';
import { encodeTraceRecords, parseTrace, renderStory } from '@contract-studio/build-service/trace';
import { startSession, openIde, shot, type Session, showMonitor } from './harness.js';
import type {} from '../../src/app/ide-hook.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/event-flood-run', import.meta.url));
const FILES = readdirSync(FIXTURE).filter((n) => n.endsWith('.csv')).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') }));
const LINES = FILES.flatMap((f) => f.text.split('\n').map((text, i) => ({ file: f.name, line: i + 1, text })))
  .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));
/** `contract trace`'s closing line for the flow (its waits over all six streaks). */
const CLOSING = renderStory(parseTrace(FILES)).find((l) => l.startsWith("PSH's events to BIN"))!;
/** Ports of this test's servers. */
const IDE_PORT = 7820;
const TRACE_PORT = 7821;

type Page = Session['page'];
const row = (page: Page) => page.locator('.monitor-flows .monitor-flow.event[data-flow="PSH:0->BIN:0"]');
const rowText = (page: Page) => row(page).textContent({ timeout: 2000 }).catch(() => null);

describe('Monitor: an event flood\'s waits for room, every streak counted', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession({ port: IDE_PORT });
    mkdirSync(join(s.workspace, 'flood'));
    cpSync(FIXTURE, join(s.workspace, 'flood'), { recursive: true, filter: (src) => !src.endsWith('README.md') });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('a recorded run: the row has the waits of all six streaks, its title trace\'s closing line', async () => {
    const { page } = s;
    expect(CLOSING).toBe("PSH's events to BIN (PSH:0 -> BIN:0) waited for room 24 times (5.767 s in all, up to 298.552 ms): BIN takes its events slower than PSH posts them; delivery latency up to 540.627 ms");
    await showMonitor(page);
    await page.locator('.monitor-sources').selectOption('dir:flood');
    await expect.poll(() => rowText(page)).toMatch(/ · ⚠ waited for room 24 times \(5\.767 s in all, up to 298\.552 ms\)$/);
    expect(await row(page).getAttribute('title')).toBe(CLOSING);
    expect(await row(page).getAttribute('data-waited')).toBe('24');
    // in the warning colour, unlike an event flow that did not wait (CAM:0 -> SUP:2)
    const color = (flow: string) => page.locator(`.monitor-flows .monitor-flow.event[data-flow="${flow}"]`).evaluate((el) => getComputedStyle(el).color);
    const warn = await page.evaluate(() => { const probe = document.createElement('span'); probe.style.color = 'var(--warn)'; document.body.append(probe); const c = getComputedStyle(probe).color; probe.remove(); return c; });
    expect(await color('PSH:0->BIN:0')).toBe(warn);
    expect(await color('CAM:0->SUP:2')).not.toBe(warn);
    await row(page).scrollIntoViewIfNeeded();
    await shot(page, 'monitor-event-flood-01-recorded');
  }, 90_000);

  it('a live run: the row\'s totals grow with each streak\'s record', async () => {
    const { page } = s;
    const server = new WebSocketServer({ port: TRACE_PORT, host: '127.0.0.1' });
    await new Promise((r) => server.once('listening', r));
    let socket: import('ws').WebSocket | undefined;
    const streaks = LINES.flatMap((l, i) => (l.text.includes(',event_waited,') ? [i] : []));
    expect(streaks).toHaveLength(6);
    server.on('connection', (ws) => {
      socket = ws;
      // up to the first streak's record
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(LINES.slice(0, streaks[0]! + 1)) }));
    });
    try {
      await page.evaluate((url) => window.__ide.monitor.followLive('flood', url), `ws://127.0.0.1:${TRACE_PORT}/api/jobs/flood/ws?trace=only`);
      await expect.poll(() => rowText(page)).toMatch(/ · ⚠ waited for room 5 times \(1\.127 s in all, up to 244\.19 ms\)$/);
      expect(await row(page).getAttribute('title')).toMatch(/^PSH's events to BIN \(PSH:0 -> BIN:0\) waited for room 5 times \(1\.127 s in all, up to 244\.19 ms\): BIN takes its events slower than PSH posts them/);
      // the second streak: both counted (the old row kept telling the first alone)
      socket!.send(JSON.stringify({ type: 'trace', seq: 2, t: Date.now(), ...encodeTraceRecords(LINES.slice(streaks[0]! + 1, streaks[1]! + 1)) }));
      await expect.poll(() => rowText(page)).toMatch(/ · ⚠ waited for room 10 times \(2\.309 s in all, up to 263\.038 ms\)$/);
      await shot(page, 'monitor-event-flood-02-live-second-streak');
      socket!.send(JSON.stringify({ type: 'trace', seq: 3, t: Date.now(), ...encodeTraceRecords(LINES.slice(streaks[1]! + 1)) }));
      socket!.send(JSON.stringify({ type: 'end', seq: 4, t: Date.now(), result: { ok: true, message: 'run finished' } }));
      await expect.poll(() => rowText(page)).toMatch(/ · ⚠ waited for room 24 times \(5\.767 s in all, up to 298\.552 ms\)$/);
      await expect.poll(() => row(page).getAttribute('title')).toBe(CLOSING);
    } finally {
      for (const c of server.clients) c.terminate();
      await new Promise((r) => server.close(r));
    }
  }, 60_000);
});
