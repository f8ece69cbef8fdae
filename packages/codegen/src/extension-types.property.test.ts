/**
 * Property (issue 17 acceptance): random type declarations with arrays, enumerations, bools and named
 * constants, and random values of them written in Cactal (`const D0 V0 = {...};`), agree between the
 * language's value model and the generated C: for every datatype, the C program (built with -Werror
 * and ASan/UBSan) parses the language's textual form of the datatype's default and of the value
 * with the generated get_, finds them eq_ to the generated static initialisers, round-trips the value
 * through serialize_/deserialize_ (eq_ again) and prints it exactly as the language model predicts;
 * the constant's macro of common/constants.h (a compound literal) is eq_ to the value too.
 */
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import fc from 'fast-check';
import { EmptyFileSystem } from 'langium';
import {
    constantValue, createCactalServices, defaultValue, formatConstant, isConstant, isDataType, typeOf,
    type CactalServices, type ConstantValue
} from '@contract-studio/language';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { cInitializer, cString } from './generators/c/c-syntax.js';
import { generateFiles } from './generators/generate-files.js';
import { architectureFromModels } from './model/from-langium.js';
import { ArchitectureIndex } from './model/lookup.js';
import { writeTree } from './writer/write-tree.js';
import { loadProject } from './test-support/load-project.js';
import { tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, STRICT_CFLAGS, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';

type Base = 'int' | 'float' | 'bool' | 'string' | { enum: number } | { datatype: number };
interface FieldSpec { base: Base; dims: Array<number | 'N'>; withDefault: boolean }
interface Spec { n: number; enums: string[][]; datatypes: FieldSpec[][] }

const MEMBER_POOL = ['IDLE', 'RUN', 'STOP', 'AUTO', 'FAULT'];

const baseArb = (enums: number, before: number): fc.Arbitrary<Base> => fc.oneof(
    fc.constantFrom<Base>('int', 'float', 'bool', 'string'),
    ...(enums > 0 ? [fc.integer({ min: 0, max: enums - 1 }).map((i): Base => ({ enum: i }))] : []),
    ...(before > 0 ? [fc.integer({ min: 0, max: before - 1 }).map((i): Base => ({ datatype: i }))] : []),
);

const specArb: fc.Arbitrary<Spec> = fc.record({
    n: fc.integer({ min: 1, max: 3 }),
    enums: fc.array(fc.shuffledSubarray(MEMBER_POOL, { minLength: 1, maxLength: 4 }), { minLength: 1, maxLength: 2 }),
    count: fc.integer({ min: 1, max: 3 }),
}).chain(({ n, enums, count }) => {
    const datatype = (before: number) => fc.array(fc.record({
        base: baseArb(enums.length, before),
        dims: fc.array(fc.oneof(fc.integer({ min: 1, max: 3 }), fc.constant<'N'>('N')), { maxLength: 2 }),
        withDefault: fc.boolean(),
    }), { minLength: 1, maxLength: 4 });
    return fc.tuple(...Array.from({ length: count }, (_, i) => datatype(i))).map((datatypes) => ({ n, enums, datatypes }));
});

/** A random Cactal value text of a field type (constants N and K used now and then). */
function valueArb(spec: Spec, base: Base, dims: Array<number | 'N'>): fc.Arbitrary<string> {
    if (dims.length > 0) {
        const size = dims[0] === 'N' ? spec.n : dims[0]!;
        return fc.array(valueArb(spec, base, dims.slice(1)), { minLength: size, maxLength: size }).map((e) => `{${e.join(', ')}}`);
    }
    if (base === 'int') return fc.oneof(fc.integer({ min: -1000, max: 1000 }).map(String), fc.constant('N'));
    if (base === 'float') return fc.oneof(fc.integer({ min: -40, max: 40 }).map((k) => (k / 4).toFixed(2)), fc.constant('K'));
    if (base === 'bool') return fc.constantFrom('true', 'false');
    if (base === 'string') return fc.stringMatching(/^[a-z0-9 ]{0,6}$/).map((s) => `"${s}"`);
    if ('enum' in base) return fc.constantFrom(...spec.enums[base.enum]!.map((m) => `E${base.enum}.${m}`));
    const fields = spec.datatypes[base.datatype]!;
    return fc.tuple(...fields.map((f) => valueArb(spec, f.base, f.dims))).map((e) => `{${e.join(', ')}}`);
}

const baseText = (b: Base) => typeof b === 'string' ? b : 'enum' in b ? `E${b.enum}` : `D${b.datatype}`;
const typeText = (f: FieldSpec) => baseText(f.base) + f.dims.map((d) => `[${d}]`).join('');

/** The project text: enumerations, constants, datatypes with random defaults, and one random value constant per datatype. */
const projectArb: fc.Arbitrary<{ spec: Spec; text: string }> = specArb.chain((spec) => {
    const defaults = spec.datatypes.map((fields) => fc.tuple(...fields.map((f) => valueArb(spec, f.base, f.dims))));
    const values = spec.datatypes.map((_, i) => valueArb(spec, { datatype: i }, []));
    return fc.tuple(fc.tuple(...defaults), fc.tuple(...values), fc.integer({ min: -40, max: 40 })).map(([defs, vals, k]) => {
        const lines = [
            `const int N = ${spec.n};`,
            `const float K = ${(k / 4).toFixed(2)};`,
            ...spec.enums.map((members, i) => `enum E${i} { ${members.join(', ')} }`),
            ...spec.datatypes.map((fields, i) => `datatype D${i} {${fields.map((f, j) => `${typeText(f)} f${j}${f.withDefault ? ` = ${defs[i]![j]}` : ''}`).join(', ')}};`),
            ...vals.map((v, i) => `const D${i} V${i} = ${v};`),
        ];
        return { spec, text: lines.join('\n') + '\n' };
    });
});

/** What the generated print_ writes for a value, from the language's value model. */
function expectedPrint(v: ConstantValue, inArray = false): string {
    switch (v.kind) {
        case 'int': return String(v.value);
        case 'float': return v.value.toFixed(6);
        case 'bool': return v.value ? 'true' : 'false';
        case 'string': return inArray ? `"${v.value}"` : v.value;
        case 'enum': return v.member;
        case 'array': return `[${v.elements.map((e) => expectedPrint(e, true)).join(',')}]`;
        case 'struct': return `(object type ${v.datatype.name} : ${v.fields.map((f) => `${f.name} : ${expectedPrint(f.value)} ; `).join('')})`;
    }
}

describe('extension types: language value model and generated C agree (property)', () => {
    let services: CactalServices;
    let lib: string;
    beforeAll(() => {
        services = createCactalServices(EmptyFileSystem).Cactal;
        lib = ensureRuntimeLibrary();
    }, 120_000);
    const dirs: Array<() => void> = [];
    afterAll(() => dirs.forEach((cleanup) => cleanup()));

    it('get_/eq_/serialize_/deserialize_/print_ of random datatypes match the value model', async () => {
        await fc.assert(fc.asyncProperty(projectArb, async ({ text }) => {
            const { models, errors } = await loadProject(services, { 'types.contract': text });
            expect(errors, text).toEqual([]);
            const elements = models[0]!.elements;
            const arch = architectureFromModels(models);
            const index = new ArchitectureIndex(arch);
            const blocks: string[] = [];
            const expected: string[] = [];
            for (const dt of elements.filter(isDataType)) {
                const D = dt.name;
                const valueDecl = elements.filter(isConstant).find((c) => c.name === `V${D.slice(1)}`)!;
                const dv = defaultValue({ kind: 'struct', datatype: dt });
                const cv = constantValue(valueDecl.value, typeOf(valueDecl.type));
                expect(dv, `default of ${D}`).toBeDefined();
                expect(cv, `value of ${D}`).toBeDefined();
                const folded = arch.constants?.find((c) => c.name === valueDecl.name)?.value;
                blocks.push(`    {
        static ${D} init = ${cInitializer(index, { datatype: D })};
        static ${D} value = ${cInitializer(index, { datatype: D }, folded)};
        static ${D} parsed, back;
        static unsigned char buffer[1 << 16];
        CHECK(get_${D}(&parsed, ${cString(formatConstant(dv!))}) > 0);
        CHECK(eq_${D}(&parsed, &init) == 1 && diff_${D}(&parsed, &init) == 0);
        CHECK(get_${D}(&parsed, ${cString(formatConstant(cv!))}) > 0);
        CHECK(eq_${D}(&parsed, &value) == 1);
        ${D} named = ${valueDecl.name};
        CHECK(eq_${D}(&named, &value) == 1);
        unsigned int n = serialize_${D}(&parsed, buffer);
        CHECK(n <= sizeof buffer && deserialize_${D}(&back, buffer) == n);
        CHECK(eq_${D}(&back, &value) == 1 && infeq_${D}(&back, &value) == 1 && supeq_${D}(&back, &value) == 1);
        print_${D}(&back); printf("\\n");
    }`);
                expected.push(expectedPrint(cv!));
            }
            const { dir, cleanup } = tempDir('codegen-extprop-');
            dirs.push(cleanup);
            writeTree(dir, generateFiles(arch));
            const common = join(dir, 'generated/architecture/common');
            const program = [
                '#include <stdio.h>',
                ...arch.datatypes.map((d) => `#include "Shared${d.name}.h"`),
                '#include "constants.h"',
                `#if N != ${/const int N = (\d+);/.exec(text)![1]}`,
                '#error N is not the constant of the .contract',
                '#endif',
                '#define CHECK(c) do { if (!(c)) { printf("FAILED line %d: %s\\n", __LINE__, #c); return 1; } } while (0)',
                'int main(void) {',
                ...blocks,
                '    printf("ALL OK\\n");',
                '    return 0;',
                '}',
            ].join('\n');
            const src = join(dir, 'ext_test.c');
            writeFileSync(src, program);
            const exe = join(dir, 'ext_test');
            run('gcc', [...STRICT_CFLAGS, '-fsanitize=address,undefined', '-fno-sanitize-recover=undefined', `-I${RUNTIME_DIR}/include`, `-I${common}`, src, lib, '-o', exe]);
            const out = run(exe, []);
            expect(out, `${text}\n${out}`).toBe([...expected, 'ALL OK', ''].join('\n'));
        }), { numRuns: 12, seed: 17, endOnFailure: true });
    }, 600_000);
});
