/**
 * src-gen is committed (docs/ci.md): one model must generate the same bytes from any folder on any
 * machine, so the runtime's location is a build-time input, never written from where the generator
 * ran (docs/architecture.md, Seam 3).
 */
import { existsSync, mkdirSync } from 'node:fs';
import { join } from 'node:path';
import { spawnSync } from 'node:child_process';
import { loadWorkspace } from '@contract-studio/language/node';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { generateArchitecture } from './generate-architecture.js';
import { DEFAULT_RUNTIME } from './generators/build-settings.js';
import { readTree, tempDir } from './test-support/temp-dir.js';
import { EXAMPLES, copyExample as copyClone, inAClone } from './test-support/tutorial-project.js';
import { REGION_COPY_NAME } from './writer/index.js';

/** A copy of an example as a fresh clone has it into `dir`: its sources, and its committed src-gen when `withSrcGen`. */
function copyExample(example: string, dir: string, withSrcGen: boolean): void {
    mkdirSync(dir, { recursive: true });
    copyClone(example, dir, withSrcGen);
}

async function generate(dir: string): Promise<ReturnType<typeof generateArchitecture>> {
    const ws = await loadWorkspace(dir);
    expect(ws.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
    return generateArchitecture(ws.documents, join(dir, 'src-gen'));
}

describe('generated trees do not depend on the folder or the machine', () => {
    let root: string;
    let cleanup: () => void;
    beforeAll(() => { ({ dir: root, cleanup } = tempDir('codegen-portable-')); });
    afterAll(() => cleanup());

    for (const example of ['tutorial', 'mobile-robot']) {
        it(`${example}: two fresh clones at different depths regenerate to the committed bytes: the first generate writes only the copy of the regions' code, the second nothing`, async () => {
            const committed = readTree(join(EXAMPLES, example, 'src-gen'));
            for (const f of [...committed.keys()]) if (!inAClone(f)) committed.delete(f);
            expect(committed.has(REGION_COPY_NAME)).toBe(false);
            const manifest = JSON.parse(committed.get('.contract-manifest.json')!) as { userCode: Record<string, string[]> };
            expect(Object.keys(manifest.userCode).length).toBeGreaterThan(0);
            for (const dir of [join(root, `${example}-a`), join(root, 'x', 'y', 'z', `${example}-b`)]) {
                copyExample(example, dir, true);
                const first = await generate(dir);
                expect(first.errors).toEqual([]);
                expect(first.created).toEqual([]);
                expect(first.updated).toEqual([]);
                expect(first.orphaned).toEqual([]);
                expect(first.filesWritten).toBe(1); // the copy, written from the committed files
                const tree = readTree(join(dir, 'src-gen'));
                const { [REGION_COPY_NAME]: copy, ...generated } = Object.fromEntries(tree);
                expect(new Map(Object.entries(generated))).toEqual(committed);
                // it holds the code of every region the manifest records as holding code, as the committed files hold it
                const held = (JSON.parse(copy!) as { files: Record<string, Record<string, string>> }).files;
                expect(Object.fromEntries(Object.entries(held).map(([f, regions]) => [f, Object.keys(regions).sort()])))
                    .toEqual(Object.fromEntries(Object.entries(manifest.userCode).map(([f, ids]) => [f, [...ids].sort()])));
                for (const [f, regions] of Object.entries(held)) for (const body of Object.values(regions)) expect(committed.get(f), f).toContain(body);
                const second = await generate(dir);
                expect(second.errors).toEqual([]);
                expect(second.filesWritten).toBe(0);
                expect(readTree(join(dir, 'src-gen'))).toEqual(tree);
            }
        }, 120_000);
    }

    it('a fresh generate in two folders writes byte-identical trees that name neither folder', async () => {
        const a = join(root, 'fresh-a');
        const b = join(root, 'deeper', 'fresh-b');
        copyExample('tutorial', a, false);
        copyExample('tutorial', b, false);
        expect((await generate(a)).errors).toEqual([]);
        expect((await generate(b)).errors).toEqual([]);
        const treeA = readTree(join(a, 'src-gen'));
        expect(treeA.size).toBeGreaterThan(0);
        expect(readTree(join(b, 'src-gen'))).toEqual(treeA);
        for (const [path, text] of treeA) {
            expect(text, path).not.toContain(root);
            expect(text, path).not.toContain(EXAMPLES);
            // every Makefile but tools/Makefile (it only calls the makecontrol<M>) sets the runtime
            if (/_mod\/Makefile$|architecture\/Makefile$|makecontrol\w+$/.test(path)) expect(text, path).toContain(`CONTRACT_RUNTIME ?= ${DEFAULT_RUNTIME}\n`);
        }
    }, 120_000);

    describe.skipIf(existsSync(DEFAULT_RUNTIME))(`without CONTRACT_RUNTIME (and no runtime at ${DEFAULT_RUNTIME})`, () => {
        const env = Object.fromEntries(Object.entries(process.env).filter(([k]) => k !== 'CONTRACT_RUNTIME' && k !== 'MAKEFLAGS'));
        const make = (dir: string, ...args: string[]) => spawnSync('make', ['-C', dir, ...args], { env, encoding: 'utf8' });
        const arch = () => join(root, 'fresh-a', 'src-gen', 'generated', 'architecture');

        it('make stops before compiling anything, saying to set CONTRACT_RUNTIME', () => {
            for (const dir of [arch(), join(arch(), 'modules', 'MAA_mod')]) {
                const r = make(dir, 'all');
                expect(r.status, r.stderr).not.toBe(0);
                expect(r.stderr).toContain(`no ContrACT runtime at CONTRACT_RUNTIME=${DEFAULT_RUNTIME}: set CONTRACT_RUNTIME to the runtime/ folder of ContrACT Studio`);
                expect(r.stderr).toContain(`or install one there: make install PREFIX=${DEFAULT_RUNTIME} from that runtime/ folder`);
                expect(r.stdout).not.toMatch(/\bcc\b|gcc/);
            }
            const tool = spawnSync('make', ['-C', join(arch(), 'tools'), '-f', 'makecontrolMSC'], { env, encoding: 'utf8' });
            expect(tool.stderr).toContain('set CONTRACT_RUNTIME');
        });

        it('make clean needs no runtime', () => {
            const r = make(arch(), 'clean');
            expect(r.stderr).not.toContain('CONTRACT_RUNTIME');
            expect(r.status, r.stderr).toBe(0);
        });
    });
});
