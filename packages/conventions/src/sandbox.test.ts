import { describe, expect, it } from 'vitest';
import { cpuMissingFrom, isCpuList, SANDBOX_CHOICES, SANDBOX_NAMES } from './sandbox.js';

describe('sandbox conventions', () => {
    it('accepts CPU lists and refuses anything else', () => {
        for (const ok of ['0', '1', '0-1', '0,2', '0-3,6,8-9']) expect(isCpuList(ok)).toBe(true);
        for (const bad of ['', 'a', '1-', '-1', '1,,2', '1 2', '0-1,', '1;rm', '1-0', '0,3-2']) expect(isCpuList(bad)).toBe(false);
    });

    it('names the first CPU of a list that a machine does not have', () => {
        expect(cpuMissingFrom('0-1', 2)).toBeUndefined();
        expect(cpuMissingFrom('1', 2)).toBeUndefined();
        expect(cpuMissingFrom('0-1,3', 2)).toBe(3);
        expect(cpuMissingFrom('0,1-9', 4)).toBe(4);
        expect(cpuMissingFrom('9', 2)).toBe(9);
        expect(cpuMissingFrom('0', 1)).toBeUndefined();
    });

    it('offers auto before the sandboxes', () => {
        expect(SANDBOX_CHOICES).toEqual(['auto', ...SANDBOX_NAMES]);
    });
});
