/**
 * `_react_to_event` and `_react_to_parameterizing` cast their parameters to void in the skeleton,
 * before their protected region (docs/codegen.md, module.c): a region body that does not use them
 * all, as the ContrACT Eclipse tool's bodies did not (docs/migrating.md), compiles with -Wall
 * -Wextra -Werror, and so does one that still holds the casts of the region's former default.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { loadWorkspace } from '@contract-studio/language/node';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { generateArchitecture } from './generate-architecture.js';
import { parseRegions } from './regions/parse-regions.js';
import { RUNTIME_DIR, STRICT_CFLAGS, run } from './test-support/c-toolchain.js';
import { tempDir } from './test-support/temp-dir.js';
import { copyTutorial } from './test-support/tutorial-project.js';

const ARCH = 'src-gen/generated/architecture';

/** `text` with the content of region `id` replaced by `body` (markers kept). */
function withRegion(text: string, id: string, body: string): string {
    const r = parseRegions(text, id).regions.find((x) => x.id === id);
    if (!r) throw new Error(`no region ${id}`);
    return text.slice(0, r.contentStart) + body + text.slice(r.contentEnd);
}

/** Compiles one module.c of the tree alone (no link), as its Makefile does, warnings as errors; returns gcc's output. */
function compileModule(dir: string, module: string): string {
    const folder = join(dir, ARCH, 'modules', `${module}_mod`);
    return run('gcc', [...STRICT_CFLAGS, `-I${join(RUNTIME_DIR, 'include')}`, '-I.', '-I../../common', '-c', 'module.c', '-o', '/dev/null'], folder);
}

describe('the reaction functions of an asynchronous module', () => {
    let dir: string;
    let cleanup: () => void;
    beforeAll(() => {
        ({ dir, cleanup } = tempDir('codegen-react-params-'));
        copyTutorial(dir);
    });
    afterAll(() => cleanup());

    it('compile without an unused-parameter warning whatever their regions hold: bodies without casts (the old tool\'s), and bodies with them', async () => {
        const maa = join(dir, ARCH, 'modules/MAA_mod/module.c');
        let text = readFileSync(maa, 'latin1');
        // the ContrACT Eclipse tool's bodies (its tutorial, §8): no (void) cast, parameters unused
        text = withRegion(text, 'protect_event_MAA', '\n    //TODO : implement the code for reaction to event notifications\n    ');
        text = withRegion(text, 'protect_param_MAA', '\n    switch(parameterport){\n        case 0: printf("MAA : new param %f %f %f\\n", param.i, param.j, param.k);\n            break;\n    }\n    ');
        writeFileSync(maa, Buffer.from(text, 'latin1'));
        // MAB keeps a body holding the casts of the former default, one of them twice: no warning either
        const mab = join(dir, ARCH, 'modules/MAB_mod/module.c');
        writeFileSync(mab, Buffer.from(withRegion(readFileSync(mab, 'latin1'), 'protect_event_MAB', '\n    (void)receiverport; (void)senderport; (void)sendermodule; (void)eventProductionTime; (void)eventReceptionTime;\n    //TODO\n    '), 'latin1'));

        const ws = await loadWorkspace(dir);
        const report = generateArchitecture(ws.documents, join(dir, 'src-gen'));
        expect([report.errors, report.orphaned]).toEqual([[], []]);
        for (const module of ['MAA', 'MAB']) expect(compileModule(dir, module), module).not.toMatch(/warning/);
        // the casts are the skeleton's, before the region
        const generated = readFileSync(maa, 'latin1');
        expect(generated).toContain('RTIME * eventReceptionTime){\n    (void)receiverport; (void)senderport; (void)sendermodule; (void)eventProductionTime; (void)eventReceptionTime;\n    /*PROTECTED REGION ID(protect_event_MAA) ENABLED START*/\n    //TODO : implement');
        expect(generated).toContain('RTIME * receptionTime){\n    (void)parameterport; (void)productionTime; (void)receptionTime;\n    /*PROTECTED REGION ID(protect_param_MAA) ENABLED START*/\n    switch(parameterport){');
    }, 120_000);
});
