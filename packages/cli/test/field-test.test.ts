/**
 * The CLI field test's defects (a new user writing a project from docs/, an attacker planting
 * files): each test fails without its fix. Fast ones on files and fake jobs; a few real bwrap
 * builds and one run.
 */
import { execFileSync, spawn } from 'node:child_process';
import { existsSync, mkdirSync, readdirSync, readFileSync, symlinkSync, utimesSync, writeFileSync } from 'node:fs';
import { hostname } from 'node:os';
import { join } from 'node:path';
import { gzipSync } from 'node:zlib';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import type { Job, RunArtifacts } from '@contract-studio/build-service';
import { NOT_A_LOG_WHY } from '@contract-studio/build-service/trace';
import { runCli } from '../src/cli.js';
import { problemLines, refusedPrevious, saveLogs, startProblem } from '../src/commands/run.js';
import { formatGccDiagnostic, noteBuildErrorLine, prepareErrors, reportBuild, type JobOutcome } from '../src/job-runner.js';
import { safeName } from '../src/terminal-text.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-field-');
    expect(await runCli(['new', 'robot'], capture(root))).toBe(0);
}, 240_000);
afterAll(() => removeSeededScratch(root));

/** A log of one module: started, one scheduler line, exited unless `crashed`. */
function moduleLog(module: string, t0: number, crashed = false): string {
    const lines = [HEADER, `${t0},w,${module},module_started,,,0,pid=1 priority=1`, `${t0 + 1000},w,${module},scheduler,,,0,activate S`];
    if (!crashed) lines.push(`${t0 + 2_000_000_000},w,${module},module_exit,,,0,status=0`);
    return lines.join('\n') + '\n';
}

/** Fake collected artifacts: CSV logs as the build service keeps them (gzip). */
function artifacts(files: Record<string, string>): RunArtifacts {
    return { files: Object.entries(files).map(([name, text]) => ({ name, gzip: gzipSync(text), size: text.length })), skipped: [], runDirLeftovers: [] } as unknown as RunArtifacts;
}

