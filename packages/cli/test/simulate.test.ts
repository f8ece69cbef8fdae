/**
 * `contract simulate`: the tutorial's scenarios pass (exit 0), a wrong expectation fails (exit 1)
 * with the step's line and the expected and actual state, scenario and usage errors exit 2,
 * `--format json` gives every step's record and `--format junit` a JUnit report. The simulators
 * are kept in the `sim/` folder of the build cache `contract build` uses (`--cache-dir`,
 * `$CONTRACT_CACHE_DIR`, the XDG cache folder), under the same trust rules.
 */
import { spawnSync } from 'node:child_process';
import { chmodSync, cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, describe, expect, it } from 'vitest';
import { resolveCacheDir } from '@contract-studio/build-service';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

const REPO = fileURLToPath(new URL('../../../', import.meta.url));
const TUTORIAL = join(REPO, 'examples', 'tutorial');
const cache = mkdtempSync(join(tmpdir(), 'contract-simulate-cli-'));
afterAll(() => rmSync(cache, { recursive: true, force: true }));
const scenario = (name: string) => join(TUTORIAL, 'scenarios', name);

// the command loads the simulator (and the language) when it runs, not when the CLI starts: the
// first test pays that load, longer than vitest's default 5 s on a loaded 2-core machine
describe('contract simulate', { timeout: 60_000 }, () => {
    it('passes the tutorial scenarios (exit 0), each step and rule change printed', async () => {
        const io = capture(REPO);
        expect(await runCli(['simulate', TUTORIAL, scenario('commutation.scenario'), scenario('mission.scenario'), '--cache-dir', cache], io)).toBe(0);
        expect(io.stdout).toContain('+ SUP.action.SECOND active  <- MAA:2 = "disconnected"');
        expect(io.stdout).toContain('- GLB.mission.SINGLE inactive  <- SUP:1 = "commutation"');
        // a timer's cause as the model writes it, as `contract trace` tells it
        expect(io.stdout).toContain('+ SUP.action.FIRST active  <- elapsed=1ms');
        expect(io.stdout).toMatch(/\n2 passed, 0 failed\n$/);
    });

    it('the scenario of docs/getting-started.md passes on a `contract new` project, as the page says', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'contract-simulate-getting-started-'));
        try {
            expect(await runCli(['new', join(dir, 'my-robot')], capture(dir))).toBe(0);
            const page = readFileSync(join(REPO, 'docs/getting-started.md'), 'utf8');
            const text = /Write `my-robot\/scenarios\/start\.scenario`:\n\n```\n([^]*?)```/.exec(page)?.[1];
            expect(text, 'the page shows the scenario').toBeTruthy();
            mkdirSync(join(dir, 'my-robot', 'scenarios'));
            writeFileSync(join(dir, 'my-robot', 'scenarios', 'start.scenario'), text!);
            const io = capture(dir);
            expect(await runCli(['simulate', 'my-robot', 'my-robot/scenarios/start.scenario', '--cache-dir', cache], io), io.stdout + io.stderr).toBe(0);
            expect(io.stdout).toContain('passed: 5/5 expectations');
            expect(page).toContain('5/5 expectations');
            expect(io.stdout).toContain('- MIS.mission.START inactive  <- CTL:0 = "arrived"');
            expect(page).toContain('`- MIS.mission.START inactive  <- CTL:0 = "arrived"`');
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });

    it('--trace writes each simulation as the trace records a run writes, one JSON object a line (the same records as --format json holds)', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'contract-simulate-trace-'));
        try {
            const io = capture(dir);
            expect(await runCli(['simulate', TUTORIAL, scenario('commutation.scenario'), scenario('mission.scenario'), '--cache-dir', cache, '--trace', 'sim.jsonl', '--format', 'json'], io), io.stderr).toBe(0);
            const records = readFileSync(join(dir, 'sim.jsonl'), 'utf8').trimEnd().split('\n').map((l) => JSON.parse(l) as { kind: string; module: string; peer: string; monoNs: string; port: number | null; detail: string; fields?: Record<string, unknown>; rule?: string; active?: boolean; cause?: string });
            // one simulation after the other, each from its sim_start at time 0 naming the scenario
            const starts = records.flatMap((r, i) => (r.kind === 'sim_start' ? [i] : []));
            expect(starts).toHaveLength(2);
            expect(records[0]!.detail).toMatch(/^simulation start: .*commutation\.scenario$/);
            expect(records[starts[1]!]!.detail).toMatch(/^simulation start: .*mission\.scenario$/);
            const first = records.slice(0, starts[1]);
            // every rule change of the steps, with its cause, and ORD's and the modules' records
            const steps = (JSON.parse(io.stdout) as { scenarios: Array<{ steps: Array<{ rules: unknown[]; records: Array<{ kind: string }> }> }> }).scenarios[0]!.steps;
            expect(first.filter((r) => r.kind === 'sup_rule')).toHaveLength(steps.reduce((n, s) => n + s.rules.length, 0));
            expect(first).toContainEqual(expect.objectContaining({ kind: 'sup_rule', module: 'SUP', rule: 'SECOND', active: true, cause: 'MAA:2 value="disconnected"', monoNs: '300000000' }));
            for (const kind of ['ord_release', 'ord_finished', 'ord_complete', 'run_started', 'run_finished', 'event_received', 'data_posted']) {
                expect(first.filter((r) => r.kind === kind).length, kind).toBe(steps.reduce((n, s) => n + s.records.filter((x) => x.kind === kind).length, 0));
                expect(first.some((r) => r.kind === kind), kind).toBe(true);
            }
            // the data a virtual module posts on a flow ORD connected: every run of MSA reaches MSC
            // (schemaCommande1's MSA:0 -> MSC:0 * 1), as many times as MSA finished a run in it
            const msaRuns = first.filter((r) => r.kind === 'run_finished' && r.module === 'MSA').length;
            expect(msaRuns).toBeGreaterThan(0);
            expect(first.filter((r) => r.kind === 'data_posted' && r.module === 'MSA' && r.peer === 'MSC' && r.port === 0 && r.detail === 'to_port=0')).toHaveLength(msaRuns);
            // in time order
            const times = first.map((r) => Number(r.monoNs));
            expect(times).toEqual([...times].sort((a, b) => a - b));
            // and at one time in the engines' order, as a run logs them: FIRST made inactive by MAA's
            // event, FIRST's undos, SECOND active, SECOND's actions, then the event's event_received
            // (a supervisor writes it once its rules have seen it: the rule changes it made, its value)
            const at300 = first.filter((r) => r.monoNs === '300000000');
            const where = (pred: (r: (typeof first)[number]) => boolean) => at300.findIndex(pred);
            const order = [
                where((r) => r.kind === 'sup_rule' && r.rule === 'FIRST' && r.active === false),
                where((r) => r.detail === 'undo: deactivate schema schemaReceptionMessage (event schema)'),
                where((r) => r.kind === 'sup_rule' && r.rule === 'SECOND' && r.active === true),
                where((r) => r.detail.startsWith('activate schema schemaCommande1(consigne = ')),
                where((r) => r.kind === 'event_received' && r.module === 'SUP' && r.peer === 'MAA' && r.port === 2),
                where((r) => r.kind === 'ord_release' && r.peer === 'MSA'),
            ];
            expect(at300[order[4]!]).toMatchObject({ detail: 'from_port=2 latency_ns=0 taken_ns=300000000 rules=2 value="disconnected"', fields: { from_port: 2, rules: 2, value: '"disconnected"' } });
            expect(order.every((i) => i >= 0), JSON.stringify(order)).toBe(true);
            expect(order).toEqual([...order].sort((a, b) => a - b));
            // contract trace tells the file: each simulation's story under its own heading, every rule change of it
            const told = capture(dir);
            expect(await runCli(['trace', 'sim.jsonl'], told), told.stderr).toBe(0);
            const story = told.stdout.split('\n');
            const headings = story.flatMap((l, i) => (l.startsWith('--- simulation start: ') ? [i] : []));
            expect(headings.map((i) => story[i]!.replace(/^.*\//, ''))).toEqual(['commutation.scenario', 'mission.scenario']);
            expect(story.slice(0, headings[1]).filter((l) => / rule \S+ (active|inactive) /.test(l))).toHaveLength(first.filter((r) => r.kind === 'sup_rule').length);
            expect(story).toContain('+0.300000s SUP  rule action.SECOND active   <- MAA:2 = "disconnected"');
            // a file that cannot be written: said, exit 1
            const bad = capture(dir);
            expect(await runCli(['simulate', TUTORIAL, scenario('mission.scenario'), '--cache-dir', cache, '--trace', join(dir, 'no', 'such', 'folder.jsonl')], bad)).toBe(1);
            expect(bad.stderr).toMatch(/contract simulate: cannot write the trace to .*folder\.jsonl: ENOENT/);
            // said before anything ran (before, after the whole run and its report)
            expect(bad.stdout).toBe('');
            // DIR a file, not a folder: a usage error (it was exit 1, as a failed run)
            const notDir = capture(dir);
            expect(await runCli(['simulate', scenario('mission.scenario'), scenario('mission.scenario'), '--cache-dir', cache], notDir)).toBe(2);
            expect(notDir.stderr).toContain('is not a directory (DIR is the folder of the .contract files)');
            // a folder with no model: said once (it was "no supervisor ..." on every line of the scenario)
            mkdirSync(join(dir, 'empty'));
            const empty = capture(dir);
            expect(await runCli(['simulate', 'empty', scenario('mission.scenario'), '--cache-dir', cache], empty)).toBe(2);
            expect(empty.stderr).toContain('error: no .contract file in this folder (or below it): DIR is the folder of the project\'s .contract files [no-model]');
            expect(empty.stderr).not.toContain('no supervisor');
            // a link planted where the trace goes (a hostile checkout): never written through, said so
            writeFileSync(join(dir, 'victim.txt'), 'mine\n');
            symlinkSync(join(dir, 'victim.txt'), join(dir, 'planted.jsonl'));
            const planted = capture(dir);
            expect(await runCli(['simulate', TUTORIAL, scenario('mission.scenario'), '--cache-dir', cache, '--trace', 'planted.jsonl'], planted)).toBe(1);
            expect(planted.stderr).toMatch(/cannot write the trace to .*planted\.jsonl: it is a symbolic link: a trace file is never written through a link/);
            expect(readFileSync(join(dir, 'victim.txt'), 'utf8')).toBe('mine\n');
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });

    it('a wrong expectation exits 1, naming the step, the expected and the actual state; junit and json say it too', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'contract-simulate-wrong-'));
        const file = join(dir, 'wrong.scenario');
        writeFileSync(file, readFileSync(scenario('commutation.scenario'), 'utf8').replace('expect rule SUP.action.FOURTH active', 'expect rule SUP.action.FOURTH inactive'));
        const line = readFileSync(file, 'utf8').split('\n').findIndex((l) => l.includes('FOURTH inactive')) + 1;
        const io = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'wrong.scenario', '--cache-dir', cache], io)).toBe(1);
        expect(io.stdout).toContain(`FAIL   1200ms  expect rule SUP.action.FOURTH inactive`);
        expect(io.stdout).toContain(`wrong.scenario:${line}: at 1200ms (expect rule SUP.action.FOURTH inactive): expected rule SUP.action.FOURTH inactive, but it is active`);
        expect(io.stdout).toMatch(/\n0 passed, 1 failed\n$/);

        const junit = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'wrong.scenario', '--cache-dir', cache, '--format', 'junit'], junit)).toBe(1);
        expect(junit.stdout).toMatch(/^<\?xml version="1.0" encoding="UTF-8"\?>\n<testsuites name="contract simulate" tests="19" failures="1">/);
        expect(junit.stdout).toContain(`<failure message="wrong.scenario:${line}: at 1200ms`);

        const json = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'wrong.scenario', '--cache-dir', cache, '--format', 'json'], json)).toBe(1);
        const out = JSON.parse(json.stdout) as { scenarios: Array<{ passed: boolean; failures: Array<{ line: number; expected: string; actual: string }>; steps: Array<{ timeNs: number; rules: unknown[]; schemas: string[]; locals: unknown[] }> }> };
        expect(out.scenarios[0]!.passed).toBe(false);
        expect(out.scenarios[0]!.failures).toMatchObject([{ line, expected: 'rule SUP.action.FOURTH inactive', actual: 'active' }]);
        const step = out.scenarios[0]!.steps.find((s) => s.timeNs === 300_000_000 && s.rules.length > 0)!;
        expect(step.schemas).toEqual(['schemaCommande1']);
        expect(step.locals.length).toBe(4);
        rmSync(dir, { recursive: true });
    });

    it('what the user\'s functions print is in the text report under its step, without --verbose', async () => {
        const io = capture(REPO);
        expect(await runCli(['simulate', TUTORIAL, scenario('commutation.scenario'), '--cache-dir', cache], io)).toBe(0);
        const lines = io.stdout.split('\n');
        // the tutorial's test function prints when MAA:2 "disconnected" makes SUP test it
        const step = lines.findIndex((l) => l.includes('MAA:2 connection_status = "disconnected"'));
        const printed = lines.findIndex((l) => /^ +output\| testit\("dedede", .*\) => 1$/.test(l));
        expect(step).toBeGreaterThan(0);
        expect(printed).toBeGreaterThan(step);
        // under that step: no other step's line between them
        expect(lines.slice(step + 1, printed).every((l) => /^ {14}/.test(l))).toBe(true);
    });

    it('a project whose C does not compile: gcc\'s errors as contract build prints them (DIR/src-gen path, line, region), no cache path; exit 1', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'contract-simulate-broken-'));
        try {
            cpSync(TUTORIAL, join(dir, 'tut'), { recursive: true });
            const rel = 'generated/architecture/common/SharedFunctiontestit.h';
            const header = join(dir, 'tut', 'src-gen', rel);
            const text = readFileSync(header, 'utf8');
            const at = text.indexOf('\n', text.indexOf('ID(protect_function_impl_testit) ENABLED START*/')) + 1;
            writeFileSync(header, text.slice(0, at) + '    int x = 1 oops;\n' + text.slice(at));
            const line = text.slice(0, at).split('\n').length;
            const io = capture(dir);
            expect(await runCli(['simulate', 'tut', join('tut', 'scenarios', 'commutation.scenario'), '--cache-dir', cache], io), io.stderr).toBe(1);
            expect(io.stderr).toMatch(new RegExp(`^tut/src-gen/${rel}:${line}:\\d+: error: .*oops.* \\[in protected region protect_function_impl_testit\\]$`, 'm'));
            expect(io.stderr).toContain('contract simulate: cannot compile the simulator: 1 error(s) in your C (above; your code is in the PROTECTED REGION blocks of tut/src-gen and in any file of your own there)');
            expect(io.stderr).not.toContain(cache);
            expect(io.stderr).not.toMatch(/sim-[0-9a-f]{20}|\.tmp-\d+-/);
            expect(io.stdout).toBe('');
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });

    it('scenario errors exit 2 with file:line:col, nothing simulated; usage errors exit 2', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'contract-simulate-bad-'));
        writeFileSync(join(dir, 'bad.scenario'), 'start SUP.action()\nexpect rule SUP.action.NOPE active\n');
        const io = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'bad.scenario', '--cache-dir', cache], io)).toBe(2);
        expect(io.stderr).toContain("bad.scenario:2:24: error: SUP.action has no rule 'NOPE' (rules: FIRST, SECOND, THIRD, FOURTH, RECEPTION) [scenario-unknown-rule]");
        expect(io.stdout).toBe('');
        expect(await runCli(['simulate', TUTORIAL], capture(dir))).toBe(2);
        expect(await runCli(['simulate', TUTORIAL, 'bad.scenario', '--format', 'xml'], capture(dir))).toBe(2);
        // a missing file: bad usage, said as such (not Node's ENOENT), before anything is built
        const missing = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'none.scenario', 'bad.scenario', 'no/such.scenario', '--cache-dir', cache], missing)).toBe(2);
        expect(missing.stderr.split('\n')[0]).toBe('contract simulate: no such scenario file: none.scenario, no/such.scenario');
        expect(missing.stderr).not.toContain('ENOENT');
        expect(missing.stderr).not.toContain('bad.scenario');
        // a link (even to a file of the project), a folder or a FIFO is not read (a FIFO is not opened: that would wait for a writer)
        symlinkSync('bad.scenario', join(dir, 'link.scenario'));
        mkdirSync(join(dir, 'folder.scenario'));
        expect(spawnSync('mkfifo', [join(dir, 'fifo.scenario')]).status).toBe(0);
        const refused = capture(dir);
        expect(await runCli(['simulate', TUTORIAL, 'link.scenario', 'folder.scenario', 'fifo.scenario', '--cache-dir', cache], refused)).toBe(2);
        expect(refused.stderr).toBe([
            'link.scenario: error: cannot read this scenario: a symbolic link (not followed)',
            'folder.scenario: error: cannot read this scenario: not a regular file',
            'fifo.scenario: error: cannot read this scenario: not a regular file',
            'contract simulate: 3 scenario file(s) with errors: nothing was simulated',
            '',
        ].join('\n'));
        rmSync(dir, { recursive: true });
    });

    it('keeps its simulators in sim/ of the build cache: --cache-dir, else $CONTRACT_CACHE_DIR, else the XDG cache folder, as contract build', async () => {
        const base = mkdtempSync(join(tmpdir(), 'contract-simulate-cache-'));
        const saved = { CONTRACT_CACHE_DIR: process.env.CONTRACT_CACHE_DIR, XDG_CACHE_HOME: process.env.XDG_CACHE_HOME };
        const harnesses = (root: string): string[] => (existsSync(join(root, 'sim')) ? readdirSync(join(root, 'sim')).filter((n) => n.startsWith('sim-')) : []);
        try {
            const args = ['simulate', TUTORIAL, scenario('commutation.scenario')];
            // the option
            expect(await runCli([...args, '--cache-dir', join(base, 'option')], capture(REPO))).toBe(0);
            expect(harnesses(join(base, 'option'))).toHaveLength(1);
            const shown = capture(REPO);
            expect(await runCli(['cache', '--cache-dir', join(base, 'option')], shown)).toBe(0);
            expect(shown.stderr).toContain('0 project work tree(s), 1 simulator(s)');
            // the environment variable of contract build
            process.env.CONTRACT_CACHE_DIR = join(base, 'env');
            expect(await runCli(args, capture(REPO))).toBe(0);
            expect(harnesses(join(base, 'env'))).toHaveLength(1);
            // XDG: the very folder contract build resolves
            delete process.env.CONTRACT_CACHE_DIR;
            process.env.XDG_CACHE_HOME = join(base, 'xdg');
            const buildCache = resolveCacheDir(undefined).dir;
            expect(buildCache).toBe(join(base, 'xdg', 'contract-studio'));
            expect(await runCli(args, capture(REPO))).toBe(0);
            expect(harnesses(buildCache)).toHaveLength(1);
            // the same project and runtime: the same harness whatever the cache
            expect(harnesses(buildCache)).toEqual(harnesses(join(base, 'option')));
        } finally {
            for (const [k, v] of Object.entries(saved)) {
                if (v === undefined) delete process.env[k];
                else process.env[k] = v;
            }
            rmSync(base, { recursive: true, force: true });
        }
    });

    it('refuses a cache it cannot trust (exit 3, the build cache\'s reason), and tells --cache users its new name (exit 2)', async () => {
        const base = mkdtempSync(join(tmpdir(), 'contract-simulate-refused-'));
        const open = join(base, 'open');
        mkdirSync(open);
        chmodSync(open, 0o777);
        const io = capture(REPO);
        expect(await runCli(['simulate', TUTORIAL, scenario('commutation.scenario'), '--cache-dir', open], io)).toBe(3);
        expect(io.stderr).toMatch(/the cache folder .*open is writable by every user \(mode 777\).*--cache-dir DIR or CONTRACT_CACHE_DIR=DIR/);
        expect(existsSync(join(open, 'sim'))).toBe(false);
        const old = capture(REPO);
        expect(await runCli(['simulate', TUTORIAL, scenario('commutation.scenario'), '--cache', base], old)).toBe(2);
        expect(old.stderr).toContain('--cache is now --cache-dir');
        rmSync(base, { recursive: true, force: true });
    });

    it('runs the project\'s C under bubblewrap: an unknown --sandbox exits 2, no working bubblewrap exits 3 with what to do', async () => {
        const bad = capture(REPO);
        expect(await runCli(['simulate', TUTORIAL, scenario('commutation.scenario'), '--sandbox', 'docker', '--cache-dir', cache], bad)).toBe(2);
        expect(bad.stderr).toContain("unknown sandbox 'docker' (expected auto, bwrap or none)");
        const path = process.env.PATH;
        const emptyPath = mkdtempSync(join(tmpdir(), 'contract-no-bwrap-'));
        process.env.PATH = emptyPath; // no bwrap on this PATH
        try {
            const none = capture(REPO);
            expect(await runCli(['simulate', TUTORIAL, scenario('commutation.scenario'), '--cache-dir', cache], none)).toBe(3);
            expect(none.stderr).toMatch(/confines them with bubblewrap, which does not work here .*apt-get install bubblewrap.*--sandbox none/);
            expect(none.stdout).toBe('');
        } finally {
            process.env.PATH = path;
            rmSync(emptyPath, { recursive: true, force: true });
        }
        const ok = capture(REPO);
        expect(await runCli(['simulate', TUTORIAL, scenario('commutation.scenario'), '--sandbox', 'bwrap', '--cache-dir', cache], ok)).toBe(0);
    });
});
