/** Quick fixes (docs/ide.md "Editor services"): add a missing import, upper-case a module name, renumber a duplicate port index, insert a rule's missing ';'. */
import { describe, expect, it } from 'vitest';
import type { CodeAction, WorkspaceEdit } from 'vscode-languageserver-protocol';
import { build, type Built } from './helpers.js';
import { ARCHITECTURE } from './lsp-workspace.js';

/** The quick fixes offered for the diagnostics of `file` with the given code. */
async function fixes(ws: Built, file: string, code: string): Promise<CodeAction[]> {
    const doc = ws.docs.get(file)!;
    const diagnostics = (doc.diagnostics ?? []).filter((d) => d.code === code);
    expect(diagnostics.length, `a ${code} diagnostic in ${file}`).toBeGreaterThan(0);
    const actions = await ws.services.lsp.CodeActionProvider!.getCodeActions(doc, {
        textDocument: { uri: doc.uri.toString() },
        range: diagnostics[0]!.range,
        context: { diagnostics }
    });
    return (actions ?? []) as CodeAction[];
}

/** New texts of the files after a workspace edit. */
function apply(ws: Built, edit: WorkspaceEdit): Record<string, string> {
    const out: Record<string, string> = {};
    for (const [file, doc] of ws.docs) {
        const edits = [...(edit.changes?.[doc.uri.toString()] ?? [])]
            .sort((a, b) => doc.textDocument.offsetAt(b.range.start) - doc.textDocument.offsetAt(a.range.start));
        let text = doc.textDocument.getText();
        for (const e of edits) text = text.slice(0, doc.textDocument.offsetAt(e.range.start)) + e.newText + text.slice(doc.textDocument.offsetAt(e.range.end));
        out[file] = text;
    }
    return out;
}

