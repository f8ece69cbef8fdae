import { describe, expect, it } from 'vitest';
import { carryRenamedRegions } from './carry-renamed-regions.js';
import { region } from './markers.js';

const file = (name: string, exec = name, exit = name) =>
    `// ${name}\n${region(`protect_exit_${exit}`, '\n  bye();\n')}\n${region(`protect_exec_${exec}`, '\n  step();\n')}\n`;
const ids = (name: string) => [`protect_exit_${name}`, `protect_exec_${name}`];
const output = (...names: string[]) => () => ({ ids: new Set(names.flatMap(ids)), paths: names.map((n) => `${n}_mod/module.c`) });

describe('carryRenamedRegions', () => {
    it("carries a gone entity's region to the missing one of the same kind, content byte for byte (git merged PLN's exec region into GTG's file)", () => {
        const existing = file('GTG', 'PLN');
        const { text, carried } = carryRenamedRegions(existing, 'GTG_mod/module.c', ids('GTG'), output('GTG', 'NAV'));
        expect(carried).toEqual([{ from: 'protect_exec_PLN', to: 'protect_exec_GTG', line: 5 }]);
        expect(text).toBe(file('GTG'));
    });

    it('carries every region of one rename (the whole file kept the old IDs)', () => {
        const { text, carried } = carryRenamedRegions(file('PLN'), 'GTG_mod/module.c', ids('GTG'), output('GTG'));
        expect(carried.map((c) => c.from)).toEqual(['protect_exit_PLN', 'protect_exec_PLN']);
        expect(text).toBe(file('GTG').replace('// GTG', '// PLN')); // only the markers' IDs change
    });

    it('carries nothing when ambiguous: the old entity still generated, the new region present, two renames in one file', () => {
        // PLN still exists: its region in GTG's file is a copy, not a rename
        expect(carryRenamedRegions(file('GTG', 'PLN'), 'f', ids('GTG'), output('GTG', 'PLN')).carried).toEqual([]);
        // NAV is still generated, a supervisor without regions
        expect(carryRenamedRegions(file('GTG', 'NAV'), 'f', ids('GTG'), () => ({ ids: new Set(ids('GTG')), paths: ['NAV_mod/module.c'] })).carried).toEqual([]);
        // GTG's own exec region is there too: PLN's is just gone
        const both = `${file('GTG')}${region('protect_exec_PLN', 'x')}\n`;
        expect(carryRenamedRegions(both, 'f', ids('GTG'), output('GTG')).carried).toEqual([]);
        // exit from AAA, exec from BBB: which one was renamed to GTG?
        expect(carryRenamedRegions(file('GTG', 'BBB', 'AAA'), 'f', ids('GTG'), output('GTG')).carried).toEqual([]);
        // nothing missing, nothing gone
        expect(carryRenamedRegions(file('GTG'), 'f', ids('GTG'), output('GTG')).carried).toEqual([]);
    });
});
