/**
 * A workspace of several projects (docs/codegen.md "Where a project is"): names, references and
 * every project-wide check look at the project of the document only — on real folders
 * (loadWorkspace: `contract check`; the stdio language server) and on an in-memory workspace told
 * its generated trees (the IDE's language worker).
 */
import { cpSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { AstUtils, EmptyFileSystem, URI } from 'langium';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { loadWorkspace, type LoadedWorkspace } from '../src/node/load-workspace.js';
import { createCactalServices } from '../src/cactal-module.js';
import { isModule, type Model } from '../src/generated/ast.js';
import { renameProblem } from '../src/lsp/name-rules.js';
import { LSP_TEST_MS, startServer, waitFor } from './lsp-stdio-client.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));

let root: string;
beforeAll(() => { root = mkdtempSync(join(tmpdir(), 'cactal-projects-')); });
afterAll(() => rmSync(root, { recursive: true, force: true }));

/** A folder of `files` (path -> text; a path ending in `/` is an empty folder) under the test's root. */
function folder(name: string, files: Record<string, string>): string {
    const dir = join(root, name);
    for (const [path, text] of Object.entries(files)) {
        if (path.endsWith('/')) { mkdirSync(join(dir, path), { recursive: true }); continue; }
        mkdirSync(dirname(join(dir, path)), { recursive: true });
        writeFileSync(join(dir, path), text);
    }
    return dir;
}

const lines = (ws: LoadedWorkspace) => ws.diagnostics.map((d) => `${d.file}:${d.line} ${d.code} ${d.message}`);
const tutorialCopy = (dir: string, without: string[] = []) =>
    cpSync(TUTORIAL, dir, { recursive: true, filter: (src) => !src.includes('/src-gen') && !without.some((w) => src.endsWith(`/${w}`)) });

describe('a folder of several projects', () => {
    it('two copies of the tutorial (no src-gen/: each first-level folder is a project) are each clean', async () => {
        const dir = join(root, 'two-tutorials');
        tutorialCopy(join(dir, 'a'));
        tutorialCopy(join(dir, 'b'));
        const ws = await loadWorkspace(dir);
        expect(lines(ws)).toEqual([]);
        expect(ws.layout.roots).toEqual(['a', 'b']);
    });

    it('a project without a scheduler configuration is told so, even when another project has one', async () => {
        const dir = join(root, 'one-without-scheduler');
        tutorialCopy(join(dir, 'a'));
        tutorialCopy(join(dir, 'b'), ['sched.contract']);
        const ws = await loadWorkspace(dir);
        const codes = new Set(ws.diagnostics.map((d) => `${d.file.split('/')[0]} ${d.code}`));
        expect(codes).toContain('b scheduler-missing');
        expect([...codes].filter((c) => c.startsWith('a '))).toEqual([]);
    });

    it('duplicates are found within a project, named by their path in it; the same names in another project are no duplicates', async () => {
        const dir = folder('eclipse-and-other', {
            'robot/src-gen/': '',
            'robot/src/types.contract': 'datatype T {int a};\nconst int speed = 1;\n',
            'robot/lib/types.contract': 'datatype T {int a};\n',
            'robot/src/more.contract': 'datatype U {int speed};\n',
            'other/types.contract': 'datatype T {int a};\ndatatype D {int speed};\ndatatype POSE {int x};\n',
            'other/pose.contract': 'datatype Q {int y};\n',
            'robot/src/pose.contract': 'datatype Pose {int x};\n'
        });
        const ws = await loadWorkspace(dir);
        const found = lines(ws);
        expect(found.filter((l) => l.startsWith('other/'))).toEqual([]);
        expect(found).toContain("robot/src/types.contract:1 type-duplicate-name Datatype 'T' is defined more than once in the project (also in lib/types.contract); datatype names are unique across the project.");
        expect(found).toContain("robot/lib/types.contract:1 type-duplicate-name Datatype 'T' is defined more than once in the project (also in src/types.contract); datatype names are unique across the project.");
        // a C-name clash (a constant is a macro) within the project only
        expect(found.some((l) => l.startsWith('robot/src/more.contract:1 identifier-c-reserved'))).toBe(true);
        // Pose and POSE would share a header's include guard in one project, not in two
        expect(found.filter((l) => l.includes('identifier-generated-clash'))).toEqual([]);
        expect(ws.layout.roots).toEqual(['other', 'robot']);
    });

    it('modules, schemas and supervisors of one name in two projects: no duplicate; in one project: a duplicate named by its path', async () => {
        const dir = join(root, 'tutorial-and-copy');
        tutorialCopy(join(dir, 'a'));
        tutorialCopy(join(dir, 'b'));
        mkdirSync(join(dir, 'a/src-gen'));
        mkdirSync(join(dir, 'a/extra'));
        cpSync(join(TUTORIAL, 'sschema1.contract'), join(dir, 'a/extra/sschema1.contract'));
        const ws = await loadWorkspace(dir);
        const found = lines(ws);
        expect(found.filter((l) => l.startsWith('b/'))).toEqual([]);
        expect(found.some((l) => l.startsWith('a/sschema1.contract') && l.includes('schema-name-duplicate') && l.includes('(also in extra/sschema1.contract)'))).toBe(true);
        expect(found.some((l) => l.startsWith('a/extra/sschema1.contract') && l.includes('(also in sschema1.contract)'))).toBe(true);
    });

    it('a rename may take a name another project uses', async () => {
        const dir = join(root, 'rename');
        tutorialCopy(join(dir, 'a'));
        tutorialCopy(join(dir, 'b'));
        writeFileSync(join(dir, 'b/extra.contract'), 'synchronous module QQQ {\n  scheduling { C=1ms; }\n}\n');
        const ws = await loadWorkspace(dir);
        const doc = ws.documents.find((d) => d.file === 'a/smodule1.contract')!;
        const module = doc.model.elements.find(isModule)!;
        const own = ws.documents.find((d) => d.file === 'a/smodule2.contract')!.model.elements.find(isModule)!.name;
        const other = ws.documents.find((d) => d.file === 'b/smodule2.contract')!.model.elements.find(isModule)!.name;
        expect(own).toBe(other);
        expect(renameProblem(module, own, ws.services.Grammar, ws.services.projects.Projects.indexOf(AstUtils.getDocument(module).uri))).toMatch(/already names a module or supervisor/);
        expect(renameProblem(module, 'QQQ', ws.services.Grammar, ws.services.projects.Projects.indexOf(AstUtils.getDocument(module).uri))).toBeUndefined();
    });
});

describe('a workspace told its generated trees (the IDE language worker)', () => {
    it('the folders holding a src-gen/ are the projects, their sub-folders part of them', async () => {
        const { shared, Cactal } = createCactalServices(EmptyFileSystem);
        const trees = new Set(['file:///workspace/p', 'file:///workspace/q']);
        Cactal.projects.Projects.configure({ openedFolders: [URI.parse('file:///workspace')], probe: (f) => trees.has(f.toString()) });
        const files: Record<string, string> = {
            'p/src/a.contract': 'datatype T {int a};\n',
            'p/lib/b.contract': 'datatype T {int a};\n',
            'q/src/a.contract': 'datatype T {int a};\n'
        };
        const docs = Object.entries(files).map(([path, text]) => {
            const doc = shared.workspace.LangiumDocumentFactory.fromString<Model>(text, URI.parse(`file:///workspace/${path}`));
            shared.workspace.LangiumDocuments.addDocument(doc);
            return doc;
        });
        await shared.workspace.DocumentBuilder.build(docs, { validation: true });
        const messages = docs.map((d) => (d.diagnostics ?? []).map((x) => x.message));
        expect(messages[0]).toEqual(["Datatype 'T' is defined more than once in the project (also in lib/b.contract); datatype names are unique across the project."]);
        expect(messages[1]).toEqual(["Datatype 'T' is defined more than once in the project (also in src/a.contract); datatype names are unique across the project."]);
        expect(messages[2]).toEqual([]);
    });
});

describe('a file added or removed that changes the projects', () => {
    it('checks the files that moved to another project again (a language server told of the change)', async () => {
        const dir = folder('layout-change', { 'a/x.contract': 'datatype T {int a};\n', 'b/y.contract': 'datatype T {int a};\n' });
        const ws = await loadWorkspace(dir);
        const builder = ws.services.shared.workspace.DocumentBuilder;
        const [a, b] = ws.documents.map((d) => d.document);
        // a/ and b/: two projects (rule 3)
        expect([a, b].map((d) => (d!.diagnostics ?? []).length)).toEqual([0, 0]);
        // a .contract file in the opened folder itself: one project (rule 2), T defined twice in it
        writeFileSync(join(dir, 'top.contract'), 'function void f(int x);\n'); // no fact of project-facts.ts: revalidates nothing by itself
        await builder.update([URI.file(join(dir, 'top.contract'))], []);
        expect(a!.diagnostics!.map((d) => d.message)).toEqual(["Datatype 'T' is defined more than once in the project (also in b/y.contract); datatype names are unique across the project."]);
        expect(b!.diagnostics!.map((d) => d.message)).toEqual(["Datatype 'T' is defined more than once in the project (also in a/x.contract); datatype names are unique across the project."]);
        rmSync(join(dir, 'top.contract'));
        await builder.update([], [URI.file(join(dir, 'top.contract'))]);
        expect([a, b].map((d) => (d!.diagnostics ?? []).length)).toEqual([0, 0]);
    });
});

describe('the language server (stdio) on a workspace folder of several projects (VS Code, Neovim rooted at a repository)', () => {
    it('publishes each file\'s diagnostics as of its project: folders holding a src-gen/ read from disk', async () => {
        const dir = join(root, 'server');
        tutorialCopy(join(dir, 'a'));
        tutorialCopy(join(dir, 'b'));
        folder('server', {
            'b/types2.contract': 'datatype TypeA {float i = 0.0};\n',
            'group/p/src-gen/': '', 'group/p/x.contract': 'datatype Pose {float x = 0.0};\n',
            'group/q/src-gen/': '', 'group/q/y.contract': 'datatype Pose {float x = 0.0};\n'
        });
        const { client } = await startServer(dir);
        try {
            const files = ['a/datatype.contract', 'b/datatype.contract', 'group/p/x.contract'];
            const uri = (f: string) => pathToFileURL(join(dir, f)).toString();
            for (const f of files) client.notify('textDocument/didOpen', { textDocument: { uri: uri(f), languageId: 'cactal', version: 1, text: readFileSync(join(dir, f), 'utf8') } });
            await waitFor(() => files.every((f) => client.latestDiagnostics(uri(f)) !== undefined));
            expect(client.latestDiagnostics(uri('a/datatype.contract'))).toEqual([]);
            expect(client.latestDiagnostics(uri('group/p/x.contract'))).toEqual([]);
            expect(client.latestDiagnostics(uri('b/datatype.contract'))!.map((d) => d.message)).toEqual([
                "Datatype 'TypeA' is defined more than once in the project (also in types2.contract); datatype names are unique across the project."
            ]);
        } finally {
            await client.stop();
        }
    }, LSP_TEST_MS);

    /**
     * group/p and group/q, each defining Pose: one project without src-gen/ (rule 2), two with
     * group/p/src-gen and group/q/src-gen (rule 1). `tell`: the client's watcher event for the
     * folders made or removed, or none (a client that watches no files for the server).
     */
    async function treesMadeAndRemoved(name: string, capabilities: Record<string, unknown>, tell: boolean): Promise<void> {
        const dir = folder(name, { 'group/p/x.contract': 'datatype Pose {float x = 0.0};\n', 'group/q/y.contract': 'datatype Pose {float x = 0.0};\n' });
        const { client } = await startServer(dir, capabilities);
        try {
            const files = ['group/p/x.contract', 'group/q/y.contract'];
            const uri = (f: string) => pathToFileURL(join(dir, f)).toString();
            const messages = () => files.map((f) => (client.latestDiagnostics(uri(f)) ?? []).map((d) => d.message));
            const duplicated = [
                ["Datatype 'Pose' is defined more than once in the project (also in group/q/y.contract); datatype names are unique across the project."],
                ["Datatype 'Pose' is defined more than once in the project (also in group/p/x.contract); datatype names are unique across the project."],
            ];
            for (const f of files) client.notify('textDocument/didOpen', { textDocument: { uri: uri(f), languageId: 'cactal', version: 1, text: readFileSync(join(dir, f), 'utf8') } });
            await waitFor(() => JSON.stringify(messages()) === JSON.stringify(duplicated));
            expect(messages()).toEqual(duplicated);
            // contract generate of each: group/p/src-gen and group/q/src-gen made, nothing else changes
            const trees = ['group/p/src-gen', 'group/q/src-gen'];
            for (const t of trees) mkdirSync(join(dir, t));
            // each folder in an event of its own, as a watcher reporting them one by one: the second
            // update cancels the first (it lost the move: the layout was worked out again with both made)
            if (tell) for (const t of trees) client.notify('workspace/didChangeWatchedFiles', { changes: [{ uri: uri(t), type: 1 }] });
            await waitFor(() => messages().every((m) => m.length === 0), 30_000);
            expect(messages()).toEqual([[], []]);
            // removed: one project again
            for (const t of trees) rmSync(join(dir, t), { recursive: true });
            if (tell) for (const t of trees) client.notify('workspace/didChangeWatchedFiles', { changes: [{ uri: uri(t), type: 3 }] });
            await waitFor(() => JSON.stringify(messages()) === JSON.stringify(duplicated), 30_000);
            expect(messages()).toEqual(duplicated);
        } finally {
            await client.stop();
        }
    }

    it('a src-gen/ folder made or removed takes effect at the watcher event the client sends for the folder (VS Code)', async () => {
        await treesMadeAndRemoved('server-trees-told', { workspace: { didChangeWatchedFiles: { dynamicRegistration: true } } }, true);
    }, LSP_TEST_MS);

    it('a src-gen/ folder made or removed on disk takes effect at once for a client that watches no files (Neovim on Linux): the server watches the folders it may appear in', async () => {
        await treesMadeAndRemoved('server-trees-watched', {}, false);
    }, LSP_TEST_MS);
});
