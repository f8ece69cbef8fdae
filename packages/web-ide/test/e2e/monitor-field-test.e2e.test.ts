/**
 * End-to-end: what a field test of the Monitor (docs/watching-a-run.md) found, in headless Chromium
 * on the real IDE server:
 * - a live run followed by a page that attached late (a reload during a long run): the records the
 *   build service did not keep are said missing while it runs, and the end-of-run label is true;
 * - Space on a focused control of the panel presses that control (▷ Play, ▶, a rule, the run list),
 *   and toggles Pause/Follow only elsewhere in the panel; the run list keeps the focus while the
 *   runs its arrows pick are read and shown;
 * - axe-core while a rule is lit on a live run; the panel's and a rule's focus rings;
 * - at 900x700: every control of the top bar on screen, the Monitor's time, histogram and causes whole;
 * - a live run's quiet stretch: the time runs with the run's clock, the state stays at its last
 *   record, nothing else is drawn again; a deadline miss names the module its cycle waited for;
 *   PERIOD = CRITICAL_DELAY is one label;
 * - a module killed mid-release (its log ends inside a release, no exit record): at the end of the
 *   replay it is said to have no exit record, not listed as running; before its end, as it was;
 * - Follow again after scrubbing a live run back (Space, Home, ], [, Space): the first frame shows
 *   the live state, not the one scrubbed to.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, mkdirSync, readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { WebSocketServer } from 'ws';
import { encodeTraceRecords } from '@contract-studio/build-service/trace';
import { startSession, openIde, shot, activeTab, openFile, type Session, showMonitor } from './harness.js';
import { axeScan, seriousOf } from './axe.js';
import type {} from '../../src/app/ide-hook.js';

const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/tutorial-run', import.meta.url));
/** The recorded tutorial run's record lines, in mono_ns order, numbered as in their logs. */
const LINES = readdirSync(FIXTURE).flatMap((file) => readFileSync(join(FIXTURE, file), 'utf8').split('\n').map((text, i) => ({ file, line: i + 1, text })))
  .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));

type Page = Session['page'];
const rule = (page: Page, id: string) => page.locator(`.monitor-rule[data-rule="${id}"]`);
const label = (page: Page) => page.locator('.monitor-source').textContent();

async function showRecorded(page: Page): Promise<void> {
  await showMonitor(page);
  await page.locator('.monitor-sources').selectOption('dir:recorded');
  await expect.poll(() => label(page)).toBe('9 CSV log(s) in recorded');
}

