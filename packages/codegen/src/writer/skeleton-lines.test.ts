/** The lines written outside the regions, from the generator's line hashes (skeleton-lines.ts). */
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { LINE_HASHES, decodeLineHashes, describeEdits, editsOutside, encodeLineHashes, skeletonLines } from './skeleton-lines.js';

const F = 'module.c';
const generated = `a\nb\n${region('protect_x', '\none\ntwo\n')} tail\nc\nd\n`;
const recorded = (text: string) => decodeLineHashes(encodeLineHashes(skeletonLines(text, F).hashes));

describe('skeleton lines', () => {
    it('a region stands as its ID on the line where it starts; the file lines after it keep their numbers', () => {
        const s = skeletonLines(generated, F);
        const lines = generated.split('\n');
        // a, b, <region> tail, c, d, (empty last line)
        expect(s.fileLines).toEqual([1, 2, 3, lines.indexOf('c') + 1, lines.indexOf('d') + 1, lines.length]);
        // the region's content is not in the skeleton: typing there changes no hash
        expect(skeletonLines(generated.replace('one', 'mine'), F).hashes).toEqual(s.hashes);
        // CRLF is the same lines
        expect(skeletonLines(generated.replace(/\n/g, '\r\n'), F).hashes).toEqual(s.hashes);
    });

    it('encode/decode round-trips 24-bit hashes, 4 characters a line', () => {
        const hashes = [0, 1, 0xffffff, 0x123456];
        const encoded = encodeLineHashes(hashes);
        expect(encoded).toHaveLength(16);
        expect(LINE_HASHES.test(encoded)).toBe(true);
        expect(decodeLineHashes(encoded)).toEqual(hashes);
        expect(LINE_HASHES.test('abc')).toBe(false);
    });

    it('names added, changed and removed lines in the file as it is', () => {
        const edited = generated.replace('b\n', 'b\nmine 1\nmine 2\n').replace('d\n', 'D\n').replace('a\n', '');
        const edits = editsOutside(recorded(generated), skeletonLines(edited, F));
        const lines = edited.split('\n');
        expect(edits.written).toEqual([lines.indexOf('mine 1') + 1, lines.indexOf('mine 2') + 1, lines.indexOf('D') + 1]);
        expect(edits.removedAfter).toEqual([0]);
        const { line, where } = describeEdits(edits);
        expect(line).toBe(2);
        expect(where).toBe(`lines 2-3, ${lines.indexOf('D') + 1} not written by the generator; generated lines removed at the top`);
    });

    it('a file with nothing changed names nothing; many places are counted, not all listed', () => {
        expect(describeEdits(editsOutside(recorded(generated), skeletonLines(generated, F)))).toEqual({ line: undefined, where: '' });
        const many = Array.from({ length: 10 }, (_, i) => `g${i}`).join('\n') + '\n';
        const edited = many.replace(/g(\d)\n/g, (all, d: string) => (Number(d) % 2 === 0 ? `${all}mine${d}\n` : all));
        expect(describeEdits(editsOutside(recorded(many), skeletonLines(edited, F))).where).toBe('lines 2, 5, 8 and 2 more place(s) not written by the generator');
    });

    it('two long, wholly different middles are one block, not a quadratic diff', () => {
        const a = Array.from({ length: 3000 }, (_, i) => `a${i}`).join('\n');
        const b = Array.from({ length: 3000 }, (_, i) => `b${i}`).join('\n');
        const start = performance.now();
        const edits = editsOutside(recorded(`top\n${a}\nend\n`), skeletonLines(`top\n${b}\nend\n`, F));
        expect(performance.now() - start).toBeLessThan(2000);
        expect(edits.written).toHaveLength(3000);
        expect(edits.written[0]).toBe(2);
        expect(edits.removedAfter).toEqual([]);
    });
});
