/** Completion (docs/ide.md "Editor services"): keywords, names in scope through imports, port indexes of the referenced module. */
import type { LangiumDocument } from 'langium';
import { describe, expect, it } from 'vitest';
import { CompletionItemKind, InsertTextFormat, type CompletionItem } from 'vscode-languageserver-protocol';
import { build, type Built } from './helpers.js';
import { ARCHITECTURE } from './lsp-workspace.js';

/** Builds the workspace plus `file` whose text has a `<|>` cursor, and completes there. */
async function completeAt(files: Record<string, string>, file: string, textWithCursor: string): Promise<{ ws: Built; items: CompletionItem[] }> {
    const offset = textWithCursor.indexOf('<|>');
    const text = textWithCursor.replace('<|>', '');
    const ws = await build({ ...files, [file]: text });
    const doc: LangiumDocument = ws.docs.get(file)!;
    const list = await ws.services.lsp.CompletionProvider!.getCompletion(doc, {
        textDocument: { uri: doc.uri.toString() }, position: doc.textDocument.positionAt(offset)
    });
    return { ws, items: list?.items ?? [] };
}

const SCHEMA_HEAD = `import "types.contract";
import "msa.contract";
import "msc.contract";
import "msd.contract";
periodic schema s2() {
    realtime { PERIOD=10ms; }
    modules { MSA(); MSC(); MSD(); }
    communications {
`;

describe('completion', () => {
    it('offers the out event ports of a module in a supervisor condition `[MSC:` and a subscription', async () => {
        const sup = (body: string) => `import "types.contract";
import "msc.contract";
supervisor SUQ { event flows { in :4 TypeD f; } go() { rules { R: ${body} } } }`;
        const cond = await completeAt(ARCHITECTURE, 'q.contract', sup('[MSC:<|>'));
        expect(cond.items.map((i) => `${i.label} ${i.detail}`)).toEqual(['1 out event :1 TypeD failing']);
        const sub = await completeAt(ARCHITECTURE, 'q.contract', sup('[elapsed=1ms] subscribe MSC:1 =* :<|>'));
        expect(sub.items.map((i) => `${i.label} ${i.detail}`)).toEqual(['4 in event :4 TypeD f']);
    });

    it('offers the output ports of the source module after `MSC:` (data or event: the line may become either), with name and type', async () => {
        const { items } = await completeAt(ARCHITECTURE, 's2.contract', SCHEMA_HEAD + '        MSC:<|>\n    }\n}');
        expect(items.map((i) => `${i.label} ${i.detail}`).sort()).toEqual(['1 out data :1 TypeB command', '1 out event :1 TypeD failing']);
        // MSA has one output data port and no event port
        const msa = await completeAt(ARCHITECTURE, 's2.contract', SCHEMA_HEAD + '        MSA:<|>\n    }\n}');
        expect(msa.items.map((i) => `${i.label} ${i.detail}`)).toEqual(['0 out data :0 TypeA coordinates']);
    });

    it('offers the input data ports of the target module after `-> MSD:`', async () => {
        const { items } = await completeAt(ARCHITECTURE, 's2.contract', SCHEMA_HEAD + '        MSC:1 -> MSD:<|>\n    }\n}');
        expect(items.map((i) => `${i.label} ${i.detail}`)).toEqual(['2 in data :2 TypeB order']);
    });

    it('offers the parameter ports of the instantiated module in `MSC(v :`', async () => {
        const { items } = await completeAt(ARCHITECTURE, 's3.contract', `import "types.contract";
import "msc.contract";
periodic schema s3(TypeA c) { modules { MSC(c :<|>); } }`);
        expect(items.map((i) => `${i.label} ${i.detail}`)).toEqual(['0 parameter :0 TypeA consigne']);
    });

    it('offers only the modules that the file imports (imports are not transitive)', async () => {
        const { items } = await completeAt(ARCHITECTURE, 's4.contract', `import "types.contract";
import "msa.contract";
periodic schema s4() { modules { <|> } }`);
        const labels = items.map((i) => i.label);
        expect(labels).toContain('MSA');
        expect(labels).not.toContain('MSC');
        expect(labels).not.toContain('MSD');
    });

    it('offers datatypes of imported files as types, with primitive type keywords', async () => {
        const { items } = await completeAt(ARCHITECTURE, 'm.contract', `import "types.contract";
synchronous module MXX { data flows { out :0 <|> } }`);
        const labels = items.map((i) => i.label);
        for (const name of ['TypeA', 'TypeB', 'int', 'float', 'string', 'bool']) expect(labels).toContain(name);
        expect(labels).not.toContain('MSA');
    });

    it('offers the top-level keywords in an empty file', async () => {
        const { items } = await completeAt({}, 'empty.contract', '<|>');
        const labels = items.map((i) => i.label);
        for (const k of ['import', 'datatype', 'function', 'synchronous', 'asynchronous', 'periodic', 'event', 'scheduler', 'supervisor']) {
            expect(labels).toContain(k);
        }
    });
});

