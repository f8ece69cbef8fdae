import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import type { Architecture, Module, PortDecl, TypeRef } from '../model/architecture.js';
import { parseRegions } from '../regions/parse-regions.js';
import { toByteString } from '../writer/byte-string.js';
import { writeTree } from '../writer/write-tree.js';
import { readTree, tempDir } from '../test-support/temp-dir.js';
import { tutorialModel } from '../test-support/tutorial-model.js';
import { generateFiles } from './generate-files.js';

const types: TypeRef[] = [{ primitive: 'int' }, { primitive: 'float' }, { primitive: 'string' }, { datatype: 'TypeA' }, { datatype: 'TypeF' }];
const moduleNames = ['MAA', 'MAB', 'MSA', 'MSC', 'MXA', 'MXB', 'MXC'];
const portLists = ['parameters', 'eventIn', 'eventOut', 'dataIn', 'dataOut'] as const;

type Edit =
    | { op: 'addModule'; name: string; async: boolean }
    | { op: 'removeModule'; module: number }
    | { op: 'renameModule'; module: number; to: string }
    | { op: 'addPort'; module: number; list: (typeof portLists)[number]; type: number; name: string }
    | { op: 'removePort'; module: number; list: (typeof portLists)[number]; port: number }
    | { op: 'renamePort'; module: number; list: (typeof portLists)[number]; port: number; to: string }
    | { op: 'addField'; name: string; type: number }
    | { op: 'removeField'; field: number }
    | { op: 'renameField'; field: number; to: string }
    | { op: 'toggleDatatype'; name: string }
    | { op: 'toggleFunction'; name: string };

const ident = fc.constantFrom('alpha', 'beta', 'gamma', 'delta', 'speed', 'mode');
const editArb: fc.Arbitrary<Edit> = fc.oneof(
    fc.record({ op: fc.constant('addModule' as const), name: fc.constantFrom(...moduleNames), async: fc.boolean() }),
    fc.record({ op: fc.constant('removeModule' as const), module: fc.nat() }),
    fc.record({ op: fc.constant('renameModule' as const), module: fc.nat(), to: fc.constantFrom(...moduleNames) }),
    fc.record({ op: fc.constant('addPort' as const), module: fc.nat(), list: fc.constantFrom(...portLists), type: fc.nat(types.length - 1), name: ident }),
    fc.record({ op: fc.constant('removePort' as const), module: fc.nat(), list: fc.constantFrom(...portLists), port: fc.nat() }),
    fc.record({ op: fc.constant('renamePort' as const), module: fc.nat(), list: fc.constantFrom(...portLists), port: fc.nat(), to: ident }),
    fc.record({ op: fc.constant('addField' as const), name: ident, type: fc.nat(2) }),
    fc.record({ op: fc.constant('removeField' as const), field: fc.nat() }),
    fc.record({ op: fc.constant('renameField' as const), field: fc.nat(), to: ident }),
    fc.record({ op: fc.constant('toggleDatatype' as const), name: fc.constantFrom('TypeX', 'TypeY') }),
    fc.record({ op: fc.constant('toggleFunction' as const), name: fc.constantFrom('check_a', 'compute_b') }),
);

function unusedName(m: Module, base: string): string {
    const used = new Set(portLists.flatMap((l) => m[l].map((p) => p.name)));
    let name = base;
    for (let n = 2; used.has(name); n++) name = `${base}${n}`;
    return name;
}