describe('Monitor field test', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession();
    mkdirSync(join(s.workspace, 'recorded'));
    cpSync(FIXTURE, join(s.workspace, 'recorded'), { recursive: true });
    // MSC killed inside its second release: its log ends with that release's run_started
    mkdirSync(join(s.workspace, 'killed'));
    cpSync(FIXTURE, join(s.workspace, 'killed'), { recursive: true });
    const msc = readFileSync(join(FIXTURE, 'MSC.csv'), 'utf8').split('\n');
    const cutAt = msc.findIndex((l, i) => i > msc.findIndex((k) => /,run_started,/.test(k)) && /,run_started,/.test(l));
    writeFileSync(join(s.workspace, 'killed', 'MSC.csv'), msc.slice(0, cutAt + 1).join('\n') + '\n');
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('a live run attached late (past the records the service keeps) says what it did not receive while it runs, and the end-of-run label is true', async () => {
    const { page } = s;
    // the service past its traceLinesKept bound (job-events.ts): the kept events replay from seq 0;
    // what was read while this page was away went to no one and is not kept; what is read after it
    // attached comes live, with the seq of the last kept event
    const kept = 80, gone = 100;
    const batches = (from: number, to: number) => {
      const out: (typeof LINES)[] = [];
      for (let i = from; i < to; i += 40) out.push(LINES.slice(i, Math.min(to, i + 40)));
      return out;
    };
    const keptEvents = batches(0, kept).map((records, i) => JSON.stringify({ type: 'trace', seq: i + 1, t: Date.now(), ...encodeTraceRecords(records) }));
    const server = new WebSocketServer({ port: 0, host: '127.0.0.1' });
    await new Promise((r) => server.once('listening', r));
    let socket: import('ws').WebSocket | undefined;
    server.on('connection', (ws) => {
      socket = ws;
      for (const e of keptEvents) ws.send(e);
    });
    const url = `ws://127.0.0.1:${(server.address() as { port: number }).port}/api/jobs/late/ws?trace=only`;
    try {
      await page.evaluate((url) => window.__ide.monitor.followLive('late', url), url);
      await expect.poll(() => page.evaluate(() => window.__ide.monitor.current?.recordCount)).toBe(kept);
      expect(await label(page)).toBe('Build & Run job late · live'); // nothing tells of a gap yet
      for (const records of batches(kept + gone, LINES.length)) socket!.send(JSON.stringify({ type: 'trace', seq: keptEvents.length, t: Date.now(), ...encodeTraceRecords(records) }));
      // each log's lines that never came before one that did
      const received = [...LINES.slice(0, kept), ...LINES.slice(kept + gone)];
      const last = new Map<string, number>();
      const count = new Map<string, number>();
      for (const l of received) (last.set(l.file, l.line), count.set(l.file, (count.get(l.file) ?? 0) + 1));
      const missed = [...last].reduce((n, [f, line]) => n + line - 1 - count.get(f)!, 0);
      expect(missed).toBeGreaterThan(50);
      const notWhole = ` (trace not whole: ${missed} records not received (the build service keeps the first 50,000 for a page that attaches later); the whole run is shown from its logs when it ends)`;
      await expect.poll(() => label(page)).toBe(`Build & Run job late · live${notWhole}`);
      expect(await page.locator('.monitor-sources option:checked').textContent()).toBe(`Build & Run job late · live${notWhole}`);
      await shot(page, 'monitor-field-01-live-not-whole');
      socket!.send(JSON.stringify({ type: 'end', seq: keptEvents.length + 1, t: Date.now(), result: { ok: true } }));
      await expect.poll(() => label(page)).toBe(`Build & Run job late · ended: succeeded${notWhole}`);
      // the job's logs come (as run-controller.ts hands them over): the whole run is shown from them,
      // and the run as streamed says how much of it came (it was never "the first N records")
      const files = readdirSync(FIXTURE).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') }));
      await page.evaluate((files) => window.__ide.monitor.showRecorded('late', { label: 'Build & Run job late', files, problems: [] }), files);
      await expect.poll(() => label(page)).toBe('Build & Run job late · CSV logs');
      expect(await page.evaluate(() => window.__ide.monitor.current!.recordCount)).toBe(LINES.length);
      expect(await page.locator('.monitor-sources option[value="live:late"]').textContent())
        .toBe(`Build & Run job late · as streamed (${received.length} of the ${LINES.length} records of its logs: ${LINES.length - received.length} not received) · ended: succeeded`);
    } finally {
      for (const c of server.clients) c.terminate();
      await new Promise((r) => server.close(r));
    }
  }, 60_000);

  it('Space on a focused control presses it (▷ Play, ▶, a rule, the run list); elsewhere in the panel it pauses and follows', async () => {
    const { page } = s;
    await showRecorded(page);
    const follow = () => page.locator('#monitor-follow').getAttribute('data-following');
    const t = async () => Number(await page.locator('.monitor-view').getAttribute('data-t'));
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('Home');
    await expect.poll(t).toBe(0);
    expect(await follow()).toBe('false');
    // ▶ Next: the next mark, as a click
    const first = await page.evaluate(() => (window.__ide.monitor.current!.marks).find((m) => m.t > 0)!.t);
    await page.locator('#monitor-next').focus();
    await page.keyboard.press('Space');
    await expect.poll(t).toBe(first);
    expect(await follow()).toBe('false');
    // ▷ Play: plays, and Space again stops it
    await page.locator('#monitor-play').focus();
    await page.keyboard.press('Space');
    await expect.poll(() => page.locator('#monitor-play').getAttribute('aria-label')).toBe('Stop playing the run');
    expect(await page.locator('#monitor-play').getAttribute('aria-pressed')).toBeNull(); // its name says its state
    expect(await follow()).toBe('false');
    await page.keyboard.press('Space');
    await expect.poll(() => page.locator('#monitor-play').getAttribute('aria-label')).toBe('Play the run from the cursor');
    expect(await follow()).toBe('false');
    // the run list: its own key (it opens), the cursor left as it was
    await page.locator('.monitor-sources').focus();
    await page.keyboard.press('Space');
    await page.keyboard.press('Escape');
    expect(await follow()).toBe('false');
    expect(await label(page)).toBe('9 CSV log(s) in recorded');
    // ⇥ End itself, and the slider and the panel: Space is the panel's pause/follow
    await page.locator('#monitor-follow').focus();
    await page.keyboard.press('Space');
    await expect.poll(follow).toBe('true');
    await page.locator('.monitor-slider').focus();
    await page.keyboard.press('Space');
    await expect.poll(follow).toBe('false');
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('Space');
    await expect.poll(follow).toBe('true');
    // a rule: opens its definition
    await openFile(page, 'datatype.contract');
    await rule(page, 'SUP.action.SECOND').focus();
    await page.keyboard.press('Space');
    await expect.poll(() => activeTab(page)).toBe('supervisor.contract');
    expect(await follow()).toBe('true');
  }, 60_000);

  it('the run list keeps the keyboard focus while the runs its arrows pick are read and shown', async () => {
    const { page } = s;
    await showRecorded(page);
    const list = page.locator('.monitor-sources');
    await list.focus();
    const focused = () => page.evaluate(() => document.activeElement?.className ?? '');
    const shown = () => page.locator('.monitor-sources option:checked').getAttribute('value');
    const options = await page.locator('.monitor-sources option:not([disabled])').evaluateAll((os) => os.map((o) => (o as HTMLOptionElement).value));
    const at = options.indexOf('dir:recorded');
    // two runs down, then back: each is read (a folder) and shown, the focus staying on the list
    for (const [key, want] of [['ArrowDown', options[at + 1]], ['ArrowUp', 'dir:recorded']] as const) {
      await page.keyboard.press(key);
      await expect.poll(shown).toBe(want);
      await expect.poll(() => label(page)).not.toMatch(/^Reading /);
      await page.waitForTimeout(300);
      expect(await focused()).toBe('monitor-sources');
    }
  }, 60_000);

  it('axe-core finds no serious violation while a rule is lit on a live run; the panel and a focused rule show a ring', async () => {
    const { page } = s;
    await page.evaluate(() => window.__ide.monitor.followLive('axe', null));
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-mode')).toBe('live');
    const upTo = LINES.findIndex((l) => l.text.includes('action.SECOND active'));
    await page.evaluate((records) => window.__ide.monitor.feed('axe', records), LINES.slice(0, upTo + 40));
    await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-active')).toBe('true');
    await expect.poll(() => page.locator('.monitor-rule[data-active=true] .rule-time').first().textContent()).toMatch(/^\+\d/);
    const scan = await axeScan(page, 'Monitor, live, a rule lit');
    expect(seriousOf(scan)).toEqual([]);
    // a lit rule is a plain button (it opens the rule) whose name says its state; the follow button
    // names what it does: neither is a "pressed" toggle
    const second = rule(page, 'SUP.action.SECOND');
    expect(await second.getAttribute('aria-pressed')).toBeNull();
    expect(await second.getAttribute('aria-label')).toMatch(/^SECOND, active since \+\d+\.\d{6} s ← MAA:2 = "disconnected" → schemaCommande1$/);
    expect(await rule(page, 'SUP.action.FIRST').getAttribute('aria-label')).toMatch(/^FIRST, inactive since \+\d+\.\d{6} s ← /);
    expect(await page.getByRole('button', { name: /^SECOND, active since/ }).count()).toBe(1);
    const followBtn = page.locator('#monitor-follow');
    expect(await followBtn.getAttribute('aria-pressed')).toBeNull();
    expect(await page.getByRole('button', { name: 'Pause', exact: true }).count()).toBe(1);
    await followBtn.click();
    expect(await followBtn.textContent()).toBe('⇥ Follow');
    expect(await page.getByRole('button', { name: 'Follow live', exact: true }).count()).toBe(1);
    expect(await followBtn.getAttribute('aria-pressed')).toBeNull();
    await followBtn.click();
    expect(await followBtn.getAttribute('aria-label')).toBe('Pause');
    // the lit rule's time: 4.5:1 at least on its row
    const ratio = await rule(page, 'SUP.action.SECOND').evaluate((b) => {
      const rgb = (c: string) => c.match(/\d+/g)!.slice(0, 3).map(Number);
      const lum = (c: number[]) => c.map((v) => v / 255).map((v) => (v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4)).reduce((s, v, i) => s + v * [0.2126, 0.7152, 0.0722][i]!, 0);
      const [a, z] = [lum(rgb(getComputedStyle(b.querySelector('.rule-time')!).color)), lum(rgb(getComputedStyle(b).backgroundColor))];
      return (Math.max(a, z) + 0.05) / (Math.min(a, z) + 0.05);
    });
    expect(ratio).toBeGreaterThanOrEqual(4.5);
    // Alt+Shift+M puts the focus in the panel: a ring shows it; Tab to a rule: a ring on the rule
    const ring = (sel: string) => page.locator(sel).evaluate((el) => {
      const cs = getComputedStyle(el);
      return { focused: el.matches(':focus-visible'), style: cs.outlineStyle, width: cs.outlineWidth, color: cs.outlineColor };
    });
    await openFile(page, 'supervisor.contract');
    await page.keyboard.press('Alt+Shift+M');
    await expect.poll(() => ring('.monitor-view')).toEqual({ focused: true, style: 'solid', width: '2px', color: 'rgb(79, 140, 255)' });
    await shot(page, 'monitor-field-02-panel-focused');
    // Tab from the control before the first rule (the run list is the first control of the panel)
    await page.locator('#monitor-next').focus();
    for (let i = 0; i < 30 && !(await page.evaluate(() => document.activeElement?.classList.contains('monitor-rule'))); i++) await page.keyboard.press('Tab');
    const focusedRule = page.locator('.monitor-rule:focus');
    expect(await focusedRule.count()).toBe(1);
    expect(await ring('.monitor-rule:focus')).toEqual({ focused: true, style: 'solid', width: '2px', color: 'rgb(79, 140, 255)' });
    await rule(page, 'SUP.action.SECOND').focus();
    await shot(page, 'monitor-field-03-rule-focused-live');
  }, 60_000);

  it('at 900x700 every control of the top bar is on screen and under the mouse; the Monitor\'s time, histogram and causes are whole', async () => {
    const { page } = s;
    await showRecorded(page);
    for (const [width, height] of [[900, 700], [800, 700]] as const) {
      await page.setViewportSize({ width, height });
      await page.waitForTimeout(200);
      const off = await page.locator('.topbar button, .topbar .workspace-name, .topbar .brand').evaluateAll((els, [w, h]) => els.flatMap((el) => {
        const r = el.getBoundingClientRect();
        const name = el.id || el.className;
        if (r.left < 0 || r.top < 0 || r.right > w || r.bottom > h) return [`${name} at ${r.left}..${r.right} x ${r.top}..${r.bottom}`];
        const hit = document.elementFromPoint(r.left + r.width / 2, r.top + r.height / 2);
        return hit && el.contains(hit) ? [] : [`${name} under ${hit?.className}`];
      }), [width, height]);
      expect(off, `${width}x${height}`).toEqual([]);
      await page.locator('#btn-monitor').click({ trial: true }); // reachable by the mouse
    }
    await page.setViewportSize({ width: 900, height: 700 });
    // the cursor where SECOND is lit with a long cause, schemaCommande1 released
    const second = await page.evaluate(() => (window.__ide.monitor.current!.marks).find((m) => m.label.startsWith('action.SECOND active'))!.t);
    await page.evaluate((t) => window.__ide.monitor.panel!.seek(t), second + 1.5e9);
    await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-active')).toBe('true');
    await page.locator('.monitor-pschema[data-periodic="schemaCommande1"] .monitor-hist').waitFor();
    const fits = await page.evaluate(() => {
      const out: string[] = [];
      const body = document.querySelector('.monitor-body') as HTMLElement;
      if (body.scrollWidth > body.clientWidth + 1) out.push(`the panel scrolls sideways: ${body.scrollWidth} > ${body.clientWidth}`);
      const time = document.querySelector('.monitor-time') as HTMLElement;
      const view = (document.querySelector('.monitor-view') as HTMLElement).getBoundingClientRect();
      const tr = time.getBoundingClientRect();
      if (time.scrollWidth > time.clientWidth + 1 || tr.right > view.right + 1) out.push(`the time is cut: ${time.textContent}`);
      for (const c of document.querySelectorAll('.monitor-hist')) {
        const r = c.getBoundingClientRect();
        const box = c.parentElement!.getBoundingClientRect();
        if (r.right > box.right + 1) out.push(`a histogram past its block: ${r.right} > ${box.right}`);
      }
      return out;
    });
    expect(fits).toEqual([]);
    // the rule's whole cause, even where its row cuts it
    expect(await rule(page, 'SUP.action.SECOND').getAttribute('title')).toMatch(/^action\.SECOND active since \+\d+\.\d{6} s ← MAA:2 = "disconnected" → schemaCommande1 · click to open it in its \.contract file$/);
    await rule(page, 'SUP.action.SECOND').scrollIntoViewIfNeeded();
    await shot(page, 'monitor-field-04-900x700-rules');
    await page.locator('.monitor-pschema[data-periodic="schemaCommande1"]').scrollIntoViewIfNeeded();
    await shot(page, 'monitor-field-05-900x700-histogram');
    await page.setViewportSize({ width: 1440, height: 900 });
  }, 60_000);
  it('a live run\'s quiet stretch: the time runs with the run\'s clock, the state stays at the last record, nothing else redrawn; a deadline miss names what its cycle waited for', async () => {
    const { page } = s;
    await page.setViewportSize({ width: 1440, height: 900 });
    await page.evaluate(() => window.__ide.monitor.followLive('quiet', null));
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-mode')).toBe('live');
    // the tutorial's run up to MSC's release in schemaCommande1's cycle 1 (PERIOD = CRITICAL_DELAY = 1s),
    // then ORD's deadline miss of that cycle (MSC not finished), then nothing: a quiet stretch
    const upTo = LINES.findIndex((l) => l.text.includes(',ord_release,MSC,') && l.text.includes('cycle=1 '));
    expect(upTo).toBeGreaterThan(0);
    const msc = LINES[upTo]!;
    const mono = Number(msc.text.split(',')[0]);
    const tick = /tick_ns=(\d+)/.exec(msc.text)![1];
    const miss = { file: msc.file, line: msc.line + 1, text: `${mono + 1000},2026-12-04T05:49:27.540500Z,ORD,ord_deadline_miss,,,0,schema=schemaCommande1 cycle=1 tick_ns=${tick}` };
    const records = [...LINES.slice(0, upTo + 1), miss];
    await page.evaluate((records) => window.__ide.monitor.feed('quiet', records), records);
    await expect.poll(() => page.evaluate(() => window.__ide.monitor.current?.recordCount)).toBe(records.length);
    const label = 'deadline miss (ORD:0) cycle 1 (not finished: MSC)';
    const marks = await page.evaluate(() => window.__ide.monitor.current!.marks);
    const mark = marks.find((m) => m.kind === 'miss')!;
    expect(mark.label).toBe(label);
    // the periodic block lists it; its tooltip says what the cycle waited for
    const missEl = page.locator('.monitor-pschema[data-periodic="schemaCommande1"] .miss');
    await expect.poll(() => missEl.getAttribute('title')).toBe(`${label} (click: the cursor goes there)`);
    // the quiet stretch: what is drawn after the last throttled parts caught up
    await page.waitForTimeout(600);
    const end = await page.evaluate(() => window.__ide.monitor.current!.end as number);
    const seen = await page.evaluate(async () => {
      const counts = { time: 0, rest: 0, frames: window.__ide.monitor.panel!.frameMs.length };
      const texts: string[] = [];
      const time = document.querySelector('.monitor-time')!;
      new MutationObserver(() => (counts.time++, texts.push(time.textContent ?? ''))).observe(time, { subtree: true, childList: true, characterData: true });
      for (const sel of ['.monitor-sups', '.monitor-periodic', '.monitor-flows', '.monitor-modules', '.monitor-schemas']) {
        new MutationObserver(() => counts.rest++).observe(document.querySelector(sel)!, { subtree: true, childList: true, characterData: true, attributes: true });
      }
      await new Promise((r) => setTimeout(r, 1600));
      counts.frames = window.__ide.monitor.panel!.frameMs.length - counts.frames;
      return { ...counts, texts, t: document.querySelector('.monitor-view')!.getAttribute('data-t') };
    });
    console.log(`[monitor field test] quiet 1.6 s: the time written ${seen.time} times (${seen.texts.at(0)} … ${seen.texts.at(-1)}), ${seen.frames} frames drawn, other parts written ${seen.rest} times`);
    expect(seen.time).toBeGreaterThanOrEqual(4); // a few times a second
    expect(seen.time).toBeLessThanOrEqual(17); // at most 10 times a second
    // the readout alone changes: no other part is written (a frame still scheduled by the parts
    // catching up on a loaded machine draws nothing: 3 such frames in one CI run, so not counted)
    expect(seen.rest).toBe(0);
    expect(seen.t).toBe(String(Math.round(end))); // the state stays at the last record
    const readout = /^\+(\d+\.\d) s · live \(last record \+(\d+\.\d{6}) s\)$/;
    const first = readout.exec(seen.texts[0]!)!, last = readout.exec(seen.texts.at(-1)!)!;
    expect(first && last).toBeTruthy();
    expect(Number(last[2])).toBeCloseTo(end / 1e9, 5);
    expect(Number(last[1]) - Number(first[1])).toBeGreaterThanOrEqual(1.0);
    expect(Number(last[1]) - Number(last[2])).toBeGreaterThanOrEqual(1.5);
    await shot(page, 'monitor-field-06-live-quiet-stretch');
    // the timeline strip's tooltip at the miss: its label
    const box = (await page.locator('.monitor-strip').boundingBox())!;
    const width = await page.locator('.monitor-strip').evaluate((c) => (c as HTMLCanvasElement).width);
    await page.mouse.move(box.x + ((1 + (mark.t / end) * (width - 3)) / width) * box.width, box.y + 35);
    await expect.poll(() => page.locator('.monitor-strip').getAttribute('title')).toContain(`schemaCommande1: ${label}`);
    await page.locator('.monitor-pschema[data-periodic="schemaCommande1"]').scrollIntoViewIfNeeded();
    await page.locator('.monitor-pschema[data-periodic="schemaCommande1"]').screenshot({ path: fileURLToPath(new URL('../../test-output/monitor-field-07-histogram-period-equals-critical-delay.png', import.meta.url)) });
    await page.mouse.move(0, 0);
  }, 60_000);

  it('a job that ends while the view shows a run the user picked (here a workspace log) is listed, not shown in its place', async () => {
    const { page } = s;
    await showRecorded(page);
    const files = readdirSync(FIXTURE).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') }));
    await page.evaluate((files) => window.__ide.monitor.showRecorded('elsewhere', { label: 'Build & Run job elsewhere', files, problems: [] }), files);
    await expect.poll(() => page.locator('.monitor-sources option').allTextContents()).toContain('Build & Run job elsewhere · CSV logs');
    expect(await label(page)).toBe('9 CSV log(s) in recorded');
  }, 60_000);

  it('a module killed mid-release is not listed as running at the end of its run: it has no exit record, said as contract trace says it', async () => {
    const { page } = s;
    if (!(await page.locator('.side-pane .monitor-view').isVisible())) await page.locator('#btn-monitor').click();
    await page.locator('.monitor-sources').selectOption('dir:killed');
    await expect.poll(() => label(page)).toBe('9 CSV log(s) in killed');
    const modules = () => page.locator('.monitor-modules').textContent();
    await expect.poll(modules).toBe("Running now: none · no exit record: MSC (crashed, killed, or ended by its code's exit(): the run's messages say which)");
    expect(await page.locator('.monitor-diagram .live-running').count()).toBe(0);
    // back at the start, nothing has ended yet
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('Home');
    await expect.poll(modules).toBe('Running now: none');
    // the run that kept every exit record says none missing at its end
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await expect.poll(() => label(page)).toBe('9 CSV log(s) in recorded');
    await expect.poll(modules).toBe('Running now: none');
  }, 60_000);

  it('Follow again after scrubbing back a live run: the first frame shows the live state, not the one scrubbed to', async () => {
    const { page } = s;
    await page.evaluate(() => window.__ide.monitor.followLive('scrub', null));
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-mode')).toBe('live');
    const half = Math.floor(LINES.length / 2);
    await page.evaluate((records) => window.__ide.monitor.feed('scrub', records), LINES.slice(0, half));
    await expect.poll(() => page.evaluate(() => window.__ide.monitor.current?.recordCount)).toBe(half);
    const sup = page.locator('.monitor-sup[data-supervisor="SUP"] .monitor-sup-name');
    const liveText = async () => page.locator('.monitor-sup[data-supervisor="SUP"] .monitor-sup-name').textContent();
    await expect.poll(liveText).toMatch(/· [1-9]\d* action\(s\) done/);
    await page.locator('.monitor-view').focus();
    await page.keyboard.press(' '); // pause
    await page.keyboard.press('Home');
    for (let i = 0; i < 3; i++) await page.keyboard.press(']');
    await page.keyboard.press('[');
    // the state at the mark comes from the worker: drawn in a frame after it answers
    const mark = await page.evaluate(() => window.__ide.monitor.panel!.time as number);
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-t')).toBe(String(Math.round(mark)));
    const scrubbed = await sup.textContent();
    // the run goes on meanwhile
    await page.evaluate((records) => window.__ide.monitor.feed('scrub', records), LINES.slice(half));
    await expect.poll(() => page.evaluate(() => window.__ide.monitor.current?.recordCount)).toBe(LINES.length);
    await page.waitForTimeout(500);
    expect(await sup.textContent()).toBe(scrubbed);
    await page.keyboard.press(' '); // follow
    const end = await page.evaluate(() => window.__ide.monitor.current!.end as number);
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-t'), { timeout: 1000 }).toBe(String(Math.round(end)));
    await expect.poll(liveText, { timeout: 300 }).not.toBe(scrubbed);
    expect(await sup.textContent()).toMatch(/· [1-9]\d* action\(s\) done/);
  }, 60_000);

  it("a long failure message leaves every control of the Build & Run panel on screen, the message whole in the status's tooltip", async () => {
    const { page } = s;
    await page.setViewportSize({ width: 1280, height: 800 });
    await page.getByRole('tab', { name: /build & run/i }).click();
    const message = `run finished with 1 problem(s): ${'the run\'s stdout went past the output limit (1 MiB per stream) '.repeat(8)}`;
    await page.evaluate((m) => window.__ide.build.setStatus('failed', m, false), message);
    const status = page.locator('.build-panel .job-status');
    await expect.poll(() => status.getAttribute('title')).toBe(`failed — ${message}`);
    const width = page.viewportSize()!.width;
    for (const control of [page.locator('.build-panel .log-search'), page.locator('.build-panel button', { hasText: 'Clear' }), page.locator('.build-panel .toggle', { hasText: 'Follow' })]) {
      const box = (await control.boundingBox())!;
      expect(box.x + box.width, await control.evaluate((e) => e.outerHTML.slice(0, 80))).toBeLessThanOrEqual(width);
    }
    await shot(page, 'monitor-field-08-build-panel-long-failure');
    // focusing the filter scrolls nothing sideways: the log's rows stay where they were
    await page.locator('.build-panel .log-search').focus();
    expect(await page.locator('.build-panel').evaluate((e) => e.scrollLeft + (e.querySelector('.log-toolbar') as HTMLElement).scrollLeft)).toBe(0);
    await page.setViewportSize({ width: 1440, height: 900 });
  }, 60_000);
});

