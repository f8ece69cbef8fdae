/**
 * Numbers reach the generated C as written, or not at all: an int is a C long written exactly (its
 * text, not the double it was read as), a float a finite C double; a value with no such C literal
 * (an infinite float, an int beyond a long, a real for an int) is refused with an error naming it,
 * never written as another value. Before, `1e400` (infinite) was written `0.0`, and
 * `99999999999999999999` and `9223372036854775807` were written as the double they were read as.
 */
import { existsSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { EmptyFileSystem } from 'langium';
import { createCactalServices } from '@contract-studio/language';
import { describe, expect, it } from 'vitest';
import type { Architecture, Value } from './model/architecture.js';
import { generateFromArchitecture } from './generate-architecture.js';
import { generateFiles } from './generators/generate-files.js';
import { cDouble, cLong } from './generators/c/c-syntax.js';
import { architectureFromModels } from './model/from-langium.js';
import { loadProject } from './test-support/load-project.js';
import { tempDir } from './test-support/temp-dir.js';
import { STRICT_CFLAGS, run } from './test-support/c-toolchain.js';

/** An architecture whose datatype T has an int field `i` and a float field `f` with the given defaults. */
function withDefaults(i: Value, f: Value): Architecture {
    return {
        datatypes: [{ name: 'T', fields: [
            { name: 'i', type: { primitive: 'int' }, default: i },
            { name: 'f', type: { primitive: 'float' }, default: f },
        ] }],
        functions: [],
        modules: [{ name: 'MAX', kind: 'asynchronous', parameters: [{ name: 't', index: 0, type: { datatype: 'T' } }], dataIn: [], dataOut: [], eventIn: [], eventOut: [] }],
        schemas: [],
        supervisors: [],
    };
}

describe('numbers in the generated C', () => {
    it('an infinite or NaN float is refused, naming it, not written 0.0', () => {
        expect(() => cDouble(Infinity)).toThrow(/the float Infinity is not a finite C double/);
        expect(() => cDouble(-Infinity)).toThrow(/the float -Infinity/);
        expect(() => cDouble(Number.NaN)).toThrow(/the float NaN/);
        expect(cDouble(-Number.MAX_VALUE)).toBe('-1.7976931348623157e+308');
        expect(cDouble(5e-324)).toBe('5e-324');
    });

    it('an int is written exactly from its text; beyond a long or not an integer, refused', () => {
        expect(cLong(9223372036854775807, '9223372036854775807')).toBe('9223372036854775807');
        expect(cLong(9007199254740992, '9007199254740993')).toBe('9007199254740993');
        expect(cLong(-(2 ** 63), '-9223372036854775808')).toBe('-9223372036854775807L - 1');
        expect(cLong(-(2 ** 63))).toBe('-9223372036854775807L - 1');
        expect(cLong(2 ** 62)).toBe('4611686018427387904');
        expect(() => cLong(1e20, '99999999999999999999')).toThrow(/the int 99999999999999999999 does not fit a C long/);
        expect(() => cLong(2 ** 63)).toThrow(/the int 9223372036854775808 does not fit a C long/);
        expect(() => cLong(Infinity)).toThrow(/the int Infinity is not an integer/);
        expect(() => cLong(1.5)).toThrow(/the int 1.5 is not an integer/);
    });

    it('generating a model with an infinite default reports it and writes nothing', () => {
        const { dir, cleanup } = tempDir('codegen-numbers-');
        try {
            expect(() => generateFiles(withDefaults({ kind: 'int', value: 1 }, { kind: 'real', value: Infinity }))).toThrow(/the float Infinity/);
            const report = generateFromArchitecture(withDefaults({ kind: 'int', value: 1 }, { kind: 'real', value: Infinity }), dir);
            expect(report.errors).toEqual([{ file: '(model)', message: expect.stringMatching(/^cannot generate: the float Infinity is not a finite C double/) }]);
            expect(existsSync(join(dir, 'generated'))).toBe(false);
            const tooLarge = generateFromArchitecture(withDefaults({ kind: 'int', value: 1e20, text: '99999999999999999999' }, { kind: 'real', value: 1 }), dir);
            expect(tooLarge.errors.map((e) => e.message)).toEqual([expect.stringMatching(/^cannot generate: the int 99999999999999999999 does not fit a C long/)]);
        } finally {
            cleanup();
        }
    });

    it('the bounds written in Cactal reach the C as written, and gcc takes them without a warning', async () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        const { models, errors } = await loadProject(services, {
            'types.contract': `datatype T {int max = 9223372036854775807, int min = -9223372036854775808, int odd = 9007199254740993, float big = -1.7976931348623157e308, float tiny = 5e-324};
const int BIG = 9223372036854775807;
const int SMALL = -9223372036854775808;`,
            'max.contract': 'import "types.contract";\nasynchronous module MAX { parameters { T t :0; int n = 9223372036854775807 :1; int k = BIG :2; } }',
        });
        expect(errors).toEqual([]);
        const files = new Map(generateFiles(architectureFromModels(models)).map((f) => [f.path, f.content]));
        const module = files.get('generated/architecture/modules/MAX_mod/module.c')!;
        expect(module).toContain('long n = 9223372036854775807;');
        expect(module).toContain('long k = 9223372036854775807;');
        const header = files.get('generated/architecture/common/constants.h')!;
        expect(header).toContain('#define BIG (9223372036854775807)');
        expect(header).toContain('#define SMALL (-9223372036854775807L - 1)');
        const initializer = /T t = (\{[^;]*\});/.exec(module)?.[1];
        expect(initializer).toBe('{ 9223372036854775807, -9223372036854775807L - 1, 9007199254740993, -1.7976931348623157e+308, 5e-324 }');
        const { dir, cleanup } = tempDir('codegen-numbers-');
        try {
            const c = join(dir, 'n.c');
            writeFileSync(c, `long a = 9223372036854775807;\nlong b = -9223372036854775807L - 1;\nstruct S { long i, j, k; double f, g; } s = ${initializer};\n`);
            expect(run('gcc', [...STRICT_CFLAGS, '-c', c, '-o', join(dir, 'n.o')])).not.toMatch(/warning/);
        } finally {
            cleanup();
        }
    });
});
