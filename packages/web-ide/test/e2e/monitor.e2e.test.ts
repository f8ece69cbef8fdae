/**
 * End-to-end: the Monitor (docs/watching-a-run.md) in headless Chromium on the real IDE server.
 * - a recorded tutorial run's CSV logs in the workspace, replayed: rules, schemas, cursor, keyboard, click-to-rule;
 * - a real Build & Run of the tutorial (bubblewrap): SUP's FIRST then SECOND after MAA's
 *   "disconnected" with that cause, the schemas each activated, schemaCommande1's releases —
 *   live when the build service streams trace events, and on the job's recorded logs after the run.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { appendFileSync, cpSync, existsSync, mkdirSync, readdirSync, readFileSync, symlinkSync, truncateSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { WebSocketServer } from 'ws';
import { encodeTraceRecords, parseTrace } from '@contract-studio/build-service/trace';
import { startSession, openIde, shot, openFile, activeTab, activeValue, MOBILE_ROBOT, TUTORIAL, type Session, showMonitor } from './harness.js';
import { activationsFromLogs } from '../../src/views/run-logs.js';
import type {} from '../../src/app/ide-hook.js';

const canBuild =
  (await import('@contract-studio/build-service').then((m) => typeof (m as Record<string, unknown>).createBuildServer === 'function').catch(() => false)) &&
  (await import('@contract-studio/codegen').then((m) => typeof (m as Record<string, unknown>).generateArchitecture === 'function').catch(() => false)) &&
  spawnSync('bwrap', ['--version']).status === 0;
// the build service streams the run's trace (docs/build-service-api.md "Trace channel") once its trace tail is in
const liveChannel = await import('@contract-studio/build-service').then(() => existsSync(fileURLToPath(new URL('../../../build-service/src/pipeline/trace-tail.ts', import.meta.url))));
/** ORD releases in the long run's log: 9.6 MB of CSV. */
const LONG_RUN_RELEASES = 80_000;
const FIXTURE = fileURLToPath(new URL('../../src/monitor/fixtures/tutorial-run', import.meta.url));

type Page = Session['page'];
interface MarkJson { t: number; kind: string; where: string; label: string }
const marksOf = (page: Page) => page.evaluate(() => (window.__ide.monitor.current?.marks ?? []) as MarkJson[]);
const rule = (page: Page, id: string) => page.locator(`.monitor-rule[data-rule="${id}"]`);
const periodic = (page: Page, name: string) => page.locator(`.monitor-pschema[data-periodic="${name}"]`);
/** What the panel says (a polite live region: null without one) of the mark ◀ / ▶ ([ / ]) jumped to: the strip's tooltip's words for the marks at `t`. */
const markSaid = (page: Page) => page.evaluate(() => document.querySelector('.monitor-mark-said[role=status][aria-live=polite]')?.textContent ?? null);
const saidOf = (marks: readonly MarkJson[], t: number) => marks.filter((m) => m.t === t).map((m) => `+${(m.t / 1e9).toFixed(6)} s ${m.where}: ${m.label}`).join('\n');

/**
 * A taller screenshot of the IDE with the monitor (for docs/watching-a-run.md), then the usual size
 * again. `hidden`: the workspace entries the other tests made (their fixtures), left out of the
 * explorer for the picture only, so that it shows the example as a user has it.
 */
async function docShot(page: Page, name: string, hidden: readonly string[] = []): Promise<void> {
  await page.setViewportSize({ width: 1440, height: 1350 });
  await page.evaluate((paths) => {
    const style = document.createElement('style');
    style.id = 'doc-shot-hidden';
    style.textContent = paths.map((p) => `[data-path="${p}"]`).join(',') + '{display:none}';
    if (paths.length) document.head.append(style);
  }, [...hidden]);
  await page.waitForTimeout(300); // re-laid out and redrawn
  await shot(page, name);
  await page.evaluate(() => document.getElementById('doc-shot-hidden')?.remove());
  await page.setViewportSize({ width: 1440, height: 900 });
}

/** The Monitor docked beside the editor (opened with its button when it is not). */
async function monitorShown(page: Page): Promise<void> {
  await showMonitor(page);
}

/** Moves the cursor to t (ns since the start) the way the panel's own controls do. */
async function seek(page: Page, t: number): Promise<void> {
  await page.evaluate((t) => window.__ide.monitor.panel!.seek(t), t);
  await expect.poll(() => page.locator('.monitor-view').getAttribute('data-t')).toBe(String(Math.round(t)));
}

/** The tutorial's story, checked at the times the trace gives: the same for live and replay. */
async function checkTutorialStory(page: Page): Promise<{ first: MarkJson; second: MarkJson }> {
  const marks = await marksOf(page);
  const first = marks.find((m) => m.kind === 'rule' && m.label.startsWith('action.FIRST active'))!;
  const firstOff = marks.find((m) => m.kind === 'rule' && m.label.startsWith('action.FIRST inactive'))!;
  const second = marks.find((m) => m.kind === 'rule' && m.label.startsWith('action.SECOND active'))!;
  expect(first && firstOff && second).toBeTruthy();
  expect(second.label).toBe('action.SECOND active ← MAA:2 = "disconnected"'); // the cause in the rule rows' words
  expect(first.t).toBeLessThan(second.t);
  // while FIRST is active: it is lit with its cause, SECOND is not, the event schema it activated is active
  await seek(page, first.t + (firstOff.t - first.t) / 2);
  await expect.poll(() => rule(page, 'SUP.action.FIRST').getAttribute('data-active')).toBe('true');
  expect(await rule(page, 'SUP.action.FIRST').getAttribute('data-cause')).toBe('elapsed=1000000ns');
  expect(await rule(page, 'SUP.action.SECOND').getAttribute('data-active')).toBe('false');
  expect(await page.locator('.monitor-schema').allTextContents()).toEqual(['● schemaReceptionMessage (event) ← SUP.action.FIRST']);
  // MAA's messages reach MAB over the schema's event flow: counted
  expect(await page.locator('.monitor-flow.event[data-flow="MAA:0->MAB:0"]').textContent()).toMatch(/^┅ MAA:0 → MAB:0 ×[1-9]\d* · last \+/);
  await expect.poll(() => page.locator('.monitor-view .arch-svg').getAttribute('data-schema'), { timeout: 10_000 }).toBe('schemaReceptionMessage');
  expect(await page.locator('.monitor-view .arch-node.live-active').evaluateAll((els) => els.map((e) => (e as SVGElement).dataset.module).sort())).toEqual(['MAA', 'MAB']);
  // after MAA's "disconnected": SECOND lit with that cause and its time, schemaCommande1 active and
  // released (ORD's activation follows SECOND by well under a millisecond; 300 ms leaves room on a loaded machine)
  await seek(page, second.t + 300e6);
  await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-active')).toBe('true');
  expect(await rule(page, 'SUP.action.SECOND').getAttribute('data-cause')).toBe('MAA:2 value="disconnected"');
  expect(Number(await rule(page, 'SUP.action.SECOND').getAttribute('data-since'))).toBe(second.t);
  expect(await rule(page, 'SUP.action.SECOND').textContent()).toContain('schemaCommande1');
  // shown in the words of the model and of `contract trace` (data-cause keeps the engine's)
  expect(await rule(page, 'SUP.action.SECOND').textContent()).toContain('← MAA:2 = "disconnected" → schemaCommande1');
  expect(await rule(page, 'SUP.action.FIRST').getAttribute('data-active')).toBe('false');
  // the "disconnected" reached SUP over its subscription MAA:2 =* :2: a delivery, counted like a module's
  expect(await page.locator('.monitor-flow.event[data-flow="MAA:2->SUP:2"]').textContent()).toMatch(/^┅ MAA:2 → SUP:2 ×[1-9]\d* · last \+/);
  expect(await page.locator('.monitor-schema').allTextContents()).toEqual(['● schemaCommande1 (periodic) ← SUP.action.SECOND']);
  await expect.poll(() => page.locator('.monitor-view .arch-svg').getAttribute('data-schema'), { timeout: 10_000 }).toBe('schemaCommande1');
  expect(Number(await periodic(page, 'schemaCommande1').getAttribute('data-releases'))).toBeGreaterThan(0);
  expect(Number(await periodic(page, 'schemaCommande1').getAttribute('data-misses'))).toBe(0);
  return { first, second };
}

