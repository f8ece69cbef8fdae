/** `contract new`, `build`, `run`: usage errors, messages, exit codes, text output — real commands on real files. */
import { spawnSync } from 'node:child_process';
import { chmodSync, existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { checkCpus, checkStart, moduleFailures, parseDuration } from '../src/commands/run.js';
import { exitCodeOf } from '../src/job-runner.js';
import type { Job, JobResult } from '@contract-studio/build-service';
import { REPO } from './e2e/harness.js';
import { capture } from './capture-io.js';
import { removeScratch } from './scratch.js';
import { seedRuntime } from '@contract-studio/build-service/test-support/runtime-seed';


let root: string;
beforeAll(async () => {
    root = mkdtempSync(join(tmpdir(), 'contract-nbr-'));
    chmodSync(root, 0o711);
    process.env.CONTRACT_CACHE_DIR = join(root, 'cache');
    // the test run's built runtime, in both caches the builds use
    for (const cache of ['cache', 'cache-opt']) await seedRuntime(join(root, cache));
}, 240_000);
afterAll(() => {
    delete process.env.CONTRACT_CACHE_DIR;
    removeScratch(root);
});

describe('contract new', () => {
    it('creates the template project, which checks without errors', async () => {
        const io = capture(root);
        expect(await runCli(['new', 'robot'], io)).toBe(0);
        expect(readdirSync(join(root, 'robot')).sort()).toEqual(['.gitignore', 'datatype.contract', 'module1.contract', 'module2.contract', 'sched.contract', 'schema.contract', 'supervisor.contract']);
        expect(io.stdout).toContain('created robot/supervisor.contract');
        // what it writes that is no source is ignored by git; src-gen/ (manifest, orphans/) is not
        const ignored = readFileSync(join(root, 'robot', '.gitignore'), 'utf8').split('\n').filter((l) => l && !l.startsWith('#'));
        expect(ignored).toEqual(['logs/', 'src-gen/.contract-lock', 'src-gen/.contract-rename.json', 'src-gen/.contract-regions.json', '*.o']);
        const check = capture(root);
        expect(await runCli(['check', 'robot'], check)).toBe(0);
        expect(check.stderr).toMatch(/^0 errors, 0 warnings/);
    }, 60_000);

    it('kept in git: the generated files and the manifest are committed, the copy of the regions\' code is not, so CI\'s generate + git diff stays clean after a region edit committed without a generate', async () => {
        const git = (dir: string, ...args: string[]) => spawnSync('git', ['-c', 'user.name=lab', '-c', 'user.email=lab@example.org', '-c', 'commit.gpgsign=false', '-c', 'core.hooksPath=/dev/null', ...args], { cwd: dir, encoding: 'utf8' });
        expect(await runCli(['new', 'team'], capture(root))).toBe(0);
        const dir = join(root, 'team');
        const ctl = join(dir, 'src-gen/generated/architecture/modules/CTL_mod/module.c');
        expect(await runCli(['generate', 'team'], capture(root))).toBe(0);
        writeFileSync(ctl, readFileSync(ctl, 'utf8').replace('//TODO : implement the activity of one period, one state per call', 'static int steps = 0; steps++; (void)steps;'));
        expect(await runCli(['generate', 'team'], capture(root))).toBe(0);
        expect(readFileSync(join(dir, 'src-gen/.contract-regions.json'), 'utf8')).toContain('steps++');
        expect(git(dir, 'init', '-q').status).toBe(0);
        expect(git(dir, 'add', '-A').status).toBe(0);
        expect(git(dir, 'commit', '-q', '-m', 'first').status).toBe(0);
        const tracked = git(dir, 'ls-files').stdout.split('\n');
        expect(tracked).toEqual(expect.arrayContaining(['.gitignore', 'src-gen/.contract-manifest.json', 'src-gen/generated/architecture/modules/CTL_mod/module.c']));
        expect(tracked).not.toContain('src-gen/.contract-regions.json');
        // a teammate changes the code in the region and commits it, generating nothing
        writeFileSync(ctl, readFileSync(ctl, 'utf8').replace('steps++;', 'steps += 2;'));
        expect(git(dir, 'commit', '-q', '-a', '-m', 'two steps').status).toBe(0);
        // CI's step (docs/ci.md): generate, then fail if src-gen/ is not committed up to date
        expect(await runCli(['generate', 'team'], capture(root))).toBe(0);
        expect(readFileSync(join(dir, 'src-gen/.contract-regions.json'), 'utf8')).toContain('steps += 2;');
        const diff = git(dir, 'diff', '--exit-code', '--stat', '--', 'src-gen');
        expect(diff.stdout).toBe('');
        expect(diff.status).toBe(0);
        expect(git(dir, 'status', '--porcelain').stdout).toBe('');
    }, 60_000);

    it('refuses a non-empty folder and leaves its files alone', async () => {
        mkdirSync(join(root, 'busy'));
        writeFileSync(join(root, 'busy', 'notes.txt'), 'mine');
        const io = capture(root);
        expect(await runCli(['new', 'busy'], io)).toBe(1);
        expect(io.stderr).toContain('busy is not empty; nothing was written');
        expect(readdirSync(join(root, 'busy'))).toEqual(['notes.txt']);
        expect(readFileSync(join(root, 'busy', 'notes.txt'), 'utf8')).toBe('mine');
    });

    it('needs a DIR', async () => {
        const io = capture(root);
        expect(await runCli(['new'], io)).toBe(2);
        expect(io.stderr).toContain('missing DIR');
    });
});

describe('contract build / run usage', () => {
    it('documents the options and exit codes in --help', async () => {
        for (const name of ['build', 'run']) {
            const io = capture(root);
            expect(await runCli([name, '--help'], io)).toBe(0);
            expect(io.stdout).toContain('--sandbox');
            expect(io.stdout).toContain('3 no usable sandbox');
        }
        const io = capture(root);
        await runCli(['run', '--help'], io);
        expect(io.stdout).toContain('--duration');
        expect(io.stdout).toContain('--start');
        expect(io.stdout).toContain('--realtime: modules take their SCHED_FIFO priorities in the sandbox');
    });

    it('refuses --realtime where nothing would bound it, saying why, before any work', async () => {
        const io = capture(root);
        expect(await runCli(['run', 'robot', '--realtime', '--sandbox', 'none', '--duration', '1s'], io)).toBe(1);
        expect(io.stderr + io.stdout).toContain('real-time mode refused: real-time mode needs the bwrap or docker sandbox');
        expect(io.stderr + io.stdout).not.toMatch(/build finished/);
        const build = capture(root);
        expect(await runCli(['build', 'robot', '--realtime'], build)).toBe(2);
        expect(build.stderr).toContain('unknown option --realtime');
    });

    it('rejects an unknown sandbox, a bad duration, a bad start request and a missing folder with exit 2', async () => {
        const cases: [string[], string][] = [
            [['build', 'robot', '--sandbox', 'vm'], "unknown sandbox 'vm' (expected auto, bwrap, docker or none)"],
            [['run', 'robot', '--duration', 'soon'], "bad duration 'soon' (expected e.g. 10s, 500ms, 2m)"],
            [['run', 'robot', '--start', 'not a call'], "bad --start 'not a call'"],
            [['build', 'nowhere'], 'nowhere is not a directory'],
            [['build'], 'missing DIR'],
            [['run', 'robot', '--format', 'xml'], "unknown format 'xml'"],
            [['run', 'robot', '--cpus', '0;reboot'], "bad --cpus '0;reboot' (expected a CPU list such as 1, 0-1 or 0,2)"],
        ];
        for (const [args, message] of cases) {
            const io = capture(root);
            expect(await runCli(args, io), args.join(' ')).toBe(2);
            expect(io.stderr).toContain(message);
        }
    });

    it('parses durations and start requests', () => {
        expect(parseDuration('10s')).toBe(10);
        expect(parseDuration('500ms')).toBe(0.5);
        expect(parseDuration('2m')).toBe(120);
        expect(parseDuration('1.5')).toBe(1.5);
        expect(() => parseDuration('0s')).toThrow(/positive/);
        expect(() => parseDuration('-1s')).toThrow(/bad duration/);
        expect(checkStart('GLB.mission(consigne={1.0,2.0,3.0})')).toBe('GLB.mission(consigne={1.0,2.0,3.0})');
        expect(checkStart('MIS.mission')).toBe('MIS.mission');
        expect(checkStart('')).toBe('');
        expect(() => checkStart('mission()')).toThrow(/SUPERVISOR\.function/);
        // what the build service refuses (a backslash, a quote other than ", a $) is bad usage here, exit 2
        expect(() => checkStart('XSU.f(s="\\x")')).toThrow(/no backslash, single quote, \$ or other sign/);
        expect(() => checkStart("XSU.f(s='a')")).toThrow(/no backslash/);
        expect(checkStart('XSU.f(s="a b", n=-1.5e3, m=Mode.AUTO)')).toBe('XSU.f(s="a b", n=-1.5e3, m=Mode.AUTO)');
        // a number glued to letters: no reader takes it; refused before the build (the supervisor refused it once started)
        expect(() => checkStart('FLT.hold(height = 1.5x)')).toThrow(/'1\.5x' is not a number/);
        expect(() => checkStart('FLT.hold(delay = 20ms)')).toThrow(/'20ms' is not a number/);
        expect(checkStart('FLT.hold(note = "1.5x", v = {1.0,-2,3e2}, m = Mode.F2, x2 = +2)')).toBe('FLT.hold(note = "1.5x", v = {1.0,-2,3e2}, m = Mode.F2, x2 = +2)');
        expect(checkCpus('0-1,3', 4)).toBe('0-1,3');
        // a CPU the machine does not have: refused before anything is built (exit 2), not after the build by the launcher
        expect(() => checkCpus('0-1,3', 2)).toThrow("bad --cpus '0-1,3': CPU 3 is not available here (2 CPUs online: 0-1)");
        expect(() => checkCpus('5-9', 8)).toThrow(/CPU 8 is not available here \(8 CPUs online: 0-7\)/);
        expect(() => checkCpus('1-')).toThrow(/CPU list/);
    });

    it('names the crashed module from the launcher lines', () => {
        const lines = [
            { source: 'launcher', stream: 'stderr', line: 'module MSC (pid 12) died by signal 11 (Segmentation fault)' },
            { source: 'MSA', stream: 'stdout', line: 'FAILED: module MSA crashed' },
            { source: 'launcher', stream: 'stderr', line: 'module MSA (pid 13) exited with status 0' },
            { source: 'launcher', stream: 'stderr', line: 'FAILED: module MSC crashed' },
        ];
        expect(moduleFailures(lines)).toEqual([{ module: 'MSC', how: 'died by signal 11 (Segmentation fault)' }]);
        // a crash or a non-zero exit while the run stopped (its exit code) is named as such
        expect(moduleFailures([
            { source: 'launcher', stream: 'stderr', line: 'module MSC (pid 12) exited with status 3 while the run stopped' },
            { source: 'launcher', stream: 'stderr', line: 'module MSB (pid 14) died by signal 6 (Aborted) while the run stopped' },
            { source: 'launcher', stream: 'stderr', line: 'FAILED: module MSC crashed' },
            { source: 'launcher', stream: 'stderr', line: 'FAILED: module MSB crashed' },
        ])).toEqual([{ module: 'MSC', how: 'exited with status 3 while the run stopped' }, { module: 'MSB', how: 'died by signal 6 (Aborted) while the run stopped' }]);
    });

    it('exits 4 for a run that hit a limit or has run issues, 1 for other failures, 130 when cancelled', () => {
        const base = { ok: false, step: 'run', exitCode: 0, signal: null, message: '', limitHit: null, issues: [], truncated: { stdout: false, stderr: false }, durations_ms: {}, mechanisms: null } as unknown as JobResult;
        const failed = { status: 'failed' } as Job;
        const limit = { name: 'runSeconds', value: 60, unit: 's', mechanism: 'service-timer' } as const;
        expect(exitCodeOf({ ...base, limitHit: limit }, failed)).toBe(4);
        expect(exitCodeOf({ ...base, issues: [{ kind: 'module-stuck', module: 'CTL', message: 'CTL has not finished release #2 after 10 periods' }] }, failed)).toBe(4);
        expect(exitCodeOf({ ...base, exitCode: 1 }, failed)).toBe(1);
        expect(exitCodeOf({ ...base, step: 'build', issues: [] }, failed)).toBe(1);
        expect(exitCodeOf({ ...base, limitHit: limit }, { status: 'cancelled' } as Job)).toBe(130);
        expect(exitCodeOf({ ...base, ok: true }, { status: 'succeeded' } as Job)).toBe(0);
    });
});

describe('contract build / run on a project (bwrap)', () => {
    it('builds the new project quietly when not on a terminal: one summary line', async () => {
        const io = capture(root);
        expect(await runCli(['build', 'robot', '--sandbox', 'bwrap'], io)).toBe(0);
        expect(io.stdout).toBe('');
        expect(io.stderr).toMatch(/^ok: build succeeded \[bwrap; prepare \d+\.\d s, build \d+\.\d s\]\n$/);
    }, 240_000);

    it('uses CONTRACT_CACHE_DIR, and --cache-dir over it; a second build writes and compiles nothing', async () => {
        const env = capture(root);
        expect(await runCli(['build', 'robot', '--sandbox', 'bwrap', '--verbose'], env)).toBe(0);
        expect(env.stderr).toContain(`build cache: ${join(root, 'cache')} (env)\n`);
        const opt = join(root, 'cache-opt');
        const first = capture(root);
        expect(await runCli(['build', 'robot', '--sandbox', 'bwrap', '--verbose', '--cache-dir', 'cache-opt'], first)).toBe(0);
        expect(first.stderr).toContain(`build cache: ${opt} (option)\n`);
        expect(readdirSync(join(opt, 'projects')).length).toBe(1);
        expect(readdirSync(join(opt, 'runtime')).filter((n) => n.startsWith('runtime-')).length).toBe(1);
        const again = capture(root);
        expect(await runCli(['build', 'robot', '--sandbox', 'bwrap', '--verbose', '--cache-dir', 'cache-opt'], again)).toBe(0);
        expect(again.stderr).toMatch(/work tree ready: \d+ file\(s\), 0 updated \(incremental\)/);
        expect(again.stderr).not.toMatch(/^g?cc /m);
        // --verbose times every step
        for (const step of ['loading the build service', 'sandbox choice', 'workspace (lock, checks)', 'work tree check (digest)', 'generation + copy', 'runtime', 'sandbox start', 'work tree digest']) {
            expect(again.stderr).toMatch(new RegExp(`^time: ${step.replace(/[()+]/g, '\\$&')}.* \\d+ ms$`, 'm'));
        }
    }, 240_000);

    it('contract cache shows the cache folder; contract cache clear removes it (mounted work trees too)', async () => {
        const show = capture(root);
        expect(await runCli(['cache', '--cache-dir', 'cache-opt'], show)).toBe(0);
        expect(show.stdout).toBe(`${join(root, 'cache-opt')}\n`);
        expect(show.stderr).toContain('1 runtime build(s), 1 project work tree(s)');
        const clear = capture(root);
        expect(await runCli(['cache', 'clear', '--cache-dir', 'cache-opt'], clear)).toBe(0);
        expect(clear.stderr).toBe(`cleared ${join(root, 'cache-opt')}\n`);
        expect(existsSync(join(root, 'cache-opt'))).toBe(false);
    });

    it('contract cache clear never empties a folder that is no build cache; an empty --cache-dir (an unset variable) is a usage error', async () => {
        // before: `--cache-dir ""` named the current folder, and clear removed it whole
        const here = join(root, 'work-here');
        mkdirSync(here, { mode: 0o700 });
        writeFileSync(join(here, 'important.txt'), 'precious');
        mkdirSync(join(here, 'projects'));
        for (const command of [['cache', 'clear', '--cache-dir', ''], ['cache', 'clear', '--cache-dir='], ['simulate', '.', 'x.scenario', '--cache-dir', ' '], ['build', '.', '--cache-dir', '']]) {
            const empty = capture(here);
            expect(await runCli(command, empty), command.join(' ')).toBe(2);
            expect(empty.stderr).toContain('--cache-dir was given an empty value (an unset variable in the command?)');
        }
        // named, a folder that holds anything else than a cache's entries is refused, nothing removed
        const named = capture(root);
        expect(await runCli(['cache', 'clear', '--cache-dir', 'work-here'], named)).toBe(1);
        expect(named.stderr).toBe(`contract cache: refusing to clear ${here}: it holds what a build cache does not ("important.txt"), so it is not one; a build cache holds runtime/, projects/, generated/, sim/, ws/ only. Nothing was removed\n`);
        expect(readFileSync(join(here, 'important.txt'), 'utf8')).toBe('precious');
        expect(existsSync(join(here, 'projects'))).toBe(true);
        expect(readdirSync(here).sort()).toEqual(['important.txt', 'projects']);
    });

    it('refuses a cache folder that is a link, or writable by others, with exit 3 and what to do', async () => {
        mkdirSync(join(root, 'open-cache'), { mode: 0o777 });
        chmodSync(join(root, 'open-cache'), 0o777);
        symlinkSync(join(root, 'cache'), join(root, 'linked-cache'));
        const open = capture(root);
        expect(await runCli(['build', 'robot', '--cache-dir', 'open-cache'], open)).toBe(3);
        expect(open.stderr).toContain(`contract build: the cache folder ${join(root, 'open-cache')} is writable by every user (mode 777)`);
        const linked = capture(root);
        expect(await runCli(['build', 'robot', '--cache-dir', 'linked-cache'], linked)).toBe(3);
        expect(linked.stderr).toContain(`the cache folder ${join(root, 'linked-cache')} is a symbolic link`);
    });

    it('shows progress on a terminal, none with --format json (under a pseudo-terminal from script(1))', () => {
        const bin = join(REPO, 'packages/cli/bin/contract.js');
        const onTty = (args: string) => spawnSync('script', ['-qec', `${process.execPath} ${bin} ${args}`, '/dev/null'], { cwd: root, encoding: 'utf8', timeout: 240_000 });
        const text = onTty('build robot --sandbox bwrap');
        expect(text.stdout).toContain('[building]');
        expect(text.stdout).toMatch(/generated src-gen\/ \(\d+ file\(s\) written|project unchanged since the last build/);
        expect(text.stdout).toContain('ok: build succeeded');
        expect(text.status).toBe(0);
        const json = onTty('build robot --sandbox bwrap --format json');
        expect(json.stdout).not.toContain('[building]');
        expect(JSON.parse(json.stdout.replace(/\r/g, '')).ok).toBe(true);
    }, 240_000);

    it('runs with a given start request and duration, and collects the CSV logs', async () => {
        const io = capture(root);
        const code = await runCli(['run', 'robot', '--sandbox', 'bwrap', '--duration', '1500ms', '--start', 'MIS.mission(goal={2.0,0.0,0.0})', '--logs', 'robot-logs', '--cpus', '1'], io);
        expect(io.stderr).toContain('contract-launch: started MIS.mission(goal={2.0,0.0,0.0})');
        expect(io.stderr).toContain('contract-launch: modules pinned to CPUs 1');
        expect(io.stdout).toContain('[ORD] activate goTo');
        expect(io.stderr).toContain('contract-launch: all modules stopped cleanly');
        // each line on its own stream: the launcher's on stderr, ORD's trace lines on stdout
        expect(io.stdout).not.toContain('contract-launch:');
        // the live trace channel's records are not output lines (docs/build-service-api.md "Trace channel")
        expect(io.stdout + io.stderr).not.toMatch(/^\d+,\d{4}-\d\d-\d\dT[^,]*,[A-Z]+,/m);
        // the folder from where the command ran, as the page shows it (`CSV logs: 4 file(s) in my-robot/logs`)
        expect(io.stderr).toContain('CSV logs: 4 file(s) in robot-logs\n');
        expect(code).toBe(0);
        const mis = readdirSync(join(root, 'robot-logs')).find((f) => f.startsWith('MIS_'))!;
        // the function's start names the values it was given
        expect(readFileSync(join(root, 'robot-logs', mis), 'utf8')).toContain('"function mission(goal = {x=2.0,y=0.0,theta=0.0}) started"');
    }, 240_000);

    it('does not write the logs through a link the project folder holds as DIR/logs; writes them into a real DIR/logs', async () => {
        // a cloned project can hold logs -> anywhere: the run's CSV files would land there
        const victim = join(root, 'victim');
        mkdirSync(victim);
        symlinkSync(victim, join(root, 'robot', 'logs'));
        const io = capture(root);
        expect(await runCli(['run', 'robot', '--sandbox', 'bwrap', '--duration', '1s'], io)).toBe(1);
        expect(io.stderr).toBe(`contract run: ${join(root, 'robot', 'logs')} is a symbolic link (to ${victim}): the CSV logs are not written through a link found in the project folder; remove it, or name a folder with --logs OUT\n`);
        expect(io.stdout).toBe(''); // refused before the run
        expect(readdirSync(victim)).toEqual([]);
        rmSync(join(root, 'robot', 'logs'));
        const ok = capture(root);
        expect(await runCli(['run', 'robot', '--sandbox', 'bwrap', '--duration', '1s'], ok)).toBe(0);
        expect(ok.stderr).toContain('CSV logs: 4 file(s) in robot/logs\n');
        expect(readdirSync(join(root, 'robot', 'logs')).filter((f) => f.endsWith('.csv'))).toHaveLength(4);
    }, 240_000);

    it('refuses before the run a --logs OUT that is a file, or whose way holds one (the logs could not be written after it)', async () => {
        writeFileSync(join(root, 'a-file'), 'mine\n');
        for (const [out, said] of [['a-file', `${join(root, 'a-file')} is not a folder: the CSV logs are written to a folder; name one with --logs OUT`],
            ['a-file/sub/logs', `${join(root, 'a-file/sub/logs')} cannot be made: ${join(root, 'a-file')} is not a folder; name a folder with --logs OUT`]] as const) {
            const io = capture(root);
            expect(await runCli(['run', 'robot', '--sandbox', 'bwrap', '--duration', '1s', '--logs', out], io)).toBe(1);
            expect(io.stderr).toBe(`contract run: ${said}\n`);
            expect(io.stdout).toBe(''); // refused before the run
        }
        expect(readFileSync(join(root, 'a-file'), 'utf8')).toBe('mine\n');
    }, 60_000);

    it("starts nothing with --start ''", async () => {
        const io = capture(root);
        expect(await runCli(['run', 'robot', '--sandbox', 'bwrap', '--duration', '1s', '--start', '', '--logs', 'idle-logs'], io)).toBe(0);
        expect(io.stdout).not.toContain('started MIS');
        expect(io.stdout).not.toContain('activate goTo');
    }, 240_000);

    it('reports model errors without building (exit 1) and says what to do', async () => {
        mkdirSync(join(root, 'broken'));
        writeFileSync(join(root, 'broken', 'types.contract'), 'datatype T {int a = 1.5};\n');
        const io = capture(root);
        expect(await runCli(['build', 'broken', '--sandbox', 'bwrap'], io)).toBe(1);
        expect(io.stderr).toMatch(/broken\/types\.contract:1:\d+: error: /);
        expect(io.stderr).toContain('FAILED: project has 1 error(s)');
        expect(io.stderr).toContain('contract check broken');
        // in JSON, with the diagnostic's code, as contract check gives it
        const json = capture(root);
        expect(await runCli(['build', 'broken', '--sandbox', 'bwrap', '--format', 'json'], json)).toBe(1);
        const check = capture(root);
        expect(await runCli(['check', 'broken', '--format', 'json'], check)).toBe(1);
        const codes = (JSON.parse(check.stdout) as { diagnostics: { code: string }[] }).diagnostics.map((d) => d.code);
        expect(codes.length).toBeGreaterThan(0);
        expect((JSON.parse(json.stdout) as { prepareDiagnostics: { code?: string }[] }).prepareDiagnostics.map((d) => d.code)).toEqual(codes);
    }, 120_000);

    it('reports the gcc errors of every module in one build, each at a path that opens from where the command was typed', async () => {
        const dir = join(root, 'gcc-errors');
        expect(await runCli(['new', 'gcc-errors'], capture(root))).toBe(0);
        expect(await runCli(['generate', 'gcc-errors'], capture(root))).toBe(0);
        const files: Record<string, string> = {};
        for (const m of ['CTL', 'LOC']) {
            const file = join(dir, `src-gen/generated/architecture/modules/${m}_mod/module.c`);
            const source = readFileSync(file, 'utf8');
            const broken = source.replace(new RegExp(`(PROTECTED REGION ID\\(protect_additional_import_${m}\\) ENABLED START\\*/)`), `$1\nstatic int broken_${m} = missing_${m};`);
            expect(broken).not.toBe(source);
            writeFileSync(file, broken);
            files[m] = `gcc-errors/src-gen/generated/architecture/modules/${m}_mod/module.c`;
        }
        const io = capture(root);
        expect(await runCli(['build', 'gcc-errors', '--sandbox', 'bwrap'], io)).toBe(1);
        for (const m of ['CTL', 'LOC']) {
            const at = new RegExp(`^(\\S+):(\\d+):\\d+: error: .missing_${m}. undeclared.* \\[in protected region protect_additional_import_${m}\\]$`, 'm').exec(io.stderr);
            expect(at, io.stderr).not.toBeNull();
            expect(at![1]).toBe(files[m]);
            // the line named holds the error, read from where the command ran
            expect(readFileSync(join(root, at![1]!), 'utf8').split('\n')[Number(at![2]) - 1]).toContain(`missing_${m}`);
        }
        expect(io.stderr).toContain('build failed: 2 error(s)');
    }, 240_000);

    /**
     * Builds a new project whose CTL exec region holds `code`; the one error the build reports must
     * be `message` at the line of `needle` in CTL's module.c, in that region, once.
     */
    async function oneRegionError(name: string, code: string, message: string, needle: string): Promise<void> {
        expect(await runCli(['new', name], capture(root))).toBe(0);
        expect(await runCli(['generate', name], capture(root))).toBe(0);
        const rel = `${name}/src-gen/generated/architecture/modules/CTL_mod/module.c`;
        const source = readFileSync(join(root, rel), 'utf8');
        const broken = source.replace(/(PROTECTED REGION ID\(protect_exec_CTL\) ENABLED START\*\/)/, `$1\n    ${code}`);
        expect(broken).not.toBe(source);
        writeFileSync(join(root, rel), broken);
        const io = capture(root);
        expect(await runCli(['build', name, '--sandbox', 'bwrap'], io)).toBe(1);
        const at = new RegExp(`^(\\S+):(\\d+): error: ${message} \\[in protected region protect_exec_CTL\\]$`, 'm').exec(io.stderr);
        expect(at, io.stderr).not.toBeNull();
        expect(at![1]).toBe(rel);
        expect(readFileSync(join(root, at![1]!), 'utf8').split('\n')[Number(at![2]) - 1]).toContain(needle);
        // the tool repeats it (ld for each use, as for each pass): the build reports it once
        expect(io.stderr.match(new RegExp(message, 'g'))).toHaveLength(1);
        expect(io.stderr).toContain('build failed: 1 error(s)');
    }

    it('a link error (a function a region calls that nobody defines) is told at the region\'s file and line, not only in --verbose', async () => {
        await oneRegionError('link-error', '{ extern int gripper_ready(void); if (gripper_ready()) { } }', "undefined reference to `gripper_ready' \\(in function \\w+\\)", 'gripper_ready()');
    }, 240_000);

    it('the assembler\'s error (an __asm__ statement of a region) is told at the region\'s file and line, once', async () => {
        await oneRegionError('asm-error', '__asm__("gripper_open");', "no such instruction: `gripper_open'", 'gripper_open');
    }, 240_000);

    it('exits 1 and names the module when user code crashes during the run', async () => {
        const dir = join(root, 'crash');
        expect(await runCli(['new', 'crash'], capture(root))).toBe(0);
        expect(await runCli(['generate', 'crash'], capture(root))).toBe(0);
        const file = join(dir, 'src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        const crashing = source.replace(
            /(PROTECTED REGION ID\(protect_exec_CTL\) ENABLED START\*\/)/,
            '$1\n    { static int calls = 0; if (++calls == 3) { volatile int *p = 0; *p = 1; } }',
        );
        expect(crashing).not.toBe(source);
        writeFileSync(file, crashing);
        const io = capture(root);
        const code = await runCli(['run', 'crash', '--sandbox', 'bwrap', '--duration', '2s'], io);
        expect(io.stderr).toContain('module CTL crashed (died by signal 11');
        // where: the line of the null store, in its region (the runtime's crash report, mapped by the service)
        const at = crashing.split('\n').findIndex((l) => l.includes('*p = 1;')) + 1;
        expect(io.stderr).toMatch(new RegExp(`^module CTL crashed \\(died by signal 11 \\(Segmentation fault\\)\\) at src-gen/generated/architecture/modules/CTL_mod/module\\.c:${at} in its protected region protect_exec_CTL \\(\\w+\\): a bad pointer: NULL, freed, or past the end of an array$`, 'm'));
        expect(io.stderr).toContain(`crash/src-gen/generated/architecture/modules/CTL_mod/module.c:${at}: error: CTL crashed here: signal 11 (SIGSEGV) at address 0x0, in `);
        expect(io.stderr).not.toContain('==contract-crash==');
        // make's "*** [...: run] Error 1" in the log and its own exit 2 are both named, not left to contradict
        expect(io.stdout + io.stderr).toMatch(/^make: \*\*\* \[Makefile:\d+: run\] Error 1$/m);
        expect(io.stderr).toContain('(contract-launch exit 1; make exit 2)');
        expect(io.stderr).toContain('contract-launch: FAILED: module CTL died by signal 11 (Segmentation fault)');
        // ORD sees the release never finish: it says the module is gone, not that its code loops
        expect(io.stderr).toMatch(/^\[ORD\] STUCK: CTL has not finished release #\d+ after \d+ periods: it is no longer running \(it crashed or was killed\)$/m);
        expect(io.stdout + io.stderr).not.toContain('*stateindex = -1?');
        expect(code).toBe(1);
        expect(readdirSync(join(dir, 'logs')).some((f) => f.startsWith('CTL_'))).toBe(true);
    }, 240_000);

    it('a module that floods its output is said printing too much, not looping (ORD reads its wchan and io)', async () => {
        const dir = join(root, 'printing');
        expect(await runCli(['new', 'printing'], capture(root))).toBe(0);
        expect(await runCli(['generate', 'printing'], capture(root))).toBe(0);
        const file = join(dir, 'src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        // lines of 4000 characters written for ever: the pipe to contract-launch is full nearly all the time
        const flooding = source.replace('*stateindex = -1; //the run is finished',
            '{ static char text[4001]; memset(text, \'x\', 4000); for (;;) printf("%s\\n", text); }');
        expect(flooding).not.toBe(source);
        writeFileSync(file, flooding);
        const io = capture(root);
        const code = await runCli(['run', 'printing', '--sandbox', 'bwrap', '--duration', '3s'], io);
        expect(io.stderr).toMatch(
            // asleep in a write to the full pipe at ORD's look (wchan), or megabytes written between its looks (io's wchar)
            /^problem: CTL has not finished release #\d+ after \d+ periods: (?:it is blocked writing its output: the pipe is full \(it prints faster than the run's output is read\): does its exec region print too much\?|it prints without end \(\d+\.\d MiB written in the last [\d.]+ s\): does its exec region print too much, or loop printing\?)$/m,
        );
        expect(io.stderr).not.toMatch(/CTL has not finished release #\d+ after \d+ periods: does its exec region loop/);
        expect(code).toBe(4);
    }, 240_000);

    it('exits 4 and names the module when an exec region never sets *stateindex = -1 (issue 18)', async () => {
        const dir = join(root, 'stuck');
        expect(await runCli(['new', 'stuck'], capture(root))).toBe(0);
        expect(await runCli(['generate', 'stuck'], capture(root))).toBe(0);
        const file = join(dir, 'src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        const looping = source.replace('*stateindex = -1; //the run is finished', '/* the end of the run forgotten */');
        expect(looping).not.toBe(source);
        writeFileSync(file, looping);
        const io = capture(root);
        const code = await runCli(['run', 'stuck', '--sandbox', 'bwrap', '--duration', '3s'], io);
        // ORD looked at CTL's thread: even on a loaded machine it got far more CPU than its 10 ms
        // period between the looks, so the line asks whether its exec region loops, not whether
        // it is starved (runtime/src/engines/ord_stuck_cause.c)
        expect(io.stderr).toMatch(
            /^\[ORD\] STUCK: CTL has not finished release #\d+ after \d+ periods: does its exec region loop, or never set \*stateindex = -1\? \(its thread got \d+% of a CPU in the last [\d.]+ s, more than a period needs; a loaded machine gives it less\)$/m,
        );
        // one line when the cycle begins to overrun (naming the module it still runs), not one per tick; and, when the schema is deactivated
        // before ORD stops, one saying how many releases the cycle skipped in all
        const overruns = io.stdout.match(/^\[ORD\] overrun.*$/gm) ?? [];
        expect(overruns[0]).toBe('[ORD] overrun: goTo cycle still running (CTL), release skipped');
        expect(overruns.slice(1)).toEqual(overruns.length > 1 ? [expect.stringMatching(/^\[ORD\] overrun: goTo cycle ended after \d+ skipped releases$/)] : []);
        expect(io.stderr).toMatch(/^FAILED: run finished with 1 problem\(s\): CTL has not finished release #\d+ after \d+ periods/m);
        expect(io.stderr).toMatch(/^problem: CTL has not finished release/m);
        expect(io.stderr).not.toMatch(/^ok:/m);
        expect(code).toBe(4);
        const json = capture(root);
        expect(await runCli(['run', 'stuck', '--sandbox', 'bwrap', '--duration', '3s', '--format', 'json'], json)).toBe(4);
        const out = JSON.parse(json.stdout) as { ok: boolean; status: string; result: { issues: { kind: string; module?: string }[] }; schemas: unknown };
        expect(out.ok).toBe(false);
        expect(out.status).toBe('failed');
        expect(out.result.issues.map((i) => [i.kind, i.module])).toEqual([['module-stuck', 'CTL']]);
        // the schema's figures from the run's logs, for a CI gate: its first cycle never completed, one
        // deadline miss, and every tick of the 3 s after it skipped (counted as ORD counts them)
        expect(out.schemas).toEqual([{ schema: 'goTo', completedCycles: 0, maxResponseNs: 0, deadlineMisses: 1, overruns: expect.any(Number), heldCycles: 0, missedTicks: expect.any(Number), lateReleases: 0 }]);
        const [goTo] = out.schemas as Array<{ overruns: number; missedTicks: number }>;
        expect(goTo!.overruns + goTo!.missedTicks).toBeGreaterThan(200);
    }, 240_000);

    it('a module flooding its output: the cut is said in place, in stdout, and the run exits 4 with the problem', async () => {
        const dir = join(root, 'flood');
        expect(await runCli(['new', 'flood'], capture(root))).toBe(0);
        expect(await runCli(['generate', 'flood'], capture(root))).toBe(0);
        const file = join(dir, 'src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        const flooding = source.replace(
            /(PROTECTED REGION ID\(protect_init_CTL\) ENABLED START\*\/)/,
            '$1\n    for (int i = 0; i < 60000; i++) printf("CTL flood line %d of 60000\\n", i);',
        );
        expect(flooding).not.toBe(source);
        writeFileSync(file, flooding);
        const io = capture(root);
        const code = await runCli(['run', 'flood', '--sandbox', 'bwrap', '--duration', '2s'], io);
        const lines = io.stdout.split('\n');
        const cut = lines.findIndex((l) => l.startsWith('[output truncated: stdout limit 1 MiB reached'));
        expect(cut, io.stdout.slice(-2000)).toBeGreaterThan(0);
        expect(lines[cut]).toBe("[output truncated: stdout limit 1 MiB reached: the rest of the run's stdout is not shown (its stderr still is); the CSV logs and --trace are whole]");
        // the line it cut: a flood line's beginning (where it is cut depends on the bytes before it),
        // said cut when the bound fell inside it (it must not read as a whole line: 'line 3' of 'line 39065')
        const cutLine = lines[cut - 1]!.replace(/ \[cut here: the output limit\]$/, '');
        expect(cutLine.startsWith('[CTL] ')).toBe(true);
        expect(lines[cut - 1]!.endsWith(' [cut here: the output limit]') || /^CTL flood line \d+ of 60000$/.test(cutLine.slice(6))).toBe(true);
        expect('CTL flood line 59999 of 60000'.startsWith(cutLine.slice(6).replace(/\d[\d of]*$/, '')) || /^CTL flood line \d+( of( \d*)?)?$/.test(cutLine.slice(6))).toBe(true);
        expect(lines.slice(cut + 1).some((l) => l.startsWith('[CTL] CTL flood line'))).toBe(false);
        expect(io.stderr).toMatch(/^problem: the run's stdout went past the output limit \(1 MiB per stream\) \(CTL wrote \d+ % of the run's output lines until then\)/m);
        expect(code).toBe(4);
    }, 240_000);
});

