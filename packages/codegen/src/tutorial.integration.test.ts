import { readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { loadWorkspace } from '@contract-studio/language/node';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { generateArchitecture } from './generate-architecture.js';
import { parseRegions } from './regions/parse-regions.js';
import { readTree, tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';
import { copyTutorial } from './test-support/tutorial-project.js';
import { REGION_COPY_NAME } from './writer/index.js';

const MODULES = 'generated/architecture/modules';

function enabledRegions(text: string, file: string): Map<string, string> {
    return new Map(parseRegions(text, file).regions.filter((r) => r.enabled).map((r) => [r.id, r.content]));
}

describe('the tutorial project (examples/tutorial)', () => {
    let dir: string;
    let cleanup: () => void;
    beforeAll(() => {
        ({ dir, cleanup } = tempDir('codegen-tutorial-'));
        copyTutorial(dir);
    });
    afterAll(() => cleanup());

    it('committed src-gen is what the generator writes: regenerating a fresh clone changes no generated file and writes only the copy of the regions\' code; again, nothing', async () => {
        const ws = await loadWorkspace(dir);
        expect(ws.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
        const before = readTree(join(dir, 'src-gen'));
        expect(before.has(REGION_COPY_NAME)).toBe(false); // the tutorial's .gitignore lists it: a clone has none
        const report = generateArchitecture(ws.documents, join(dir, 'src-gen'));
        expect(report.errors).toEqual([]);
        expect([...report.created, ...report.updated, ...report.orphaned]).toEqual([]);
        expect(report.filesWritten).toBe(1);
        const after = readTree(join(dir, 'src-gen'));
        expect(after.get(REGION_COPY_NAME)).toContain('_post_status(\\"connected\\");'); // MAA's code, from its module.c
        after.delete(REGION_COPY_NAME);
        expect(after).toEqual(before);
        const again = generateArchitecture((await loadWorkspace(dir)).documents, join(dir, 'src-gen'));
        expect(again.errors).toEqual([]);
        expect(again.filesWritten).toBe(0);
    }, 60_000);

    it("keeps the report's MAA and MSC user code when a port is added to MAA", async () => {
        const maaFile = `${MODULES}/MAA_mod/module.c`;
        const mscFile = `${MODULES}/MSC_mod/module.c`;
        const maaBefore = enabledRegions(readFileSync(join(dir, 'src-gen', maaFile), 'latin1'), maaFile);
        const mscBefore = readFileSync(join(dir, 'src-gen', mscFile), 'latin1');
        expect(maaBefore.get('protect_exec_MAA')).toContain('_post_status("connected");');

        const source = join(dir, 'amodule1.contract');
        writeFileSync(source, readFileSync(source, 'utf8').replace('out :2 string connection_status;', 'out :2 string connection_status;\n        out :3 TypeD link_quality;'));
        const ws = await loadWorkspace(dir);
        expect(ws.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
        const report = generateArchitecture(ws.documents, join(dir, 'src-gen'));
        expect(report.errors).toEqual([]);
        expect(report.updated).toContain(maaFile);
        expect(report.orphaned).toEqual([]);

        const maaAfter = readFileSync(join(dir, 'src-gen', maaFile), 'latin1');
        expect(maaAfter).toContain('TypeD link_quality = { "\\0", 0 };');
        expect(maaAfter).toContain('{ &link_quality, 3, sizeof(TypeD)}');
        const kept = enabledRegions(maaAfter, maaFile);
        for (const [id, content] of maaBefore) expect(kept.get(id), id).toBe(content);
        expect(readFileSync(join(dir, 'src-gen', mscFile), 'latin1')).toBe(mscBefore);
    }, 60_000);

    it('committed src-gen builds with gcc -std=c11 -Wall -Wextra -Werror against the runtime (make all, parallel)', () => {
        const { dir: buildDir, cleanup: done } = tempDir('codegen-build-');
        try {
            copyTutorial(buildDir);
            ensureRuntimeLibrary();
            const arch = join(buildDir, 'src-gen', 'generated', 'architecture');
            const out = run('make', ['-j2', '-C', arch, 'all', `CONTRACT_RUNTIME=${RUNTIME_DIR}`, 'EXTRA_CFLAGS=-Werror -O1']);
            expect(out).not.toMatch(/warning:/);
            for (const exe of ['ORD', 'MAA', 'MAB', 'MSA', 'MSB', 'MSC', 'MSD', 'SUP', 'GLB']) {
                expect(readdirSync(join(arch, 'modules', `${exe}_mod`))).toContain(exe);
            }
            expect(readdirSync(join(arch, 'tools'))).toContain('controlGLB');
        } finally {
            done();
        }
    }, 240_000);
});