/** Applies a model edit the way a user would (only edits that keep the model valid are applied). */
function applyEdit(arch: Architecture, e: Edit): void {
    const pick = (n: number) => arch.modules[n % Math.max(1, arch.modules.length)];
    const typeF = arch.datatypes.find((d) => d.name === 'TypeF')!;
    switch (e.op) {
        case 'addModule':
            if (!arch.modules.some((m) => m.name === e.name) && !arch.supervisors.some((s) => s.name === e.name)) {
                arch.modules.push({ name: e.name, kind: e.async ? 'asynchronous' : 'synchronous', parameters: [], dataIn: [], dataOut: [], eventIn: [], eventOut: [], wcetNs: e.async ? undefined : 1000 } as Module);
            }
            break;
        case 'removeModule': {
            const m = pick(e.module);
            if (m && m.name.startsWith('MX')) arch.modules.splice(arch.modules.indexOf(m), 1);
            break;
        }
        case 'renameModule': {
            const m = pick(e.module);
            if (m && m.name.startsWith('MX') && !arch.modules.some((x) => x.name === e.to) && !arch.supervisors.some((s) => s.name === e.to)) m.name = e.to;
            break;
        }
        case 'addPort': {
            const m = pick(e.module);
            if (!m || (m.kind === 'asynchronous' && e.list.startsWith('data')) || (m.kind === 'synchronous' && e.list === 'eventIn')) break;
            const list: PortDecl[] = m[e.list];
            const index = list.reduce((max, p) => Math.max(max, p.index + 1), 0);
            list.push({ name: unusedName(m, e.name), index, type: types[e.type]! });
            break;
        }
        case 'removePort': {
            const m = pick(e.module);
            if (m && m.name.startsWith('MX') && m[e.list].length) m[e.list].splice(e.port % m[e.list].length, 1);
            break;
        }
        case 'renamePort': {
            const m = pick(e.module);
            if (m && m.name.startsWith('MX') && m[e.list].length) m[e.list][e.port % m[e.list].length]!.name = unusedName(m, e.to);
            break;
        }
        case 'addField':
            if (!typeF.fields.some((f) => f.name === e.name)) typeF.fields.push({ name: e.name, type: types[e.type]! });
            break;
        case 'removeField':
            if (typeF.fields.length > 1) typeF.fields.splice(e.field % typeF.fields.length, 1);
            break;
        case 'renameField': {
            const f = typeF.fields[e.field % typeF.fields.length]!;
            if (!typeF.fields.some((x) => x.name === e.to)) f.name = e.to;
            break;
        }
        case 'toggleDatatype': {
            const i = arch.datatypes.findIndex((d) => d.name === e.name);
            if (i >= 0) arch.datatypes.splice(i, 1);
            else arch.datatypes.push({ name: e.name, fields: [{ name: 'x', type: { primitive: 'float' } }, { name: 'label', type: { primitive: 'string' } }] });
            break;
        }
        case 'toggleFunction': {
            const i = arch.functions.findIndex((f) => f.name === e.name);
            if (i >= 0) arch.functions.splice(i, 1);
            else arch.functions.push({ name: e.name, returns: e.name.startsWith('check') ? 'bool' : 'void', args: [{ name: 'value', type: { datatype: 'TypeF' } }] });
            break;
        }
    }
}

const userText = fc
    .string({ unit: fc.constantFrom('x', 'é', '\n', '\t', ' ', '*', '/', '{', '}', '"', ';', '€', '\r'), maxLength: 24 })
    .filter((s) => !s.includes('PROTECTED'));
const userEdit = fc.record({ file: fc.nat(), region: fc.nat(), text: userText });

describe('regenerating the C tree after random user edits and model edits (property, real generators)', () => {
    it('keeps every byte of user code in place or in orphans/, and a second regeneration writes nothing', () => {
        fc.assert(
            fc.property(fc.array(fc.tuple(fc.array(userEdit, { minLength: 1, maxLength: 5 }), fc.array(editArb, { minLength: 1, maxLength: 4 })), { minLength: 1, maxLength: 3 }), (rounds) => {
                const { dir, cleanup } = tempDir('codegen-regen-');
                try {
                    const arch = tutorialModel();
                    expect(writeTree(dir, generateFiles(arch)).errors).toEqual([]);
                    const live = new Map<string, string>();
                    let tag = 0;
                    for (const [userEdits, modelEdits] of rounds) {
                        for (const ue of userEdits) {
                            const files = [...readTree(dir, 'generated').entries()].filter(([, t]) => t.includes('PROTECTED REGION'));
                            const [path, text] = files[ue.file % files.length]!;
                            const regions = parseRegions(text, path).regions;
                            const r = regions[ue.region % regions.length]!;
                            const content = toByteString(`/*user${tag++}*/${ue.text}`);
                            writeFileSync(join(dir, path), text.slice(0, r.contentStart) + content + text.slice(r.contentEnd), 'latin1');
                            live.set(`${path}#${r.id}`, content);
                        }
                        for (const e of modelEdits) applyEdit(arch, e);
                        const report = writeTree(dir, generateFiles(arch));
                        expect(report.errors).toEqual([]);
                        const tree = readTree(dir);
                        const orphans = [...tree.entries()].filter(([p]) => p.startsWith('orphans/')).map(([, t]) => t);
                        for (const [key, content] of live) {
                            const [path, id] = key.split('#') as [string, string];
                            const current = tree.get(path);
                            const inPlace = current !== undefined && parseRegions(current, path).regions.some((r) => r.id === id && r.content === content);
                            expect(inPlace || orphans.some((o) => o.includes(content)), `user code of ${key} lost`).toBe(true);
                            if (!inPlace) live.delete(key);
                        }
                        const again = writeTree(dir, generateFiles(arch));
                        expect(again.filesWritten).toBe(0);
                        expect(readFileSync(join(dir, '.contract-manifest.json'), 'utf8')).toBe(tree.get('.contract-manifest.json'));
                    }
                } finally {
                    cleanup();
                }
            }),
            { numRuns: 15 },
        );
    }, 120_000);
});
