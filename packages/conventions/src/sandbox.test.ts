import { describe, expect, it } from 'vitest';
import { isCpuList, SANDBOX_CHOICES, SANDBOX_NAMES } from './sandbox.js';

describe('sandbox conventions', () => {
    it('accepts CPU lists and refuses anything else', () => {
        for (const ok of ['0', '1', '0-1', '0,2', '0-3,6,8-9']) expect(isCpuList(ok)).toBe(true);
        for (const bad of ['', 'a', '1-', '-1', '1,,2', '1 2', '0-1,', '1;rm']) expect(isCpuList(bad)).toBe(false);
    });

    it('offers auto before the sandboxes', () => {
        expect(SANDBOX_CHOICES).toEqual(['auto', ...SANDBOX_NAMES]);
    });
});
