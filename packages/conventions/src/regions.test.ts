import { describe, expect, it } from 'vitest';
import { END, normaliseRegionId, region, scanRegions, startMarker } from './regions.js';

describe('scanRegions', () => {
    it('finds the regions the generators write, with offsets and lines of both markers', () => {
        const text = `int a;\n${region('protect_x', '\n  mine();\n')}\nint b;\n${startMarker('protect_y')}${END}\n`;
        const { regions, errors } = scanRegions(text);
        expect(errors).toEqual([]);
        expect(regions.map((r) => [r.id, r.enabled, r.line, r.endLine])).toEqual([['protect_x', true, 2, 4], ['protect_y', true, 6, 6]]);
        const x = regions[0]!;
        expect(text.slice(x.contentStart, x.contentEnd)).toBe('\n  mine();\n');
        expect(text.slice(x.start, x.end)).toBe(region('protect_x', '\n  mine();\n'));
    });

    it('reads pasted markers: blanks and line breaks between words, blanks around the ID, `additionnal`, no ENABLED', () => {
        const text = '/* PROTECTED  REGION\nID( protect_additionnal_x ) START */body/*PROTECTED   REGION END */';
        const { regions, errors } = scanRegions(text);
        expect(errors).toEqual([]);
        expect(regions).toMatchObject([{ id: 'protect_additional_x', rawId: ' protect_additionnal_x ', enabled: false, line: 1, endLine: 2 }]);
        expect(normaliseRegionId(' a_additionnal ')).toBe('a_additional');
    });

    it('reports every structural problem in text order, with its line, and keeps the well-formed regions', () => {
        const text = [
            startMarker('x'), // 1
            startMarker('x'), // 2: nested, duplicate
            END, // 3
            END, // 4: stray
            startMarker(' '), // 5: empty ID, never closed
        ].join('\n');
        const { regions, errors } = scanRegions(text);
        expect(regions.map((r) => [r.id, r.line, r.endLine])).toEqual([['x', 2, 3]]);
        expect(errors.map((e) => [e.line, e.message])).toEqual([
            [2, "nested protected region start 'x' inside region 'x' (opened line 1, never closed)"],
            [2, "duplicate protected region ID 'x' (first at line 1)"],
            [4, 'protected region END without a START'],
            [5, 'protected region with an empty ID'],
            [5, "protected region ' ' START without END"],
        ]);
        expect(errors[0]!.offset).toBe(text.indexOf('\n') + 1);
    });
});
