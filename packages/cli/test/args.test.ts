import { describe, expect, it } from 'vitest';
import { parseArgs } from '../src/args.js';
import { UsageError } from '../src/command.js';

describe('parseArgs', () => {
    it('separates positionals, valued options and flags', () => {
        const r = parseArgs(['dir', '--format', 'json', '--quiet', '--out=x', '--', '--not-an-option'], ['format', 'out'], ['quiet']);
        expect(r.positionals).toEqual(['dir', '--not-an-option']);
        expect([...r.options]).toEqual([['format', 'json'], ['quiet', true], ['out', 'x']]);
    });
    it('rejects unknown options and missing values', () => {
        expect(() => parseArgs(['--nope'], [])).toThrow(UsageError);
        expect(() => parseArgs(['--format'], ['format'])).toThrow(/needs a value/);
    });
});

describe('bad usage', () => {
    it('says what is wrong, then the synopsis and where the options are listed, not every option', async () => {
        const { runCli } = await import('../src/cli.js');
        const { capture } = await import('./capture-io.js');
        const io = capture(process.cwd());
        expect(await runCli(['run', '.', '--start', 'FLT.hold(height = 1.5x)'], io)).toBe(2);
        const lines = io.stderr.trimEnd().split('\n');
        expect(lines[0]).toBe("contract run: bad --start 'FLT.hold(height = 1.5x)': '1.5x' is not a number (a value starting with a digit is a number: 1.5, -2, 1e3); nothing was started");
        expect(lines[1]).toMatch(/^usage: contract run DIR /);
        expect(lines.slice(2)).toEqual(['(contract run --help lists every option)']);
    });
});

describe('contract run durations: a number without a unit', () => {
    it('is seconds, as documented, said on stderr for every duration option (field test ft58c: `--duration 500` meant as milliseconds ran 500 s)', async () => {
        const { runCli } = await import('../src/cli.js');
        const { capture } = await import('./capture-io.js');
        const { bareDurationWarning, parseDuration } = await import('../src/commands/run.js');
        expect(parseDuration('500')).toBe(500);
        // a bad --start stops the command after the durations are read: nothing is built
        const io = capture(process.cwd());
        expect(await runCli(['run', '.', '--duration', '500', '--run-limit', '4', '--ready-timeout=1.5', '--start', 'FLT.hold(height = 1.5x)'], io)).toBe(2);
        expect(io.stderr.split('\n').slice(0, 3)).toEqual([
            'contract run: warning: --duration 500: a number without a unit is seconds (500 s); write 500ms for milliseconds, 500s to say seconds',
            'contract run: warning: --run-limit 4: a number without a unit is seconds (4 s); write 4ms for milliseconds, 4s to say seconds',
            'contract run: warning: --ready-timeout 1.5: a number without a unit is seconds (1.5 s); write 1.5ms for milliseconds, 1.5s to say seconds',
        ]);
        // with its unit, or a value refused anyway: no warning
        const quiet = capture(process.cwd());
        expect(await runCli(['run', '.', '--duration', '500ms', '--run-limit', '4s', '--start', 'FLT.hold(height = 1.5x)'], quiet)).toBe(2);
        expect(quiet.stderr).not.toContain('warning');
        for (const text of ['500ms', '2m', '10s', '0', 'soon', '-1']) expect(bareDurationWarning('duration', text)).toBeNull();
        const help = capture(process.cwd());
        expect(await runCli(['run', '--help'], help)).toBe(0);
        expect(help.stdout).toContain('a number without a unit is seconds, with a warning on stderr');
    });
});

describe('contract run: the logs folder as the text report names it', () => {
    it('is relative to where the command ran when inside it (`CSV logs: 4 file(s) in my-robot/logs`), else absolute', async () => {
        const { fromCwd } = await import('../src/commands/run.js');
        expect(fromCwd('/home/me', '/home/me/my-robot/logs')).toBe('my-robot/logs');
        expect(fromCwd('/home/me', '/home/me')).toBe('.');
        expect(fromCwd('/home/me/my-robot', '/home/me/logs')).toBe('/home/me/logs');
        expect(fromCwd('/home/me', '/home/me/..logs/x')).toBe('..logs/x');
        expect(fromCwd('/home/me', '/tmp/logs')).toBe('/tmp/logs');
    });
});
