/**
 * The one edit distance of every "Did you mean" (model/near-names.ts): optimal string alignment, so
 * two adjacent letters swapped are one edit, as a letter missing, extra or wrong.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { closestName, editDistance, nearKeywords } from '../src/model/near-names.js';
import { closestName as scenarioClosestName, editDistance as scenarioEditDistance } from '../src/scenario/did-you-mean.js';

/** Optimal string alignment distance, the whole matrix (Wikipedia, "Damerau-Levenshtein distance"). */
function textbook(a: string, b: string): number {
    const d = Array.from({ length: a.length + 1 }, (_, i) => Array.from({ length: b.length + 1 }, (_, j) => (i === 0 ? j : j === 0 ? i : 0)));
    for (let i = 1; i <= a.length; i++) {
        for (let j = 1; j <= b.length; j++) {
            const cost = a[i - 1] === b[j - 1] ? 0 : 1;
            d[i]![j] = Math.min(d[i - 1]![j]! + 1, d[i]![j - 1]! + 1, d[i - 1]![j - 1]! + cost);
            if (i > 1 && j > 1 && a[i - 1] === b[j - 2] && a[i - 2] === b[j - 1]) d[i]![j] = Math.min(d[i]![j]!, d[i - 2]![j - 2]! + 1);
        }
    }
    return d[a.length]![b.length]!;
}

describe('edit distance', () => {
    it('counts a swap of two adjacent letters as one edit', () => {
        expect(editDistance('rulse', 'rules')).toBe(1);
        expect(editDistance('rlues', 'rules')).toBe(1);
        expect(editDistance('grahp', 'graph')).toBe(1);
        expect(editDistance('SMA', 'MSA')).toBe(1);
        // letters wrong, missing, extra; case ignored
        expect(editDistance('rulez', 'rules')).toBe(1);
        expect(editDistance('rule', 'rules')).toBe(1);
        expect(editDistance('Rules', 'rules')).toBe(0);
        expect(editDistance('', 'abc')).toBe(3);
        // restricted: a swapped pair is not edited again ('ca' -> 'ac' -> 'abc' is 3, not 2)
        expect(editDistance('ca', 'abc')).toBe(3);
    });

    it('is the textbook distance; with a bound, that or bound + 1 (fast-check)', () => {
        const word = fc.string({ unit: fc.constantFrom('a', 'b', 'c', 'D', 'd'), maxLength: 9 });
        fc.assert(fc.property(word, word, fc.integer({ min: 0, max: 4 }), (a, b, max) => {
            const full = textbook(a.toLowerCase(), b.toLowerCase());
            expect(editDistance(a, b)).toBe(full);
            expect(editDistance(b, a)).toBe(full);
            expect(editDistance(a, b, max)).toBe(Math.min(full, max + 1));
        }), { numRuns: 3000, seed: 31 });
    });

    it('is the one the scenario checker uses', () => {
        expect(scenarioEditDistance).toBe(editDistance);
        expect(scenarioClosestName).toBe(closestName);
    });
});

describe('near names and keywords', () => {
    it('suggests a name with two letters swapped', () => {
        expect(closestName('SMA', ['MAA', 'MSA', 'MSC'])).toBe('MSA');
        expect(closestName('SECNOD', ['FIRST', 'SECOND', 'THIRD'])).toBe('SECOND');
        expect(closestName('FIFTH', ['FIRST', 'SECOND', 'THIRD', 'FOURTH'])).toBeUndefined();
    });

    it('suggests a keyword with two letters swapped, within 1 edit under 7 letters', () => {
        expect(nearKeywords('rulse', ['rules', 'graph', 'realtime'])).toEqual(['rules']);
        expect(nearKeywords('rlues', ['rules'])).toEqual(['rules']);
        expect(nearKeywords('grahp', ['graph', 'group'])).toEqual(['graph']);
        expect(nearKeywords('ruels', ['rules', 'rule'])).toEqual(['rules']);
        // two edits are too many for a short word, fine for a long one
        expect(nearKeywords('rluse', ['rules'])).toEqual([]);
        expect(nearKeywords('suprevisro', ['supervisor'])).toEqual(['supervisor']);
        // not the word itself, nor a name shorter than 3 letters
        expect(nearKeywords('rules', ['rules'])).toEqual([]);
        expect(nearKeywords('ru', ['rule'])).toEqual([]);
    });
});
