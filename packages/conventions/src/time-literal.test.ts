import { describe, expect, it } from 'vitest';
import { formatNanoseconds } from './index.js';

describe('formatNanoseconds', () => {
    it('writes a duration in the coarsest unit that keeps it whole', () => {
        expect([2e9, 1.5e9, 1e6, 250e3, 1234, 0].map(formatNanoseconds)).toEqual(['2s', '1500ms', '1ms', '250us', '1234ns', '0ns']);
    });
});
