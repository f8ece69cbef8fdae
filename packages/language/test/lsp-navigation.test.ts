/** Go to definition, find references and rename across files (docs/ide.md "Editor services"), ports by index included. */
import { describe, expect, it } from 'vitest';
import type { Location, LocationLink, WorkspaceEdit } from 'vscode-languageserver-protocol';
import { build, uriOf, type Built } from './helpers.js';
import { ARCHITECTURE, offsetOf, positionParams } from './lsp-workspace.js';

/** `file:text` of each location (the text under the range). */
function describeLocations(ws: Built, locations: Array<{ uri: string; range: Location['range'] }>): string[] {
    const byUri = new Map([...ws.docs.entries()].map(([file, doc]) => [doc.uri.toString(), { file, doc }]));
    return locations.map((l) => {
        const entry = byUri.get(l.uri)!;
        const text = entry.doc.textDocument.getText(l.range);
        return `${entry.file}:${l.range.start.line + 1}:${text}`;
    }).sort();
}

/** Applies a workspace edit to the texts of the workspace (name -> new text). */
function applyEdit(ws: Built, edit: WorkspaceEdit): Record<string, string> {
    const result: Record<string, string> = {};
    for (const [file, doc] of ws.docs) {
        const edits = [...(edit.changes?.[doc.uri.toString()] ?? [])]
            .sort((a, b) => doc.textDocument.offsetAt(b.range.start) - doc.textDocument.offsetAt(a.range.start));
        let text = doc.textDocument.getText();
        for (const e of edits) {
            text = text.slice(0, doc.textDocument.offsetAt(e.range.start)) + e.newText + text.slice(doc.textDocument.offsetAt(e.range.end));
        }
        result[file] = text;
    }
    return result;
}

describe('go to definition', () => {
    it('jumps from a module reference to the module in another file', async () => {
        const ws = await build(ARCHITECTURE);
        const schema = ws.docs.get('schema.contract')!;
        const links = await ws.services.lsp.DefinitionProvider!.getDefinition(schema, positionParams(schema, offsetOf(schema, 'MSC(consigne', 1))) as LocationLink[];
        expect(links).toHaveLength(1);
        expect(links[0]!.targetUri).toBe(uriOf('msc.contract').toString());
        expect(describeLocations(ws, [{ uri: links[0]!.targetUri, range: links[0]!.targetSelectionRange }])).toEqual(['msc.contract:2:MSC']);
    });

    it('jumps from a port index (MSC:1 in a supervisor) to the port declaration of that kind and direction', async () => {
        const ws = await build(ARCHITECTURE);
        const sup = ws.docs.get('sup.contract')!;
        const links = await ws.services.lsp.DefinitionProvider!.getDefinition(sup, positionParams(sup, offsetOf(sup, 'MSC:1 =*', 4))) as LocationLink[];
        // MSC has data out :1 (command) and event out :1 (failing): a subscription names the event port
        expect(describeLocations(ws, links.map((l) => ({ uri: l.targetUri, range: l.targetSelectionRange })))).toEqual(['msc.contract:6:failing']);
    });

    it('jumps from a parameter setting `(consigne :0)` to parameter port 0', async () => {
        const ws = await build(ARCHITECTURE);
        const schema = ws.docs.get('schema.contract')!;
        const links = await ws.services.lsp.DefinitionProvider!.getDefinition(schema, positionParams(schema, offsetOf(schema, 'consigne :0', 10))) as LocationLink[];
        expect(describeLocations(ws, links.map((l) => ({ uri: l.targetUri, range: l.targetSelectionRange })))).toEqual(['msc.contract:3:consigne']);
    });

    it('opens the imported file from an import path', async () => {
        const ws = await build(ARCHITECTURE);
        const schema = ws.docs.get('schema.contract')!;
        const links = await ws.services.lsp.DefinitionProvider!.getDefinition(schema, positionParams(schema, offsetOf(schema, 'msa.contract', 2))) as LocationLink[];
        expect(links.map((l) => l.targetUri)).toEqual([uriOf('msa.contract').toString()]);
    });
});

