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
