import { describe, expect, it } from 'vitest';
import { includeLines, includedCommonHeaders } from './header-dependencies.js';

const OWN = 'arch/modules/M_mod';
const COMMON = 'arch/common';
const folders = { own: OWN, common: COMMON };
const GENERATED = new Set(['A', 'B', 'C', 'D'].map((n) => `${COMMON}/Shared${n}.h`));

/** A tree of files: text by path; any other path is absent. */
const treeOf = (files: Record<string, string>) => (path: string) => files[path];

describe('includeLines', () => {
    it('reads quoted and angled includes, with spaces after # and CRLF endings', () => {
        expect(includeLines('#include <stdio.h>\r\n  #  include "SharedA.h"\r\nint x; // #include "no.h"\n#include"B.h"\n')).toEqual([
            { name: 'stdio.h', quoted: false },
            { name: 'SharedA.h', quoted: true },
            { name: 'B.h', quoted: true },
        ]);
    });
});

describe('includedCommonHeaders', () => {
    it('follows the generated headers\' own includes, and no header that nothing includes', () => {
        const tree = treeOf({
            [`${OWN}/module.c`]: '#include <libmodule/libmodule.h>\n#include "tools.h"\n#include "SharedB.h"\n',
            [`${COMMON}/SharedA.h`]: '#include "tools.h"\n',
            [`${COMMON}/SharedB.h`]: '#include "tools.h"\n#include "SharedA.h"\n',
            [`${COMMON}/SharedC.h`]: '#include "SharedA.h"\n',
            [`${COMMON}/SharedD.h`]: '',
        });
        expect(includedCommonHeaders([`${OWN}/module.c`], folders, GENERATED, tree)).toEqual([`${COMMON}/SharedA.h`, `${COMMON}/SharedB.h`]);
    });

    it('follows an include written in a protected region, through a header of the own folder and a user header of common/, cycles included', () => {
        const tree = treeOf({
            [`${OWN}/module.c`]: '#include "own.h"\n/*PROTECTED REGION ID(protect_additional_import_M) ENABLED START*/\n#include "../../common/mine.h"\n/*PROTECTED REGION END*/\n',
            [`${OWN}/own.h`]: '#include <own.h>\n#include "SharedD.h"\n',
            [`${COMMON}/mine.h`]: '#include "mine.h"\n#include "SharedC.h"\n',
            [`${COMMON}/SharedC.h`]: '#include "SharedA.h"\n',
            [`${COMMON}/SharedA.h`]: '',
            [`${COMMON}/SharedD.h`]: '',
        });
        expect(includedCommonHeaders([`${OWN}/module.c`], folders, GENERATED, tree)).toEqual([`${COMMON}/SharedA.h`, `${COMMON}/SharedC.h`, `${COMMON}/SharedD.h`, `${COMMON}/mine.h`]);
    });

    it('names the files of your own in common/ it includes, a .c and one in a subfolder too', () => {
        const tree = treeOf({
            [`${OWN}/module.c`]: '/*PROTECTED REGION ID(protect_additional_import_M) ENABLED START*/\n#include "axis_ctl.c"\n/*PROTECTED REGION END*/\n',
            [`${COMMON}/axis_ctl.c`]: '#include "lib/gain.h"\n#include "SharedA.h"\n',
            [`${COMMON}/lib/gain.h`]: '#define GAIN 3\n',
            [`${COMMON}/SharedA.h`]: '',
            [`${COMMON}/unused.c`]: '',
        });
        expect(includedCommonHeaders([`${OWN}/module.c`], folders, GENERATED, tree)).toEqual([`${COMMON}/SharedA.h`, `${COMMON}/axis_ctl.c`, `${COMMON}/lib/gain.h`]);
    });

    it('ignores includes leaving the tree (the runtime\'s, the system\'s)', () => {
        const tree = treeOf({ [`${OWN}/module.c`]: '#include "/usr/include/SharedA.h"\n#include "../../../../SharedA.h"\n', [`${COMMON}/SharedA.h`]: '' });
        expect(includedCommonHeaders([`${OWN}/module.c`], folders, GENERATED, tree)).toEqual([]);
    });

    it('is undefined (every header a dependency) when a file cannot be read', () => {
        const tree = (path: string) => {
            if (path === `${COMMON}/mine.h`) throw new Error('a link');
            return path === `${OWN}/module.c` ? '#include "mine.h"\n' : undefined;
        };
        expect(includedCommonHeaders([`${OWN}/module.c`], folders, GENERATED, tree)).toBeUndefined();
    });
});
