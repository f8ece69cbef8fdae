import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { parseRegions } from '../regions/parse-regions.js';
import { toByteString } from './byte-string.js';
import { readTree, tempDir } from '../test-support/temp-dir.js';
import { writeTree, type GeneratedFile } from './write-tree.js';

/** An abstract model: file name -> ordered region IDs. */
type Model = Map<string, string[]>;

const ids = ['init', 'exit', 'exec', 'event', 'param', 'eq', 'diff', 'additionnal_import', 'vars'];
const names = ['A', 'B', 'C', 'D', 'E'];

/** Generates files from a model; some regions have a non-TODO default, like the comparison functions. */
function generate(model: Model): GeneratedFile[] {
    return [...model.entries()].map(([name, regionIds]) => ({
        path: `generated/${name}_mod/module.c`,
        content: `// module ${name}\n` + regionIds.map((id) =>
            `void f_${id}(void) {\n${region(`protect_${id.replace('additionnal', 'additional')}_${name}`, id.startsWith('e') ? `\n    return_${id}();\n` : '\n//TODO\n')}\n}\n`).join(''),
    }));
}

const modelArb: fc.Arbitrary<Model> = fc
    .uniqueArray(fc.constantFrom(...names), { minLength: 1, maxLength: 4 })
    .chain((files) => fc.tuple(...files.map((f) => fc.subarray(ids, { minLength: 1 }).map((r) => [f, r] as const))))
    .map((entries) => new Map(entries));

type ModelEdit =
    | { op: 'removeRegion'; file: number; region: number }
    | { op: 'addRegion'; file: number; id: string }
    | { op: 'renameFile'; file: number; to: string }
    | { op: 'removeFile'; file: number }
    | { op: 'addFile'; name: string; regions: string[] };

const editArb: fc.Arbitrary<ModelEdit> = fc.oneof(
    fc.record({ op: fc.constant('removeRegion' as const), file: fc.nat(), region: fc.nat() }),
    fc.record({ op: fc.constant('addRegion' as const), file: fc.nat(), id: fc.constantFrom(...ids) }),
    fc.record({ op: fc.constant('renameFile' as const), file: fc.nat(), to: fc.constantFrom(...names, 'F', 'G') }),
    fc.record({ op: fc.constant('removeFile' as const), file: fc.nat() }),
    fc.record({ op: fc.constant('addFile' as const), name: fc.constantFrom(...names, 'H'), regions: fc.subarray(ids, { minLength: 1 }) }),
);

function applyEdit(model: Model, e: ModelEdit): Model {
    const next = new Map([...model.entries()].map(([k, v]) => [k, [...v]]));
    const keys = [...next.keys()];
    if (e.op === 'addFile') {
        if (!next.has(e.name)) next.set(e.name, e.regions);
        return next;
    }
    if (keys.length === 0) return next;
    const key = keys[e.file % keys.length]!;
    const regions = next.get(key)!;
    switch (e.op) {
        case 'removeRegion':
            if (regions.length > 0) regions.splice(e.region % regions.length, 1);
            break;
        case 'addRegion':
            if (!regions.includes(e.id)) regions.splice(regions.length ? e.id.length % regions.length : 0, 0, e.id);
            break;
        case 'renameFile':
            if (!next.has(e.to)) {
                next.delete(key);
                next.set(e.to, regions);
            }
            break;
        case 'removeFile':
            next.delete(key);
            break;
    }
    return next;
}

/** User text: a unique tag plus arbitrary text (any Unicode, newlines, C comment bits), never a marker. */
const userTextArb = fc
    .string({ unit: fc.constantFrom('a', 'é', '\n', '\t', ' ', '*', '/', '{', '}', '"', '\\', '€', '\r', 'Z'), maxLength: 30 })
    .filter((s) => !s.includes('PROTECTED'));

interface UserEdit { file: number; region: number; text: string }
const userEditArb: fc.Arbitrary<UserEdit> = fc.record({ file: fc.nat(), region: fc.nat(), text: userTextArb });

describe('protected regions under random user edits and model edits (property)', () => {
    it('never loses a byte of user text and rewrites nothing when the model does not change', () => {
        fc.assert(
            fc.property(modelArb, fc.array(fc.tuple(fc.array(userEditArb, { maxLength: 4 }), fc.array(editArb, { maxLength: 3 })), { minLength: 1, maxLength: 4 }), (model0, rounds) => {
                const { dir, cleanup } = tempDir('codegen-prop-');
                try {
                    let model = model0;
                    let tag = 0;
                    /** Every user text still expected somewhere: key file#id -> byte-string text. */
                    const live = new Map<string, string>();
                    const first = writeTree(dir, generate(model));
                    expect(first.errors).toEqual([]);
                    for (const [userEdits, modelEdits] of rounds) {
                        for (const ue of userEdits) {
                            const tree = [...readTree(dir, 'generated').keys()];
                            if (tree.length === 0) break;
                            const path = tree[ue.file % tree.length]!;
                            const abs = join(dir, path);
                            const text = readFileSync(abs, 'latin1');
                            const regions = parseRegions(text, path).regions;
                            if (regions.length === 0) continue;
                            const r = regions[ue.region % regions.length]!;
                            const userText = toByteString(`/*u${tag++}*/${ue.text}`);
                            writeFileSync(abs, text.slice(0, r.contentStart) + userText + text.slice(r.contentEnd), 'latin1');
                            live.set(`${path}#${r.id}`, userText);
                        }
                        for (const me of modelEdits) model = applyEdit(model, me);
                        const report = writeTree(dir, generate(model));
                        expect(report.errors).toEqual([]);
                        const tree = readTree(dir);
                        const orphans = [...tree.entries()].filter(([p]) => p.startsWith('orphans/')).map(([, c]) => c);
                        for (const [key, userText] of live) {
                            const [path, id] = key.split('#') as [string, string];
                            const current = tree.get(path);
                            const inPlace = current !== undefined && parseRegions(current, path).regions.some((r) => r.id === id && r.content === userText);
                            const orphaned = orphans.some((o) => o.includes(userText));
                            expect(inPlace || orphaned, `user text of ${key} lost`).toBe(true);
                            if (!inPlace) live.delete(key); // once orphaned, it stays in orphans/ (never overwritten)
                        }
                        const again = writeTree(dir, generate(model));
                        expect(again.filesWritten).toBe(0);
                        expect(again.created.length + again.updated.length + again.orphaned.length + again.removed.length).toBe(0);
                        expect(readTree(dir)).toEqual(tree);
                    }
                } finally {
                    cleanup();
                }
            }),
            { numRuns: 50 },
        );
    }, 120_000);
});