describe('quick fixes', () => {
    it('adds the missing import after the existing ones, and the file then checks clean of that error', async () => {
        const files = { ...ARCHITECTURE, 'nested/s5.contract': 'import "../msa.contract";\nperiodic schema s5() { realtime { PERIOD=1s; } modules { MSA(); MSD(); } }\n' };
        const ws = await build(files);
        const [action, ...rest] = await fixes(ws, 'nested/s5.contract', 'import-not-imported');
        expect(rest).toEqual([]);
        expect(action!.title).toBe('Add import "../msd.contract"');
        const fixed = apply(ws, action!.edit!)['nested/s5.contract']!;
        expect(fixed).toBe('import "../msa.contract";\nimport "../msd.contract";\nperiodic schema s5() { realtime { PERIOD=1s; } modules { MSA(); MSD(); } }\n');
        const again = await build({ ...files, 'nested/s5.contract': fixed });
        expect(again.diagnostics.filter((d) => d.file === 'nested/s5.contract' && d.code === 'import-not-imported')).toEqual([]);
    });

    it('adds an import at the top of a file without imports', async () => {
        const ws = await build({ ...ARCHITECTURE, 'm.contract': 'synchronous module MXX { scheduling { C=1ms; } data flows { out :0 TypeA a; } }' });
        const [action] = await fixes(ws, 'm.contract', 'import-not-imported');
        expect(apply(ws, action!.edit!)['m.contract']).toMatch(/^import "types\.contract";\nsynchronous module MXX/);
    });

    it('upper-cases a module name in its file and in the files that refer to it', async () => {
        const ws = await build({
            ...ARCHITECTURE,
            'msa.contract': ARCHITECTURE['msa.contract']!.replace('module MSA', 'module msa'),
            'schema.contract': ARCHITECTURE['schema.contract']!.replace(/MSA/g, 'msa')
        });
        const [action] = await fixes(ws, 'msa.contract', 'module-name-format');
        expect(action!.title).toBe("Rename 'msa' to 'MSA'");
        const texts = apply(ws, action!.edit!);
        expect(texts['msa.contract']).toContain('synchronous module MSA {');
        expect(texts['schema.contract']).toContain('MSA -> MSC;');
        expect(texts['schema.contract']).toContain('MSA:0 -> MSC:0 * 1;');
        expect(texts["schema.contract"]).not.toMatch(/\bmsa\b(?!\.contract)/);
    });

    it('renumbers a duplicate port index to the free index', async () => {
        const ws = await build({ 'types.contract': ARCHITECTURE['types.contract']!, 'm.contract': `import "types.contract";
synchronous module MXX { scheduling { C=1ms; } data flows { out :0 int a; out :0 int b; out :1 int c; } }` });
        const [action] = await fixes(ws, 'm.contract', 'port-index-duplicate');
        expect(action!.title).toBe('Renumber to :2');
        expect(apply(ws, action!.edit!)['m.contract']).toContain('out :0 int a; out :2 int b; out :1 int c;');
    });

    it("inserts a rule's missing ';' between two actions, after the first one, and the file then checks clean", async () => {
        const text = (sep: string) => `supervisor SUP {\n  event flows { in :1 int x; in :2 int y; }\n  f() { rules { R: [elapsed=1ms] subscribe MAA:2 =* :1${sep} // keep\n    subscribe MAA:0 =* :2 [elapsed=1ms] } }\n}\n`;
        const files = { 'maa.contract': 'asynchronous module MAA { event flows { out :0 int a; out :2 int b; } }', 'sup.contract': 'import "maa.contract";\n' + text('') };
        const ws = await build(files);
        const [action, ...rest] = await fixes(ws, 'sup.contract', 'supervisor-action-separator');
        expect(rest).toEqual([]);
        expect(action!.title).toBe("Insert ';'");
        const fixed = apply(ws, action!.edit!)['sup.contract']!;
        expect(fixed).toBe('import "maa.contract";\n' + text(';'));
        const again = await build({ ...files, 'sup.contract': fixed });
        expect(again.diagnostics.filter((d) => d.file === 'sup.contract')).toEqual([]);
    });

    it('turns elapsed=t that ends a rule only once into duration(R)=t, and the file then checks clean', async () => {
        const text = (end: string) => `supervisor SUP {\n  f() { rules {\n    A: [elapsed=1ms or endof(B)] [${end}]\n    B: [endof(A)] [duration(B)=2ms]\n  } }\n}\n`;
        const ws = await build({ 'sup.contract': text('elapsed=10ms') });
        const [action, ...rest] = await fixes(ws, 'sup.contract', 'supervisor-elapsed-once');
        expect(rest).toEqual([]);
        expect(action!.title).toBe('Use duration(A)=10ms (ends it 10ms after each activation)');
        const fixed = apply(ws, action!.edit!)['sup.contract']!;
        expect(fixed).toBe(text('duration(A)=10ms'));
        const again = await build({ 'sup.contract': fixed });
        expect(again.diagnostics.filter((d) => d.file === 'sup.contract')).toEqual([]);
        // a rule that nothing makes active again (its precondition only elapsed, or a module event): no warning
        for (const pre of ['elapsed=1ms', 'elapsed=1ms or elapsed=5ms']) {
            const once = await build({ 'sup.contract': `supervisor SUP {\n  f() { rules {\n    A: [${pre}] [elapsed=10ms]\n  } }\n}\n` });
            expect(once.diagnostics.filter((d) => d.code === 'supervisor-elapsed-once')).toEqual([]);
        }
    });

    it("replaces a misspelt keyword by the one the syntax error suggests, and the file then checks clean", async () => {
        const good = ARCHITECTURE['msa.contract']!;
        expect(good).toContain('synchronous module');
        const ws = await build({ ...ARCHITECTURE, 'msa.contract': good.replace('synchronous module', 'synchronus module') });
        const doc = ws.docs.get('msa.contract')!;
        const syntax = (doc.diagnostics ?? []).filter((d) => (d.data as { code?: string } | undefined)?.code === 'parsing-error');
        expect(syntax.map((d) => d.message).join('\n')).toContain("Did you mean 'synchronous'");
        const actions = (await ws.services.lsp.CodeActionProvider!.getCodeActions(doc, {
            textDocument: { uri: doc.uri.toString() }, range: syntax[0]!.range, context: { diagnostics: syntax }
        })) as CodeAction[];
        const fix = actions.find((a) => a.title === "Replace 'synchronus' with 'synchronous'");
        expect(fix, actions.map((a) => a.title).join(', ')).toBeDefined();
        const fixed = apply(ws, fix!.edit!)['msa.contract']!;
        expect(fixed).toBe(good);
        const again = await build({ ...ARCHITECTURE, 'msa.contract': fixed });
        expect(again.diagnostics.filter((d) => d.file === 'msa.contract' && d.severity === 'error')).toEqual([]);
    });

    it('offers no keyword fix when the squiggled text is not a near miss of the suggested keyword', async () => {
        const ws = await build({ ...ARCHITECTURE, 'msa.contract': ARCHITECTURE['msa.contract']!.replace('synchronous module', 'synchronus module') });
        const doc = ws.docs.get('msa.contract')!;
        const syntax = (doc.diagnostics ?? []).filter((d) => (d.data as { code?: string } | undefined)?.code === 'parsing-error');
        // the same message on a range holding another word: no edit is offered
        const moved = syntax.map((d) => ({ ...d, range: { start: { line: 0, character: 0 }, end: { line: 0, character: 6 } } }));
        const actions = await ws.services.lsp.CodeActionProvider!.getCodeActions(doc, {
            textDocument: { uri: doc.uri.toString() }, range: moved[0]!.range, context: { diagnostics: moved }
        });
        expect(actions).toEqual([]);
    });

    it('offers nothing for diagnostics without a fix', async () => {
        const ws = await build({ 'a.contract': 'import "nosuch.contract";\ndatatype T {int a};' });
        const doc = ws.docs.get('a.contract')!;
        const actions = await ws.services.lsp.CodeActionProvider!.getCodeActions(doc, {
            textDocument: { uri: doc.uri.toString() }, range: doc.diagnostics![0]!.range, context: { diagnostics: doc.diagnostics! }
        });
        expect(actions).toEqual([]);
    });
});
