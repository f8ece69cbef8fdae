/**
 * End-to-end, in headless Chromium on the real IDE server: the Timeline draws the events an
 * asynchronous module handles, from the real records of src/monitor/fixtures/async-handler-run (the
 * tutorial, its MAB's handler spending 2.4 ms on each of MAA's notifications: its README). MAB's
 * START run ends at once; each event it handles is a bar of its lane at the event's time, checked on
 * the pixels of a screenshot of the lane.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, mkdirSync, readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { startSession, openIde, shot, type Session } from './harness.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/async-handler-run', import.meta.url));
const MAB = readFileSync(join(FIXTURE, readdirSync(FIXTURE).find((n) => n.startsWith('MAB'))!), 'utf8').split('\n');
const timesOf = (event: string) => MAB.filter((l) => l.split(',')[3] === event).map((l) => Number(l.split(',')[0]));

describe("Timeline: an asynchronous module's work", () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession({ port: 8021, buildService: false });
    mkdirSync(join(s.workspace, 'logs'));
    cpSync(FIXTURE, join(s.workspace, 'logs'), { recursive: true, filter: (src) => !src.endsWith('README.md') });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it("MAB's lane has a bar at each event it handled, where the event's time puts it", async () => {
    const { page } = s;
    const started = timesOf('run_started');
    const received = timesOf('event_received');
    expect(started).toHaveLength(1);
    expect(received.length).toBeGreaterThanOrEqual(3);
    await page.locator('#btn-timeline').click();
    await page.locator('.timeline-svg').waitFor({ timeout: 10_000 });
    await expect.poll(() => page.locator('.timeline-view .muted').first().textContent()).toMatch(new RegExp(`· ${received.length} events handled`));
    const labels = await page.locator('.lane-label').allTextContents();
    const lane = labels.indexOf('MAB');
    expect(lane).toBeGreaterThanOrEqual(0);
    await shot(page, 'timeline-async-module');
    // the pixels of MAB's lane, in a screenshot of the timeline: the runs of bar colour along its middle
    const png = (await page.locator('.timeline-svg').screenshot()).toString('base64');
    const runs = await page.evaluate(async ({ png, y }) => {
      const img = new Image();
      img.src = `data:image/png;base64,${png}`;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width;
      c.height = img.height;
      const g = c.getContext('2d')!;
      g.drawImage(img, 0, 0);
      const scale = img.width / Number(document.querySelector('.timeline-svg')!.getAttribute('width'));
      const row = g.getImageData(0, Math.round(y * scale), img.width, 1).data;
      const colour = (x: number) => `#${[row[x * 4]!, row[x * 4 + 1]!, row[x * 4 + 2]!].map((v) => v.toString(16).padStart(2, '0')).join('')}`;
      const bar = (sel: string) => { const r = document.createElementNS('http://www.w3.org/2000/svg', 'rect'); r.setAttribute('class', sel); document.querySelector('.timeline-svg')!.append(r); const f = getComputedStyle(r).fill; r.remove(); return f; };
      const hex = (rgb: string) => `#${(rgb.match(/\d+/g) ?? []).slice(0, 3).map((v) => Number(v).toString(16).padStart(2, '0')).join('')}`;
      const kinds: Record<string, string> = { [hex(bar('act-bar'))]: 'run', [hex(bar('act-bar event'))]: 'event' };
      const found: { kind: string; x: number }[] = [];
      let prev = '';
      for (let x = 0; x < img.width; x++) {
        const k = kinds[colour(x)] ?? '';
        if (k && k !== prev) found.push({ kind: k, x: x / scale });
        prev = k;
      }
      return { found, kinds: Object.values(kinds) };
    }, { png, y: lane * 26 + 13 });
    expect(runs.kinds).toEqual(['run', 'event']); // two colours
    // the START run (a sliver at MAB's start), then a bar per event
    expect(runs.found.map((r) => r.kind)).toEqual(['run', ...received.map(() => 'event')]);
    // each where its time puts it: the pixels apart as the times are (2 px of rounding)
    const times = [started[0]!, ...received];
    const xs = runs.found.map((r) => r.x);
    const pxPerNs = (xs.at(-1)! - xs[0]!) / (times.at(-1)! - times[0]!);
    expect(pxPerNs).toBeGreaterThan(0);
    times.forEach((t, i) => expect(Math.abs(xs[i]! - (xs[0]! + (t - times[0]!) * pxPerNs)), `bar ${i}`).toBeLessThan(2));
    // the tooltip of the first event's bar says the handler's time, as event_handled gives it
    const handled = timesOf('event_handled');
    const title = await page.locator('.act-bar.event title').first().textContent();
    expect(title).toMatch(new RegExp(`^MAB handled an event from MAA:0 at [0-9.]+ ms: handled in ${((handled[0]! - received[0]!) / 1e6).toFixed(3)} ms`));
  }, 60_000);
});
