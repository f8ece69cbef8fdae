import { describe, expect, it } from 'vitest';
import { mergeRegions } from './merge-regions.js';
import { region } from './markers.js';

const isTodo = (_id: string, c: string) => c.trim() === '//TODO';

describe('mergeRegions', () => {
    it('keeps ENABLED content byte for byte and takes the rest from the new output', () => {
        const oldText = `old header\n${region('a', '\r\n\tuser é code  \n')}\n${region('b', '//TODO')}\n`;
        const newText = `new header\n${region('b', '//TODO')}\nmiddle\n${region('a', '//TODO')}\n`;
        const r = mergeRegions(newText, oldText, 'f.c', isTodo);
        expect(r.text).toBe(`new header\n${region('b', '//TODO')}\nmiddle\n${region('a', '\r\n\tuser é code  \n')}\n`);
        expect(r.orphans).toEqual([]);
    });

    it('regenerates a region whose ENABLED flag the user removed', () => {
        const oldText = `/*PROTECTED REGION ID(a) START*/stale/*PROTECTED REGION END*/`;
        const r = mergeRegions(region('a', 'fresh'), oldText, 'f.c', isTodo);
        expect(r.text).toBe(region('a', 'fresh'));
    });

    it('lists a region without ENABLED whose content was user code (not the known default, else not the fresh one)', () => {
        const oldText = `/*PROTECTED REGION ID(a) START*/mine/*PROTECTED REGION END*/${region('b', 'x')}/*PROTECTED REGION ID(c) START*/old default/*PROTECTED REGION END*/`;
        const known = (id: string, c: string) => (id === 'c' ? c === 'old default' : undefined);
        const r = mergeRegions(region('a', 'fresh') + region('b', 'y') + region('c', 'new default'), oldText, 'f.c', isTodo, known);
        expect(r.text).toBe(region('a', 'fresh') + region('b', 'x') + region('c', 'new default'));
        expect(r.disabled.map((d) => [d.id, d.content])).toEqual([['a', 'mine']]);
        expect(mergeRegions(region('a', 'mine'), '/*PROTECTED REGION ID(a) START*/mine/*PROTECTED REGION END*/', 'f.c', isTodo).disabled).toEqual([]);
    });

    it('maps legacy additionnal IDs onto additional ones and writes the new spelling', () => {
        const oldText = `/*PROTECTED REGION ID(protect_additionnal_import_X) ENABLED START*/#include <math.h>/*PROTECTED REGION END*/`;
        const r = mergeRegions(region('protect_additional_import_X', '//TODO'), oldText, 'f.c', isTodo);
        expect(r.text).toBe(region('protect_additional_import_X', '#include <math.h>'));
    });

    it('reports vanished regions holding user code as orphans, not default ones', () => {
        const oldText = `${region('gone', 'mine')}${region('gone2', '//TODO')}${region('kept', 'k')}`;
        const r = mergeRegions(region('kept', ''), oldText, 'f.c', isTodo);
        expect(r.orphans.map((o) => [o.id, o.content])).toEqual([['gone', 'mine']]);
        expect(r.text).toBe(region('kept', 'k'));
    });

    it('throws on a malformed existing file', () => {
        expect(() => mergeRegions(region('a', ''), '/*PROTECTED REGION ID(a) ENABLED START*/x', 'f.c', isTodo)).toThrow(/f\.c:1/);
    });
});