describe('find references', () => {
    it('finds a module in every file that names it', async () => {
        const ws = await build(ARCHITECTURE);
        const msc = ws.docs.get('msc.contract')!;
        const refs = await ws.services.lsp.ReferencesProvider!.findReferences(msc, { ...positionParams(msc, offsetOf(msc, 'MSC', 1)), context: { includeDeclaration: true } });
        expect(describeLocations(ws, refs)).toEqual([
            'msc.contract:2:MSC', 'schema.contract:7:MSC', 'schema.contract:8:MSC', 'schema.contract:9:MSC', 'schema.contract:9:MSC',
            'sup.contract:9:MSC', 'sup.contract:9:MSC'
        ]);
    });

    it('finds a port both by index (MSC:1) and by its variable name', async () => {
        const ws = await build(ARCHITECTURE);
        const sup = ws.docs.get('sup.contract')!;
        const refs = await ws.services.lsp.ReferencesProvider!.findReferences(sup, { ...positionParams(sup, offsetOf(sup, 'failure;', 1)), context: { includeDeclaration: false } });
        // `:3` in the subscription (index) and `failure` in the extraction (name)
        expect(describeLocations(ws, refs)).toEqual(['sup.contract:9:3', 'sup.contract:9:failure']);
        const msc = ws.docs.get('msc.contract')!;
        const portRefs = await ws.services.lsp.ReferencesProvider!.findReferences(msc, { ...positionParams(msc, offsetOf(msc, 'failing', 1)), context: { includeDeclaration: false } });
        expect(describeLocations(ws, portRefs)).toEqual(['sup.contract:9:1', 'sup.contract:9:1']);
    });
});

describe('rename', () => {
    it('renames a module in its file and every file referring to it', async () => {
        const ws = await build(ARCHITECTURE);
        const msc = ws.docs.get('msc.contract')!;
        const edit = await ws.services.lsp.RenameProvider!.rename(msc, { ...positionParams(msc, offsetOf(msc, 'MSC', 1)), newName: 'MSK' });
        const texts = applyEdit(ws, edit!);
        expect(texts['msc.contract']).toContain('synchronous module MSK {');
        expect(texts['schema.contract']).toContain('modules { MSA(); MSK(consigne :0); MSD(); }');
        expect(texts['schema.contract']).toContain('MSA:0 -> MSK:0 * 1; MSK:1 -> MSD:2 * 2;');
        expect(texts['sup.contract']).toContain('subscribe MSK:1 =* :3;');
        expect(texts['sup.contract']).toContain('[MSK:1(failure_data = failure)]');
        expect(Object.values(texts).join('\n')).not.toMatch(/\bMSC\b/);
    });

    it('renames a port variable without touching the references that use its index', async () => {
        const ws = await build(ARCHITECTURE);
        const sup = ws.docs.get('sup.contract')!;
        const edit = await ws.services.lsp.RenameProvider!.rename(sup, { ...positionParams(sup, offsetOf(sup, 'failure)]', 1)), newName: 'fault' });
        const texts = applyEdit(ws, edit!);
        expect(texts['sup.contract']).toContain('in :3 TypeD fault;');
        expect(texts['sup.contract']).toContain('subscribe MSC:1 =* :3;');
        expect(texts['sup.contract']).toContain('(failure_data = fault)');
    });

    it('renames a datatype field through its path uses and a rule label through started/endof', async () => {
        const ws = await build(ARCHITECTURE);
        const types = ws.docs.get('types.contract')!;
        const edit = await ws.services.lsp.RenameProvider!.rename(types, { ...positionParams(types, offsetOf(types, 'float k', 6)), newName: 'z' });
        const texts = applyEdit(ws, edit!);
        expect(texts['types.contract']).toContain('float z=0.0');
        expect(texts['sup.contract']).toContain('compute doit("x", target.z)');

        const sup = ws.docs.get('sup.contract')!;
        const edit2 = await ws.services.lsp.RenameProvider!.rename(sup, { ...positionParams(sup, offsetOf(sup, 'FIRST:', 1)), newName: 'START' });
        expect(applyEdit(ws, edit2!)['sup.contract']).toContain('[endof(START)]');
    });

    it('refuses names that break the naming rules, with a message', async () => {
        const ws = await build(ARCHITECTURE);
        const msc = ws.docs.get('msc.contract')!;
        const at = positionParams(msc, offsetOf(msc, 'MSC', 1));
        const rename = ws.services.lsp.RenameProvider!;
        await expect(async () => rename.rename(msc, { ...at, newName: 'Msk' })).rejects.toThrow(/exactly three upper-case letters/);
        await expect(async () => rename.rename(msc, { ...at, newName: 'ORD' })).rejects.toThrow(/scheduler/);
        await expect(async () => rename.rename(msc, { ...at, newName: 'MSA' })).rejects.toThrow(/already names a module or supervisor/);
        const types = ws.docs.get('types.contract')!;
        const typeAt = positionParams(types, offsetOf(types, 'TypeA', 1));
        await expect(async () => rename.rename(types, { ...typeAt, newName: 'double' })).rejects.toThrow(/C keyword/);
        await expect(async () => rename.rename(types, { ...typeAt, newName: '2x' })).rejects.toThrow(/not a valid name/);
        await expect(async () => rename.rename(types, { ...typeAt, newName: 'TypeB' })).rejects.toThrow(/already names a datatype/);
        const fieldAt = positionParams(types, offsetOf(types, 'float j', 6));
        await expect(async () => rename.rename(types, { ...fieldAt, newName: 'i' })).rejects.toThrow(/already used/);
    });
});