describe('Monitor in headless Chromium', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession();
    mkdirSync(join(s.workspace, 'recorded'));
    cpSync(FIXTURE, join(s.workspace, 'recorded'), { recursive: true });
    // a longer run's logs (`contract run` writes them to PROJECT/logs): ORD's, past the editor's
    // 8 MiB file bound, and one past the 256 MiB the replay reads of a log: CTL's two records, then zeros (sparse: no disk used)
    mkdirSync(join(s.workspace, 'long-run'));
    const ord = ['mono_ns,wall_time,module,event,peer,port,size,detail', '999000000,2026-11-29T10:00:00.000000Z,ORD,scheduler,,,0,activate S'];
    for (let i = 0; i < LONG_RUN_RELEASES; i++) ord.push(`${1_000_000_000 + i * 1_000_000},2026-11-29T10:00:01.000000Z,ORD,ord_release,CTL,,0,schema=S cycle=${i} tick_ns=${1_000_000_000 + i * 1_000_000} release_ns=${1_000_000_100 + i * 1_000_000} release=${i + 1}`);
    writeFileSync(join(s.workspace, 'long-run', 'ORD_29-Nov-2026-10h00m00s.csv'), ord.join('\n') + '\n');
    writeFileSync(join(s.workspace, 'long-run', 'CTL_29-Nov-2026-10h00m00s.csv'), ['mono_ns,wall_time,module,event,peer,port,size,detail',
      '1000005000,2026-11-29T10:00:01.000000Z,CTL,run_started,ORD,,0,activation=1', '1000050000,2026-11-29T10:00:01.000000Z,CTL,run_finished,ORD,,0,activation=1 cpu_ns=41000 ACK_FINISHED', ''].join('\n'));
    truncateSync(join(s.workspace, 'long-run', 'CTL_29-Nov-2026-10h00m00s.csv'), 256 * 1024 * 1024 + 1);
    // a folder where a file named like a log is 40 MB of short lines that are no records
    mkdirSync(join(s.workspace, 'junk-run'));
    writeFileSync(join(s.workspace, 'junk-run', 'ORD_29-Nov-2026-10h00m00s.csv'), ord.slice(0, 1002).join('\n') + '\n');
    // (after the runtime's header: a file without it is no log, refused whole at its line 1)
    writeFileSync(join(s.workspace, 'junk-run', 'JNK_29-Nov-2026-10h00m00s.csv'), `${ord[0]}\n${'x\n'.repeat(20_000_000)}`);
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('replays a recorded run from workspace CSV logs: rules, schemas, cursor, keyboard, rule -> definition', async () => {
    const { page } = s;
    await page.locator('#btn-monitor').click();
    await page.locator('.side-pane .monitor-view').waitFor();
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('9 CSV log(s) in recorded');
    await checkTutorialStory(page);
    await shot(page, 'monitor-01-replay-tutorial');
    // keyboard: Home goes to the start (nothing active yet), ] steps to the next mark
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('Home');
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-t')).toBe('0');
    expect(await page.locator('.monitor-rule[data-active=true]').count()).toBe(0);
    const marks = await marksOf(page);
    // the timeline strip: every mark is a tick of its kind's colour in its row (binned by pixel column)
    const strip = await page.evaluate(() => {
      const c = document.querySelector('.monitor-strip') as HTMLCanvasElement;
      const m = window.__ide.monitor.current!;
      const d = c.getContext('2d')!.getImageData(0, 0, c.width, c.height).data;
      const px = (x: number, y: number) => { const i = (y * c.width + x) * 4; return `#${[d[i]!, d[i + 1]!, d[i + 2]!].map((v) => v.toString(16).padStart(2, '0')).join('')}`; };
      // (the strip's rows: timeline-strip.ts ROW)
      const row: Record<string, number> = { function: 0, user: 0, error: 0, unheard: 0, kept: 0, crash: 0, rule: 1, schema: 2, miss: 3, overrun: 3 };
      const col = (t: number) => Math.floor(1 + (t / Math.max(1, m.end)) * (c.width - 3));
      const cursor = col(0);
      return m.marks.filter((k) => Math.abs(col(k.t) - cursor) > 2).map((k) => ({ kind: k.kind, on: k.on, colour: px(col(k.t), 3 + row[k.kind]! * 10 + 4) }));
    });
    expect(strip.length).toBeGreaterThan(3);
    for (const k of strip) expect(k.colour, JSON.stringify(k)).not.toBe('#20242c');
    expect(strip.filter((k) => k.kind === 'schema').map((k) => k.colour)).toContain('#61afef');
    expect(strip.filter((k) => k.kind === 'rule' && k.on).map((k) => k.colour)).toContain('#98c379');
    await page.keyboard.press(']');
    await expect.poll(async () => Number(await page.locator('.monitor-view').getAttribute('data-t'))).toBe(marks.find((m) => m.t > 0)!.t);
    // the mark jumped to is said and shown, in the words of the strip's tooltip
    expect(await markSaid(page)).toBe(saidOf(marks, marks.find((m) => m.t > 0)!.t));
    // End follows the end again: every function stopped, no rule lit
    await page.keyboard.press('End');
    await expect.poll(() => page.locator('#monitor-follow').getAttribute('data-following')).toBe('true');
    expect(await page.locator('.monitor-rule[data-active=true]').count()).toBe(0);
    // a click on a rule opens its definition
    await rule(page, 'SUP.action.SECOND').click();
    await expect.poll(() => activeTab(page)).toBe('supervisor.contract');
    const line = await page.evaluate(() => window.__ide.editors.editor.getPosition()!.lineNumber);
    expect((await activeValue(page)).split('\n')[line - 1]).toMatch(/^\s*SECOND:/);
    // renamed since the run (here on disk, as by another editor): the run's SECOND is marked as not
    // in the model, after the model's SECOND_X; a click opens its function and says why
    const supFile = join(s.workspace, 'supervisor.contract');
    const supText = readFileSync(supFile, 'utf8');
    writeFileSync(supFile, supText.replaceAll('SECOND', 'SECOND_X'));
    await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-in-model'), { timeout: 10_000 }).toBe('false');
    expect(await rule(page, 'SUP.action.SECOND').getAttribute('aria-label')).toMatch(/^SECOND, inactive since .*, not in the model: renamed or removed since this run$/);
    expect(await rule(page, 'SUP.action.SECOND_X').getAttribute('data-in-model')).toBe('true');
    expect(await rule(page, 'SUP.action.FIRST').getAttribute('data-in-model')).toBe('true');
    await rule(page, 'SUP.action.SECOND').click();
    await expect.poll(() => page.locator('.toast').allTextContents()).toContainEqual(expect.stringContaining('Rule SECOND is not in SUP.action any more'));
    const fnLine = await page.evaluate(() => window.__ide.editors.editor.getPosition()!.lineNumber);
    expect((await activeValue(page)).split('\n')[fnLine - 1]).toMatch(/^\s*action\(/);
    writeFileSync(supFile, supText);
    await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-in-model'), { timeout: 10_000 }).toBe('true');
    expect(await rule(page, 'SUP.action.SECOND_X').count()).toBe(0);
    // a whole supervisor renamed since the run (GLB, now GLA): the run's GLB, its function and its
    // rule are all marked as not in the model, like a renamed rule; a click says so and opens nothing
    const glbFile = join(s.workspace, 'supervisor2.contract');
    const glbText = readFileSync(glbFile, 'utf8');
    writeFileSync(glbFile, glbText.replace('supervisor GLB{', 'supervisor GLA{'));
    const glbHeader = page.locator('.monitor-sup[data-supervisor="GLB"] .monitor-sup-name');
    await expect.poll(() => glbHeader.getAttribute('data-in-model'), { timeout: 10_000 }).toBe('false');
    expect(await glbHeader.textContent()).toMatch(/^GLB \(not in the model\)/);
    expect(await page.locator('.monitor-fn[data-function="GLB.mission"]').getAttribute('data-in-model')).toBe('false');
    expect(await page.locator('.monitor-fn[data-function="GLB.mission"]').textContent()).toMatch(/^mission\(\) \(not in the model\) — /);
    expect(await rule(page, 'GLB.mission.SINGLE').getAttribute('data-in-model')).toBe('false');
    expect(await rule(page, 'GLB.mission.SINGLE').getAttribute('aria-label')).toMatch(/^SINGLE, .*, not in the model: renamed or removed since this run$/);
    expect(await rule(page, 'GLB.mission.SINGLE').getAttribute('title')).toMatch(/ · not in the model: renamed or removed since this run, and so is its function: nothing to open$/);
    expect(await rule(page, 'GLB.mission.SINGLE').locator('.rule-name').evaluate((e) => getComputedStyle(e).textDecorationLine)).toBe('line-through');
    expect(await rule(page, 'GLA.mission.SINGLE').getAttribute('data-in-model')).toBe('true');
    expect(await rule(page, 'SUP.action.SECOND').getAttribute('data-in-model')).toBe('true');
    await rule(page, 'GLB.mission.SINGLE').click();
    await expect.poll(() => page.locator('.toast').allTextContents()).toContainEqual(expect.stringContaining('GLB.mission is not in the model'));
    // with a mark jumped to (GLB's rule lit): the picture of both
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('Home');
    await expect.poll(() => markSaid(page)).toBe('');
    await page.keyboard.press(']');
    await page.keyboard.press(']');
    const glbRuleOn = marks.filter((m) => m.t > 0)[1]!;
    expect(glbRuleOn).toMatchObject({ where: 'GLB', label: expect.stringMatching(/^mission\.SINGLE active/) });
    await expect.poll(() => markSaid(page)).toBe(saidOf(marks, glbRuleOn.t));
    await expect.poll(() => rule(page, 'GLB.mission.SINGLE').getAttribute('data-active')).toBe('true');
    expect(await rule(page, 'GLB.mission.SINGLE').getAttribute('data-in-model')).toBe('false');
    await shot(page, 'monitor-01b-supervisor-not-in-model-mark-said');
    writeFileSync(glbFile, glbText);
    await expect.poll(() => glbHeader.getAttribute('data-in-model'), { timeout: 10_000 }).toBe('true');
    expect(await rule(page, 'GLB.mission.SINGLE').getAttribute('data-in-model')).toBe('true');
    // ◉ Monitor hides it and shows it again, on the same run
    await page.locator('#btn-monitor').click();
    await expect.poll(() => page.locator('.side-pane').isHidden()).toBe(true);
    await page.locator('#btn-monitor').click();
    await page.locator('.side-pane .monitor-view').waitFor();
    expect(await page.locator('.monitor-source').textContent()).toBe('9 CSV log(s) in recorded');
  });

  it('replays a trace file of the workspace (contract run --trace) as the logs it was written from: the same story at the same times', async () => {
    const { page } = s;
    await monitorShown(page);
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('9 CSV log(s) in recorded');
    const fromLogs = await marksOf(page);
    // the file as `contract run --trace` writes it (one JSON object a line), with a simulation's first
    // line (`contract simulate --trace`), and a line that is no record
    const records = parseTrace(readdirSync(FIXTURE).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') })));
    const sim = JSON.stringify({ kind: 'sim_start', monoNs: '0', wallTime: '', module: 'SIM', peer: '', port: null, size: 0, detail: 'simulation start', fields: {} });
    writeFileSync(join(s.workspace, 'recorded.jsonl'), [sim, 'not json', ...records.map((r) => JSON.stringify(r))].join('\n') + '\n');
    await expect.poll(() => page.locator('.monitor-sources option[value="file:recorded.jsonl"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption('file:recorded.jsonl');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe(`Trace file recorded.jsonl · a simulation · ${records.length} record(s), 1 unreadable line(s) (not whole: line 2: not JSON)`);
    expect(await marksOf(page)).toEqual(fromLogs);
    await checkTutorialStory(page);
    // a click on the file in the explorer opens it in the Monitor (not as text in an editor tab)
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('9 CSV log(s) in recorded');
    await page.locator('.tree-row[data-path="recorded.jsonl"]').click();
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toMatch(/^Trace file recorded\.jsonl · /);
    expect(await page.locator('.tab[data-path="recorded.jsonl"]').count()).toBe(0);
    // the Timeline offers it too: the activations of the logs it was written from
    // the runs, not the events an asynchronous module handled (counted apart)
    const expected = activationsFromLogs(readdirSync(FIXTURE).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') }))).acts.filter((a) => !a.event).length;
    expect(expected).toBeGreaterThan(10);
    await page.locator('#btn-timeline').click();
    await page.locator('.timeline-view').waitFor();
    await expect.poll(() => page.locator('.timeline-source option[value="file:recorded.jsonl"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.timeline-source').selectOption('file:recorded.jsonl');
    await expect.poll(() => page.locator('.timeline-view .muted').first().textContent(), { timeout: 10_000 }).toMatch(new RegExp(`^${expected} activations · \\d+ modules`));
    await page.locator('.timeline-source').selectOption('local'); // as the Timeline test below expects it
    await monitorShown(page);
    // changed on disk while shown: read again (the bad line gone)
    writeFileSync(join(s.workspace, 'recorded.jsonl'), records.map((r) => JSON.stringify(r)).join('\n') + '\n');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 10_000 }).toBe(`Trace file recorded.jsonl · ${records.length} record(s)`);
    expect(await marksOf(page)).toEqual(fromLogs);
  });

  it('replays workspace logs past the editor\'s 8 MiB bound whole, a log past 256 MiB for its first 256 MiB (said), and names a log it leaves out', async () => {
    const { page } = s;
    await page.locator('.monitor-sources').selectOption('dir:long-run');
    // before GET /api/log the replay took the logs through GET /api/file, 413 past 8 MiB, and left ORD's out without a word;
    // then a log past 256 MiB was left out whole (CTL's records too): now its first 256 MiB are read, its whole lines, and that is said
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 60_000 })
      .toBe('2 CSV log(s) in long-run (not whole: CTL_29-Nov-2026-10h00m00s.csv: only its first 230 bytes of 256.0 MiB read (the IDE reads 256.0 MiB of a log for a replay): ' +
        'its later records are not shown; the whole log is long-run/CTL_29-Nov-2026-10h00m00s.csv in the workspace (`contract trace` reads it whole))');
    expect(await page.evaluate(() => window.__ide.monitor.current!.recordCount)).toBe(LONG_RUN_RELEASES + 1 + 2);
    await shot(page, 'monitor-02-replay-left-out');
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('End');
    await expect.poll(() => periodic(page, 'S').getAttribute('data-releases')).toBe(String(LONG_RUN_RELEASES));
    // the schema's block says its module's CPU per release (CTL's run_finished cpu_ns), ORD's none
    await expect.poll(() => periodic(page, 'S').locator('.monitor-pstats').textContent()).toContain(' · CPU per release: CTL last 41 µs, max 41 µs');
    // the replay's total bound (512 MiB: a folder of sparse 255 MiB logs must not fill the tab): a
    // log past what is left is not downloaded, and named (ORD's is read first: run-logs.ts replayOrder)
    await page.evaluate(() => (window.__ide.monitor.replayBytes = 1_000_000));
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await page.evaluate(() => window.__ide.monitor.openFolder('long-run'));
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 })
      .toMatch(/^0 of 2 CSV logs in long-run \(left out: ORD_29-Nov-2026-10h00m00s\.csv: \d+ bytes, past the 1000000 bytes left of the replay's bound; CTL_29-Nov-2026-10h00m00s\.csv: 268435456 bytes, past the \d+ bytes left of the replay's bound\) — `contract trace long-run` tells a run of any length$/);
    // a trace file past it: named, and the command that tells it whole
    await page.evaluate(() => (window.__ide.monitor.replayBytes = 1000));
    await page.evaluate(() => window.__ide.monitor.openTraceFile('recorded.jsonl'));
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 })
      .toMatch(/^Trace file recorded\.jsonl · 0 record\(s\) \(not whole: recorded\.jsonl: \d+ bytes, past the 1000 bytes left of the replay's bound\) — `contract trace recorded\.jsonl` tells a run of any length$/);
    await page.evaluate(() => (window.__ide.monitor.replayBytes = 512 * 1024 * 1024));
  }, 60_000);

  it('replays a folder with a log of millions of lines that are no records: the rest of that log left out, said, the page responsive', async () => {
    const { page } = s;
    await page.evaluate(() => window.__ide.monitor.openFolder('junk-run'));
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 })
      .toBe('2 CSV log(s) in junk-run · 1,001 record(s), 100,000 unreadable line(s) (not whole: JNK_29-Nov-2026-10h00m00s.csv: more than 100000 lines that are not trace records, the rest of it from line 100002 left out)');
    // ORD's 1,001 records and the 100,000 unreadable lines kept: counted, the rest not read
    const m = await page.evaluate(() => { const c = window.__ide.monitor.current!; return { n: c.recordCount, records: c.live.records, unknown: c.live.unknownLines }; });
    expect(m).toEqual({ n: 1001 + 100_000, records: 1001, unknown: 100_000 });
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('End');
    await expect.poll(() => periodic(page, 'S').getAttribute('data-releases')).toBe('1000');
  }, 60_000);

  it('a folder of 258 logs, a link and a FIFO: 256 read, the others named or counted; a trace file counts every line that is no record, as contract trace does', async () => {
    const { page } = s;
    const dir = join(s.workspace, 'odd-run');
    mkdirSync(dir);
    const header = 'mono_ns,wall_time,module,event,peer,port,size,detail';
    for (let i = 0; i < 258; i++) {
      const m = `M${String(i).padStart(3, '0')}`;
      writeFileSync(join(dir, `${m}_1.csv`), `${header}\n${1000 + i},w,${m},module_started,,,0,pid=${i + 1} priority=10\n`);
    }
    // the Explorer lists neither: before, the replay left them out without a word
    symlinkSync('/etc/passwd', join(dir, 'PWD_1.csv'));
    spawnSync('mkfifo', [join(dir, 'FIF_1.csv')]);
    await monitorShown(page);
    await expect.poll(() => page.locator('.monitor-sources option[value="dir:odd-run"]').count(), { timeout: 10_000 }).toBe(1);
    // what the label says while the folder is read
    await page.evaluate(() => {
      const label = document.querySelector('.monitor-source')!;
      (window as any).__labels = [];
      new MutationObserver(() => (window as any).__labels.push(label.textContent)).observe(label, { childList: true, characterData: true, subtree: true });
    });
    await page.locator('.monitor-sources').selectOption('dir:odd-run');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 })
      .toBe('256 of 260 CSV logs in odd-run (left out: FIF_1.csv: a FIFO, not read; PWD_1.csv: a symbolic link, not read (logs are never read through a link); 2 more CSV log(s) past the first 256: a replay reads 256 at most) — `contract trace odd-run` tells a run of any length');
    expect(await page.evaluate(() => window.__ide.monitor.current!.recordCount)).toBe(256);
    expect(await page.evaluate(() => (window as any).__labels[0])).toBe('Reading the CSV logs in odd-run…');
    // a trace file: the lines that are no record counted (the first 20 named), as `contract trace` counts them
    const records = Array.from({ length: 500 }, (_, i) => JSON.stringify({ kind: 'module_started', monoNs: String(1000 + i), wallTime: 'w', module: 'ORD', peer: '', port: null, size: 0, detail: 'pid=1 priority=10' }));
    const lines = records.flatMap((r, i) => (i % 20 === 0 ? [r, '{"deep":' + '['.repeat(50) + ']'.repeat(50) + '}', 'garbage \u0001'] : [r]));
    writeFileSync(join(s.workspace, 'odd.jsonl'), lines.join('\n') + '\n');
    await expect.poll(() => page.locator('.monitor-sources option[value="file:odd.jsonl"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption('file:odd.jsonl');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 }).toMatch(/^Trace file odd\.jsonl · 500 record\(s\), 50 unreadable line\(s\) \(not whole: line 2: kind, monoNs, module and detail must be strings; line 3: not JSON; .*; 30 more line\(s\) that are no record\)$/);
    expect(await page.evaluate(() => (window as any).__labels)).toContain('Reading trace file odd.jsonl…');
  }, 60_000);

  it('a folder opened while another is still read and built: the last one asked for is shown, the other listed', async () => {
    const { page } = s;
    const shownAfter = await page.evaluate(async () => {
      const m = window.__ide.monitor;
      const before = m.runs.get('dir:long-run');
      // long-run (9.6 MB, 80,001 records) asked for first, the tutorial's small run right after
      const slow = m.openFolder('long-run');
      const fast = m.openFolder('recorded');
      await Promise.all([slow, fast]);
      return { rebuilt: m.runs.get('dir:long-run') !== before, label: document.querySelector('.monitor-source')!.textContent, options: [...document.querySelectorAll('.monitor-sources option')].map((o) => (o as HTMLOptionElement).value) };
    });
    expect(shownAfter.rebuilt).toBe(true);
    expect(shownAfter.label).toBe('9 CSV log(s) in recorded');
    expect(shownAfter.options).toContain('dir:long-run');
  }, 60_000);

  it('live path: TraceEvents of a run, fed at the run\'s own pace, are followed live and give the same story at the same times as its replay', async () => {
    const { page } = s;
    // the TraceEvent stream of the recorded run: every record line, in mono_ns order, batched per 50 ms of run time
    const lines = readdirSync(FIXTURE).flatMap((file) => readFileSync(join(FIXTURE, file), 'utf8').split('\n').map((text, i) => ({ file, line: i + 1, text })))
      .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));
    const mono = (l: { text: string }) => Number(l.text.split(',')[0]);
    const batches: Array<{ at: number; records: typeof lines }> = [];
    for (const l of lines) {
      const at = Math.floor((mono(l) - mono(lines[0]!)) / 50e6) * 50;
      if (batches.at(-1)?.at === at) batches.at(-1)!.records.push(l);
      else batches.push({ at, records: [l] });
    }
    await page.evaluate(() => window.__ide.monitor.followLive('fed', null)); // as Build & Run does, the lines fed by the test
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-mode')).toBe('live');
    // the live run drawn (its first frame: an empty run, followed), not the run shown before it
    await expect.poll(() => page.locator('.monitor-time').textContent()).toContain('· live');
    const feeding = page.evaluate(async (batches) => {
      const t0 = performance.now();
      for (const b of batches) {
        const wait = b.at - (performance.now() - t0);
        if (wait > 0) await new Promise((r) => setTimeout(r, wait));
        window.__ide.monitor.feed('fed', b.records);
      }
    }, batches);
    // while it runs, following the end: FIRST lit (MAA's messages arrive), then SECOND after "disconnected"
    await expect.poll(() => rule(page, 'SUP.action.FIRST').getAttribute('data-active'), { timeout: 3000 }).toBe('true');
    expect(await page.locator('#monitor-follow').getAttribute('data-following')).toBe('true');
    expect(await page.locator('#monitor-follow').getAttribute('aria-label')).toBe('Pause');
    expect(await page.locator('.monitor-time').textContent()).toContain('· live');
    await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-active'), { timeout: 5000 }).toBe('true');
    expect(await rule(page, 'SUP.action.SECOND').getAttribute('data-cause')).toBe('MAA:2 value="disconnected"');
    await shot(page, 'monitor-02-live-fed-tutorial');
    await feeding;
    // every line folded in (by the live run's worker, off the page's main thread)
    await expect.poll(() => page.evaluate(() => window.__ide.monitor.current!.recordCount)).toBe(lines.length);
    const liveMarks = await marksOf(page);
    const { second } = await checkTutorialStory(page);
    // played back from just before SECOND: the states come from the live run's worker as the cursor moves
    await seek(page, second.t - 300e6);
    await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-active')).toBe('false');
    const drawnBefore = await page.evaluate(() => window.__ide.monitor.panel!.frameMs.length);
    await page.locator('#monitor-play').click();
    await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-active'), { timeout: 5000 }).toBe('true');
    await page.locator('#monitor-play').click();
    // drawn along the way, not only at the end (a frame per state that came)
    expect(await page.evaluate(() => window.__ide.monitor.panel!.frameMs.length) - drawnBefore).toBeGreaterThan(5);
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('9 CSV log(s) in recorded');
    expect(await marksOf(page)).toEqual(liveMarks);
  });

  it('following a 1 kHz run live, the time is written at most 10 times a second, the diagram\'s marks too, the deliveries\' counts 5 times, and exactly once it pauses or ends', async () => {
    const { page } = s;
    await page.evaluate(() => window.__ide.monitor.followLive('khz', null));
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-mode')).toBe('live');
    await page.waitForSelector('.monitor-view .arch-svg');
    // MAB receiving MAA's event at 1 kHz for 2 s (and MSA running every other 20 ms), in 20 ms
    // trace events at the run's own pace;
    // the deliveries' rows counted per write (one batch of mutations), against the frames drawn
    const seen = await page.evaluate(async () => {
      const counts = { writes: 0, clock: 0, diagram: 0, frames: 0 };
      const observers = [
        new MutationObserver(() => counts.writes++),
        new MutationObserver(() => counts.clock++),
        new MutationObserver(() => counts.diagram++),
      ];
      observers[0]!.observe(document.querySelector('.monitor-flows')!, { subtree: true, childList: true, characterData: true });
      observers[1]!.observe(document.querySelector('.monitor-time')!, { subtree: true, childList: true, characterData: true });
      observers[2]!.observe(document.querySelector('.monitor-view .monitor-diagram')!, { subtree: true, childList: true, attributes: true, attributeFilter: ['class', 'data-live'] });
      let version = -1;
      let feeding = true;
      const tick = () => {
        const drawn = window.__ide.monitor.panel!.drawn.version;
        if (drawn !== version) (version = drawn), counts.frames++;
        if (feeding) requestAnimationFrame(tick);
      };
      requestAnimationFrame(tick);
      const t0 = performance.now();
      for (let batch = 0; batch < 100; batch++) {
        const records = [];
        for (let i = 0; i < 20; i++) {
          const n = batch * 20 + i;
          records.push({ file: 'MAB.csv', line: n + 2, text: `${1_000_000_000 + n * 1_000_000},2026-11-29T10:00:01.000000Z,MAB,event_received,MAA,0,288,from_port=0 latency_ns=1000` });
        }
        // MSA runs in one batch, stops in the next: the diagram's "running" mark changes with each
        records.push({ file: 'MSA.csv', line: batch + 2, text: `${1_000_000_000 + (batch * 20 + 19) * 1_000_000 + 500_000},2026-11-29T10:00:01.000000Z,MSA,${batch % 2 ? 'run_finished' : 'run_started'},ORD,,0,activation=${batch + 1}` });
        window.__ide.monitor.feed('khz', records);
        const wait = (batch + 1) * 20 - (performance.now() - t0);
        if (wait > 0) await new Promise((r) => setTimeout(r, wait));
      }
      feeding = false;
      for (const o of observers) o.disconnect();
      return { ...counts, seconds: (performance.now() - t0) / 1000 };
    });
    console.log(`[monitor e2e] 1 kHz feed for ${seen.seconds.toFixed(2)} s: ${seen.frames} frames drawn; deliveries written ${seen.writes} times, the time ${seen.clock}, the diagram's marks ${seen.diagram}`);
    expect(seen.frames).toBeGreaterThan(3 * seen.writes);
    expect(seen.writes).toBeLessThanOrEqual(Math.ceil(seen.seconds * 5) + 1);
    expect(seen.clock).toBeGreaterThan(seen.writes);
    expect(seen.clock).toBeLessThanOrEqual(Math.ceil(seen.seconds * 10) + 1);
    expect(seen.diagram).toBeGreaterThan(2);
    expect(seen.diagram).toBeLessThanOrEqual(Math.ceil(seen.seconds * 10) + 1);
    // once the records stop, the last count is shown
    const row = page.locator('.monitor-flow.event[data-flow="MAA:0->MAB:0"]');
    await expect.poll(() => row.textContent()).toBe('┅ MAA:0 → MAB:0 ×2000 · last +1.999000 s');
    // following live, the readout runs with the run's clock and names the last record's time (the state shown)
    await expect.poll(() => page.locator('.monitor-time').textContent()).toMatch(/^\+\d+\.\d s · live \(last record \+\d+\.\d{6} s\)$/);
    await expect.poll(async () => (await page.locator('.monitor-time').textContent())!.match(/\d+\.\d{6}/)![0]).toBe('1.999500');
    // paused right after a record came (a throttled part then waits): the view is exact at once
    const paused = await page.evaluate(async () => {
      const frame = () => new Promise((r) => requestAnimationFrame(r));
      const time = document.querySelector('.monitor-time')!;
      // just after the time was written, a record comes and its frame is drawn: the time waits
      const written = new Promise((r) => new MutationObserver((_, o) => (o.disconnect(), r(undefined))).observe(time, { subtree: true, childList: true, characterData: true }));
      const m = window.__ide.monitor.lastLive!;
      // the two records below are counted from here: the write awaited may be the clock's own tick, before the first is folded
      const before = m.recordCount;
      window.__ide.monitor.feed('khz', [{ file: 'MAB.csv', line: 2002, text: '3500000000,2026-11-29T10:00:03.500000Z,MSA,run_finished,ORD,,0,activation=1000 cpu_ns=41000' }]);
      const wrote = await Promise.race([written.then(() => true), new Promise((r) => setTimeout(() => r(false), 2000))]);
      if (!wrote) return { time: `the time was not written: ${time.textContent}`, row: '' };
      window.__ide.monitor.feed('khz', [{ file: 'MAB.csv', line: 2003, text: '4000000000,2026-11-29T10:00:04.000000Z,MAB,event_received,MAA,0,288,from_port=0 latency_ns=1000' }]);
      // folded by the live run's worker: in the page's model at its next snapshot
      while (m.recordCount < before + 2) await frame();
      window.__ide.monitor.panel!.setFollow(false);
      await frame();
      return { time: time.textContent, row: document.querySelector('.monitor-flow.event[data-flow="MAA:0->MAB:0"]')!.textContent };
    });
    expect(paused).toEqual({ time: '+3.000000 s / +3.000000 s', row: '┅ MAA:0 → MAB:0 ×2001 · last +3.000000 s' });
    // paused, the counts are those at the cursor at once
    await seek(page, 1_000_000_000);
    await expect.poll(() => row.textContent(), { timeout: 1000 }).toBe('┅ MAA:0 → MAB:0 ×1001 · last +1.000000 s');
  });

  it('a live run that ends stops saying live in the readout at once, not at the next frame (a large run\'s frame came seconds later while the run list said ended)', async () => {
    const { page } = s;
    await page.evaluate(() => window.__ide.monitor.followLive('ends', null));
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-mode')).toBe('live');
    await page.evaluate(() => window.__ide.monitor.feed('ends', [{ file: 'MAB.csv', line: 2, text: '1000000000,2026-11-29T10:00:01.000000Z,MAB,event_received,MAA,0,288,from_port=0 latency_ns=1000' }]));
    await expect.poll(() => page.locator('.monitor-time').textContent()).toMatch(/ · live \(last record \+\d+\.\d{6} s\)$/);
    // ended, then read in the same task: no frame has been drawn in between
    const readout = await page.evaluate(() => {
      window.__ide.monitor.panel!.endLive('Build & Run job ends · ended: cancelled');
      return document.querySelector('.monitor-time')!.textContent;
    });
    expect(readout).not.toContain('live');
    expect(readout).toMatch(/^\+\d+\.\d{6} s \/ \+\d+\.\d{6} s$/);
  });

  it('a log naming a supervisor function `constructor` and a rule `__proto__` is shown like any other, and pollutes nothing', async () => {
    const { page } = s;
    await monitorShown(page);
    const errors: string[] = [];
    page.on('pageerror', (e) => errors.push(e.message));
    mkdirSync(join(s.workspace, 'hostile-run'));
    // (each module's records in its own log: a line of ORD's in SUP's log is no record of ORD's)
    writeFileSync(join(s.workspace, 'hostile-run', 'ORD_1-Jan-2026-00h00m00s.csv'), ['mono_ns,wall_time,module,event,peer,port,size,detail',
      '3000,w,ORD,request_received,SUP,,0,START __proto__', '4000,w,ORD,scheduler,,,0,activate __proto__'].join('\n') + '\n');
    writeFileSync(join(s.workspace, 'hostile-run', 'SUP_1-Jan-2026-00h00m00s.csv'), ['mono_ns,wall_time,module,event,peer,port,size,detail',
      '1000,w,SUP,supervisor,,,0,function constructor started', '2000,w,SUP,sup_rule,,,0,constructor.__proto__ active cause=elapsed=1ns',
      '5000,w,SUP,sup_rule,,,0,action.toString active cause=elapsed=1000ns',
      // long names: a rule name of 27 characters is shown whole, a function name of 2,000 is cut to the pane
      '6000,w,SUP,sup_rule,,,0,action.OBSTACLE_AVOIDANCE_RECOVERY active cause=elapsed=1000ns', `7000,w,SUP,supervisor,,,0,function ${'F'.repeat(2000)} started`].join('\n') + '\n');
    await expect.poll(() => page.locator('.monitor-sources option[value="dir:hostile-run"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption('dir:hostile-run');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('2 CSV log(s) in hostile-run');
    await expect.poll(() => page.locator('.monitor-fn[data-function="SUP.constructor"]').textContent()).toMatch(/^constructor\(\) \(not in the model\) — running since/);
    expect(await rule(page, 'SUP.constructor.__proto__').getAttribute('data-active')).toBe('true');
    expect(await rule(page, 'SUP.action.toString').getAttribute('data-active')).toBe('true');
    // ORD's log ends with no exit record: its schema `__proto__` is shown ended at ORD's last record, with the mark that says so
    expect(await page.locator('.monitor-schema').allTextContents()).toEqual([]);
    expect(await page.evaluate(() => (window.__ide.monitor.current!.marks)
      .filter((m) => m.kind === 'schema' && m.label.startsWith('ORD gone')).map((m) => m.where))).toEqual(['__proto__']);
    expect(await page.evaluate(() => ({} as any).by ?? null)).toBeNull();
    const longRule = rule(page, 'SUP.action.OBSTACLE_AVOIDANCE_RECOVERY').locator('.rule-name');
    expect(await longRule.evaluate((e) => e.scrollWidth <= e.clientWidth)).toBe(true);
    const sups = page.locator('.monitor-sups');
    expect(await sups.evaluate((e) => e.scrollWidth <= e.clientWidth)).toBe(true);
    expect(await page.locator(`.monitor-fn[data-function="SUP.${'F'.repeat(2000)}"]`).getAttribute('title')).toMatch(/^F{2000}\(\) \(not in the model\) — running since/);
    expect(errors).toEqual([]);
  });

  it('a workspace log folder is read again when picked again and when its logs change; a new one is listed at once', async () => {
    const { page } = s;
    await monitorShown(page);
    const dir = join(s.workspace, 'growing-run');
    mkdirSync(dir);
    const lines = ['mono_ns,wall_time,module,event,peer,port,size,detail', '1000000,w,SUP,supervisor,,,0,function action started'];
    writeFileSync(join(dir, 'SUP_1-Jan-2026-00h00m00s.csv'), lines.join('\n') + '\n');
    // listed while the Monitor stays open (no close and reopen)
    await expect.poll(() => page.locator('.monitor-sources option[value="dir:growing-run"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption('dir:growing-run');
    await expect.poll(() => page.evaluate(() => window.__ide.monitor.current?.recordCount)).toBe(1);
    // the run writes on: the shown folder is read again
    lines.push('2000000,w,SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000000ns');
    writeFileSync(join(dir, 'SUP_1-Jan-2026-00h00m00s.csv'), lines.join('\n') + '\n');
    await expect.poll(() => page.evaluate(() => window.__ide.monitor.current?.recordCount), { timeout: 15_000 }).toBe(2);
    await expect.poll(() => rule(page, 'SUP.action.FIRST').getAttribute('data-active')).toBe('true');
    // a log added while another run is shown: read when the folder is picked again
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('9 CSV log(s) in recorded');
    writeFileSync(join(dir, 'ORD_1-Jan-2026-00h00m00s.csv'), 'mono_ns,wall_time,module,event,peer,port,size,detail\n3000000,w,ORD,scheduler,,,0,activate schemaCommande1\n');
    // the watcher's change reaches the page: the tree lists the new log (the Monitor hears of it in the same update)
    await expect.poll(() => page.evaluate(() => (window as any).__ide.workspace.hasFile('growing-run/ORD_1-Jan-2026-00h00m00s.csv')), { timeout: 15_000 }).toBe(true);
    await page.locator('.monitor-sources').selectOption('dir:growing-run');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('2 CSV log(s) in growing-run');
    expect(await page.evaluate(() => window.__ide.monitor.current?.recordCount)).toBe(3);
  }, 60_000);

  it('a shown workspace log folder a run keeps writing is read again 1 s after a change, not only once the writes pause: the view catches up while they go on', async () => {
    const { page } = s;
    await monitorShown(page);
    const dir = join(s.workspace, 'busy-run');
    mkdirSync(dir);
    const header = 'mono_ns,wall_time,module,event,peer,port,size,detail';
    // a large log beside the one written to (a read takes a while: changes come while it goes on)
    const ord = [header, '999000000,w,ORD,scheduler,,,0,activate S'];
    for (let i = 0; i < 200_000; i++) ord.push(`${1_000_000_000 + i * 1_000_000},w,ORD,ord_release,CTL,,0,schema=S cycle=${i} tick_ns=${1_000_000_000 + i * 1_000_000} release_ns=${1_000_000_100 + i * 1_000_000} release=${i + 1}`);
    writeFileSync(join(dir, 'ORD_1-Jan-2026-00h00m00s.csv'), ord.join('\n') + '\n');
    const sup = join(dir, 'SUP_1-Jan-2026-00h00m00s.csv');
    writeFileSync(sup, `${header}\n1000000,w,SUP,supervisor,,,0,function action started\n`);
    await expect.poll(() => page.locator('.monitor-sources option[value="dir:busy-run"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption('dir:busy-run');
    const records = () => page.evaluate(() => window.__ide.monitor.current?.recordCount as number | undefined);
    await expect.poll(records, { timeout: 30_000 }).toBe(200_002);
    // the run writes a line every 0.3 s, without a pause of 1 s, for 20 s
    let n = 0;
    const writer = setInterval(() => appendFileSync(sup, `${2_000_000 + n++},w,SUP,user,,,0,tick\n`), 300);
    try {
      // read again while the writes go on (before: each change put the re-read off by 1 s more, so it never came)
      await expect.poll(records, { timeout: 12_000, interval: 250 }).toBeGreaterThan(200_002);
      const caughtUp = (await records())!;
      // and again: it follows the end
      await expect.poll(records, { timeout: 8_000, interval: 250 }).toBeGreaterThan(caughtUp);
    } finally {
      clearInterval(writer);
    }
  }, 90_000);

  it('a reload brings back the workspace folder or trace file the Monitor showed, read again; a Monitor hidden before the reload stays hidden', async () => {
    const { page } = s;
    const reloaded = async () => {
      await page.reload();
      await page.waitForSelector('body[data-ready=true]', { timeout: 60_000 });
    };
    await monitorShown(page);
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('9 CSV log(s) in recorded');
    const marks = await marksOf(page);
    await reloaded();
    // before, the Monitor was closed after a reload (and, opened, said "No run yet")
    await page.locator('.side-pane .monitor-view').waitFor({ timeout: 30_000 });
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 }).toBe('9 CSV log(s) in recorded');
    expect(await page.locator('.monitor-sources').inputValue()).toBe('dir:recorded');
    expect(await marksOf(page)).toEqual(marks);
    // a trace file, the same
    const records = parseTrace(readdirSync(FIXTURE).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') })));
    writeFileSync(join(s.workspace, 'reload.jsonl'), records.map((r) => JSON.stringify(r)).join('\n') + '\n');
    await expect.poll(() => page.locator('.monitor-sources option[value="file:reload.jsonl"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption('file:reload.jsonl');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe(`Trace file reload.jsonl · ${records.length} record(s)`);
    await reloaded();
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 }).toBe(`Trace file reload.jsonl · ${records.length} record(s)`);
    expect(await marksOf(page)).toEqual(marks);
    // hidden, then reloaded: not shown again
    await page.locator('#btn-monitor').click();
    await expect.poll(() => page.locator('.side-pane').isHidden()).toBe(true);
    await reloaded();
    await page.waitForTimeout(1000);
    expect(await page.locator('.side-pane .monitor-view').count()).toBe(0);
    // a kept folder gone from the workspace since: nothing opens, nothing is said wrong
    await page.evaluate(() => sessionStorage.setItem('contract-studio:monitor-replay', 'dir:no-such-folder'));
    await reloaded();
    await page.waitForTimeout(1000);
    expect(await page.locator('.side-pane .monitor-view').count()).toBe(0);
    expect(await page.evaluate(() => sessionStorage.getItem('contract-studio:monitor-replay'))).toBeNull();
  }, 120_000);

  it('a periodic schema with more deadline misses than it lists says the list holds the last ones', async () => {
    const { page } = s;
    await monitorShown(page);
    const dir = join(s.workspace, 'many-misses');
    mkdirSync(dir, { recursive: true });
    const ord = ['mono_ns,wall_time,module,event,peer,port,size,detail', '1000000,w,ORD,scheduler,,,0,activate S'];
    for (let c = 0; c < 9; c++) ord.push(`${2_000_000 + c * 1_000_000},w,ORD,ord_deadline_miss,,,0,schema=S cycle=${c} tick_ns=${1_000_000 + c * 1_000_000}`);
    writeFileSync(join(dir, 'ORD_1-Jan-2026-00h00m00s.csv'), ord.join('\n') + '\n');
    await expect.poll(() => page.locator('.monitor-sources option[value="dir:many-misses"]').count(), { timeout: 10_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption('dir:many-misses');
    await page.locator('.monitor-view').focus();
    await page.keyboard.press('End');
    await expect.poll(() => periodic(page, 'S').getAttribute('data-misses')).toBe('9');
    // before, 5 chips under "9 deadline miss(es)", and nothing said of the 4 others
    expect(await periodic(page, 'S').locator('.monitor-misses > *').allTextContents()).toEqual([
      'the last 5 of 9 deadline misses:', ...[4, 5, 6, 7, 8].map((c) => expect.stringMatching(new RegExp(`^ORD:0 cycle ${c} at `))),
    ]);
  });

  it('keyboard: Open Monitor (Alt+Shift+M) opens it and puts the focus in it, again keeps it open; the brackets step marks from the slider', async () => {
    const { page } = s;
    await monitorShown(page);
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('9 CSV log(s) in recorded');
    await page.locator('#btn-monitor').click(); // hidden
    await expect.poll(() => page.locator('.side-pane').isHidden()).toBe(true);
    await openFile(page, 'supervisor.contract');
    await page.keyboard.press('Alt+Shift+M');
    await page.locator('.side-pane .monitor-view').waitFor();
    await expect.poll(() => page.evaluate(() => !!document.activeElement?.closest('.monitor-view'))).toBe(true);
    // "Open", not toggle: pressed again it stays open, the focus in it
    await page.keyboard.press('Alt+Shift+M');
    await page.waitForTimeout(300);
    expect(await page.locator('.side-pane .monitor-view').isVisible()).toBe(true);
    expect(await page.evaluate(() => !!document.activeElement?.closest('.monitor-view'))).toBe(true);
    // [ and ] from the time slider
    const marks = await marksOf(page);
    await page.locator('.monitor-slider').focus();
    await page.keyboard.press('Home');
    await seek(page, 0);
    await page.locator('.monitor-slider').focus();
    await page.keyboard.press(']');
    const firstMark = marks.find((m) => m.t > 0)!.t;
    await expect.poll(async () => Number(await page.locator('.monitor-view').getAttribute('data-t'))).toBe(firstMark);
    await page.keyboard.press(']');
    const second = marks.find((m) => m.t > firstMark)!.t;
    await expect.poll(async () => Number(await page.locator('.monitor-view').getAttribute('data-t'))).toBe(second);
    expect(await markSaid(page)).toBe(saidOf(marks, second));
    await page.keyboard.press('[');
    await expect.poll(async () => Number(await page.locator('.monitor-view').getAttribute('data-t'))).toBe(firstMark);
    expect(await markSaid(page)).toBe(saidOf(marks, firstMark));
    expect(await page.evaluate(() => document.activeElement?.classList.contains('monitor-slider'))).toBe(true);
    // moved otherwise (Home), nothing is said; at the start, no previous mark: said so
    await page.keyboard.press('Home');
    await expect.poll(async () => Number(await page.locator('.monitor-view').getAttribute('data-t'))).toBe(0);
    expect(await markSaid(page)).toBe('');
    await page.keyboard.press('[');
    await expect.poll(() => markSaid(page)).toBe('No previous mark: the start of the run');
  });

  it('looks: the panel scrolled past the diagram\'s top, what is seen there is the diagram, not its toolbar; a narrow Monitor keeps its cursor buttons on one line', async () => {
    const { page } = s;
    await monitorShown(page);
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await page.locator('.monitor-view .arch-svg').waitFor();
    await page.waitForTimeout(500);
    // the panel scrolled so that the diagram passes its top: the toolbar went with the view's top (it stuck there, over the diagram)
    const seen = await page.evaluate(() => {
      const body = document.querySelector('.monitor-body') as HTMLElement;
      const canvas = document.querySelector('.monitor-diagram .arch-canvas') as HTMLElement;
      body.scrollTop = (document.querySelector('.monitor-diagram') as HTMLElement).offsetTop + 120;
      const top = body.getBoundingClientRect().top;
      const r = canvas.getBoundingClientRect();
      const hits = [0.2, 0.5, 0.8].flatMap((fx) => [2, 20].map((dy) => document.elementFromPoint(r.left + r.width * fx, top + dy)));
      return { inCanvas: hits.map((e) => !!e && canvas.contains(e)), paneAbove: r.top < top };
    });
    expect(seen.paneAbove).toBe(true);
    expect(seen.inCanvas).toEqual([true, true, true, true, true, true]);
    await shot(page, 'monitor-05-diagram-scrolled');
    await page.evaluate(() => ((document.querySelector('.monitor-body') as HTMLElement).scrollTop = 0));
    for (const width of [300, 340, 420, 520]) {
      await page.evaluate((w) => { const sp = document.querySelector('.side-pane') as HTMLElement; sp.style.width = `${w}px`; sp.style.flex = `0 0 ${w}px`; }, width);
      await page.waitForTimeout(100);
      const tops = await page.evaluate(() => ['#monitor-prev', '#monitor-follow', '#monitor-play', '#monitor-next'].map((id) => Math.round((document.querySelector(id) as HTMLElement).getBoundingClientRect().top)));
      expect(new Set(tops).size, `${width}px: ${tops}`).toBe(1);
    }
    await shot(page, 'monitor-06-narrow');
    await page.evaluate(() => { const sp = document.querySelector('.side-pane') as HTMLElement; sp.style.width = ''; sp.style.flex = ''; });
  });

  it('Timeline: finds the logs `contract run` writes (DIR/logs), takes the focus (Alt+Shift+T), and its axis labels do not overlap', async () => {
    const { page } = s;
    await page.locator('#btn-timeline').click();
    await page.locator('.timeline-view').waitFor();
    await expect.poll(() => page.locator('.timeline-canvas').textContent()).toContain('No CSV logs in logs/ nor in src-gen/generated/architecture/logs/ yet.');
    // `contract run DIR` writes DIR/logs (packages/cli run.ts), the runs before in logs/previous/
    mkdirSync(join(s.workspace, 'logs', 'previous', 'run-1'), { recursive: true });
    for (const [m, off] of [['MSA', 0], ['MSC', 200_000]] as const) {
      const rows = ['mono_ns,wall_time,module,event,peer,port,size,detail'];
      for (let k = 0; k < 1237; k++) { const t = 1_000_000_000 + k * 10_000_000 + off; rows.push(`${t},w,${m},run_started,ORD,,0,`, `${t + 150_000},w,${m},run_finished,,,0,`); }
      writeFileSync(join(s.workspace, 'logs', `${m}_1-Jan-2026-00h00m00s.csv`), rows.join('\n') + '\n');
    }
    writeFileSync(join(s.workspace, 'logs', 'previous', 'run-1', 'OLD_1-Jan-2026-00h00m00s.csv'), 'mono_ns,wall_time,module,event,peer,port,size,detail\n1,w,OLD,run_started,ORD,,0,\n');
    await openFile(page, 'supervisor.contract');
    await page.keyboard.press('Alt+Shift+T');
    await expect.poll(() => page.evaluate(() => document.activeElement?.classList.contains('timeline-canvas'))).toBe(true);
    await page.locator('.timeline-view button', { hasText: 'Reload logs' }).click();
    await expect.poll(() => page.locator('.lane-label').allTextContents(), { timeout: 10_000 }).toEqual(['MSA', 'MSC']);
    expect(await page.locator('.timeline-source option:checked').textContent()).toBe('Local logs: logs/');
    for (const zoom of ['0', '3']) {
      await page.locator('.timeline-view input.zoom').fill(zoom);
      for (const at of ['start', 'end']) {
        const overlaps = await page.evaluate((at) => {
          const c = document.querySelector('.timeline-canvas') as HTMLElement;
          c.scrollLeft = at === 'end' ? c.scrollWidth : 0;
          return new Promise<string[]>((done) => requestAnimationFrame(() => requestAnimationFrame(() => {
            const labels = [...document.querySelectorAll('.timeline-svg .period-label')].map((e) => ({ text: e.textContent, r: e.getBoundingClientRect() }));
            const svg = document.querySelector('.timeline-svg')!.getBoundingClientRect();
            const out: string[] = [];
            labels.forEach((a, i) => {
              if (a.r.right > svg.right + 0.5) out.push(`${a.text} cut at the right edge`);
              for (const b of labels.slice(i + 1)) if (a.r.left < b.r.right && b.r.left < a.r.right && a.r.top < b.r.bottom && b.r.top < a.r.bottom) out.push(`${a.text} / ${b.text}`);
            });
            done(out);
          })));
        }, at);
        expect(overlaps, `zoom ${zoom}, ${at}`).toEqual([]);
      }
    }
    await shot(page, 'timeline-contract-run-logs');
  });

  it('a job that ended — cancelled, failed, or its service gone — shows as ended with how, nowhere as live', async () => {
    const { page } = s;
    // the job's trace stream as the build service sends it (trace events, then its end), served by this test
    const lines = readdirSync(FIXTURE).flatMap((file) => readFileSync(join(FIXTURE, file), 'utf8').split('\n').map((text, i) => ({ file, line: i + 1, text })))
      .filter((l) => /^\d+,/.test(l.text)).sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!))).slice(0, 60);
    const server = new WebSocketServer({ port: 0, host: '127.0.0.1' });
    await new Promise((r) => server.once('listening', r));
    const ends: Record<string, unknown> = { cancelled: { ok: false, message: 'cancelled' }, failed: { ok: false, message: 'run: MAA exited with status 3' } };
    server.on('connection', (ws, req) => {
      const job = /\/api\/jobs\/([^/]+)\//.exec(req.url ?? '')![1]!;
      if (job === 'killed' && req.url!.includes('after=')) return ws.terminate(); // the service is gone: every reconnection refused
      ws.send(JSON.stringify({ type: 'trace', seq: 1, t: Date.now(), ...encodeTraceRecords(lines) }));
      if (job === 'killed') setTimeout(() => ws.terminate(), 300);
      else setTimeout(() => ws.send(JSON.stringify({ type: 'end', seq: 2, t: Date.now(), result: ends[job] })), 300);
    });
    const url = (job: string) => `ws://127.0.0.1:${(server.address() as { port: number }).port}/api/jobs/${job}/ws?trace=only`;
    try {
      for (const [job, outcome] of [['cancelled', 'cancelled'], ['failed', 'failed: run: MAA exited with status 3'], ['killed', 'connection to the build service lost']] as const) {
        await page.evaluate(([job, url]) => window.__ide.monitor.followLive(job, url), [job, url(job)]);
        // (the lost stream also says, as before, that the trace is not whole)
        const label = `Build & Run job ${job} · ended: ${outcome}${job === 'killed' ? ' (trace not whole: lost the connection to the build service: the trace stops here (if the build service is still there when the job ends, the Monitor shows the run from its CSV logs))' : ''}`;
        await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 30_000 }).toBe(label);
        // nowhere live: the header, the run list, the time line, the follow button
        expect(await page.locator('.monitor-view').getAttribute('data-mode')).toBe('replay');
        // the run list's entry: the label, shortened at a word when long, whole in its title
        const entry = page.locator('.monitor-sources option:checked');
        expect([await entry.getAttribute('title') ?? await entry.textContent(), label.startsWith(((await entry.textContent()) ?? '').replace(/…$/, ''))]).toEqual([label, true]);
        expect(await page.locator('.monitor-sources option').allTextContents()).not.toContain(`Build & Run job ${job} · live`);
        await expect.poll(() => page.locator('.monitor-time').textContent()).toMatch(/^\+\d+\.\d{6} s \/ \+\d+\.\d{6} s$/);
        expect(await page.locator('#monitor-follow').textContent()).toBe('⇥ End');
        // what the stream brought is still shown: FIRST became active in those records
        expect(await page.evaluate(() => window.__ide.monitor.current!.recordCount)).toBe(lines.length);
      }
      await shot(page, 'monitor-04-ended-job');
    } finally {
      await new Promise((r) => server.close(r));
    }
  }, 90_000);

  it.skipIf(!canBuild)('Build & Run of the tutorial: live while it runs (when the service streams the trace), then the job replayed, same story at the same times', async () => {
    const { page } = s;
    await openFile(page, 'supervisor.contract');
    await page.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 4, start: 'GLB.mission(consigne={1.0,2.0,3.0})' })));
    // a page just opened, Build & Run pressed at once: the Monitor is made before the language
    // server has built the model, and reads the schemas again once it has (PERIOD, CRITICAL_DELAY)
    const cdp = await page.context().newCDPSession(page);
    await cdp.send('Network.setCacheDisabled', { cacheDisabled: true }); // a cold load, as a first visit
    await page.reload();
    await page.waitForSelector('#btn-run:not([disabled])');
    // the page is whole (its language server has built the workspace: __ide is set then), as openIde waits
    await page.waitForSelector('body[data-ready=true]', { timeout: 60_000 });
    await cdp.send('Network.setCacheDisabled', { cacheDisabled: false });
    await cdp.detach();
    // every event the page's own sockets receive, by type: the trace goes to the live run's worker only
    await page.evaluate(() => {
      const w = window as any;
      w.__pageEvents = {} as Record<string, number>;
      const Native = WebSocket;
      w.WebSocket = class extends Native {
        constructor(url: string | URL, protocols?: string | string[]) {
          super(url, protocols);
          this.addEventListener('message', (m) => {
            // a frame is one event, or several (`?batch=1`: a JSON array of them)
            let data: unknown;
            try {
              data = JSON.parse(String(m.data));
            } catch {
              data = undefined;
            }
            for (const e of Array.isArray(data) ? data : [data]) {
              const type = typeof (e as { type?: unknown })?.type === 'string' ? (e as { type: string }).type : '?';
              w.__pageEvents[type] = (w.__pageEvents[type] ?? 0) + 1;
            }
          });
        }
      };
    });
    await page.locator('#btn-run').click();
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-mode'), { timeout: 10_000 }).toBe('live');
    const jobId = /^Build & Run job (\S+) · live$/.exec((await page.locator('.monitor-source').textContent())!)![1]!;
    const running = () => page.locator('#status-job').getAttribute('data-status');
    if (liveChannel) {
      // during the run, following it live: FIRST lit, then SECOND lit after MAA's "disconnected"
      // with that cause, schemaCommande1 activated by it and released — all while the job runs
      await expect.poll(() => rule(page, 'SUP.action.FIRST').getAttribute('data-active'), { timeout: 180_000 }).toBe('true');
      expect(await rule(page, 'SUP.action.FIRST').getAttribute('data-cause')).toBe('elapsed=1000000ns');
      expect(await running()).toBe('running');
      await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-active'), { timeout: 10_000 }).toBe('true');
      expect(await rule(page, 'SUP.action.SECOND').getAttribute('data-cause')).toBe('MAA:2 value="disconnected"');
      expect(await rule(page, 'SUP.action.FIRST').getAttribute('data-active')).toBe('false');
      await expect.poll(() => page.locator('.monitor-schema').allTextContents(), { timeout: 5000 }).toEqual(['● schemaCommande1 (periodic) ← SUP.action.SECOND']);
      await expect.poll(async () => Number(await periodic(page, 'schemaCommande1').getAttribute('data-releases')), { timeout: 5000 }).toBeGreaterThan(0);
      await expect.poll(() => periodic(page, 'schemaCommande1').locator('.monitor-pname').textContent(), { timeout: 5000 }).toBe('schemaCommande1 · PERIOD 1s · CRITICAL_DELAY 1s');
      expect(await running()).toBe('running');
      expect(await page.locator('.monitor-time').textContent()).toContain('· live');
      await shot(page, 'monitor-02b-live-tutorial-during-run');
    }
    await expect.poll(running, { timeout: 180_000 }).toBe('succeeded');
    await expect.poll(() => page.evaluate(() => window.__ide.monitor.lastLive?.ended)).toBe(true); // its worker has folded the whole stream
    const streamed = await page.evaluate(() => window.__ide.monitor.lastLive?.recordCount ?? 0);
    // the page's main thread got the job's log, status and end, and not one trace event: its worker took them
    const pageEvents = await page.evaluate(() => (window as any).__pageEvents as Record<string, number>);
    expect(pageEvents['line'] ?? 0).toBeGreaterThan(0);
    expect(pageEvents['end']).toBe(1);
    expect(pageEvents['trace'] ?? 0).toBe(0);
    let liveMarks: MarkJson[] = [];
    if (streamed > 0) {
      // the live trace arrived (trace-live producer): the story as it was streamed
      await page.locator('.monitor-sources').selectOption(`live:${jobId}`);
      await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe(`Build & Run job ${jobId} · as streamed · ended: succeeded`);
      liveMarks = await marksOf(page);
      await checkTutorialStory(page);
      await shot(page, 'monitor-02-live-tutorial');
    }
    // the job's CSV logs: the recorded run
    await expect.poll(() => page.locator(`.monitor-sources option[value="job:${jobId}"]`).count(), { timeout: 20_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption(`job:${jobId}`);
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toMatch(/· CSV logs$/);
    const { second } = await checkTutorialStory(page);
    await shot(page, 'monitor-03-job-replay-tutorial');
    await seek(page, second.t + 1.5e9);
    await rule(page, 'SUP.action.SECOND').focus();
    await docShot(page, 'doc-monitor-tutorial', ['growing-run', 'hostile-run', 'junk-run', 'logs', 'long-run', 'recorded', 'recorded.jsonl']);
    const replayMarks = await marksOf(page);
    if (liveChannel) {
      expect(streamed).toBeGreaterThan(0);
      // the same story at the same times: every mark (rules, functions, schemas, misses) equal
      expect(replayMarks).toEqual(liveMarks);
    }
    // play back from just before SECOND: the cursor moves through it in real time
    await seek(page, second.t - 200e6);
    await page.locator('#monitor-play').click();
    await expect.poll(() => rule(page, 'SUP.action.SECOND').getAttribute('data-active'), { timeout: 5000 }).toBe('true');
    console.log(`[monitor e2e] live channel: ${liveChannel}; live records streamed: ${streamed}; replay marks: ${replayMarks.length}`);

    // many runs later (here: 7 recorded runs of other jobs, one an unknown one), the page keeps 6
    // recorded runs: this job's is let go, listed still, and read again from the build service
    // when picked, the same story; one the service does not know is said and dropped
    await page.locator('.monitor-sources').selectOption('dir:recorded');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toBe('9 CSV log(s) in recorded');
    const fixture = readdirSync(FIXTURE).map((name) => ({ name, text: readFileSync(join(FIXTURE, name), 'utf8') }));
    for (let i = 0; i < 7; i++) {
      await page.evaluate(({ id, files }) => window.__ide.monitor.showRecorded(id, { label: id, files, problems: [] }), { id: `j-other-${i}`, files: fixture });
    }
    const option = (id: string) => page.locator(`.monitor-sources option[value="job:${id}"]`);
    await expect.poll(() => option(jobId).textContent()).toBe(`Build & Run job ${jobId} · CSV logs · read again when picked`);
    expect(await option('j-other-0').textContent()).toBe('Build & Run job j-other-0 · CSV logs · read again when picked');
    expect(await option('j-other-6').textContent()).toBe('Build & Run job j-other-6 · CSV logs');
    await page.locator('.monitor-sources').selectOption(`job:${jobId}`);
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 20_000 }).toBe(`Build & Run job ${jobId} · CSV logs`);
    expect(await marksOf(page)).toEqual(replayMarks);
    await page.locator('.monitor-sources').selectOption('job:j-other-0');
    await page.locator('.toast', { hasText: 'Build & Run job j-other-0: its logs could not be read again' }).waitFor({ timeout: 10_000 });
    await expect.poll(() => option('j-other-0').count()).toBe(0);
  }, 240_000);
});

