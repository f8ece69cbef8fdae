import { describe, expect, it } from 'vitest';
import { parseRegions } from './parse-regions.js';
import { RegionSyntaxError } from './region-error.js';

const S = (id: string, enabled = true) => `/*PROTECTED REGION ID(${id})${enabled ? ' ENABLED' : ''} START*/`;
const E = '/*PROTECTED REGION END*/';

function errorOf(text: string): RegionSyntaxError {
    try {
        parseRegions(text, 'f.c');
    } catch (e) {
        return e as RegionSyntaxError;
    }
    throw new Error('no error');
}

describe('parseRegions', () => {
    it('finds regions with their exact content, ENABLED flag and line', () => {
        const text = `a\n${S('one')}\n  x = 1;\n${E}\nb ${S('two', false)}"inline"${E};\n`;
        const { regions } = parseRegions(text, 'f.c');
        expect(regions.map((r) => [r.id, r.enabled, r.content, r.line])).toEqual([
            ['one', true, '\n  x = 1;\n', 2],
            ['two', false, '"inline"', 5],
        ]);
        expect(text.slice(regions[1]!.start, regions[1]!.end)).toBe(`${S('two', false)}"inline"${E}`);
    });

    it('accepts markers broken over lines, as pasted from the report', () => {
        const text = '/*PROTECTED REGION ID(protect_description_MAA) ENABLED\nSTART*/"text"/*PROTECTED\nREGION END*/';
        const { regions } = parseRegions(text, 'f.c');
        expect(regions.map((r) => [r.id, r.enabled, r.content])).toEqual([['protect_description_MAA', true, '"text"']]);
    });

    it('reads the legacy additionnal spelling as additional', () => {
        const { regions } = parseRegions(`${S('protect_additionnal_import_MAA')}x${E}`, 'f.c');
        expect(regions[0]!.id).toBe('protect_additional_import_MAA');
        expect(regions[0]!.rawId).toBe('protect_additionnal_import_MAA');
    });

    it('rejects START without END with the line of the START', () => {
        const e = errorOf(`l1\nl2\n${S('a')}\nbody\n`);
        expect(e).toBeInstanceOf(RegionSyntaxError);
        expect([e.file, e.line]).toEqual(['f.c', 3]);
        expect(e.message).toMatch(/START without END/);
    });

    it('rejects a nested START at its line', () => {
        const e = errorOf(`${S('a')}\n\n${S('b')}\n${E}\n${E}`);
        expect(e.line).toBe(3);
        expect(e.message).toMatch(/nested/);
    });

    it('rejects a duplicate ID, also across spellings', () => {
        const e = errorOf(`${S('protect_additional_x')}${E}\n${S('protect_additionnal_x')}${E}`);
        expect(e.line).toBe(2);
        expect(e.message).toMatch(/duplicate .*protect_additional_x.*line 1/);
    });

    it('rejects END without START', () => {
        const e = errorOf(`${S('a')}${E}\n\n${E}`);
        expect(e.line).toBe(3);
        expect(e.message).toMatch(/END without a START/);
    });

    it('rejects a start marker with a typo at its own line, saying what was expected', () => {
        const e = errorOf(`${S('a')}${E}\n/*PROTECTED REGION ID(protect_exec_X) ENABELD START*/\n  mine();\n${E}\n`);
        expect([e.file, e.line]).toEqual(['f.c', 2]);
        expect(e.message).toBe("f.c:2: protected region start 'protect_exec_X' is malformed: 'ENABELD START' (expected 'ENABLED START' or 'START')");
    });
});