describe('rename: keywords', () => {
    it('accepts a word that is a keyword elsewhere where the grammar allows it as a name, refuses it elsewhere', async () => {
        const ws = await build(ARCHITECTURE);
        const rename = ws.services.lsp.RenameProvider!;
        const types = ws.docs.get('types.contract')!;
        // fields are `Name`s: `data` is allowed there
        const edit = await rename.rename(types, { ...positionParams(types, offsetOf(types, 'float j', 6)), newName: 'data' });
        expect(applyEdit(ws, edit!)['types.contract']).toContain('float data =0.0');
        // a datatype name is an ID: `module` is not
        await expect(async () => rename.rename(types, { ...positionParams(types, offsetOf(types, 'TypeA', 1)), newName: 'module' })).rejects.toThrow(/Cactal keyword/);
    });
});

describe('prepare rename', () => {
    it('offers the name on a declaration, the port name as placeholder on an index reference, nothing on ORD', async () => {
        const ws = await build({ ...ARCHITECTURE, 'o.contract': 'supervisor SUO { go() { rules { R: [ORD:0] [elapsed=1ms] } } }' });
        const rename = ws.services.lsp.RenameProvider!;
        const msc = ws.docs.get('msc.contract')!;
        const onName = await rename.prepareRename(msc, positionParams(msc, offsetOf(msc, 'MSC', 1)));
        expect(onName && msc.textDocument.getText(onName)).toBe('MSC');
        const sup = ws.docs.get('sup.contract')!;
        const onIndex = await rename.prepareRename(sup, positionParams(sup, offsetOf(sup, 'MSC:1 =*', 4))) as unknown as { range: Location['range']; placeholder: string };
        expect(onIndex.placeholder).toBe('failing');
        expect(sup.textDocument.getText(onIndex.range)).toBe('1');
        const ord = ws.docs.get('o.contract')!;
        expect(await rename.prepareRename(ord, positionParams(ord, offsetOf(ord, 'ORD', 1)))).toBeUndefined();
    });
});
