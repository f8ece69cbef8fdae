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
            [4, "protected region END without a START; region 'x' before it ended at line 3: is that END (or a marker inside a string or comment of its code) one too many?"],
            [5, 'protected region with an empty ID'],
            [5, "protected region ' ' START without END"],
        ]);
        expect(errors[0]!.offset).toBe(text.indexOf('\n') + 1);
    });
});

describe('scanRegions and a start marker with a typo', () => {
    it('reports the malformed start at its own line, not "END without a START" at the END', () => {
        const text = [
            'int a;', // 1
            region('protect_init_X', '\n  ok();\n'), // 2-4
            '/*PROTECTED REGION ID(protect_exec_X) ENABELD START*/', // 5
            '  mine();', // 6
            END, // 7
        ].join('\n');
        const { regions, errors } = scanRegions(text);
        expect(regions.map((r) => r.id)).toEqual(['protect_init_X']);
        expect(errors).toEqual([{
            offset: text.indexOf('/*PROTECTED REGION ID(protect_exec_X)'),
            line: 5,
            message: "protected region start 'protect_exec_X' is malformed: 'ENABELD START' (expected 'ENABLED START' or 'START')",
        }]);
    });

    it('reads other typos and pasted blanks, and keeps "END without a START" when nothing looks like a start', () => {
        const at = (text: string) => scanRegions(text).errors.map((e) => [e.line, e.message]);
        expect(at('/* PROTECTED REGION ID( a )\n ENABLED STRAT */\nx\n' + END)).toEqual([[1, "protected region start 'a' is malformed: 'ENABLED STRAT' (expected 'ENABLED START' or 'START')"]]);
        expect(at('\n/*PROTECTED REGION ID(a) ENABLED*/x' + END)).toEqual([[2, "protected region start 'a' is malformed: 'ENABLED' (expected 'ENABLED START' or 'START')"]]);
        expect(at('/*PROTECTED REGIN ID(a) ENABLED START*/\nx\n' + END)).toEqual([[1, "protected region start marker is malformed: '/*PROTECTED REGIN ID(a) ENABLED START*/' (expected '/*PROTECTED REGION ID(<id>) ENABLED START*/')"]]);
        expect(at(`${region('a', 'x')}\n/* a comment */\n${END}`)).toEqual([[3, "protected region END without a START; region 'a' before it ended at line 1: is that END (or a marker inside a string or comment of its code) one too many?"]]);
        // a typo'd start before an earlier, well-formed region is not blamed for a later stray END
        expect(at(`/*PROTECTED REGION ID(a) ENABELD START*/${region('b', 'x')}\n${END}`)).toEqual([[2, "protected region END without a START; region 'b' before it ended at line 1: is that END (or a marker inside a string or comment of its code) one too many?"]]);
        // an END with no region before it says nothing more
        expect(at(`int a;\n${END}`)).toEqual([[2, 'protected region END without a START']]);
    });

    it('stays linear on hostile texts (ReDoS)', () => {
        const hostile = [
            '/*PROTECTED'.repeat(200_000) + END,
            '/*PROTECTED REGION ID(x) '.repeat(40_000) + END,
            ('/*PROTECTED REGION ID(x) ' + ' '.repeat(300)).repeat(3_000) + END,
            '/*' + ' '.repeat(1_000_000) + END,
            '/*PROTECTED REGION ID(' + 'a'.repeat(1_000_000) + END,
            (END + '/*PROTECTED REGION ID(x) X*/').repeat(50_000),
            END.repeat(200_000), // no line feed: lines were searched to the end of the text for each marker
            ('/*PROTECTED REGION ID(x) START*/' + '/*PROTECTED\n'.repeat(20)).repeat(10_000) + END,
        ];
        // CPU time of this process (the suite runs niced beside others: a wall-time bound would count
        // the time it waited for a CPU); the quadratic scan this guards against took 6.3 s on one of them
        const cpuMs = () => { const u = process.cpuUsage(); return (u.user + u.system) / 1000; };
        for (const text of hostile) {
            const t0 = cpuMs();
            scanRegions(text);
            expect(cpuMs() - t0, `${text.length} chars`).toBeLessThan(1_500);
        }
    }, 120_000); // niced beside the other suites it may wait long for a CPU: the bound above is on CPU time
});
