/**
 * With real make on the tutorial: a change to one datatype, or to a file of your own in common/,
 * rebuilds only the executables whose code can include it (the generated includes, those written
 * in protected regions, and what those headers include), not every executable.
 */
import { mkdirSync, readFileSync, rmSync, utimesSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { loadWorkspace } from '@contract-studio/language/node';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { generateArchitecture } from './generate-architecture.js';
import { RUNTIME_DIR, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';
import { tempDir } from './test-support/temp-dir.js';
import { copyTutorial } from './test-support/tutorial-project.js';


describe('the executables a datatype change rebuilds (tutorial, real make)', () => {
    let dir: string;
    let cleanup: () => void;
    let arch: string;
    const make = (...args: string[]) => run('make', ['-C', arch, `CONTRACT_RUNTIME=${RUNTIME_DIR}`, ...args]);
    /** The executables and control tools `make all` would link now (make -n: nothing is built). */
    const wouldRebuild = () => [...make('-n', 'all').matchAll(/ -o (\w+) /g)].map((m) => m[1]!).sort();
    const edit = (file: string, from: string, to: string) => {
        const text = readFileSync(file, 'latin1');
        expect(text).toContain(from);
        writeFileSync(file, text.replace(from, to), 'latin1');
    };
    const generate = async () => {
        const ws = await loadWorkspace(dir);
        expect(ws.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
        const report = generateArchitecture(ws.documents, join(dir, 'src-gen'));
        expect(report.errors).toEqual([]);
        return report;
    };

    beforeAll(() => {
        ({ dir, cleanup } = tempDir('codegen-makedeps-'));
        copyTutorial(dir);
        ensureRuntimeLibrary();
        arch = join(dir, 'src-gen', 'generated', 'architecture');
        make('-j2', 'all');
    }, 240_000);
    afterAll(() => cleanup());

    it('is built: make all has nothing left to link', () => {
        expect(wouldRebuild()).toEqual([]);
    });

    it('a field added to TypeE (used by MAA only) rebuilds MAA alone', async () => {
        edit(join(dir, 'datatype.contract'), 'datatype TypeE {TypeC message, TypeD data_ };', 'datatype TypeE {TypeC message, TypeD data_, int extra = 0 };');
        const report = await generate();
        expect(report.updated).toContain('generated/architecture/common/SharedTypeE.h');
        expect(wouldRebuild()).toEqual(['MAA']);
        make('-j2', 'all');
        expect(wouldRebuild()).toEqual([]);
    }, 120_000);

    it('a change to TypeC rebuilds the executables including it or a header that includes it (SharedTypeE.h)', async () => {
        edit(join(dir, 'datatype.contract'), 'datatype TypeC {string message, int messagetype=0, TypeA value };', 'datatype TypeC {string message, int messagetype=0, TypeA value, int extra = 0 };');
        await generate();
        expect(wouldRebuild()).toEqual(['MAA', 'MAB', 'SUP']);
        make('-j2', 'all');
    }, 120_000);

    it('an #include of SharedTypeF.h written in MSA\'s protected region makes MSA (alone) rebuild when TypeF changes', async () => {
        const msa = join(arch, 'modules', 'MSA_mod', 'module.c');
        edit(msa, '/*PROTECTED REGION ID(protect_additional_import_MSA) ENABLED START*/\n//TODO\n', '/*PROTECTED REGION ID(protect_additional_import_MSA) ENABLED START*/\n#include "SharedTypeF.h"\n');
        const regenerated = await generate();
        expect(regenerated.updated).toEqual(['generated/architecture/modules/MSA_mod/Makefile']);
        expect(readFileSync(join(arch, 'modules', 'MSA_mod', 'Makefile'), 'latin1')).toMatch(/^COMMON_HEADERS = .*SharedTypeF\.h/m);
        make('-j2', 'all');
        expect(wouldRebuild()).toEqual([]);

        edit(join(dir, 'datatype.contract'), 'datatype TypeF {int fufu, int juju};', 'datatype TypeF {int fufu, int juju, int extra = 0};');
        await generate();
        expect(wouldRebuild()).toEqual(['MSA']);
    }, 120_000);

    it('a helper .c of your own in common/ (and the header it includes from a subfolder) rebuilds the module including it when edited, no other', async () => {
        make('-j2', 'all');
        mkdirSync(join(arch, 'common', 'lib'), { recursive: true });
        writeFileSync(join(arch, 'common', 'lib', 'gain.h'), '#define GAIN 3\n');
        writeFileSync(join(arch, 'common', 'axis_ctl.c'), '#include "lib/gain.h"\nstatic inline int helper_gain(void) { return GAIN; }\n');
        const msb = join(arch, 'modules', 'MSB_mod', 'module.c');
        edit(msb, '/*PROTECTED REGION ID(protect_additional_import_MSB) ENABLED START*/\n', '/*PROTECTED REGION ID(protect_additional_import_MSB) ENABLED START*/\n#include "axis_ctl.c"\n');
        await generate();
        make('-j2', 'all');
        expect(wouldRebuild()).toEqual([]);
        const touch = (file: string) => {
            const now = new Date(); // later than the executables make just wrote
            utimesSync(file, now, now);
        };
        // the header in a subfolder: MSB alone (found through the include lines)
        touch(join(arch, 'common', 'lib', 'gain.h'));
        expect(wouldRebuild()).toEqual(['MSB']);
        make('-j2', 'all');
        // the .c of your own at common/'s top: MSB alone too
        touch(join(arch, 'common', 'axis_ctl.c'));
        expect(wouldRebuild()).toEqual(['MSB']);
        make('-j2', 'all');
    }, 120_000);

    it('an #include typed into a region: a hand-run make rebuilds that module (its module.c changed); the header\'s later edits rebuild it once a generation (contract build) rewrote the Makefile', async () => {
        make('-j2', 'all');
        writeFileSync(join(arch, 'common', 'myhelper.h'), '#define MY_HELPER 1\n');
        expect(wouldRebuild()).toEqual([]);
        const maa = join(arch, 'modules', 'MAA_mod', 'module.c');
        edit(maa, '/*PROTECTED REGION ID(protect_additional_import_MAA) ENABLED START*/\n', '/*PROTECTED REGION ID(protect_additional_import_MAA) ENABLED START*/\n#include "myhelper.h"\n');
        expect(wouldRebuild()).toEqual(['MAA']);
        make('-j2', 'all');
        const touch = (file: string) => {
            const now = new Date();
            utimesSync(file, now, now);
        };
        touch(join(arch, 'common', 'myhelper.h'));
        expect(wouldRebuild()).toEqual([]); // the Makefile written before the include does not name it
        await generate();
        expect(wouldRebuild()).toEqual(['MAA']); // its Makefile changed: it names myhelper.h now
        make('-j2', 'all');
        touch(join(arch, 'common', 'myhelper.h'));
        expect(wouldRebuild()).toEqual(['MAA']);
        make('-j2', 'all');
        edit(maa, '#include "myhelper.h"\n', '');
        rmSync(join(arch, 'common', 'myhelper.h'));
        await generate();
        make('-j2', 'all');
    }, 120_000);

    it('a header of your own that a region includes, deleted: the module is rebuilt (and the compiler says it is missing), not left on its old binary', async () => {
        const mine = join(arch, 'modules', 'MSC_mod', 'mine.h');
        writeFileSync(mine, '#define MINE 2\n');
        writeFileSync(join(arch, 'common', 'shared_gain.h'), '#define SHARED_GAIN 4\n');
        const msc = join(arch, 'modules', 'MSC_mod', 'module.c');
        edit(msc, '/*PROTECTED REGION ID(protect_additional_import_MSC) ENABLED START*/\n', '/*PROTECTED REGION ID(protect_additional_import_MSC) ENABLED START*/\n#include "mine.h"\n#include "shared_gain.h"\n');
        await generate();
        make('-j2', 'all');
        expect(wouldRebuild()).toEqual([]);
        for (const deleted of [mine, join(arch, 'common', 'shared_gain.h')]) {
            rmSync(deleted);
            await generate(); // as contract build does before make
            expect(wouldRebuild(), deleted).toContain('MSC');
            expect(() => make('-j2', 'all'), deleted).toThrow(/No such file or directory/);
            writeFileSync(deleted, '#define PUT_BACK 1\n');
            await generate();
            make('-j2', 'all');
        }
        edit(msc, '#include "mine.h"\n#include "shared_gain.h"\n', '');
        rmSync(mine);
        rmSync(join(arch, 'common', 'shared_gain.h'));
        await generate();
        make('-j2', 'all');
    }, 120_000);

    it('a header of common/ the generator did not write, included by no one, rebuilds nothing; an #include of a macro name makes every file of yours at common/\'s top a dependency of that module', async () => {
        make('-j2', 'all');
        writeFileSync(join(arch, 'common', 'mine.h'), '#define MINE 1\n');
        expect(wouldRebuild()).toEqual([]);
        const msd = join(arch, 'modules', 'MSD_mod', 'module.c');
        edit(msd, '/*PROTECTED REGION ID(protect_additional_import_MSD) ENABLED START*/\n', '/*PROTECTED REGION ID(protect_additional_import_MSD) ENABLED START*/\n#define MINE_H "mine.h"\n#include MINE_H\n');
        await generate();
        make('-j2', 'all');
        const now = new Date();
        utimesSync(join(arch, 'common', 'mine.h'), now, now);
        expect(wouldRebuild()).toEqual(['MSD']);
    }, 120_000);
});
