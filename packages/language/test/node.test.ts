/** loadWorkspace on real files: nested folders, files imported from outside DIR, diagnostics form. */
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { URI } from 'langium';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { findContractFiles, loadWorkspace } from '../src/node/load-workspace.js';

let root: string;
beforeAll(() => {
    root = mkdtempSync(join(tmpdir(), 'cactal-node-'));
    mkdirSync(join(root, 'lib'));
    mkdirSync(join(root, 'proj/modules'), { recursive: true });
    mkdirSync(join(root, 'proj/node_modules'));
    writeFileSync(join(root, 'lib/types.contract'), 'datatype Vec {float x, float y};\n');
    writeFileSync(join(root, 'proj/modules/msa.contract'), 'import "../../lib/types.contract";\nsynchronous module MSA {\n  scheduling { C=1ms; }\n  data flows { out :0 Vec v = {1, 2.5}; }\n}\n');
    writeFileSync(join(root, 'proj/bad.contract'), 'datatype T {int a = "x"};\n');
    writeFileSync(join(root, 'proj/node_modules/ignored.contract'), 'this is not Cactal');
    writeFileSync(join(root, 'proj/notes.txt'), 'not a contract file');
});
afterAll(() => rmSync(root, { recursive: true, force: true }));

describe('loadWorkspace', () => {
    it('finds .contract files recursively, skipping node_modules', async () => {
        const files = await findContractFiles(join(root, 'proj'));
        expect(files.map((f) => f.slice(root.length + 1))).toEqual(['proj/bad.contract', 'proj/modules/msa.contract']);
    });

    it('loads files imported from outside DIR and reports 1-based diagnostics relative to DIR', async () => {
        const ws = await loadWorkspace(join(root, 'proj'));
        expect(ws.documents.map((d) => d.file)).toEqual(['bad.contract', 'modules/msa.contract', '../lib/types.contract']);
        expect(ws.diagnostics.map((d) => [d.file, d.line, d.column, d.severity, d.code])).toEqual([
            ['bad.contract', 1, 21, 'error', 'value-type-mismatch']
        ]);
    });
});

describe('incremental rebuilds', () => {
    it('revalidates a file when a file it imports is created or deleted', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'cactal-incr-'));
        try {
            writeFileSync(join(dir, 'a.contract'), 'import "b.contract";\ndatatype A {int x};\n');
            const ws = await loadWorkspace(dir);
            const codesOfA = () => (ws.services.shared.workspace.LangiumDocuments.getDocument(URI.file(join(dir, 'a.contract')))!.diagnostics ?? [])
                .map((d) => d.code);
            expect(codesOfA()).toEqual(['import-missing-file']);
            const b = join(dir, 'b.contract');
            writeFileSync(b, 'datatype B {int y};\n');
            await ws.services.shared.workspace.DocumentBuilder.update([URI.file(b)], []);
            expect(codesOfA()).toEqual(['import-unused']);
            rmSync(b);
            await ws.services.shared.workspace.DocumentBuilder.update([], [URI.file(b)]);
            expect(codesOfA()).toEqual(['import-missing-file']);
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });

    it('revalidates the other file of a duplicated name when the duplicate appears or disappears', async () => {
        const dir = mkdtempSync(join(tmpdir(), 'cactal-dup-'));
        try {
            const module = (name: string) => `synchronous module ${name} { scheduling { C=1ms; } }\n`;
            writeFileSync(join(dir, 'a.contract'), module('MSA'));
            const b = join(dir, 'b.contract');
            writeFileSync(b, module('MSB'));
            const ws = await loadWorkspace(dir);
            const codesOfA = () => (ws.services.shared.workspace.LangiumDocuments.getDocument(URI.file(join(dir, 'a.contract')))!.diagnostics ?? [])
                .map((d) => d.code);
            expect(codesOfA()).toEqual([]);
            writeFileSync(b, module('MSA'));
            await ws.services.shared.workspace.DocumentBuilder.update([URI.file(b)], []);
            expect(codesOfA()).toEqual(['module-name-duplicate']);
            writeFileSync(b, module('MSB'));
            await ws.services.shared.workspace.DocumentBuilder.update([URI.file(b)], []);
            expect(codesOfA()).toEqual([]);
        } finally {
            rmSync(dir, { recursive: true, force: true });
        }
    });
});