describe('completion on an empty line of a rule body', () => {
    const sup = (body: string) => `import "types.contract";
import "msc.contract";
supervisor SUQ { event flows { out :1 TypeD f; } go() { rules {
    R: [elapsed=1ms]
        ${body}
} } }`;

    it('offers whole actions (activate schema / supervisor / module, subscribe, notify, ...) and conditions as snippets', async () => {
        const { items } = await completeAt(ARCHITECTURE, 'q.contract', sup('<|>\n        [endof(R)]'));
        const snippets = items.filter((i) => i.kind === CompletionItemKind.Snippet);
        const labels = snippets.map((i) => i.label);
        for (const l of ['activate schema', 'activate supervisor', 'activate critical module', 'subscribe', 'notify', 'parameterize', 'compute', '[endof(rule)]', '[elapsed=time]', '[ORD:0]']) {
            expect(labels).toContain(l);
        }
        const activate = snippets.find((i) => i.label === 'activate supervisor')!;
        expect(activate.insertTextFormat).toBe(InsertTextFormat.Snippet);
        expect(activate.textEdit?.newText ?? activate.insertText).toBe('activate supervisor ${1:SUP}.${2:function}(${3})');
        // the snippets come first, the bare keywords stay
        expect(items.findIndex((i) => i.kind === CompletionItemKind.Snippet)).toBeLessThan(items.findIndex((i) => i.label === 'activate'));
    });

    it('after an action, the next line offers actions and the closing condition again', async () => {
        const { items } = await completeAt(ARCHITECTURE, 'q.contract', sup('notify :1;\n        <|>'));
        const labels = items.map((i) => i.label);
        expect(labels).toContain('activate schema');
        expect(labels).toContain('[endof(rule)]');
    });

    it('outside rules (a module body) no rule snippet is offered', async () => {
        const { items } = await completeAt(ARCHITECTURE, 'm.contract', 'synchronous module MZ {\n    <|>\n}');
        expect(items.some((i) => i.kind === CompletionItemKind.Snippet)).toBe(false);
    });
});

describe('completion inside comments and strings', () => {
    it('offers nothing in a comment or a string being typed, and keywords again right after it', async () => {
        const file = (at: string) => `import "types.contract";\n${at}\nsynchronous module MZ { }`;
        for (const where of ['// written while the server was <|>', '/* a note <|> */', '/* still open <|>', 'import "types <|>']) {
            const { items } = await completeAt(ARCHITECTURE, 'c.contract', file(where));
            expect(items.map((i) => i.label), where).toEqual([]);
        }
        for (const where of ['// a comment\n<|>', '/* closed */ <|>', '/* a "quote" */ <|>']) {
            const { items } = await completeAt(ARCHITECTURE, 'c.contract', file(where));
            expect(items.map((i) => i.label), where).toContain('synchronous');
        }
    });
});