describe.skipIf(!canBuild)('Monitor on examples/mobile-robot with a velocity-loop module sleeping past CRITICAL_DELAY', () => {
  let s: Session;
  const VEL = 'src-gen/generated/architecture/modules/VEL_mod/module.c';
  beforeAll(async () => {
    s = await startSession({ example: MOBILE_ROBOT });
    // VEL (velocityLoop, PERIOD = CRITICAL_DELAY = 10 ms) sleeps 100 ms once, 2.2 s after its first
    // run: in autonomous mode (the operator hands over at 1.5 s), before the obstacle (3.0 s)
    const path = join(s.workspace, VEL);
    const code = readFileSync(path, 'utf8');
    const edited = code.replace(/(PROTECTED REGION ID\(protect_exec_VEL\) ENABLED START\*\/)/, `$1
    {
        static struct timespec first;
        static int slept;
        struct timespec now;
        clock_gettime(CLOCK_MONOTONIC, &now);
        if (!first.tv_sec) first = now;
        if (!slept && (now.tv_sec - first.tv_sec) * 1000 + (now.tv_nsec - first.tv_nsec) / 1000000 > 2200) {
            struct timespec late = { 0, 100000000 };
            slept = 1;
            printf("VEL: test sleeps 100 ms past CRITICAL_DELAY\\n");
            ContractLog("test_sleep", "", -1, 0, "100 ms past CRITICAL_DELAY");
            nanosleep(&late, NULL);
        }
    }`);
    expect(edited).not.toBe(code);
    writeFileSync(path, edited);
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('shows the deadline miss as ORD:0 on the cycle VEL overran, and MIS reacting (AUTO ends on ORD:0, STOP)', async () => {
    const { page } = s;
    await openFile(page, 'mission.contract');
    await page.evaluate(() => localStorage.setItem('contract-studio:run-settings', JSON.stringify({ duration: 4 })));
    await page.locator('#btn-run').click();
    await expect.poll(() => page.locator('#status-job').getAttribute('data-status'), { timeout: 240_000 }).toBe('succeeded');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 20_000 }).toMatch(/· (CSV logs|as streamed.*)$/);
    if (!(await page.locator('.monitor-source').textContent())!.endsWith('CSV logs')) {
      const i = await page.locator('.monitor-sources option').evaluateAll((os) => os.findIndex((o) => (o as HTMLOptionElement).value.startsWith('job:')));
      await page.locator('.monitor-sources').selectOption({ index: i });
    }
    const marks = await marksOf(page);
    // ORD's own records of the run (its CSV log, collected by the build service)
    const jobId = (await page.locator('.monitor-source').textContent())!.match(/job (\S+)/)![1]!;
    const ordLog = await page.evaluate(async (id) => {
      const base = `/api/jobs/${encodeURIComponent(id)}/artifacts`;
      const listing = await (await fetch(base)).json();
      const ord = listing.artifacts.files.find((f: { name: string }) => f.name.startsWith('ORD'));
      return (await fetch(`${base}/${encodeURIComponent(ord.name)}`)).text();
    }, jobId);
    const field = (l: string, k: string) => Number(new RegExp(`${k}=(\\d+)`).exec(l)![1]);
    const ordLines = ordLog.split('\n').filter((l) => l.includes('schema=velocityLoop'));
    const ordMisses = ordLines.filter((l) => l.includes(',ord_deadline_miss,')).map((l) => ({ cycle: field(l, 'cycle'), tick: field(l, 'tick_ns') }));
    // every miss ORD recorded is on the monitor, on its cycle, in order (a loaded machine may add misses of its own)
    const shownMisses = marks.filter((m) => m.kind === 'miss' && m.where === 'velocityLoop');
    expect(shownMisses.map((m) => Number(/cycle (\d+)/.exec(m.label)![1]))).toEqual(ordMisses.map((m) => m.cycle));
    // the injected one: the VEL release that VEL itself took 90 ms or more to finish, from ORD's release
    // to its ack (response_ns counts from the cycle's tick: a cycle whose WHL or ODO a loaded machine
    // stalled has a VEL ack that late too, and its miss rightly names them). ORD logs that ack as
    // ord_finished, or as a late ack when a supervisor re-activated the schema meanwhile (the reaction
    // to the miss can do that)
    const mono = (l: string) => Number(l.split(',')[0]);
    const releases = new Map(ordLines.filter((l) => l.includes(',ord_release,VEL,')).map((l) => [field(l, 'release'), { tick: field(l, 'tick_ns'), cycle: field(l, 'cycle'), sent: field(l, 'release_ns') }]));
    const finished = ordLines.filter((l) => l.includes(',ord_finished,VEL,')).map((l) => ({ l, r: releases.get(field(l, 'release')) }))
      .filter(({ l, r }) => r && r.tick + field(l, 'response_ns') - r.sent >= 90e6).map(({ r }) => r);
    const late = ordLog.split('\n').filter((l) => l.includes('late ack: VEL finished release #')).map((l) => ({ l, r: releases.get(Number(/release #(\d+)/.exec(l)![1])) }))
      .filter(({ l, r }) => r && mono(l) - r.sent >= 90e6).map(({ r }) => r);
    const slept = [...finished, ...late][0];
    expect(slept, 'VEL slept 100 ms in one release').toBeTruthy();
    const index = ordMisses.findIndex((m) => m.tick === slept!.tick);
    expect(index).toBeGreaterThanOrEqual(0);
    const miss = shownMisses[index]!;
    const cycle = ordMisses[index]!.cycle;
    expect(cycle).toBe(slept!.cycle);
    // VEL's own record of its sleep (ContractLog under a name of its own) is a mark of the timeline, by the miss
    const own = marks.filter((m) => m.kind === 'user');
    expect(own.map((m) => `${m.where} ${m.label}`)).toEqual(['VEL test_sleep: 100 ms past CRITICAL_DELAY']);
    expect(Math.abs(miss.t - own[0]!.t)).toBeLessThan(150e6);
    // the cursor on it: the panel lists it, ORD:0 on that cycle at that time
    await seek(page, miss.t + 1);
    await expect.poll(() => periodic(page, 'velocityLoop').getAttribute('data-misses')).toBe(String(index + 1));
    expect(await periodic(page, 'velocityLoop').locator('.miss').allTextContents()).toContain(`ORD:0 cycle ${cycle} at +${(miss.t / 1e9).toFixed(6)} s`);
    // the miss names what its cycle was still waiting for: VEL, asleep (as `contract trace` says it), in its label and tooltip;
    // on a loaded host ORD itself may wake late, take VEL's completion first, and say it released the cycle late
    // (from a tenth of its CRITICAL_DELAY of 10 ms on; with less than a tenth of it left, ORD late and no module blamed)
    expect(miss.label).toMatch(/ \((not finished: ([A-Z]+, )*VEL(, [A-Z]+)*(; ORD released the cycle [\d.]+ m?s after its tick, of CRITICAL_DELAY 10 ms)?|not finished: [A-Z]+(, [A-Z]+)*; ORD released the cycle [\d.]+ m?s after its tick, of CRITICAL_DELAY 10 ms|ORD late: it released the cycle [\d.]+ m?s after its tick, (past|[\d.]+ [mµ]?s before) CRITICAL_DELAY 10 ms(, leaving [A-Z, ]+ (no time|[\d.]+ [mµ]?s))?|held: nothing released, VEL still runs an earlier release|(not finished: [A-Z, ]+; )?[A-Z]+ finished at \+[\d.]+ ms \(its (ack sent|run finished)\), ORD had not read it at the deadline, [\d.]+ [mµ]?s later: ORD was late( reading it)?(; ORD released the cycle [\d.]+ m?s after its tick, of CRITICAL_DELAY 10 ms)?)\)$/);
    const chip = periodic(page, 'velocityLoop').locator(`.miss[data-cycle="${cycle}"]`).last();
    expect(await chip.getAttribute('title')).toBe(`${miss.label} (click: the cursor goes there)`);
    // the miss is a button: a click takes the cursor to it (from a nanosecond past it)
    await chip.click();
    await expect.poll(() => page.locator('.monitor-view').getAttribute('data-t')).toBe(String(Math.round(miss.t)));
    // the reaction to the first miss while MIS.mission.AUTO is active (autonomous mode, from 1.5 s)
    const story = JSON.stringify(marks.map((m) => `${(m.t / 1e9).toFixed(3)} ${m.where} ${m.label}`));
    const autoOn = marks.find((m) => m.kind === 'rule' && m.where === 'MIS' && m.label.startsWith('mission.AUTO active'))!;
    expect(autoOn, story).toBeTruthy();
    const reacted = shownMisses.find((m) => m.t >= autoOn.t)!;
    expect(reacted, story).toBeTruthy();
    // the supervisor's reaction: MIS.mission.AUTO ends on ORD:0 (velocityLoop), STOP takes over (endof(AUTO))
    const autoOff = marks.find((m) => m.kind === 'rule' && m.where === 'MIS' && m.t >= reacted.t && m.label.startsWith('mission.AUTO inactive'))!;
    expect(autoOff?.label, story).toBe('mission.AUTO inactive ← ORD:0 = "velocityLoop"');
    const stop = marks.find((m) => m.kind === 'rule' && m.where === 'MIS' && m.t >= autoOff.t && m.label.startsWith('mission.STOP active'))!;
    expect(stop?.label, story).toContain('endof(AUTO)');
    await seek(page, stop.t);
    await expect.poll(() => rule(page, 'MIS.mission.STOP').getAttribute('data-active')).toBe('true');
    expect(await rule(page, 'MIS.mission.AUTO').getAttribute('data-cause')).toBe('ORD:0 value="velocityLoop"');
    expect(await rule(page, 'MIS.mission.AUTO').getAttribute('data-active')).toBe('false');
    await shot(page, 'monitor-04-mobile-robot-deadline-miss');
    await docShot(page, 'doc-monitor-mobile-robot');
  }, 300_000);
});

describe('Monitor in a workspace of two projects', () => {
  let s: Session;
  beforeAll(async () => {
    s = await startSession({ empty: true });
    cpSync(TUTORIAL, join(s.workspace, 'tut'), { recursive: true, filter: (src) => !/[\/]logs$/.test(src) });
    cpSync(MOBILE_ROBOT, join(s.workspace, 'mob'), { recursive: true, filter: (src) => !/[\/]logs$/.test(src) });
    cpSync(FIXTURE, join(s.workspace, 'tut', 'logs'), { recursive: true });
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('replays a project\'s logs against that project\'s model, whichever project\'s file the editor shows', async () => {
    const { page } = s;
    // the active tab is the other project's: its model is not the run's
    const mobFile = readdirSync(join(s.workspace, 'mob')).find((f) => f.endsWith('.contract'))!;
    await openFile(page, `mob/${mobFile}`);
    await page.keyboard.press('Alt+Shift+M');
    await expect.poll(() => page.locator('.monitor-sources option[value="dir:tut/logs"]').count(), { timeout: 15_000 }).toBe(1);
    await page.locator('.monitor-sources').selectOption('dir:tut/logs');
    await expect.poll(() => page.locator('.monitor-source').textContent(), { timeout: 15_000 }).toMatch(/ in tut\/logs$/);
    // the model's supervisors read (for the run shown): the tutorial's, not the active tab's project
    await expect.poll(() => page.evaluate(() => window.__ide.monitor.symbols?.catalogue.size ?? 0), { timeout: 15_000 }).toBeGreaterThan(0);
    expect(await page.evaluate(() => [...window.__ide.monitor.symbols!.catalogue.keys()].sort())).toEqual(['GLB', 'SUP']);
    // SUP's rules are in its model (they were "not in the model", struck through), mobile-robot's MIS is not listed
    await expect.poll(() => page.locator('.monitor-sup[data-supervisor="SUP"] .monitor-sup-name').getAttribute('data-in-model'), { timeout: 15_000 }).toBe('true');
    await expect.poll(() => rule(page, 'SUP.action.FIRST').getAttribute('data-in-model')).toBe('true');
    expect(await page.locator('.monitor-sup[data-supervisor="MIS"]').count()).toBe(0);
    // the schemas the panel reads are the tutorial's, none of mobile-robot's
    const schemas = await page.evaluate(async () => ((await window.__ide.monitor.projectSchemas()) as { name: string }[]).map((x) => x.name).sort());
    expect(schemas).toEqual(['schemaCommande1', 'schemaCommande2', 'schemaReceptionMessage']);
  }, 120_000);
});
