import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { quantileBin } from './index.js';

describe('quantileBin', () => {
    it('is the bin of the nearest-rank quantile of the values counted (the value of rank ceil(q * n) among them sorted), any values and bins', () => {
        fc.assert(fc.property(fc.array(fc.nat(99), { minLength: 1, maxLength: 200 }), fc.integer({ min: 1, max: 20 }), fc.double({ min: 0.001, max: 0.999, noNaN: true }), (values, width, q) => {
            const binOf = (v: number) => Math.floor(v / width);
            const counts = new Array<number>(binOf(99) + 1).fill(0);
            for (const v of values) counts[binOf(v)]!++;
            const sorted = [...values].sort((a, b) => a - b);
            expect(quantileBin(counts, values.length, q)).toBe(binOf(sorted[Math.ceil(q * values.length) - 1]!));
        }));
    });

    it('p50 and p99 of 100 values, one a bin: the 50th and the 99th bins; -1 when the counts fall short of the total', () => {
        const counts = new Uint32Array(100).fill(1);
        expect([quantileBin(counts, 100, 0.5), quantileBin(counts, 100, 0.99)]).toEqual([49, 98]);
        expect(quantileBin([0, 3, 0, 1], 4, 0.5)).toBe(1);
        expect(quantileBin([0, 3, 0, 1], 4, 0.99)).toBe(3);
        expect(quantileBin([1, 1], 5, 0.9)).toBe(-1);
    });
});
