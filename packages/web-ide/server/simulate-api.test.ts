/**
 * POST /api/simulate over HTTP on a copy of examples/tutorial: the real server, the real
 * simulator (native harness built with gcc on the real engine cores). The §4.7 story step by step,
 * a scenario file of the workspace, diagnostics instead of a run, the session token, and hostile
 * bodies answered with 4xx, never a crash. The simulators go in `sim/` of the build cache
 * (`$CONTRACT_CACHE_DIR` here: a folder of the test).
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { chmodSync, cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, realpathSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { startIdeServer, type IdeServer } from './ide-server.js';
import type { SimulateDiagnostic, SimulateResponse } from './api-types.js';
import { MAX_ITEMS_PER_ANSWER } from './simulate-api.js';
import { stepsToTrace } from '@contract-studio/simulator/trace';
import { MonitorModel } from '../src/monitor/monitor-model.js';
import { ScenarioSession } from '../src/simulate/scenario-session.js';

const TUTORIAL = resolve(__dirname, '../../../examples/tutorial');
let base: string;
let ide: IdeServer;
const savedCacheDir = process.env.CONTRACT_CACHE_DIR;

beforeAll(async () => {
  base = realpathSync(mkdtempSync(join(tmpdir(), 'ide-simulate-')));
  process.env.CONTRACT_CACHE_DIR = join(base, 'cache');
  cpSync(TUTORIAL, join(base, 'tutorial'), { recursive: true });
  symlinkSync('/etc/passwd', join(base, 'tutorial', 'scenarios', 'evil.scenario'));
  ide = await startIdeServer({ workspace: join(base, 'tutorial'), port: 0, buildService: false, distDir: join(base, 'no-dist') });
}, 60_000);
afterAll(async () => {
  if (savedCacheDir === undefined) delete process.env.CONTRACT_CACHE_DIR;
  else process.env.CONTRACT_CACHE_DIR = savedCacheDir;
  await ide?.close();
  rmSync(base, { recursive: true, force: true });
});

/** The answer: the run (200), else `{ error }`, with the `diagnostics` of a 422 (nothing ran). */
type Answer = SimulateResponse & { diagnostics?: SimulateDiagnostic[] };

async function post(body: unknown, token = ide.token): Promise<{ status: number; json: Answer }> {
  const res = await fetch(`${ide.url}/api/simulate`, {
    method: 'POST',
    headers: { 'content-type': 'application/json', 'x-contract-token': token },
    body: typeof body === 'string' ? body : JSON.stringify(body),
  });
  return { status: res.status, json: (await res.json()) as Answer };
}

// a step's record holds what happened up to it (the 1 ms timer too): its last change of the rule
const rule = (s: SimulateResponse['steps'][number] | undefined, name: string) => s?.rules.findLast((r) => r.rule === name);

