import { describe, expect, it } from 'vitest';
import { crashSignalMeaning, withCrashMeaning } from './crash-signals.js';

describe('crash signals', () => {
    it('tells a beginner what each crash signal means, by number or name', () => {
        expect(crashSignalMeaning(11)).toMatch(/bad pointer: NULL, freed/);
        expect(crashSignalMeaning('SIGFPE')).toMatch(/integer division by zero/);
        expect(crashSignalMeaning(4)).toMatch(/division by a constant zero/);
        expect(crashSignalMeaning('SIGBUS')).toMatch(/misaligned/);
        expect(crashSignalMeaning(6)).toMatch(/abort\(\).*assert\(\)/);
        expect(crashSignalMeaning(9)).toBeUndefined();
    });

    it('appends the meaning to a text naming a crash signal, once', () => {
        const told = withCrashMeaning('died by signal 8 (Floating point exception)');
        expect(told).toBe('died by signal 8 (Floating point exception): an integer division by zero, or INT_MIN / -1');
        expect(withCrashMeaning(told)).toBe(told);
        expect(withCrashMeaning('died by signal 9 (Killed)')).toBe('died by signal 9 (Killed)');
        expect(withCrashMeaning('exited with status 3')).toBe('exited with status 3');
    });
});
