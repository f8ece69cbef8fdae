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