describe('1. contract trace: a link among the logs, a missing folder', () => {
    it('leaves a log that is a symbolic link (or a FIFO) out with a warning and tells the others', async () => {
        const dir = join(root, 'trace-links');
        mkdirSync(dir);
        writeFileSync(join(dir, 'ORD_1.csv'), moduleLog('ORD', 1_000_000_000));
        symlinkSync('/etc/passwd', join(dir, 'EVL_1.csv'));
        execFileSync('mkfifo', [join(dir, 'FIF_1.csv')]);
        const io = capture(root);
        expect(await runCli(['trace', 'trace-links'], io)).toBe(0);
        expect(io.stdout).toContain('ORD  activate S');
        expect(io.stderr).toBe(
            'contract trace: warning: EVL_1.csv: a symbolic link, not read (logs are never read through a link)\n' +
            'contract trace: warning: FIF_1.csv: a FIFO, not read\n');
        // only links: nothing readable, exit 1, each said
        const only = join(root, 'trace-only-links');
        mkdirSync(only);
        symlinkSync('/etc/passwd', join(only, 'EVL_1.csv'));
        const none = capture(root);
        expect(await runCli(['trace', 'trace-only-links'], none)).toBe(1);
        expect(none.stderr).toContain('warning: EVL_1.csv: a symbolic link');
        expect(none.stderr).toContain(`contract trace: no readable CSV log in ${only}\n`);
    });

    it('a LOGDIR that does not exist, or is a file, is a usage error (exit 2) that says so', async () => {
        const io = capture(root);
        expect(await runCli(['trace', 'nosuchdir'], io)).toBe(2);
        expect(io.stderr).toMatch(/^contract trace: nosuchdir is not a folder \(it does not exist\): give the folder of a run's CSV logs/);
        expect(io.stderr).not.toContain('ENOENT');
        writeFileSync(join(root, 'a-file'), 'x');
        const file = capture(root);
        expect(await runCli(['trace', 'a-file'], file)).toBe(2);
        expect(file.stderr).toMatch(/^contract trace: a-file is not a folder: /);
    });
});

describe('2. contract run: a link planted among the logs', () => {
    it('writes every other log, refuses the one whose name a link holds, writes nothing through it', async () => {
        const out = join(root, 'planted');
        mkdirSync(out);
        const victim = join(root, 'victim.txt');
        writeFileSync(victim, 'mine\n');
        symlinkSync(victim, join(out, 'CTL_3-Dec-2026-02h00m00s.csv'));
        execFileSync('mkfifo', [join(out, 'LOC_3-Dec-2026-02h00m00s.csv')]);
        const saved = await saveLogs(artifacts({
            'CTL_3-Dec-2026-02h00m00s.csv': moduleLog('CTL', 1),
            'LOC_3-Dec-2026-02h00m00s.csv': moduleLog('LOC', 1),
            'MIS_3-Dec-2026-02h00m00s.csv': moduleLog('MIS', 1),
            'ORD_3-Dec-2026-02h00m00s.csv': moduleLog('ORD', 1),
        }), out, true);
        expect(saved.saved).toEqual(['MIS_3-Dec-2026-02h00m00s.csv', 'ORD_3-Dec-2026-02h00m00s.csv']);
        expect(saved.refused).toEqual([
            'CTL_3-Dec-2026-02h00m00s.csv: a symbolic link of that name is there (never written through)',
            'LOC_3-Dec-2026-02h00m00s.csv: a FIFO of that name is there',
        ]);
        expect(readFileSync(victim, 'utf8')).toBe('mine\n');
        expect(readFileSync(join(out, 'ORD_3-Dec-2026-02h00m00s.csv'), 'utf8')).toBe(moduleLog('ORD', 1));
    });

    it("a run whose log could not be saved does not end on an 'ok' line (it said ok, then refused the log, then exited 1)", () => {
        const outcome = {
            job: { sandboxName: 'bwrap', warnings: [], prepareDiagnostics: [], foreignMakefiles: [], status: 'succeeded' },
            result: { ok: true, message: 'run finished (exit 0)', step: 'run', issues: [], durations_ms: { prepare: 1900, build: 900, run: 2300 } },
            runLines: [], buildTail: [],
        } as unknown as JobOutcome;
        const io = capture(root);
        reportBuild({ format: 'text', dirArg: 'cell' } as Parameters<typeof reportBuild>[0], outcome, io, {}, [], ['log CEL_4-Dec-2026-11h27m40s.csv not written: a symbolic link of that name is there (never written through)']);
        expect(io.stderr).toBe('FAILED: run finished (exit 0), but log CEL_4-Dec-2026-11h27m40s.csv not written: a symbolic link of that name is there (never written through) [bwrap; prepare 1.9 s, build 0.9 s, run 2.3 s]\n');
        const fine = capture(root);
        reportBuild({ format: 'text', dirArg: 'cell' } as Parameters<typeof reportBuild>[0], outcome, fine);
        expect(fine.stderr).toMatch(/^ok: run finished \(exit 0\) \[bwrap;/);
    });
});

describe('a build that fails with no compiler, assembler or linker diagnostic', () => {
    const lines = [
        ['build', 'build', "make[1]: Entering directory '/work/src-gen/generated/architecture/modules/CTL_mod'"],
        ['build', 'build', 'cc -std=c11 -o CTL module.c'],
        ['build', 'build', 'cc: fatal error: Killed signal terminated program cc1'],
        ['build', 'build', 'compilation terminated.'],
        ['build', 'build', 'make[1]: *** [Makefile:23: CTL] Error 1'],
        ['build', 'build', "make[1]: Target 'all' not remade because of errors."],
        ['build', 'service', 'build: exit 2'],
        ['run', 'CTL', 'error: a module\'s own line is not the build\'s'],
    ] as const;
    const failed = (buildTail: string[], diagnostics: unknown[]) => ({
        job: { sandboxName: 'bwrap', warnings: [], prepareDiagnostics: [], foreignMakefiles: [], status: 'failed', diagnostics },
        result: { ok: false, message: 'build failed (make exit 2)', step: 'build', issues: [], durations_ms: { prepare: 300, build: 900 } },
        runLines: [], buildTail,
    } as unknown as JobOutcome);

    it('shows the build\'s error lines (the compiler killed, make\'s ***), not "the gcc errors above" with none above', () => {
        const tail: string[] = [];
        for (const [step, source, line] of lines) noteBuildErrorLine(tail, { type: 'line', step, source, stream: 'stdout', line } as never);
        expect(tail).toEqual(['cc: fatal error: Killed signal terminated program cc1', 'make[1]: *** [Makefile:23: CTL] Error 1']);
        const io = capture(root);
        reportBuild({ format: 'text', dirArg: 'cell' } as Parameters<typeof reportBuild>[0], failed(tail, []), io);
        expect(io.stderr).toBe([
            'FAILED: build failed (make exit 2) [bwrap; prepare 0.3 s, build 0.9 s]',
            "no compiler or linker error was reported; the build's last error lines:",
            '  | cc: fatal error: Killed signal terminated program cc1',
            '  | make[1]: *** [Makefile:23: CTL] Error 1',
            "fix what the build's error lines say, then build again; --verbose shows every build line",
            '',
        ].join('\n'));
    });

    it('says when gcc\'s diagnostics could not be read (a line of its JSON unreadable), not that no error was reported', () => {
        const tail = ['[{"kind": "error", "message": "x" ,, ]', 'make[1]: *** [Makefile:23: CTL] Error 1'];
        const outcome = failed(tail, []);
        (outcome.job as unknown as { unreadableDiagnosticLines: number }).unreadableDiagnosticLines = 1;
        const io = capture(root);
        reportBuild({ format: 'text', dirArg: 'cell' } as Parameters<typeof reportBuild>[0], outcome, io);
        expect(io.stderr).not.toContain('no compiler or linker error was reported');
        expect(io.stderr).toContain("gcc's diagnostics could not be read (1 line(s) of its JSON output): no error of theirs is reported, they may hold the build's errors; the build's last error lines:\n  | [{\"kind\": \"error\"");
    });

    it('keeps the last 15 such lines, each cut at 500 characters, its controls escaped; with a diagnostic, the usual words', () => {
        const tail: string[] = [];
        for (let i = 0; i < 40; i++) noteBuildErrorLine(tail, { type: 'line', step: 'build', source: 'build', stream: 'stdout', line: `error ${i}: \u001b[2J${'x'.repeat(i === 39 ? 900 : 1)}` } as never);
        expect(tail).toHaveLength(15);
        const io = capture(root);
        reportBuild({ format: 'text', dirArg: 'cell' } as Parameters<typeof reportBuild>[0], failed(tail, []), io);
        expect(io.stderr).toContain('  | error 25:');
        expect(io.stderr).not.toContain('  | error 24:');
        expect(io.stderr).not.toContain('\u001b');
        expect(io.stderr.split('\n').find((l) => l.includes('error 39'))!.length).toBeLessThan(520);
        const withError = capture(root);
        reportBuild({ format: 'text', dirArg: 'cell' } as Parameters<typeof reportBuild>[0], failed(tail, [{ severity: 'error' }]), withError);
        expect(withError.stderr).not.toContain('last error lines');
        expect(withError.stderr).toContain('fix the gcc errors above');
    });
});

describe('3. contract run: one run per logs folder', () => {
    it('moves the previous run\'s logs to OUT/previous/run-<time>/ (never deleted); `contract trace OUT` tells the new run only', async () => {
        const out = join(root, 'rotate');
        const first = await saveLogs(artifacts({ 'ORD_1-Dec-2026-10h00m00s.csv': moduleLog('ORD', 5_000_000_000), 'MIS_1-Dec-2026-10h00m00s.csv': moduleLog('MIS', 5_000_000_000) }), out, true);
        expect(first.movedAside).toBeNull();
        writeFileSync(join(out, 'notes.txt'), 'mine');
        const when = new Date(2026, 11, 1, 10, 0, 7);
        for (const f of first.saved) utimesSync(join(out, f), when, when);
        const second = await saveLogs(artifacts({ 'ORD_2-Dec-2026-11h00m00s.csv': moduleLog('ORD', 9_000_000_000) }), out, true);
        expect(second.movedAside).toEqual({ folder: join(out, 'previous', 'run-2026-12-01T10-00-07'), files: 2 });
        expect(readdirSync(out).sort()).toEqual(['ORD_2-Dec-2026-11h00m00s.csv', 'notes.txt', 'previous']);
        expect(readdirSync(join(out, 'previous', 'run-2026-12-01T10-00-07')).sort()).toEqual(['MIS_1-Dec-2026-10h00m00s.csv', 'ORD_1-Dec-2026-10h00m00s.csv']);
        const io = capture(root);
        expect(await runCli(['trace', 'rotate'], io)).toBe(0);
        expect(io.stdout).toMatch(/^3 records: /m); // one module's log of the new run, not five of two runs
        expect(io.stdout).not.toContain('MIS');
        // a third run: the second one's log gets a folder of its own (same time: a suffix)
        utimesSync(join(out, 'ORD_2-Dec-2026-11h00m00s.csv'), when, when);
        const third = await saveLogs(artifacts({ 'ORD_3-Dec-2026-12h00m00s.csv': moduleLog('ORD', 1) }), out, true);
        expect(third.movedAside).toEqual({ folder: join(out, 'previous', 'run-2026-12-01T10-00-07-2'), files: 1 });
    });

    it("a crashed module's crash file is saved with the logs, and moved aside with them at the next run (a .crash of another name, or a note of yours, left alone)", async () => {
        const out = join(root, 'crash-file');
        const report = 'contract crash report: module EST, signal 11\n';
        const first = await saveLogs(artifacts({ 'EST_1-Dec-2026-10h00m00s.csv': moduleLog('EST', 1, true), 'EST.crash': report, 'not-a-module!.crash': 'x', 'EST.core': 'x' }), out, true);
        expect(first.saved).toEqual(['EST.crash', 'EST_1-Dec-2026-10h00m00s.csv']);
        expect(readFileSync(join(out, 'EST.crash'), 'utf8')).toBe(report);
        writeFileSync(join(out, 'mine.crash.txt'), 'mine');
        const second = await saveLogs(artifacts({ 'EST_2-Dec-2026-10h00m00s.csv': moduleLog('EST', 2) }), out, true);
        expect(second.movedAside?.files).toBe(2);
        expect(readdirSync(out).sort()).toEqual(['EST_2-Dec-2026-10h00m00s.csv', 'mine.crash.txt', 'previous']);
    });

    it('two runs ending at once into one logs folder (two projects, one --logs): one run\'s logs stay, the other\'s and the earlier run\'s are moved aside whole, none lost or mixed', async () => {
        for (let round = 0; round < 10; round++) {
            const out = join(root, `shared-${round}`);
            await saveLogs(artifacts({ 'OLD_1.csv': moduleLog('OLD', 1), 'ORD_1.csv': moduleLog('ORD', 1) }), out, true);
            const a = artifacts(Object.fromEntries(['AAA', 'ABB', 'ACC', 'ORD'].map((m) => [`${m}_2.csv`, moduleLog(m, 2)])));
            const b = artifacts(Object.fromEntries(['BAA', 'BBB', 'ORD'].map((m) => [`${m}_2.csv`, moduleLog(m, 3)])));
            const [ra, rb] = await Promise.all([saveLogs(a, out, true), saveLogs(b, out, true)]);
            expect(ra.refused).toEqual([]);
            expect(rb.refused).toEqual([]);
            // every folder holds one run's logs, whole: the earlier run, and the two runs in either order
            const runs = [out, ...readdirSync(join(out, 'previous')).map((f) => join(out, 'previous', f))]
                .map((dir) => readdirSync(dir).filter((f) => f.endsWith('.csv')).sort()
                    .map((f) => `${f}:${readFileSync(join(dir, f), 'utf8').split('\n')[1].split(',')[0]}`).join(' '));
            expect(runs.sort()).toEqual([
                'AAA_2.csv:2 ABB_2.csv:2 ACC_2.csv:2 ORD_2.csv:2',
                'BAA_2.csv:3 BBB_2.csv:3 ORD_2.csv:3',
                'OLD_1.csv:1 ORD_1.csv:1',
            ]);
        }
    });

    it('a run of another process saving into the folder (its .contract-lock) is waited for, then the logs are saved', async () => {
        const out = join(root, 'shared-process');
        mkdirSync(out);
        const other = spawn('sleep', ['30'], { stdio: 'ignore' });
        try {
            writeFileSync(join(out, '.contract-lock'), `${other.pid} ${hostname()}\n`);
            let done = false;
            const saving = saveLogs(artifacts({ 'ORD_1.csv': moduleLog('ORD', 1) }), out, true).then((r) => { done = true; return r; });
            await new Promise((r) => setTimeout(r, 400));
            expect(done).toBe(false); // the other run holds the folder
            expect(readdirSync(out)).toEqual(['.contract-lock']);
            other.kill('SIGKILL');
            await new Promise((r) => other.once('exit', r));
            expect((await saving).saved).toEqual(['ORD_1.csv']); // its lock is stale once it is gone
            expect(readdirSync(out)).toEqual(['ORD_1.csv']); // and this one's is released
        } finally {
            other.kill('SIGKILL');
        }
    });

    it('a run that collects no log leaves the previous run\'s in place', async () => {
        const out = join(root, 'rotate-none');
        await saveLogs(artifacts({ 'ORD_1.csv': moduleLog('ORD', 1) }), out, true);
        const none = await saveLogs(artifacts({}), out, true);
        expect(none).toEqual({ saved: [], refused: [], movedAside: null });
        expect(readdirSync(out)).toEqual(['ORD_1.csv']);
    });

    it('refuses, before the run, an OUT/previous that is a link (the old logs would go through it)', async () => {
        const out = join(root, 'prev-link');
        mkdirSync(out);
        symlinkSync(join(root, 'victim-dir'), join(out, 'previous'));
        expect(await refusedPrevious(out)).toBe(`${join(out, 'previous')} is a symbolic link: the previous run's logs are moved there (never through a link); remove it, or name another folder with --logs OUT`);
        expect(await refusedPrevious(join(root, 'rotate'))).toBeNull();
        const io = capture(root);
        expect(await runCli(['run', 'robot', '--sandbox', 'none', '--logs', 'prev-link'], io)).toBe(1);
        expect(io.stderr).toContain('is a symbolic link: the previous run\'s logs are moved there');
        expect(io.stdout).toBe('');
    });
});

describe('4. --start naming a function the model does not have', () => {
    it('is refused before anything is built, exit 2, with a did-you-mean and the functions the model has', async () => {
        expect(await startProblem('MIS.misson()', join(root, 'robot'))).toBe(
            "bad --start 'MIS.misson()': supervisor MIS has no function 'misson'. Did you mean 'MIS.mission'? (the model's supervision functions: MIS.mission); nothing was started");
        expect(await startProblem('MSI.mission()', join(root, 'robot'))).toMatch(/^bad --start 'MSI\.mission\(\)': the model has no supervisor 'MSI'\. Did you mean 'MIS\.mission'\?/);
        expect(await startProblem('MIS.mission(goal={1.0,2.0,0.0})', join(root, 'robot'))).toBeNull();
        const io = capture(root);
        expect(await runCli(['run', 'robot', '--sandbox', 'bwrap', '--start', 'MIS.misson()', '--logs', 'never'], io)).toBe(2);
        const [message, synopsis, more] = io.stderr.split('\n');
        expect(message).toBe("contract run: bad --start 'MIS.misson()': supervisor MIS has no function 'misson'. Did you mean 'MIS.mission'? (the model's supervision functions: MIS.mission); nothing was started");
        expect(synopsis).toMatch(/^usage: contract run DIR /); // bad usage as any other: the synopsis follows
        expect(more).toBe('(contract run --help lists every option)');
        expect(io.stdout).toBe('');
        expect(existsSync(join(root, 'cache', 'projects'))).toBe(false); // nothing prepared
    });

    it('a parameter the function does not have, or a value of the wrong type, is refused the same way', async () => {
        expect(await startProblem('MIS.mission(gaol={1.0,2.0,0.0})', join(root, 'robot'))).toBe(
            "bad --start 'MIS.mission(gaol={1.0,2.0,0.0})': MIS.mission has no parameter 'gaol' (parameters: goal). Did you mean 'goal'?; nothing was started");
        expect(await startProblem('MIS.mission(goal="far")', join(root, 'robot'))).toMatch(/^bad --start 'MIS\.mission\(goal="far"\)': Expected .* for parameter 'goal', found a string; nothing was started$/);
        // written in a way the scenario reader does not take: left to the supervisor (a refusal is a run issue, start-refused)
        expect(await startProblem('MIS.mission(goal={1.0,2.0,0.0', join(root, 'robot'))).toBeNull();
    });
});

describe('5. model and generation problems in build/run: once, at the right path, with a true hint', () => {
    it('formats a generator problem at its src-gen path without a column 0, a model problem at its project path', () => {
        const job = {
            prepareDiagnostics: [
                { file: 'types.contract', line: 1, column: 21, severity: 'error', message: 'Expected an int' },
                { file: 'generated/architecture/modules/CTL_mod/module.c', line: 17, column: 0, severity: 'error', message: 'nested protected region start' },
                { file: '(manifest)', line: 0, column: 0, severity: 'warning', message: 'note' },
            ],
        } as unknown as Job;
        expect(prepareErrors(job, 'robot')).toBe(
            'robot/types.contract:1:21: error: Expected an int\n' +
            'robot/src-gen/generated/architecture/modules/CTL_mod/module.c:17: error: nested protected region start\n' +
            '(manifest): warning: note\n');
    });

    it('a model error is printed once (bwrap)', async () => {
        mkdirSync(join(root, 'broken'));
        writeFileSync(join(root, 'broken', 'types.contract'), 'datatype T {int a = 1.5};\n');
        const io = capture(root);
        expect(await runCli(['build', 'broken', '--sandbox', 'bwrap'], io)).toBe(1);
        expect(io.stderr.match(/\S*types\.contract:1:\d+: error: /g)).toEqual(['broken/types.contract:1:21: error: ']);
        expect(io.stderr).toContain('fix the model errors above (`contract check broken` lists them), then build again');
    }, 240_000);

    it('a run whose build fails leaves an earlier --trace file as it was, and says so; --trace takes only a *.jsonl name (bwrap)', async () => {
        mkdirSync(join(root, 'broken-run'));
        writeFileSync(join(root, 'broken-run', 'types.contract'), 'datatype T {int a = 1.5};\n');
        writeFileSync(join(root, 'earlier.jsonl'), 'the earlier run\n');
        const io = capture(root);
        expect(await runCli(['run', 'broken-run', '--sandbox', 'bwrap', '--duration', '1s', '--trace', 'earlier.jsonl'], io)).toBe(1);
        expect(readFileSync(join(root, 'earlier.jsonl'), 'utf8')).toBe('the earlier run\n');
        expect(io.stderr).toMatch(/earlier\.jsonl was left as it was \(no record: nothing ran\)/);
        // a slip of the name: refused before anything is built, the file untouched
        const model = readFileSync(join(root, 'broken-run', 'types.contract'), 'utf8');
        const slip = capture(root);
        expect(await runCli(['run', 'broken-run', '--sandbox', 'bwrap', '--trace', 'broken-run/types.contract'], slip)).toBe(2);
        expect(slip.stderr).toContain('a trace file is named *.jsonl');
        expect(readFileSync(join(root, 'broken-run', 'types.contract'), 'utf8')).toBe(model);
    }, 240_000);

    it('a broken protected-region marker is printed once at its src-gen path, and the hint names the command that lists it (bwrap)', async () => {
        expect(await runCli(['new', 'marker'], capture(root))).toBe(0);
        expect(await runCli(['generate', 'marker'], capture(root))).toBe(0);
        const file = join(root, 'marker/src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        writeFileSync(file, source.replace('/*PROTECTED REGION END*/', '/*PROTECTED REGOIN END*/'));
        const io = capture(root);
        expect(await runCli(['build', 'marker', '--sandbox', 'bwrap'], io)).toBe(1);
        // (the generator's wording of a broken marker may change: the place and the count are what is checked)
        const lines = io.stderr.split('\n').filter((l) => /module\.c(:\d+)*: error: /.test(l));
        expect(lines).toEqual([expect.stringMatching(/^marker\/src-gen\/generated\/architecture\/modules\/CTL_mod\/module\.c:\d+: error: /)]);
        expect(io.stderr).toContain('`contract generate marker` lists them');
        expect(io.stderr).not.toContain('contract check');
        // and that command does list it
        const generate = capture(root);
        expect(await runCli(['generate', 'marker'], generate)).toBe(1);
        expect(generate.stderr).toMatch(/^error: marker\/src-gen\/generated\/architecture\/modules\/CTL_mod\/module\.c:\d+: /m);
    }, 240_000);
});

describe('6. a crashed module', () => {
    it('gets no "set *stateindex = -1?" advice, in the problems and the summary line', () => {
        const issues = [
            { kind: 'module-stuck', module: 'CTL', message: 'CTL has not finished release #6 after 100 periods: does its exec region set *stateindex = -1?' },
            { kind: 'module-stuck', module: 'LOC', message: 'LOC has not finished release #2 after 100 periods: does its exec region set *stateindex = -1?' },
        ];
        expect(problemLines(issues, [{ module: 'CTL', how: 'died by signal 11 (Segmentation fault)' }])).toEqual([
            'CTL has not finished release #6 after 100 periods: it crashed (died by signal 11 (Segmentation fault))',
            'LOC has not finished release #2 after 100 periods: does its exec region set *stateindex = -1?',
        ]);
    });

    it('contract trace says which module has no exit record, or no record at all', async () => {
        const dir = join(root, 'crashed-logs');
        mkdirSync(dir);
        writeFileSync(join(dir, 'ORD_1.csv'), moduleLog('ORD', 1_000_000_000));
        writeFileSync(join(dir, 'CTL_1.csv'), moduleLog('CTL', 1_000_000_000, true));
        writeFileSync(join(dir, 'LOC_1.csv'), `${HEADER}\n`);
        const io = capture(root);
        expect(await runCli(['trace', 'crashed-logs'], io)).toBe(0);
        const lines = io.stdout.split('\n');
        expect(lines.at(-4)).toBe('+0.000001s CTL  its last record: no exit record follows (it crashed, was killed, or its code called exit(); the launcher\'s output says which)');
        expect(lines.at(-3)).toBe('           LOC  no record in its log: it crashed, hung or was killed before writing any (the launcher\'s output says which)');
        expect(lines.at(-2)).toMatch(/^5 records: /);
    });

    it('contract trace tells a file named as a log that holds no record, only unreadable lines, as no runtime log, and not as its module\'s second log', async () => {
        const dir = join(root, 'not-logs');
        mkdirSync(dir);
        writeFileSync(join(dir, 'ORD_1.csv'), moduleLog('ORD', 1_000_000_000));
        writeFileSync(join(dir, 'CTL_1.csv'), moduleLog('CTL', 1_000_000_000));
        writeFileSync(join(dir, 'CTL_2.csv'), '{"not":"a log"}\n'); // a second file under CTL's name
        writeFileSync(join(dir, 'JSN_1.csv'), '{"kind":"user"}\n');
        writeFileSync(join(dir, 'EMP_1.csv'), `${HEADER}\n`);
        const io = capture(root);
        expect(await runCli(['trace', 'not-logs', '--merge-logs'], io)).toBe(0);
        const lines = io.stdout.split('\n');
        // CTL_2.csv does not begin with the runtime's header: no log, refused whole, no second log of CTL
        expect(io.stdout + io.stderr).not.toContain('logs of it');
        expect(io.stderr).toContain(`contract trace: warning: CTL_2.csv: ${NOT_A_LOG_WHY}`);
        expect(io.stderr).toContain(`contract trace: warning: JSN_1.csv: ${NOT_A_LOG_WHY}`);
        expect(lines).toContain('           JSN  no record in its log, only 1 unreadable line(s): not a runtime log (one begins with the CSV header, then the module\'s start record)');
        expect(lines).toContain('           EMP  no record in its log: it crashed, hung or was killed before writing any (the launcher\'s output says which)');
        expect(lines.filter((l) => / ORD  .*logs of it|ORD  no record/.test(l))).toEqual([]);
    });

    it('contract trace reads a log folder as the Monitor does: every *.csv file, a module named with _ is one module, a log of another name is read and its lines said', async () => {
        const dir = join(root, 'underscore-logs');
        mkdirSync(dir);
        writeFileSync(join(dir, 'ORD_6-Dec-2026-18h00m00s.csv'), moduleLog('ORD', 1_000_000_000));
        writeFileSync(join(dir, 'ARM_CTL_6-Dec-2026-18h00m00s.csv'), moduleLog('ARM_CTL', 1_000_000_000));
        writeFileSync(join(dir, 'ARM_GRIP_6-Dec-2026-18h00m00s.csv'), moduleLog('ARM_GRIP', 1_000_000_000, true));
        writeFileSync(join(dir, 'calibration.csv'), 'x,y\n1,2\n');
        const io = capture(root);
        expect(await runCli(['trace', 'underscore-logs'], io)).toBe(0);
        expect(io.stdout).not.toContain('logs of it in this folder');
        expect(io.stdout).toContain('ARM_GRIP its last record: no exit record follows');
        expect(io.stdout).toContain('unreadable: calibration.csv line 1:');
        const json = capture(root);
        expect(await runCli(['trace', 'underscore-logs', '--format', 'json'], json)).toBe(0);
        const modules = new Set(json.stdout.trim().split('\n').map((l) => JSON.parse(l) as { module?: string }).map((r) => r.module).filter(Boolean));
        expect([...modules].sort()).toEqual(['ARM_CTL', 'ARM_GRIP', 'ORD']);
    });

    it('contract trace says a log that lacks its start record was cut or rewritten (its module truncated it), and how it ended is not in it', async () => {
        const dir = join(root, 'truncated-logs');
        mkdirSync(dir);
        writeFileSync(join(dir, 'ORD_1.csv'), moduleLog('ORD', 1_000_000_000));
        // HOG's code truncated its log mid-run, then was killed: no start, no exit (its header kept:
        // a log without it is no log, refused whole, runtime-api.md "Whose records, and their times")
        writeFileSync(join(dir, 'HOG_1.csv'), `${HEADER}\n1000400000,w,HOG,user,,,0,alloc 4 MiB\n1000500000,w,HOG,user,,,0,alloc 4 MiB\n`);
        // CTL's lost its start only
        writeFileSync(join(dir, 'CTL_1.csv'), `${HEADER}\n1000001000,w,CTL,scheduler,,,0,activate S\n1002000000,w,CTL,module_exit,,,0,status=0\n`);
        const io = capture(root);
        expect(await runCli(['trace', 'truncated-logs'], io)).toBe(0);
        expect(io.stdout).toContain('+0.000500s HOG  its last record; its log holds neither its start nor its exit record: it was cut or rewritten after the module began (its code may have truncated it), and how it ended is not in it (the launcher\'s output says it)\n');
        expect(io.stdout).toContain('           CTL  its log lacks its start record: it was cut or rewritten after the module began (its code may have truncated it)\n');
        expect(io.stdout).not.toContain('ORD  its log lacks');
    });

    it('contract trace says a log the build service cut (its log-capped record) was cut, not that its module crashed', async () => {
        const dir = join(root, 'cut-by-service');
        mkdirSync(dir);
        writeFileSync(join(dir, 'ORD_1.csv'), moduleLog('ORD', 1_000_000_000));
        const ctl = moduleLog('CTL', 1_000_000_000, true) + '1000001000,2026-12-05T19:00:00.000Z,CTL,log-capped,build-service,,99999,collected the first 4000 of 99999 bytes (the 4096-byte bound of the build service)\n';
        writeFileSync(join(dir, 'CTL_1.csv'), ctl);
        const io = capture(root);
        expect(await runCli(['trace', 'cut-by-service'], io)).toBe(0);
        expect(io.stdout).toContain('+0.000001s CTL  its log was cut here by the build service (its bound on a collected log): later records, its exit record among them, are not in it\n');
        expect(io.stdout).not.toContain('no exit record follows');
        expect(io.stdout).toMatch(/, 0 unreadable lines\n$/);
    });

    it('a module other modules\' records name, whose log is not read (a link under its name) or not there, is told, not left out of the story', async () => {
        const dir = join(root, 'trace-unlogged');
        mkdirSync(dir);
        const ord = moduleLog('ORD', 1_000_000_000).split('\n');
        // ORD releases HOG; CTL posts values to SRT; a control tool's request and a launcher's name no module
        ord.splice(3, 0, '1000002000,w,ORD,ord_release,HOG,,0,schema=S cycle=0 tick_ns=1000002000 release_ns=1000002000 release=1',
            '1000003000,w,ORD,request_received,controlHOG-77,,0,STATUS', '1000003500,w,ORD,data_posted,CTL,0,8,to_port=0');
        writeFileSync(join(dir, 'ORD_1.csv'), ord.join('\n'));
        const ctl = moduleLog('CTL', 1_000_000_000).split('\n');
        ctl.splice(3, 0, '1000004000,w,CTL,data_posted,SRT,0,8,to_port=1', '1000005000,w,CTL,data_posted,not-a-module,0,8,to_port=1');
        writeFileSync(join(dir, 'CTL_1.csv'), ctl.join('\n'));
        symlinkSync('/etc/passwd', join(dir, 'HOG_1.csv'));
        const io = capture(root);
        expect(await runCli(['trace', 'trace-unlogged'], io)).toBe(0);
        expect(io.stderr).toBe('contract trace: warning: HOG_1.csv: a symbolic link, not read (logs are never read through a link)\n');
        expect(io.stdout.split('\n').filter((l) => l.includes('no log of it here'))).toEqual([
            "+0.000002s HOG  no log of it here, though other modules' records name it (the first: ORD's ord_release): its log was not collected (`contract run` says why) or was removed",
            "+0.000004s SRT  no log of it here, though other modules' records name it (the first: CTL's data_posted): its log was not collected (`contract run` says why) or was removed",
        ]);
        // a forged log naming many modules: 16 named, the others counted
        const many = moduleLog('CTL', 1_000_000_000).split('\n');
        many.splice(3, 0, ...Array.from({ length: 20 }, (_, i) => `${1_000_010_000 + i},w,CTL,data_posted,M${i},0,8,to_port=0`));
        writeFileSync(join(dir, 'CTL_1.csv'), many.join('\n'));
        const forged = capture(root);
        expect(await runCli(['trace', 'trace-unlogged'], forged)).toBe(0);
        const told = forged.stdout.split('\n').filter((l) => / no log of it here|with no log here$/.test(l));
        expect(told).toHaveLength(17);
        expect(told.at(-1)).toBe("           5 more module(s) named by other modules' records with no log here");
    });

    it('contract trace names modules without an exit record in the order of their last record, and a whole run killed in one line', async () => {
        // two modules crashed (CTL's last record after LOC's, CTL read first), ORD exited
        const two = join(root, 'two-crashed');
        mkdirSync(two);
        writeFileSync(join(two, 'CTL_1.csv'), moduleLog('CTL', 1_000_500_000, true));
        writeFileSync(join(two, 'LOC_1.csv'), moduleLog('LOC', 1_000_000_000, true));
        writeFileSync(join(two, 'ORD_1.csv'), moduleLog('ORD', 1_000_000_000));
        let io = capture(root);
        expect(await runCli(['trace', 'two-crashed'], io)).toBe(0);
        expect(io.stdout.split('\n').filter((l) => l.includes('no exit record'))).toEqual([
            '+0.000001s LOC  its last record: no exit record follows (it crashed, was killed, or its code called exit(); the launcher\'s output says which)',
            '+0.000501s CTL  its last record: no exit record follows (it crashed, was killed, or its code called exit(); the launcher\'s output says which)',
        ]);
        // every module without its exit record (the runner killed): one line, at the last record
        const killed = join(root, 'run-killed');
        mkdirSync(killed);
        for (const [m, t] of [['CTL', 1_000_500_000], ['LOC', 1_000_000_000], ['ORD', 1_000_200_000]] as const) writeFileSync(join(killed, `${m}_1.csv`), moduleLog(m, t, true));
        io = capture(root);
        expect(await runCli(['trace', 'run-killed'], io)).toBe(0);
        expect(io.stdout.split('\n').filter((l) => l.includes('exit record'))).toEqual([
            '+0.000501s the records end here: no module wrote its exit record (3 modules): the run was killed before its end, or is still running',
        ]);
    });

    it('a real crash (bwrap): exit 1, the crash named, no advice to set *stateindex', async () => {
        expect(await runCli(['new', 'crash'], capture(root))).toBe(0);
        expect(await runCli(['generate', 'crash'], capture(root))).toBe(0);
        const file = join(root, 'crash/src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        writeFileSync(file, source.replace(/(PROTECTED REGION ID\(protect_exec_CTL\) ENABLED START\*\/)/, '$1\n    { static int calls = 0; if (++calls == 3) { volatile int *p = 0; *p = 1; } }'));
        const io = capture(root);
        expect(await runCli(['run', 'crash', '--sandbox', 'bwrap', '--duration', '3s'], io)).toBe(1);
        expect(io.stderr).toContain('module CTL crashed (died by signal 11');
        expect(io.stderr).not.toContain('stateindex');
        const trace = capture(root);
        expect(await runCli(['trace', 'crash/logs'], trace)).toBe(0);
        // the runtime writes the records it had not written, then its crash record (docs/runtime-api.md "CSV log")
        expect(trace.stdout).toMatch(/^\+\d+\.\d{6}s CTL  crashed: signal 11 \(SIGSEGV\): a bad pointer: NULL, freed, or past the end of an array$/m);
        expect(trace.stdout).not.toContain('CTL  its last record: no exit record follows');
    }, 240_000);

    it('a --ready-timeout below 100 ms, or not a duration, is a usage error', async () => {
        for (const bad of ['50ms', 'soon', '-1s']) {
            const io = capture(root);
            expect(await runCli(['run', 'robot', '--ready-timeout', bad], io)).toBe(2);
            expect(io.stderr).toMatch(/bad --ready-timeout '50ms': at least 100ms|bad duration 'soon'|bad duration '-1s'/);
        }
    });

    it('a real init region that blocks for ever (bwrap): exit 4 at the ready timeout, not ready named, no start sent, its records kept', async () => {
        expect(await runCli(['new', 'stall'], capture(root))).toBe(0);
        expect(await runCli(['generate', 'stall'], capture(root))).toBe(0);
        const file = join(root, 'stall/src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        const edited = source.replace(/(PROTECTED REGION ID\(protect_init_CTL\) ENABLED START\*\/)/, '$1\n    ContractLog("waiting", "", -1, 0, "for the gripper"); for (;;) { struct timespec t = { 1, 0 }; nanosleep(&t, NULL); }');
        expect(edited).not.toBe(source);
        writeFileSync(file, edited);
        // built first: the run's own build is then the cache's, and its wall time is the run's (a cold build on a loaded machine took 20 s)
        expect(await runCli(['build', 'stall', '--sandbox', 'bwrap'], capture(root))).toBe(0);
        const io = capture(root);
        const t0 = Date.now();
        expect(await runCli(['run', 'stall', '--sandbox', 'bwrap', '--duration', '30s', '--ready-timeout', '3s'], io)).toBe(4);
        expect(Date.now() - t0).toBeLessThan(30_000); // the 3 s ready timeout asked, not the 30 s of the run
        expect(io.stderr).toContain('problem: CTL was not ready after 3 s: its init region had not returned (does it loop or block?), so the run stopped before its start request');
        expect(io.stderr).not.toContain('CTL did not end when the run stopped'); // the same fault, told once
        expect(io.stdout + io.stderr).not.toMatch(/started [A-Z]+\.\w+\(/); // the start request was never sent
        const trace = capture(root);
        expect(await runCli(['trace', 'stall/logs'], trace)).toBe(0);
        // terminated at the stop (SIGTERM), it still wrote what it logged in its init (docs/runtime-api.md "CSV log")
        // (its own record, logged with ContractLog: docs/runtime-api.md)
        expect(trace.stdout).toMatch(/^\+\d+\.\d{6}s CTL  waiting: for the gripper$/m);
        expect(trace.stdout).toContain(' 0 unreadable lines');
    }, 240_000);
});

describe('7. names from a project or a sandbox cannot forge a line', () => {
    it('safeName escapes newlines, tabs, CR, every control, line separators, bidi overrides and directional marks', () => {
        expect(safeName('a\nok: run finished (exit 0)')).toBe('a\\u000aok: run finished (exit 0)');
        expect(safeName('t\tb\rc\x1b[2J\x9b\u2028\u202e')).toBe('t\\u0009b\\u000dc\\u001b[2J\\u009b\\u2028\\u202e');
        // the marks reorder what is around them as the overrides do (the IDE's and the job log's rule, conventions' visibleText)
        expect(safeName('ORD_\u200fvsc.csv \u200e\u061c')).toBe('ORD_\\u200fvsc.csv \\u200e\\u061c');
        expect(safeName('robot/src-gen/modules/CTL_mod/module.c')).toBe('robot/src-gen/modules/CTL_mod/module.c');
    });

    it('contract check on a project file whose name holds a newline prints it on one line', async () => {
        mkdirSync(join(root, 'nl'));
        writeFileSync(join(root, 'nl', 'x\nok: run finished (exit 0) [bwrap].contract'), 'datatype T {int a = 1.5};\n');
        const io = capture(root);
        expect(await runCli(['check', 'nl'], io)).toBe(1);
        expect(io.stdout).toMatch(/^nl\/x\\u000aok: run finished \(exit 0\) \[bwrap\]\.contract:1:21 error /);
        expect(io.stdout.split('\n').filter((l) => l.startsWith('ok:'))).toEqual([]);
    });

    it('contract check on a project file whose name holds a directional mark prints the mark escaped', async () => {
        mkdirSync(join(root, 'rlm'));
        writeFileSync(join(root, 'rlm', 'types\u200f.contract'), 'datatype T {int a = 1.5};\n');
        const io = capture(root);
        expect(await runCli(['check', 'rlm'], io)).toBe(1);
        expect(io.stdout).toMatch(/^rlm\/types\\u200f\.contract:1:21 error /);
    });

    it('gcc and prepare diagnostics, and the logs folder, are printed escaped', () => {
        expect(formatGccDiagnostic({ file: 'm\nok: run finished.c', line: 1, column: 2, severity: 'error', message: 'x' } as never, 'robot')).toBe('robot/src-gen/m\\u000aok: run finished.c:1:2: error: x\n');
        const job = { prepareDiagnostics: [{ file: 'a\nFAILED: x.contract', line: 1, column: 1, severity: 'error', message: 'm' }] } as unknown as Job;
        expect(prepareErrors(job, 'robot')).toBe('robot/a\\u000aFAILED: x.contract:1:1: error: m\n');
    });
});

describe('7. contract simulate', () => {
    it('prints a scenario file name holding a newline escaped in its messages', async () => {
        const scenarios = join(root, 'sim-names');
        mkdirSync(scenarios);
        const name = 'x\nok: 1 passed, 0 failed.scenario';
        writeFileSync(join(scenarios, name), 'this is no scenario\n');
        const io = capture(scenarios);
        expect(await runCli(['simulate', join(root, 'robot'), name, '--cache-dir', join(root, 'sim-cache')], io)).toBe(2);
        expect(io.stderr).toContain('x\\u000aok: 1 passed, 0 failed.scenario:1:');
        expect(io.stderr.split('\n').filter((l) => l.startsWith('ok:'))).toEqual([]);
    }, 240_000);
});

describe('8. small ones', () => {
    it('an unknown command gets a did-you-mean', async () => {
        const io = capture(root);
        expect(await runCli(['trcae', 'x'], io)).toBe(2);
        expect(io.stderr).toMatch(/^contract: unknown command 'trcae'; did you mean 'trace'\?\n/);
        const far = capture(root);
        expect(await runCli(['deploy'], far)).toBe(2);
        expect(far.stderr).toMatch(/^contract: unknown command 'deploy'\n/);
    });

    it('contract build --help names --cache-dir in its usage line', async () => {
        for (const name of ['build', 'run']) {
            const io = capture(root);
            expect(await runCli([name, '--help'], io)).toBe(0);
            expect(io.stdout.split('\n')[0]).toContain('[--cache-dir DIR]');
        }
    });
});

describe('3. one run per logs folder, end to end (bwrap)', () => {
    it('two runs into one folder: contract trace OUT tells the second only, equal to its --trace file; the first is in OUT/previous', async () => {
        const first = capture(root);
        expect(await runCli(['run', 'robot', '--sandbox', 'bwrap', '--duration', '1s', '--logs', 'two-runs'], first)).toBe(0);
        expect(first.stderr).not.toContain('previous run');
        const firstLogs = readdirSync(join(root, 'two-runs')).sort();
        const second = capture(root);
        expect(await runCli(['run', 'robot', '--sandbox', 'bwrap', '--duration', '1s', '--logs', 'two-runs', '--trace', 'two-runs.jsonl'], second)).toBe(0);
        expect(second.stderr).toMatch(/^previous run's CSV logs: 4 file\(s\) moved to two-runs\/previous\/run-[\d-]+T[\d-]+$/m);
        const [older] = readdirSync(join(root, 'two-runs', 'previous'));
        expect(readdirSync(join(root, 'two-runs', 'previous', older!)).sort()).toEqual(firstLogs);
        const json = capture(root);
        expect(await runCli(['trace', 'two-runs', '--format', 'json'], json)).toBe(0);
        expect(json.stdout).toBe(readFileSync(join(root, 'two-runs.jsonl'), 'utf8'));
        // one run: each module started once
        expect(json.stdout.split('\n').filter((l) => l.includes('"kind":"module_started"'))).toHaveLength(4);
    }, 240_000);
});
