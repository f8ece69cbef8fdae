/**
 * The CLI's own limits (README "Limits"): `contract run --run-limit` (parsed, documented, and a real
 * run that does not stop in time ends `killed: run time limit`, exit 4), the limits the CLI gives
 * its job by default (the run lasts as long as asked), and the advice after a build a limit
 * stopped (no "gcc errors above" when there were none).
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { checkRunLimit } from '../src/commands/run.js';
import { CLI_BUILD_SECONDS, cliLimits, reportBuild, type JobOutcome } from '../src/job-runner.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-limits-');
}, 240_000);
afterAll(() => removeSeededScratch(root));

describe('contract run --run-limit: parsing and the limits the CLI gives its job', () => {
    it('parses a duration; refuses a bad or non-positive one', () => {
        expect(checkRunLimit('3s')).toBe(3);
        expect(checkRunLimit('2500ms')).toBe(2.5);
        expect(checkRunLimit('2m')).toBe(120);
        expect(() => checkRunLimit('0s')).toThrow("bad --run-limit '0s': the duration must be positive");
        expect(() => checkRunLimit('soon')).toThrow("bad --run-limit 'soon': bad duration 'soon'");
    });

    it('by default the run lasts as long as asked: its duration and the inits past 10 s, plus 60 s; the build 600 s; --run-limit sets the run\'s', () => {
        expect(cliLimits({ action: 'run' })).toEqual({ runSeconds: 70, buildSeconds: CLI_BUILD_SECONDS });
        expect(cliLimits({ action: 'run', duration: 120 })).toEqual({ runSeconds: 180, buildSeconds: 600 });
        expect(cliLimits({ action: 'run', duration: 2.5, readyTimeout: 30 })).toEqual({ runSeconds: 83, buildSeconds: 600 });
        expect(cliLimits({ action: 'run', duration: 120, runLimit: 30 })).toEqual({ runSeconds: 30, buildSeconds: 600 });
    });

    it('is in --help with the CLI\'s other limits; a bad value is a usage error (exit 2) before any work', async () => {
        const help = capture(root);
        expect(await runCli(['run', '--help'], help)).toBe(0);
        expect(help.stdout).toContain('[--run-limit DURATION]');
        expect(help.stdout).toContain('--run-limit: the run step\'s wall time limit (default: the duration + 60s');
        expect(help.stdout).toContain('The build step\'s limit is 600s');
        const bad = capture(root);
        expect(await runCli(['run', root, '--run-limit', '-1s'], bad)).toBe(2);
        expect(bad.stderr).toContain("contract run: bad --run-limit '-1s'");
    });
});

describe('contract run and contract build --limit NAME=VALUE: the build service\'s limits, read as contract serve reads them', () => {
    it('is in --help of both; a bad value or an unknown limit is a usage error (exit 2) before any work, said as contract serve says it', async () => {
        for (const command of ['run', 'build']) {
            const help = capture(root);
            expect(await runCli([command, '--help'], help)).toBe(0);
            expect(help.stdout).toContain('[--limit NAME=VALUE]...');
            expect(help.stdout).toContain('e.g. processes=512 for an architecture of more than 126 module processes');
            for (const [value, said] of [
                ['processes', '--limit needs NAME=VALUE with a positive number (e.g. processes=512, runSeconds=3600), got processes'],
                ['processes=0', '--limit needs NAME=VALUE with a positive number'],
                ['bogus=1', '--limit: unknown limit "bogus"'],
                ['processes=10.5', '--limit: limit processes must be a whole number (a count or a size), got 10.5'],
                ['processes=12345678901234567', '--limit: limit processes must be at most 4194304, got 12345678901234567'],
            ] as const) {
                const bad = capture(root);
                expect(await runCli([command, root, '--limit', value], bad), `${command} --limit ${value}`).toBe(2);
                expect(bad.stderr).toContain(`contract ${command}: ${said}`);
            }
        }
    });

    it('a name given twice, or --limit runSeconds beside --run-limit or under its least value, is a usage error (it was taken silently: the later value, or runSeconds, won)', async () => {
        const twice = capture(root);
        expect(await runCli(['run', root, '--limit', 'processes=512', '--limit', 'processes=20'], twice)).toBe(2);
        expect(twice.stderr).toContain('contract run: --limit processes is given twice (512 and 20): give it once');
        const both = capture(root);
        expect(await runCli(['run', root, '--run-limit', '20s', '--limit', 'runSeconds=4'], both)).toBe(2);
        expect(both.stderr).toContain("contract run: --run-limit and --limit runSeconds=4 both set the run's time limit: give one");
        const short = capture(root);
        expect(await runCli(['run', root, '--limit', 'runSeconds=1'], short)).toBe(2);
        expect(short.stderr).toContain('contract run: bad --limit runSeconds=1: at least 2 (the architecture needs about 1 s to start and 1 s to stop');
    });

    it('reaches the job: a build under --limit buildSeconds=0.001 is stopped by that limit', async () => {
        expect(await runCli(['new', 'limited'], capture(root))).toBe(0);
        const io = capture(root);
        expect(await runCli(['build', 'limited', '--sandbox', 'bwrap', '--limit=buildSeconds=0.001', '--limit', 'processes=512'], io)).not.toBe(0);
        expect(io.stderr).toMatch(/build time limit 0\.001 s/);
    }, 240_000);
});

describe('the advice after a build that failed', () => {
    const outcome = (result: Record<string, unknown>, diagnostics: unknown[] = [], status = 'failed') => ({
        job: { sandboxName: 'bwrap', warnings: [], prepareDiagnostics: [], foreignMakefiles: [], status, diagnostics },
        result: { ok: false, step: 'build', issues: [], durations_ms: { prepare: 300, build: 700 }, ...result },
        runLines: [], buildTail: [],
    } as unknown as JobOutcome);
    const opts = { format: 'text', dirArg: 'arm' } as Parameters<typeof reportBuild>[0];

    it('a build stopped by a limit, with no gcc error: the limit is the problem, not "the gcc errors above"', () => {
        const io = capture(root);
        const message = 'killed: disk limit 256 MiB (work dir): filled by logs/CTL_6-Dec-2026-02h49m15s.csv 249.24 MiB (of 255.8 MiB in 77 file(s))';
        expect(reportBuild(opts, outcome({ message, exitCode: 0, limitHit: { name: 'workDiskMiB', value: 268435456, unit: 'bytes', mechanism: 'tmpfs-size' } }), io)).toBe(1);
        expect(io.stderr).toBe([
            `FAILED: ${message} [bwrap; prepare 0.3 s, build 0.7 s]`,
            'the build was stopped by a sandbox limit, not by a compiler error (docs/sandbox.md "Limits"); --verbose shows every build line',
            '',
        ].join('\n'));
    });

    it('gcc errors: "fix the gcc errors above"; a cancelled build: no advice', () => {
        const io = capture(root);
        reportBuild(opts, outcome({ message: 'build failed: 1 error(s) (make exit 2)', exitCode: 2, limitHit: null }, [{ severity: 'error' }]), io);
        expect(io.stderr).toContain('fix the gcc errors above (your code is in the PROTECTED REGION blocks of arm/src-gen and in any file of your own there)');
        const cancelled = capture(root);
        reportBuild(opts, outcome({ message: 'cancelled', exitCode: null, limitHit: null }, [], 'cancelled'), cancelled);
        expect(cancelled.stderr).toBe('FAILED: cancelled [bwrap; prepare 0.3 s, build 0.7 s]\n');
    });
});

describe('contract run --run-limit on a real run (bwrap)', () => {
    it('a module deaf to its stop keeps the run going past --run-limit: killed: run time limit, exit 4; a --duration too long for it is shortened, said', async () => {
        expect(await runCli(['new', 'deaf'], capture(root))).toBe(0);
        expect(await runCli(['generate', 'deaf'], capture(root))).toBe(0);
        const file = join(root, 'deaf', 'src-gen/generated/architecture/modules/CTL_mod/module.c');
        const source = readFileSync(file, 'utf8');
        // CTL's 20th release never ends: its KILL request is never read, SIGTERM blocked (the launcher waits 2 s, 1 s, then SIGKILL)
        const deaf = source
            .replace(/(PROTECTED REGION ID\(protect_additional_import_CTL\) ENABLED START\*\/)/, '$1\n#include <signal.h>')
            .replace(
                /(PROTECTED REGION ID\(protect_exec_CTL\) ENABLED START\*\/)/,
                '$1\n    { static int calls = 0; if (++calls == 20) { sigset_t s; sigemptyset(&s); sigaddset(&s, SIGTERM); sigprocmask(SIG_BLOCK, &s, NULL); for (;;) {} } }',
            );
        expect(deaf).not.toBe(source);
        writeFileSync(file, deaf);
        const io = capture(root);
        const t0 = Date.now();
        const code = await runCli(['run', 'deaf', '--sandbox', 'bwrap', '--duration', '5s', '--run-limit', '3s'], io);
        expect(io.stderr).toContain('duration 5 s capped to 1.5 s: the run time limit is 3 s, of which 1.5 s are kept to start and stop the architecture\n');
        expect(io.stderr).toMatch(/^FAILED: killed: run time limit 3 s \[bwrap; /m);
        expect(io.stderr).toContain('problem: the run was stopped by the run time limit 3 s\n');
        expect(code).toBe(4);
        expect(Date.now() - t0).toBeLessThan(60_000);
    }, 240_000);
});

describe('a --duration too long for --run-limit (bwrap)', () => {
    it('is among the warnings of --format json and said on stderr, in json as in text (once)', async () => {
        expect(await runCli(['new', 'capped'], capture(root))).toBe(0);
        const said = 'duration 10 s capped to 1 s: the run time limit is 2 s, of which 1 s are kept to start and stop the architecture';
        const json = capture(root);
        await runCli(['run', 'capped', '--sandbox', 'bwrap', '--duration', '10s', '--run-limit', '2s', '--format', 'json'], json);
        const out = JSON.parse(json.stdout) as { warnings: string[] };
        expect(out.warnings).toContain(said);
        expect(json.stderr).toContain(`${said}\n`);
        const text = capture(root);
        await runCli(['run', 'capped', '--sandbox', 'bwrap', '--duration', '10s', '--run-limit', '2s'], text);
        expect(text.stderr.split(said).length - 1).toBe(1);
    }, 240_000);
});
