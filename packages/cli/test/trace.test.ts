/** `contract trace`: story and JSON lines of a log folder, hostile lines, links, usage errors. */
import { execFileSync, spawn } from 'node:child_process';
import { closeSync, mkdirSync, mkdtempSync, openSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { toJsonLines } from '../src/trace-files.js';
import { NOT_A_LOG_WHY, type TraceRecord } from '@contract-studio/build-service/trace';

const BIN = new URL('../bin/contract.js', import.meta.url).pathname;


const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';
let dir: string;
beforeAll(() => {
    dir = mkdtempSync(join(tmpdir(), 'contract-trace-'));
    writeFileSync(join(dir, 'SUP_24-Nov-2026-18h30m15s.csv'), [HEADER,
        '2000000000,w,SUP,supervisor,,,0,function action started',
        '2001000000,w,SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000000ns',
        '2001000100,w,SUP,supervisor,MAA,,0,subscribe MAA:2 =* :2', // an action: not told
        '2001000200,w,SUP,supervisor,,,0,activate schema R (event schema)', // an event schema's: told
        '\u001b]0;pwned\u0007 garbage',
        '2499000000,w,SUP,supervisor,,,0,undo: deactivate schema R (event schema)',
        '2500000000,w,SUP,sup_rule,,,0,"action.SECOND active cause=MAA:2 value=""dis\u001b[2Jconnected"""', ''].join('\n'));
    writeFileSync(join(dir, 'ORD_24-Nov-2026-18h30m15s.csv'), [HEADER,
        '2000500000,w,ORD,scheduler,,,0,activate S',
        '2000500001,w,ORD,ord_release,MSA,,0,schema=S cycle=0 tick_ns=2000500000 release_ns=2000500001 release=1',
        '2300000000,w,ORD,ord_deadline_miss,,,0,schema=S cycle=0 tick_ns=2000500000', ''].join('\n'));
    writeFileSync(join(dir, 'notes.txt'), 'not a log');
    execFileSync('mkfifo', [join(dir, 'FIF_24-Nov-2026-18h30m15s.csv')]); // left out, not waited on
    symlinkSync('/etc/passwd', join(dir, 'EVL_1.csv'));
});
afterAll(() => rmSync(dir, { recursive: true, force: true }));

/** A new temporary folder holding ORD's log of `n` releases, one a microsecond (the caller removes it). */
function releasesFolder(n: number): string {
    const folder = mkdtempSync(join(tmpdir(), 'contract-trace-releases-'));
    const lines = [HEADER];
    for (let i = 0; i < n; i++) lines.push(`${1_000_000_000 + i * 1000},w,ORD,ord_release,MSA,,0,schema=S cycle=${i} tick_ns=${1_000_000_000 + i * 1000} release_ns=${1_000_000_001 + i * 1000} release=${i + 1}`);
    writeFileSync(join(folder, 'ORD_24-Nov-2026-18h30m15s.csv'), lines.join('\n') + '\n');
    return folder;
}

describe('contract trace', () => {
    it('tells the run in time order, control characters made visible, links and FIFOs left out with a warning', async () => {
        const ok = capture(dir);
        expect(await runCli(['trace', '.'], ok)).toBe(0);
        expect(ok.stderr).toBe('contract trace: warning: EVL_1.csv: a symbolic link, not read (logs are never read through a link)\ncontract trace: warning: FIF_24-Nov-2026-18h30m15s.csv: a FIFO, not read\n');
        rmSync(join(dir, 'EVL_1.csv'));
        expect(ok.stdout).toBe([
            '+0.000000s SUP  function action started',
            '+0.000500s ORD  activate S',
            '+0.001000s SUP  rule action.FIRST active   <- elapsed=1ms',
            '+0.001000s SUP  subscribe MAA:2 =* :2',
            '+0.001000s SUP  activate schema R (event schema)',
            '+0.300000s ORD  deadline miss (ORD:0): S cycle 0 (not finished: MSA)',
            '+0.499000s SUP  undo: deactivate schema R (event schema)',
            '+0.500000s SUP  rule action.SECOND active   <- MAA:2 = "dis\\u001b[2Jconnected"',
            'schema S: 0 completed cycles, 1 deadline miss, 0 overruns; release lateness p50 1 ns, p99 1 ns, max 1 ns', // its release came 1 ns after its tick
            // the readable records, the unreadable line apart (as the IDE's Monitor counts them)
            '9 records: 1 module release, 0 completed cycles, 1 deadline miss, 0 overruns, 0 held cycles, 2 rule changes, 0 data and an unknown number of event deliveries (SUP\'s log is of an older version, which records no event a supervisor takes, though its rules changed on module events), 1 unreadable line',
            // which line, in which file (the control characters of the line itself are not printed)
            'unreadable: SUP_24-Nov-2026-18h30m15s.csv line 6: 1 fields, expected 8',
            '',
        ].join('\n'));
    });

    it("a module's forged ORD records and times (its own log) are its user records and unreadable lines: not ORD's misses, not the run's time base; run's schema figures agree", async () => {
        const folder = mkdtempSync(join(tmpdir(), 'contract-trace-forged-'));
        try {
            const W = '2026-11-24T18:30:15.123456Z';
            writeFileSync(join(folder, 'ORD_24-Nov-2026-18h30m15s.csv'), [HEADER,
                `40000000000000,${W},ORD,scheduler,,,0,activate S`,
                `40000000000001,${W},ORD,ord_release,MSA,,0,schema=S cycle=0 tick_ns=40000000000000 release_ns=40000000000001 release=1`,
                `40000001000000,${W},ORD,ord_complete,,,0,schema=S cycle=0 tick_ns=40000000000000 response_ns=1000000`,
                `900,${W},ORD,ord_deadline_miss,,,0,schema=S cycle=0 tick_ns=1`, ''].join('\n'));
            writeFileSync(join(folder, 'MSA_24-Nov-2026-18h30m15s.csv'), [HEADER,
                `40000000000002,${W},MSA,run_started,ORD,,0,activation=1`,
                `40000002000000,${W},MSA,ord_deadline_miss,,,0,schema=S cycle=99 tick_ns=1`,
                `1,${W},MSA,user,,,0,EARLY`,
                `18000000000000000000,${W},MSA,user,,,0,LATE`, ''].join('\n'));
            const out = capture(folder);
            expect(await runCli(['trace', '.'], out)).toBe(0);
            expect(out.stdout).toContain("+0.002000s MSA  ord_deadline_miss: schema=S cycle=99 tick_ns=1 [MSA's own record under the name of ORD's records: not taken for ORD's]");
            expect(out.stdout).toContain('schema S: 1 completed cycle (response max 1 ms), 0 deadline misses, 0 overruns');
            expect(out.stdout).not.toMatch(/EARLY|LATE|\+18000000000|\+4000\d\./);
            expect(out.stdout).toContain('unreadable: ORD_24-Nov-2026-18h30m15s.csv line 5: mono_ns goes back in its log');
            expect(out.stdout).toContain('unreadable: MSA_24-Nov-2026-18h30m15s.csv line 4: mono_ns goes back in its log');
            expect(out.stdout).toContain('unreadable: MSA_24-Nov-2026-18h30m15s.csv line 5: mono_ns is past a 64-bit time');
            // contract run --format json's figures (the CI gate) read the saved logs the same way
            const { runFigures } = await import('../src/commands/run-schemas.js');
            expect((await runFigures(folder, ['MSA_24-Nov-2026-18h30m15s.csv', 'ORD_24-Nov-2026-18h30m15s.csv']))?.schemas).toEqual([expect.objectContaining({ schema: 'S', deadlineMisses: 0, completedCycles: 1 })]);
            // the same records as a trace file: the same story, the forged lines named
            const json = capture(folder);
            expect(await runCli(['trace', '.', '--format', 'json'], json)).toBe(0);
            writeFileSync(join(folder, 't.jsonl'), json.stdout);
            const back = capture(folder);
            await runCli(['trace', 't.jsonl'], back);
            expect(back.stdout).toContain('schema S: 1 completed cycle (response max 1 ms), 0 deadline misses, 0 overruns');
        } finally {
            rmSync(folder, { recursive: true, force: true });
        }
    });

    it('exits 1 for logs that hold no record (empty, or only their header), saying so', async () => {
        const folder = mkdtempSync(join(tmpdir(), 'contract-trace-empty-'));
        try {
            writeFileSync(join(folder, 'EMP_24-Nov-2026-18h30m15s.csv'), '');
            writeFileSync(join(folder, 'HDR_24-Nov-2026-18h30m15s.csv'), `${HEADER}\n`);
            for (const format of ['text', 'json']) {
                const io = capture(folder);
                expect(await runCli(['trace', '.', '--format', format], io)).toBe(1);
                expect(io.stderr).toContain('contract trace: no record in the 2 log(s) of . (empty, or only their header)');
            }
        } finally {
            rmSync(folder, { recursive: true, force: true });
        }
    });

    it("says of a module's log that holds another number of records than its exit record counts that it is not whole (a line removed, one repeated), not of a capped log", async () => {
        const folder = mkdtempSync(join(tmpdir(), 'contract-trace-whole-'));
        try {
            const log = (m: string, records: string[], counted: number) => writeFileSync(join(folder, `${m}_24-Nov-2026-18h30m15s.csv`), [HEADER,
                `1000000000,w,${m},module_started,,,0,pid=7 priority=10`, ...records, `3000000000,w,${m},module_exit,,,0,status=0 records=${counted}`, ''].join('\n'));
            const rule = (t: number, r: string, m = 'CEL') => `${t},w,${m},sup_rule,,,0,cell.${r} active cause=elapsed=1000000ns`;
            log('CEL', [rule(2000000000, 'PICK'), rule(2100000000, 'RECOVER')], 5);          // one removed
            log('SAF', [rule(2000000000, 'WATCH', 'SAF'), rule(2000000000, 'WATCH', 'SAF')], 3);          // one repeated
            log('ARM', ['2000000000,w,ARM,log-capped,,,4096,log reached its 4096-byte bound (CONTRACT_LOG_MAX_BYTES): later records are not written'], 4);          // capped: left out on purpose
            log('CAM', [rule(2000000000, 'X', 'CAM'), '\u00ff\u00fe junk'], 4);                      // an unreadable line counts
            const io = capture(folder);
            expect(await runCli(['trace', '.'], io)).toBe(0);
            const said = io.stdout.split('\n').filter((l) => l.includes('not whole'));
            expect(said).toEqual([
                '           CEL  not whole: its log holds 4 record(s), its exit record counts 5: 1 missing (removed or cut after the run?)',
                '           SAF  not whole: its log holds 4 record(s), its exit record counts 3: 1 more than it wrote (repeated or added after the run?)',
            ]);
        } finally {
            rmSync(folder, { recursive: true, force: true });
        }
    });

    it("tells a module's crash record (the runtime's signal handler writes it) as its crash, not as a log without an exit record; its count checks the log", async () => {
        const folder = mkdtempSync(join(tmpdir(), 'contract-trace-crashed-'));
        try {
            const log = (m: string, lines: string[]) => writeFileSync(join(folder, `${m}_24-Nov-2026-18h30m15s.csv`), [HEADER, `1000000000,w,${m},module_started,,,0,pid=7 priority=10`, ...lines, ''].join('\n'));
            log('MSC', ['2000000000,w,MSC,request_received,ORD,,0,START', '2000100000,w,MSC,module_crashed,,,0,signal 11 (SIGSEGV) records=3']);
            log('MAB', ['1760000000,w,MAB,module_crashed,,,0,signal 6 (SIGABRT) records=4']);   // its handler skipped a record: lost at the crash
            log('ORD', ['3000000000,w,ORD,module_exit,,,0,status=0 records=2']);
            const io = capture(folder);
            expect(await runCli(['trace', '.'], io)).toBe(0);
            const lines = io.stdout.split('\n');
            expect(lines).toContain('+1.000100s MSC  crashed: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array');
            expect(lines).toContain('+0.760000s MAB  crashed: signal 6 (SIGABRT): the code called abort(), or an assert() failed: its message is on stderr');
            expect(io.stdout).not.toContain('no exit record');
            expect(lines.filter((l) => l.includes('not whole'))).toEqual([
                '           MAB  not whole: its log holds 2 record(s), its crash record counts 4: 2 missing (lost at the crash, or removed or cut after the run?)',
            ]);
        } finally {
            rmSync(folder, { recursive: true, force: true });
        }
    });

    it('--format json: one record per line, unknown lines kept with the reason', async () => {
        const io = capture(dir);
        expect(await runCli(['trace', dir, '--format', 'json'], io)).toBe(0);
        const records = io.stdout.trim().split('\n').map((l) => JSON.parse(l) as { kind: string; reason?: string; fields?: Record<string, unknown> });
        expect(records.map((r) => r.kind)).toEqual(['supervisor', 'scheduler', 'ord_release', 'sup_rule', 'supervisor', 'supervisor', 'unknown', 'ord_deadline_miss', 'supervisor', 'sup_rule']);
        expect(records[6]!.reason).toBe('1 fields, expected 8');
        expect(records[5]!.fields).toEqual({ what: 'action', schema: 'R' });
        expect(records[2]!.fields).toEqual({ schema: 'S', cycle: 0, tick_ns: 2000500000, release_ns: 2000500001, release: 1 });
    });

    it("tells a supervisor's requests kept for a full mailbox, and --format json gives their typed fields", async () => {
        const folder = mkdtempSync(join(tmpdir(), 'contract-trace-kept-'));
        try {
            writeFileSync(join(folder, 'SUP_24-Nov-2026-18h30m15s.csv'), [HEADER,
                '5100000000,2026-11-24T18:30:15.123456Z,SUP,requests_kept,VEL,,0,request=STOP',
                '7100000000,2026-11-24T18:30:17.123456Z,SUP,requests_kept_end,VEL,,0,sent=4 failed=1 replaced=73 kept_ns=2000000000', ''].join('\n'));
            const story = capture(folder);
            expect(await runCli(['trace', folder], story)).toBe(0);
            expect(story.stdout.split('\n').slice(0, 2)).toEqual([
                "+0.000000s SUP  VEL's mailbox is full: its STOP request is kept (tried again every 5 ms, for up to 2 s)",
                "+2.000000s SUP  the requests kept for VEL's full mailbox ended after 2 s: 4 sent, 1 failed, 73 values replaced by later ones",
            ]);
            const json = capture(folder);
            expect(await runCli(['trace', folder, '--format', 'json'], json)).toBe(0);
            const records = json.stdout.trim().split('\n').map((l) => JSON.parse(l) as { kind: string; peer: string; fields?: Record<string, unknown> });
            expect(records.map((r) => [r.kind, r.peer, r.fields])).toEqual([
                ['requests_kept', 'VEL', { request: 'STOP' }],
                ['requests_kept_end', 'VEL', { sent: 4, failed: 1, replaced: 73, kept_ns: 2000000000 }],
            ]);
        } finally {
            rmSync(folder, { recursive: true, force: true });
        }
    });

    it('--format json: the same counts as the story, each unreadable line an object of kind "unknown"; logs of unreadable lines only hold no record', async () => {
        const json = capture(dir);
        expect(await runCli(['trace', dir, '--format', 'json'], json)).toBe(0);
        const kinds = json.stdout.trim().split('\n').map((l) => (JSON.parse(l) as { kind: string }).kind);
        const text = capture(dir);
        expect(await runCli(['trace', dir], text)).toBe(0);
        const counts = /^(\d+) records: .*, (\d+) unreadable lines?$/m.exec(text.stdout)!;
        expect([kinds.filter((k) => k !== 'unknown').length, kinds.filter((k) => k === 'unknown').length]).toEqual([9, 1]);
        expect([Number(counts[1]), Number(counts[2])]).toEqual([9, 1]);
        const junk = mkdtempSync(join(tmpdir(), 'contract-trace-junk-'));
        try {
            writeFileSync(join(junk, 'JNK_24-Nov-2026-18h30m15s.csv'), [HEADER, 'junk', 'more junk', ''].join('\n'));
            for (const format of ['text', 'json']) {
                const io = capture(junk);
                expect(await runCli(['trace', '.', '--format', format], io)).toBe(1);
                expect(io.stderr).toBe('contract trace: no record in the 1 log(s) of . (only 2 unreadable line(s))\n');
            }
        } finally {
            rmSync(junk, { recursive: true, force: true });
        }
    });

    it('usage errors exit 2; a folder without logs exits 1', async () => {
        const none = capture(dir);
        expect(await runCli(['trace'], none)).toBe(2);
        expect(await runCli(['trace', dir, '--format', 'xml'], capture(dir))).toBe(2);
        const empty = mkdtempSync(join(tmpdir(), 'contract-trace-empty-'));
        const io = capture(dir);
        expect(await runCli(['trace', empty], io)).toBe(1);
        expect(io.stderr).toBe(`contract trace: no CSV log (*.csv) in ${empty}\n`);
        // named as typed: a relative folder stays relative
        const typed = capture(tmpdir());
        expect(await runCli(['trace', basename(empty)], typed)).toBe(1);
        expect(typed.stderr).toBe(`contract trace: no CSV log (*.csv) in ${basename(empty)}\n`);
        // a project folder given for its logs: where contract run wrote them is said
        mkdirSync(join(empty, 'logs'));
        const project = capture(tmpdir());
        expect(await runCli(['trace', basename(empty)], project)).toBe(1);
        expect(project.stderr).toBe(`contract trace: no CSV log (*.csv) in ${basename(empty)}; its logs/ folder (where contract run writes a run's logs) may hold them: contract trace ${basename(empty)}/logs\n`);
        rmSync(empty, { recursive: true });
    });

    it('a trace file (FILE.jsonl: --format json, contract run --trace) tells the same story as the logs it was written from', async () => {
        const json = capture(dir);
        expect(await runCli(['trace', dir, '--format', 'json'], json)).toBe(0);
        const file = join(dir, 'run.jsonl');
        writeFileSync(file, json.stdout);
        try {
            const fromLogs = capture(dir);
            expect(await runCli(['trace', '.'], fromLogs)).toBe(0);
            const fromFile = capture(dir);
            expect(await runCli(['trace', 'run.jsonl'], fromFile)).toBe(0);
            expect(fromFile.stdout).toBe(fromLogs.stdout);
            // the unreadable line the logs held is in the file as an unknown record: counted as it was, no warning
            expect(fromFile.stderr).toBe('');
            const again = capture(dir);
            expect(await runCli(['trace', 'run.jsonl', '--format', 'json'], again)).toBe(0);
            expect(again.stdout).toBe(json.stdout);
        } finally {
            rmSync(file);
        }
    });

    it('a --trace file is spelled as --format json prints: C1 and bidi characters escaped in both, the same JSON', async () => {
        const odd = mkdtempSync(join(tmpdir(), 'contract-trace-c1-'));
        try {
            writeFileSync(join(odd, 'EVL_1.csv'), `${HEADER}\n1000,w,EVL,error,,,0,x\u009b31m \u202eevil\n`);
            const io = capture(odd);
            expect(await runCli(['trace', '.', '--format', 'json'], io)).toBe(0);
            expect(io.stdout).not.toMatch(/[\u0080-\u009f\u202a-\u202e]/);
            expect(io.stdout).toContain('x\\u009b31m \\u202eevil');
            const records = io.stdout.trim().split('\n').map((l) => JSON.parse(l) as TraceRecord);
            expect((records[0] as { detail: string }).detail).toBe('x\u009b31m \u202eevil');
            expect(toJsonLines(records)).toBe(io.stdout); // what run --trace and simulate --trace write
        } finally {
            rmSync(odd, { recursive: true });
        }
    });

    it('a trace file of two simulations: each starts at time 0 again (no time-order warning, no record unreadable) and ends with its own counts', async () => {
        const two = mkdtempSync(join(tmpdir(), 'contract-trace-two-sims-'));
        try {
            const sim = (name: string, t: string) => [
                { kind: 'sim_start', monoNs: '0', wallTime: '', module: 'SIM', peer: '', port: null, size: 0, detail: `simulation start: ${name}` },
                { kind: 'supervisor', monoNs: '1000000', wallTime: '', module: 'SUP', peer: '', port: null, size: 0, detail: 'function action started' },
                { kind: 'sup_rule', monoNs: t, wallTime: '', module: 'SUP', peer: '', port: null, size: 0, detail: 'action.FIRST active cause=elapsed=1000000ns' },
            ];
            writeFileSync(join(two, 'sims.jsonl'), [...sim('a.scenario', '2000000000'), ...sim('b.scenario', '3000000')].map((r) => JSON.stringify(r)).join('\n') + '\n');
            const io = capture(two);
            expect(await runCli(['trace', 'sims.jsonl'], io)).toBe(0);
            expect(io.stderr).toBe('');
            const lines = io.stdout.trimEnd().split('\n');
            const counts = lines.filter((l) => /^\d+ records: /.test(l));
            expect(counts).toHaveLength(2);
            for (const c of counts) expect(c).toMatch(/^2 records: .*1 rule change.*0 unreadable lines$/);
            // the second simulation's story comes after the first one's counts, under its own heading
            expect(lines.indexOf('--- simulation start: b.scenario')).toBeGreaterThan(lines.indexOf(counts[0]!));
            expect(lines.filter((l) => l.startsWith('+0.002000s SUP  rule action.FIRST active'))).toHaveLength(1);
        } finally {
            rmSync(two, { recursive: true });
        }
    });

    it('characters of no width (U+200B-U+200D, U+2060, the BOM U+FEFF) in a record are shown as their escapes, in the story and the JSON alike', async () => {
        const odd = mkdtempSync(join(tmpdir(), 'contract-trace-zw-'));
        try {
            writeFileSync(join(odd, 'SUP_1.csv'), [HEADER,
                '2000000000,w,SUP,supervisor,,,0,function action started',
                '2500000000,w,SUP,sup_rule,,,0,"action.SECOND active cause=MAA:2 value=""go\u200b\u200c\u200d\u2060\ufeff"""', ''].join('\n'));
            const io = capture(odd);
            expect(await runCli(['trace', '.'], io)).toBe(0);
            expect(io.stdout).not.toMatch(/[\u200b-\u200d\u2060\ufeff]/);
            expect(io.stdout).toContain('"go\\u200b\\u200c\\u200d\\u2060\\ufeff"');
            const json = capture(odd);
            expect(await runCli(['trace', '.', '--format', 'json'], json)).toBe(0);
            expect(json.stdout).not.toMatch(/[\u200b-\u200d\u2060\ufeff]/);
            const rule = json.stdout.trim().split('\n').map((l) => JSON.parse(l) as TraceRecord).find((r) => r.kind === 'sup_rule') as { detail: string };
            expect(rule.detail).toContain('go\u200b\u200c\u200d\u2060\ufeff'); // the JSON parses back to the raw value
        } finally {
            rmSync(odd, { recursive: true });
        }
    });

    it('a trace file cannot forge story lines: a newline or a bidi override in a detail or a reason stays inside its line', async () => {
        const odd = mkdtempSync(join(tmpdir(), 'contract-trace-forge-'));
        try {
            writeFileSync(join(odd, 'forge.jsonl'), [
                { kind: 'sim_start', monoNs: '0', wallTime: '', module: 'SIM', peer: '', port: null, size: 0, detail: 'simulation start: x\n+0.000000s ORD  deadline miss (ORD:0): forged cycle 1' },
                { kind: 'supervisor', monoNs: '1000', wallTime: 'w', module: 'EVL', peer: '', port: null, size: 0, detail: 'function x started' },
                { kind: 'supervisor', monoNs: '2000', wallTime: 'w', module: 'EVL', peer: '', port: null, size: 0, detail: 'refused: \u202eevil' },
                { kind: 'unknown', file: 'EVL_1.csv', line: 3, reason: 'bad\n+9.000000s ORD  forged via reason\nok: all good', text: 't' },
            ].map((r) => JSON.stringify(r)).join('\n') + '\n');
            const io = capture(odd);
            expect(await runCli(['trace', 'forge.jsonl'], io)).toBe(0);
            const lines = io.stdout.trimEnd().split('\n');
            expect(lines.every((l) => /^(--- |[+-]\d+\.\d{6}s |\d+ records: |unreadable: )/.test(l))).toBe(true);
            expect(lines).toHaveLength(5);
            expect(io.stdout).not.toMatch(/[\u202a-\u202e]/);
            expect(io.stdout).toContain('refused: \\u202eevil');
        } finally {
            rmSync(odd, { recursive: true });
        }
    });

    it('a hostile trace file: each line that is no record named (20, then counted), a line without end bounded, no record exits 1, another file exits 2', async () => {
        const odd = mkdtempSync(join(tmpdir(), 'contract-trace-jsonl-'));
        try {
            const rule = JSON.stringify({ kind: 'sup_rule', monoNs: '2001000000', wallTime: 'w', module: 'SUP', peer: '', port: null, size: 0, detail: 'action.FIRST active cause=elapsed=1000000ns', causeEvent: { kind: 'stop' } });
            const bad = Array.from({ length: 25 }, (_, i) => (i % 2 ? '[1]' : `{"kind":"sup_rule","monoNs":"1","module":"../x","detail":"${i}"}`));
            writeFileSync(join(odd, 'a.jsonl'), [rule, ...bad, 'x'.repeat(100_000), rule].join('\n') + '\n');
            const io = capture(odd);
            expect(await runCli(['trace', 'a.jsonl'], io)).toBe(0);
            // the rule's cause is read from its detail, not from the line's causeEvent
            expect(io.stdout.split('\n').slice(0, 2)).toEqual(['+0.000000s SUP  rule action.FIRST active   <- elapsed=1ms', '+0.000000s SUP  rule action.FIRST active   <- elapsed=1ms']);
            const warnings = io.stderr.trim().split('\n');
            expect(warnings[0]).toBe('contract trace: warning: a.jsonl:2: bad module name');
            expect(warnings[1]).toBe('contract trace: warning: a.jsonl:3: not a JSON object');
            expect(warnings).toHaveLength(21);
            expect(warnings[20]).toBe('contract trace: warning: 6 more line(s) of a.jsonl that are no record');
            execFileSync('truncate', ['-s', '1T', join(odd, 'sparse.jsonl')]);
            const t0 = Date.now();
            const sparse = capture(odd);
            expect(await runCli(['trace', 'sparse.jsonl'], sparse)).toBe(1);
            expect(Date.now() - t0).toBeLessThan(20_000);
            expect(sparse.stderr).toBe(`contract trace: warning: sparse.jsonl:1: no line end in 64 MiB: the rest of the file (${2 ** 40 - 65 * 2 ** 20} bytes) left out\ncontract trace: no record in sparse.jsonl\n`);
            writeFileSync(join(odd, 'empty.jsonl'), '');
            expect(await runCli(['trace', 'empty.jsonl'], capture(odd))).toBe(1);
            writeFileSync(join(odd, 'notes.txt'), rule);
            const other = capture(odd);
            expect(await runCli(['trace', 'notes.txt'], other)).toBe(2);
            expect(other.stderr).toMatch(/notes\.txt is not a folder: give the folder of a run's CSV logs .* or a trace file \(FILE\.jsonl/);
        } finally {
            rmSync(odd, { recursive: true, force: true });
        }
    });

    it('a last line cut by a writer stopped mid-line (a killed module, `contract run --trace` killed) is said to be cut, in a log and in a trace file', async () => {
        const cut = mkdtempSync(join(tmpdir(), 'contract-trace-cut-'));
        try {
            const rule = '2001000000,w,SUP,sup_rule,,,0,action.FIRST active cause=elapsed=1000000ns';
            writeFileSync(join(cut, 'SUP_1.csv'), [HEADER, rule, '2002000000,w,SUP,super'].join('\n'));
            const io = capture(cut);
            expect(await runCli(['trace', '.'], io)).toBe(0);
            expect(io.stdout).toContain('unreadable: SUP_1.csv line 3: 4 fields, expected 8 (the file ends inside this line: its writer was stopped, or is still writing it)');
            // a bad line that has its line end is not said to be cut
            writeFileSync(join(cut, 'SUP_1.csv'), [HEADER, '2002000000,w,SUP,super', rule, ''].join('\n'));
            const whole = capture(cut);
            expect(await runCli(['trace', '.'], whole)).toBe(0);
            expect(whole.stdout).toContain('unreadable: SUP_1.csv line 2: 4 fields, expected 8\n');
            const json = JSON.stringify({ kind: 'sup_rule', monoNs: '2001000000', wallTime: 'w', module: 'SUP', peer: '', port: null, size: 0, detail: 'action.FIRST active cause=elapsed=1000000ns' });
            writeFileSync(join(cut, 'run.jsonl'), `${json}\n${json.slice(0, 40)}`);
            const file = capture(cut);
            expect(await runCli(['trace', 'run.jsonl'], file)).toBe(0);
            expect(file.stderr).toBe('contract trace: warning: run.jsonl:2: not JSON (the file ends inside this line: its writer was stopped, or is still writing it)\n');
        } finally {
            rmSync(cut, { recursive: true, force: true });
        }
    });

    it('a last line cut inside its detail that still reads as a record (8 fields) is told as cut, kept in the JSON and in a trace file read back', async () => {
        const cut = mkdtempSync(join(tmpdir(), 'contract-trace-cut8-'));
        try {
            const rule = '2001000000,w,CTL,module_started,,,0,pid=41 priority=40';
            // CTL was killed inside its user record `burst`: the detail lost its end, the line its newline
            writeFileSync(join(cut, 'CTL_1.csv'), [HEADER, rule, '2002000000,w,CTL,burst,,,0,seq=2046970 padding=xxxxx'].join('\n'));
            const io = capture(cut);
            expect(await runCli(['trace', '.'], io)).toBe(0);
            expect(io.stdout).toMatch(/^\+0\.001000s CTL  burst: seq=2046970 padding=xxxxx \[cut: its log ends inside this line, with no line end; the record may have lost its end/m);
            expect(io.stdout).toContain('2 records');
            // a record of a kind the story does not tell is told when cut
            writeFileSync(join(cut, 'CTL_1.csv'), [HEADER, rule, '2002000000,w,CTL,data_posted,MOT,0,24,to_port=0'].join('\n'));
            const untold = capture(cut);
            expect(await runCli(['trace', '.'], untold)).toBe(0);
            expect(untold.stdout).toMatch(/^\+0\.001000s CTL  data_posted record \[cut: /m);
            // the same line with its line end is whole: not said
            writeFileSync(join(cut, 'CTL_1.csv'), [HEADER, rule, '2002000000,w,CTL,burst,,,0,seq=2046970 padding=xxxxx', ''].join('\n'));
            const whole = capture(cut);
            expect(await runCli(['trace', '.'], whole)).toBe(0);
            expect(whole.stdout).not.toContain('[cut:');
            writeFileSync(join(cut, 'CTL_1.csv'), [HEADER, rule, '2002000000,w,CTL,burst,,,0,seq=2046970 padding=xxxxx'].join('\n'));
            const json = capture(cut);
            expect(await runCli(['trace', '.', '--format', 'json'], json)).toBe(0);
            const lines = json.stdout.trim().split('\n').map((l) => JSON.parse(l) as Record<string, unknown>);
            expect(lines.map((l) => l['cut'])).toEqual([undefined, true]);
            writeFileSync(join(cut, 'run.jsonl'), json.stdout);
            rmSync(join(cut, 'CTL_1.csv'));
            const back = capture(cut);
            expect(await runCli(['trace', 'run.jsonl'], back)).toBe(0);
            expect(back.stdout).toContain('padding=xxxxx [cut: ');
        } finally {
            rmSync(cut, { recursive: true, force: true });
        }
    });

    it('a folder of more logs than a run writes is refused with why, before any is opened', async () => {
        const many = mkdtempSync(join(tmpdir(), 'contract-trace-many-'));
        try {
            for (let i = 0; i < 1025; i++) writeFileSync(join(many, `M${i}_1.csv`), `${HEADER}\n`);
            const io = capture(many);
            expect(await runCli(['trace', '.'], io)).toBe(1);
            expect(io.stderr).toBe(`contract trace: . holds 1025 CSV logs: more than the 1024 read at once (a run writes one per module); give the folder of one run\n`);
            rmSync(join(many, 'M0_1.csv'));
            // 1024 are read (each holds only its header: no record, exit 1 saying so)
            const ok = capture(many);
            expect(await runCli(['trace', '.'], ok)).toBe(1);
            expect(ok.stdout).toBe('0 records: 0 module releases, 0 completed cycles, 0 deadline misses, 0 overruns, 0 held cycles, 0 rule changes, 0 data and 0 event deliveries, 0 unreadable lines\n');
            expect(ok.stderr).toBe('contract trace: no record in the 1024 log(s) of . (empty, or only their header)\n');
        } finally {
            rmSync(many, { recursive: true, force: true });
        }
    });

    it('a log with no line end (a sparse file of a terabyte named like a log) is read no further than 64 MiB, and said', async () => {
        const odd = mkdtempSync(join(tmpdir(), 'contract-trace-sparse-'));
        try {
            writeFileSync(join(odd, 'ORD_1.csv'), `${HEADER}\n2000500000,w,ORD,scheduler,,,0,activate S\n`);
            execFileSync('truncate', ['-s', '1T', join(odd, 'ZZZ_1.csv')]);
            const t0 = Date.now();
            const io = capture(odd);
            expect(await runCli(['trace', '.'], io)).toBe(0);
            expect(Date.now() - t0).toBeLessThan(20_000); // read whole, a terabyte of zeros took hours
            // its first line is not the runtime's header: no log, refused whole (docs/runtime-api.md "Whose records, and their times")
            expect(io.stdout).toBe(`+0.000000s ORD  activate S\n${io.stdout.split('\n')[1]}\nunreadable: ZZZ_1.csv line 1: ${NOT_A_LOG_WHY}\n`);
            expect(io.stdout.split('\n')[1]).toMatch(/^1 record: .* 1 unreadable line$/);
            // 65 chunks of 1 MiB read: the line passed 64 MiB (as in a trace file: one reader of lines, bounded-lines.ts)
            expect(io.stderr).toBe(`contract trace: warning: ZZZ_1.csv: ${NOT_A_LOG_WHY}\ncontract trace: warning: ZZZ_1.csv: no line end in 64 MiB after line 1: the rest of the file (${2 ** 40 - 65 * 2 ** 20} bytes) left out\n`);
        } finally {
            rmSync(odd, { recursive: true, force: true });
        }
    });

    it('a reader that goes away (`| head`) ends nothing badly: no stack trace, exit 0', async () => {
        // 20,000 records: far more than a pipe holds, so the command is still writing when the reader closes
        const big = releasesFolder(20_000);
        try {
            for (const format of ['json', 'text']) {
                const child = spawn(process.execPath, [BIN, 'trace', big, '--format', format], { stdio: ['ignore', 'pipe', 'pipe'] });
                let stderr = '';
                child.stderr.on('data', (d: Buffer) => { stderr += d.toString(); });
                const first = await new Promise<string>((resolve) => child.stdout.once('data', (d: Buffer) => resolve(d.toString())));
                child.stdout.destroy(); // as `head -c` does once it has its bytes
                const code = await new Promise<number | null>((resolve) => child.on('close', (c) => resolve(c)));
                expect(first.length).toBeGreaterThan(0);
                expect(stderr, format).toBe('');
                expect(code, format).toBe(0);
            }
        } finally {
            rmSync(big, { recursive: true, force: true });
        }
    });

    it('prints in pieces, each once the reader took the last (a run of gigabytes is not held in memory)', async () => {
        const big = releasesFolder(5_000);
        try {
            const io = capture(big);
            const pieces: number[] = [];
            let release: () => void = () => {};
            io.out = (text: string) => { pieces.push(text.length); io.stdout += text; };
            io.drained = () => new Promise<void>((r) => { release = r; });
            const done = runCli(['trace', '.', '--format', 'json'], io);
            await new Promise((r) => setTimeout(r, 300));
            expect(pieces).toHaveLength(1); // the reader has not taken the first piece: nothing more read or printed
            expect(pieces[0]).toBeGreaterThanOrEqual(64 * 1024);
            for (let i = 0; i < 100 && pieces.length < 3; i++) {
                release();
                await new Promise((r) => setTimeout(r, 10));
            }
            expect(pieces.length).toBeGreaterThan(1);
            const poll = setInterval(() => release(), 1);
            expect(await done).toBe(0);
            clearInterval(poll);
            expect(io.stdout.trim().split('\n')).toHaveLength(5_000);
        } finally {
            rmSync(big, { recursive: true, force: true });
        }
    });

    it('a standard output that fails (a full disk) is said, and the command does not exit 0', async () => {
        const logs = mkdtempSync(join(tmpdir(), 'contract-trace-full-'));
        writeFileSync(join(logs, 'ORD_24-Nov-2026-18h30m15s.csv'), `${HEADER}\n2000500000,w,ORD,scheduler,,,0,activate S\n`);
        const full = openSync('/dev/full', 'w');
        try {
            const child = spawn(process.execPath, [BIN, 'trace', logs, '--format', 'json'], { stdio: ['ignore', full, 'pipe'] });
            let stderr = '';
            child.stderr!.on('data', (d: Buffer) => { stderr += d.toString(); });
            const code = await new Promise<number | null>((resolve) => child.on('close', (c) => resolve(c)));
            expect(stderr).toBe('contract: cannot write the standard output (ENOSPC): stopping\n');
            expect(code).toBe(1);
        } finally {
            closeSync(full);
            rmSync(logs, { recursive: true, force: true });
        }
    });
});