describe('POST /api/simulate', () => {
  it('runs a session scenario: start SUP.action, FIRST at 1 ms, MAA:2 "disconnected" makes SECOND active with its cause', async () => {
    const scenario = ['until 1ms', 'start SUP.action(consigne = {1.0, 2.0, 3.0})', 't=1ms MAA:2 connection_status = "disconnected"'].join('\n');
    const first = await post({ scenario: 'until 1ms\nstart SUP.action(consigne = {1.0, 2.0, 3.0})\n' });
    expect(first.status, JSON.stringify(first.json)).toBe(200);
    const r1 = first.json as SimulateResponse;
    expect(r1.passed).toBe(true);
    const all1 = r1.steps.flatMap((s) => s.rules);
    expect(all1.find((r) => r.rule === 'FIRST' && r.active)).toBeTruthy();
    expect(r1.steps.at(-1)!.kind).toBe('end');
    expect(r1.steps.at(-1)!.timeNs).toBe(1_000_000);

    const second = await post({ scenario });
    expect(second.status).toBe(200);
    const r2 = second.json as SimulateResponse;
    const ev = r2.steps.find((s) => s.kind === 'event')!;
    expect(ev.line).toBe(3);
    expect(ev.timeNs).toBe(1_000_000);
    expect(rule(ev, 'SECOND')).toMatchObject({ active: true, supervisor: 'SUP', function: 'action', cause: 'MAA:2 value="disconnected"' });
    expect(rule(ev, 'FIRST')?.active).toBe(false);
    expect(ev.schemas).toContain('schemaCommande1');
    expect(ev.locals.some((l) => l.supervisor === 'SUP' && l.function === 'action')).toBe(true);
    expect(ev.actions.length).toBeGreaterThan(0);
    expect(r2.ms).toBeGreaterThan(0);
  }, 120_000);

  it('keeps the simulator in sim/ of the build cache ($CONTRACT_CACHE_DIR), as contract simulate does', () => {
    expect(readdirSync(join(base, 'cache', 'sim')).filter((n) => n.startsWith('sim-'))).toHaveLength(1);
  });

  it('runs a scenario file of the workspace and reports its expectations', async () => {
    const { status, json } = await post({ path: 'scenarios/commutation.scenario' });
    expect(status).toBe(200);
    expect((json as SimulateResponse).passed).toBe(true);
    expect((json as SimulateResponse).failures).toEqual([]);
  }, 60_000);

  it('a failed expectation is reported with its line and message, not as an HTTP error', async () => {
    const { status, json } = await post({ scenario: 'start SUP.action\nexpect at 1ms rule SUP.action.SECOND active\n' });
    expect(status).toBe(200);
    expect(json.passed).toBe(false);
    expect(json.failures[0].line).toBe(2);
    expect(json.failures[0].message).toMatch(/expected rule SUP.action.SECOND active, but it is inactive/);
  }, 60_000);

  it('scenario errors: 422 with diagnostics (line, column, code, did-you-mean), nothing ran', async () => {
    const { status, json } = await post({ scenario: 'start SUP.action\nexpect rule SUP.action.SECNOD active\nt=1ms MAA:2 3\n' });
    expect(status).toBe(422);
    expect(json.error).toMatch(/error\(s\)/);
    const d = json.diagnostics ?? [];
    expect(d.find((x) => x.line === 2)?.message).toMatch(/Did you mean 'SECOND'/);
    expect(d.find((x) => x.line === 3)?.code).toBe('scenario-value-type');
  }, 60_000);

  it('a scenario whose records pass the simulator\'s bound: the answer says from which step they were not kept, and those steps are marked', async () => {
    // schemaCommande2 for 40,000 s of virtual time, a step every 5,000 s: past 48 MiB of records at line 9
    const scenario = ['until 40000s', 'start SUP.action(consigne = {1.0, 2.0, 3.0})', 't=300ms MAA:2 connection_status = "disconnected"',
      't=1.2s MSC:1 failing_data = {"overheat", 3}', ...[1, 2, 3, 4, 5, 6, 7].map((i) => `expect at ${i * 5000}s schema schemaCommande2 active`)].join('\n');
    const { status, json } = await post({ scenario });
    expect(status, JSON.stringify(json).slice(0, 500)).toBe(200);
    const r = json as SimulateResponse;
    expect(r.passed).toBe(true); // the verdicts are the whole scenario's
    expect(r.trimmed).toMatchObject({ line: expect.any(Number), timeNs: expect.any(Number) });
    const from = r.trimmed!.line;
    expect(from).toBeGreaterThan(4);
    expect(r.trimmed!.message).toMatch(new RegExp(`^not whole: the steps' records passed the simulator's bound on a scenario's records; from line ${from} \\(\\d+\\.\\d{6}s\\) on, the steps were kept without their actions`));
    const at = r.steps.findIndex((s) => s.line === from);
    expect(r.steps.slice(0, at).every((s) => s.trimmed === undefined)).toBe(true);
    expect(r.steps.slice(at).every((s) => s.trimmed === 'compact' && s.schemas.length === 0 && s.actions.length === 0)).toBe(true);
  }, 120_000);

  it('answers the typed records of each step, and keeps at most MAX_ITEMS_PER_ANSWER items of all steps\' lists, the rest counted', async () => {
    // schemaCommande2 (two modules, 1 s) for 15,000 s of virtual time: about 13 records and 3 engine
    // lines a cycle, 80,000 items a step of 5,000 s (under the harness's 100,000 a list), 240,000 in all
    const scenario = ['until 15000s', 'start SUP.action(consigne = {1.0, 2.0, 3.0})', 't=300ms MAA:2 connection_status = "disconnected"',
      't=1.2s MSC:1 failing_data = {"overheat", 3}', 'expect at 5000s schema schemaCommande2 active', 'expect at 10000s schema schemaCommande2 active'].join('\n');
    const { status, json } = await post({ scenario });
    expect(status, JSON.stringify(json).slice(0, 500)).toBe(200);
    const r = json as SimulateResponse;
    expect(r.passed).toBe(true);
    const ev = r.steps.find((s) => s.kind === 'event')!;
    // the value and the rules it changed, as a run's supervisor writes them
    expect(ev.records).toContainEqual({ timeNs: 300_000_000, seq: expect.any(Number), module: 'SUP', kind: 'event_received', peer: 'MAA', port: 2, detail: expect.stringMatching(/^from_port=2 latency_ns=0 taken_ns=300000000 rules=\d+ value="disconnected"$/) });
    expect(ev.records).toContainEqual(expect.objectContaining({ module: 'ORD', kind: 'ord_release', peer: 'MSA' }));
    const items = (s: SimulateResponse['steps'][number]) => s.rules.length + s.actions.length + s.schemas.length + s.locals.length + (s.records?.length ?? 0) + (s.log?.length ?? 0);
    const kept = r.steps.reduce((n, s) => n + items(s), 0);
    const dropped = r.steps.reduce((n, s) => n + (s.dropped ?? 0), 0);
    expect(kept).toBe(MAX_ITEMS_PER_ANSWER);
    expect(dropped).toBeGreaterThan(20_000);
    // the steps are answered in order: the first ones whole, the last one cut (its state is still there)
    expect(r.steps.slice(0, -1).every((s) => s.dropped === undefined)).toBe(true);
    expect(r.steps.at(-1)!.dropped).toBe(dropped);
    expect(r.steps.at(-1)!.kind).toBe('end');
    expect(r.steps.at(-1)!.schemas).toEqual(['schemaCommande2']);
  }, 120_000);

  it('Save as scenario pins ORD\'s overruns as the simulator counts them (every skipped release), and the saved file passes', async () => {
    // MSA runs 3.5 s in schemaCommande1's first cycle (PERIOD 1s): ORD skips the releases at 1, 2 and 3 s,
    // tells the first at once and the count when the cycle ends (3.5 s)
    const session = new ScenarioSession();
    session.begin({ supervisor: 'SUP', fn: 'action', params: 'consigne = {1.0, 2.0, 3.0}' });
    session.advance('1ms');
    expect(session.inject('exec MSA 3.5s once')).toBeUndefined();
    expect(session.inject('MAA:2 connection_status = "disconnected"')).toBeUndefined();
    const saveAt = async (until: string) => {
      session.advance(until);
      const { status, json } = await post({ scenario: session.text() });
      expect(status, JSON.stringify(json)).toBe(200);
      const steps = (json as SimulateResponse).steps;
      const model = new MonitorModel(); // as the Simulate panel: the Monitor's state of the steps
      model.pushAll(stepsToTrace(steps));
      return { text: session.withExpectations(steps, model.live), shown: model.live.periodic.get('schemaCommande1')! };
    };
    // mid-cycle: one skip seen, the others not told yet: not pinned, said why
    const mid = await saveAt('2.5s');
    expect(mid.shown).toMatchObject({ overruns: 1, overrunning: true, deadlineMisses: 1 });
    expect(mid.text).toContain('expect at 2500ms deadline misses schemaCommande1 == 1\n# overruns of schemaCommande1 not pinned: its cycle still overran at 2500ms');
    expect(mid.text).not.toContain('expect at 2500ms overruns');
    // the cycle ended: 3 skipped releases, as ORD counted them
    const after = await saveAt('5s');
    expect(after.shown).toMatchObject({ overruns: 3, overrunning: false, deadlineMisses: 1 });
    expect(after.text).toContain('expect at 5s deadline misses schemaCommande1 == 1\nexpect at 5s overruns schemaCommande1 == 3\n');
    for (const saved of [mid.text, after.text]) {
      const run = await post({ scenario: saved });
      expect(run.status, JSON.stringify(run.json)).toBe(200);
      expect((run.json as SimulateResponse).passed, saved).toBe(true);
    }
    // and the count is ORD's: one more than the simulator counted fails
    const wrong = await post({ scenario: after.text.replace('overruns schemaCommande1 == 3', 'overruns schemaCommande1 == 4') });
    expect((wrong.json as SimulateResponse).passed).toBe(false);
  }, 120_000);

  it("the project's C not compiling: 422 with its src-gen file, line and region, no cache path; the run works again once mended", async () => {
    const file = join(base, 'tutorial', 'src-gen', 'generated', 'architecture', 'common', 'SharedFunctiontestit.h');
    const before = readFileSync(file, 'latin1');
    const marker = 'ID(protect_function_impl_testit) ENABLED START*/';
    const at = before.indexOf('\n', before.indexOf(marker)) + 1;
    expect(at).toBeGreaterThan(marker.length);
    writeFileSync(file, `${before.slice(0, at)}    int x = 1 oops;\n${before.slice(at)}`, 'latin1');
    try {
      const { status, json } = await post({ scenario: 'until 1ms\nstart SUP.action(consigne = {1.0, 2.0, 3.0})\n' });
      expect(status, JSON.stringify(json)).toBe(422);
      expect(json.error).toMatch(/^the project's C does not compile for the simulator: 1 error\(s\) in src-gen\//);
      const line = before.slice(0, at).split('\n').length;
      expect(json.diagnostics?.[0]).toMatchObject({ file: 'src-gen/generated/architecture/common/SharedFunctiontestit.h', line, severity: 'error' });
      expect(json.diagnostics?.[0]?.message).toMatch(/oops.* \(in protected region protect_function_impl_testit\)$/);
      expect(JSON.stringify(json)).not.toContain(join(base, 'cache'));
    } finally {
      writeFileSync(file, before, 'latin1');
    }
    expect((await post({ scenario: 'until 1ms\nstart SUP.action(consigne = {1.0, 2.0, 3.0})\n' })).status).toBe(200);
  }, 120_000);

  it('needs the session token; hostile bodies get 4xx', async () => {
    expect((await post({ scenario: '' }, 'wrong')).status).toBe(401);
    expect((await post('[1,2]')).status).toBe(400);
    expect((await post({})).status).toBe(400);
    expect((await post({ scenario: 3 })).status).toBe(400);
    expect((await post({ project: '../..', scenario: 'until 1ms' })).status).toBe(403);
    expect((await post({ path: '../../etc/x.scenario' })).status).toBeGreaterThanOrEqual(400);
    expect((await post({ path: 'scenarios/evil.scenario' })).status).toBe(403);
    // a missing file, a folder, a path that is no .scenario, a file that is no UTF-8: said with the path (it was a bare "not found" or the generic 400)
    expect(await post({ path: 'scenarios/none.scenario' })).toMatchObject({ status: 404, json: { error: 'no such scenario file in the workspace: scenarios/none.scenario' } });
    mkdirSync(join(base, 'tutorial', 'scenarios', 'dir.scenario'), { recursive: true });
    expect(await post({ path: 'scenarios/dir.scenario' })).toMatchObject({ status: 400, json: { error: 'scenarios/dir.scenario is a folder, not a scenario file' } });
    expect(await post({ path: 'scenarios' })).toMatchObject({ status: 400, json: { error: 'path must name a .scenario file of the workspace ("scenarios" does not)' } });
    writeFileSync(join(base, 'tutorial', 'scenarios', 'latin1.scenario'), Buffer.from('start SUP.action()\nt=1ms MAA:2 connection_status = "déjà"\n', 'latin1'));
    expect(await post({ path: 'scenarios/latin1.scenario' })).toMatchObject({ status: 422, json: { error: 'scenarios/latin1.scenario: not UTF-8 text: byte 0xe9 on line 2 is no UTF-8 (Latin-1? save it as UTF-8)' } });
    expect((await post({ scenario: 'x'.repeat(300_000) })).status).toBe(413);
    const junk = await post({ scenario: '\u0000\u0001 t=-5 start start ((((\n'.repeat(50) });
    expect(junk.status).toBe(422);
    // a burst: at most 8 wait behind the one running, the others get 429; every answer is JSON
    const burst = await Promise.all(Array.from({ length: 16 }, () => post({ scenario: 'until 10ms\nstart SUP.action\n' })));
    const codes = burst.map((b) => b.status);
    expect(codes.filter((c) => c === 200).length).toBeGreaterThanOrEqual(8);
    expect(codes.every((c) => c === 200 || c === 429)).toBe(true);
    expect(codes.filter((c) => c === 429).length).toBeGreaterThan(0);
  }, 60_000);
});

describe('POST /api/simulate with a build cache it cannot trust', () => {
  it('simulates in a private temporary cache, never in the refused folder', async () => {
    const open = join(base, 'open-cache');
    mkdirSync(open);
    chmodSync(open, 0o777);
    const saved = process.env.CONTRACT_CACHE_DIR;
    process.env.CONTRACT_CACHE_DIR = open;
    const other = await startIdeServer({ workspace: join(base, 'tutorial'), port: 0, buildService: false, distDir: join(base, 'no-dist') });
    try {
      const res = await fetch(`${other.url}/api/simulate`, {
        method: 'POST',
        headers: { 'content-type': 'application/json', 'x-contract-token': other.token },
        body: JSON.stringify({ scenario: 'until 1ms\nstart SUP.action(consigne = {1.0, 2.0, 3.0})\n' }),
      });
      const json = (await res.json()) as SimulateResponse;
      expect(res.status, JSON.stringify(json)).toBe(200);
      expect(json.passed).toBe(true);
      expect(existsSync(join(open, 'sim'))).toBe(false);
    } finally {
      process.env.CONTRACT_CACHE_DIR = saved;
      await other.close();
    }
  }, 120_000);
});
