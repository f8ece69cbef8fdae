/**
 * Numbers that do not fit where the generated C holds them are errors (number-out-of-range), wherever
 * they are written: an int value is a C long, a float value a finite C double (docs/language-reference.md
 * §2); port indexes, periodicities and array sizes are C ints; durations are at most 2^53 - 1 ns.
 * Before, `float level = 1e400` and `int periodMs = 99999999999999999999` passed `contract check` and
 * reached the C changed (`0.0`, and a constant gcc truncates).
 */
import { describe, expect, it } from 'vitest';
import { EmptyFileSystem } from 'langium';
import { createCactalServices } from '../src/cactal-module.js';
import type { Model } from '../src/generated/ast.js';
import { checkScenario, indexModels, parseScenario } from '../src/scenario/index.js';
import { build, type Built } from './helpers.js';

const services = createCactalServices(EmptyFileSystem).Cactal;
const CODE = 'number-out-of-range';

const INT_MAX = '9223372036854775807';
const INT_MIN = '-9223372036854775808';
const FLOAT_MAX = '1.7976931348623157e308';

const errors = (built: Built) => built.diagnostics.filter((d) => d.severity === 'error');
const outOfRange = (built: Built) => built.diagnostics.filter((d) => d.code === CODE);

/** One datatype field of `type` with default `literal`: the number-out-of-range messages. */
async function fieldDefault(type: string, literal: string): Promise<string[]> {
    const built = await build({ 'a.contract': `datatype T {${type} a = ${literal}};` }, services);
    expect(errors(built).filter((d) => d.code !== CODE), built.lines.join('\n')).toEqual([]);
    return outOfRange(built).map((d) => d.message);
}

describe('number-out-of-range: the bounds of int (C long) and float (C double)', () => {
    // each case: a number at the bound that fits, and the one past it that does not
    it.each([
        ['int', INT_MAX, '9223372036854775808', "The integer 9223372036854775808 for 'a' is too large for an int (an int is a C long, from -9223372036854775808 to 9223372036854775807)."],
        ['int', INT_MIN, '-9223372036854775809', "The integer -9223372036854775809 for 'a' is too small for an int (an int is a C long, from -9223372036854775808 to 9223372036854775807)."],
        // read exactly (beyond 2^53, where a double is no longer exact)
        ['int', '9007199254740993', '99999999999999999999', "The integer 99999999999999999999 for 'a' is too large for an int"],
        ['float', FLOAT_MAX, '1.8e308', "The real 1.8e308 for 'a' is too large for a float"],
        ['float', '1e308', '1e400', "The real 1e400 for 'a' is too large for a float (a float is a C double, from -1.7976931348623157e+308 to 1.7976931348623157e+308): it would be infinite."],
        // a Cactal float is a C double, not a C float: 1e38 and 1e39 fit, 1e309 does not
        ['float', '1e39', '1e309', "The real 1e309 for 'a' is too large for a float"],
        ['float', '1e38', '-1e309', "The real -1e309 for 'a' is too small for a float"],
        ['float', `-${FLOAT_MAX}`, '-1e400', "The real -1e400 for 'a' is too small for a float"],
        ['float', '5e-324', '1e-400', "The real 1e-400 for 'a' is too close to 0 for a float (a float is a C double; its smallest value but 0 is 5e-324): it would be 0."],
        ['float', '0e-400', '-2.5e-400', "The real -2.5e-400 for 'a' is too close to 0 for a float"],
        // an integer for a float is a double: beyond a long is fine, beyond a double is not
        ['float', '-9223372036854775809', '1' + '0'.repeat(309), `The integer 1${'0'.repeat(309)} for 'a' is too large for a float`],
    ])('%s: %s fits, %s does not', async (type, good, bad, message) => {
        expect(await fieldDefault(type, good)).toEqual([]);
        const found = await fieldDefault(type, bad);
        expect(found).toHaveLength(1);
        expect(found[0]).toContain(message);
    });
});

/**
 * A project with a number at every place a value is written: `@I<n>@` an int, `@F<n>@` a float,
 * `@N<n>@` an integer for a float (compared with a float).
 */
const PROJECT: Record<string, string> = {
    'types.contract': `
datatype P {float x = @F1@, int n = @I1@};
function bool near(float a, int b);
function void note(float a, int b);
const int CI = @I2@;
const float CF = @F2@;
const P CP = {@F3@, @I3@};
const float[2] CA = {@F4@, @N1@};
`,
    'msa.contract': `import "types.contract";
synchronous module MSA {
    parameters { int gain = @I4@ :0; float scale = @F5@ :1; P p = {@F6@, @I5@} :2; }
    scheduling { C=1ms; }
    data flows { out :0 int count = @I6@; out :1 float level = @F7@; }
    event flows { out :2 float ev = @F8@; out :3 int iv; }
}
`,
    's.contract': `import "msa.contract";
periodic schema s(int k = @I7@, float f = @F9@) {
    realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; }
    modules { MSA (@I8@ :0, @F10@ :1, {@F11@, @I9@} :2); }
}
`,
    'sched.contract': `import "msa.contract";
import "s.contract";
scheduler configuration { modules { MSA; } schemas { s; } }
`,
    'sub.contract': `supervisor SUB { g(int c, float d) { rules { G: [elapsed=1ms] [elapsed=2ms] } } }
`,
    'sup.contract': `import "types.contract";
import "msa.contract";
import "s.contract";
import "sub.contract";
supervisor SUP {
    event flows { in :0 float ev; in :1 int iv; out :0 int o; }
    f(int a = @I10@, float b = @F12@) {
        local { int li = @I11@; float lf = @F13@; P lp = {@F14@, @I12@}; float[2] arr = {@F15@, @N2@}; }
        rules {
            R: [MSA:2<(ev < @F16@) | ev == @N3@ | near(@F17@, @I13@)>(lf = @F18@) or MSA:3<(iv > @I14@)>(li = @I15@)]
                subscribe MSA:2 =* :0; subscribe MSA:3 =* :1;
                parameterize MSA(@I16@ :0, @F19@ :1);
                activate schema s(k = @I17@, f = @F20@);
                activate supervisor SUB.g(c = @I18@, d = @F21@);
                compute note(@F22@, @I19@);
                notify :0(o = @I20@)
                [elapsed=1ms]
        }
    }
}
`,
};

const GOOD: Record<string, string[]> = {
    I: [INT_MAX, INT_MIN, '0'],
    F: [FLOAT_MAX, `-${FLOAT_MAX}`, '5e-324', '1e308'],
    N: ['99999999999999999999'],
};
const BAD: Record<string, string> = { I: '9223372036854775808', F: '1e400', N: '1' + '0'.repeat(400) };

function project(bad?: string): Record<string, string> {
    let n = 0;
    return Object.fromEntries(Object.entries(PROJECT).map(([file, text]) => [file,
        text.replace(/@([IFN])\d+@/g, (marker, kind: string) => marker === bad ? BAD[kind]! : GOOD[kind]![n++ % GOOD[kind]!.length]!)]));
}

const MARKERS = Object.values(PROJECT).flatMap((text) => [...text.matchAll(/@[IFN]\d+@/g)].map((m) => m[0]));

describe('number-out-of-range: every place a number is written', () => {
    it('the project has no error with numbers at their bounds, one per number past them', async () => {
        expect(MARKERS).toHaveLength(22 + 20 + 3);
        const built = await build(project(), services);
        expect(errors(built), built.lines.join('\n')).toEqual([]);
        const bad = Object.fromEntries(Object.entries(PROJECT).map(([file, text]) => [file, text.replace(/@([IFN])\d+@/g, (_m, kind: string) => BAD[kind]!)]));
        const all = await build(bad, services);
        expect(errors(all).map((d) => d.code)).toEqual(MARKERS.map(() => CODE));
    });

    it.each(MARKERS)('%s out of range is that one error, on it', async (marker) => {
        const files = project(marker);
        const built = await build(files, services);
        const file = Object.keys(PROJECT).find((f) => PROJECT[f]!.includes(marker))!;
        const line = PROJECT[file]!.split('\n').findIndex((l) => l.includes(marker)) + 1;
        expect(errors(built).map((d) => `${d.file}:${d.line} ${d.code}`), built.lines.join('\n')).toEqual([`${file}:${line} ${CODE}`]);
        expect(outOfRange(built)[0]!.message).toContain(BAD[marker[1]!]!.slice(0, 40));
    });
});

describe('number-out-of-range: C ints and durations', () => {
    const module = (ports: string, c = '1ms') => `synchronous module MSA { scheduling { C=${c}; } data flows { ${ports} } }`;
    const schema = (k: string) => ({
        'a.contract': module('out :0 int x;'),
        'b.contract': 'synchronous module MSB { scheduling { C=1ms; } data flows { in :0 int x; } }',
        's.contract': `import "a.contract";\nimport "b.contract";\nperiodic schema s() { realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; } modules { MSA (); MSB (); } communications { MSA:0 -> MSB:0 * ${k}; } }`,
    });
    it.each([
        ['a port index', { 'a.contract': module('out :2147483647 int x;') }, { 'a.contract': module('out :2147483648 int x;') }, 'Port index 2147483648 is too large: a port index is a C int'],
        ['a periodicity', schema('2147483647'), schema('2147483648'), 'Periodicity 2147483648 is too large'],
        ['an array size', { 'a.contract': 'datatype T {bool[2147483647] v};' }, { 'a.contract': 'datatype T {bool[99999999999999999999] v};' }, 'Array size 99999999999999999999 is too large: an array size is a C int'],
        ['an array size (a constant)', { 'a.contract': 'const int N = 2147483647;\ndatatype T {bool[N] v};' }, { 'a.contract': 'const int N = 2147483648;\ndatatype T {bool[N] v};' }, "Array size 'N' is too large"],
        ['a duration', { 'a.contract': module('', '9007199254740991ns') }, { 'a.contract': module('', '9007199.254740992s') }, 'Duration 9007199.254740992s is too long: a duration is at most 9007199254740991ns'],
    ])('%s', async (_what, good, bad, message) => {
        const ok = await build(good, services);
        expect(outOfRange(ok), ok.lines.join('\n')).toEqual([]);
        const built = await build(bad, services);
        expect(outOfRange(built).map((d) => d.message), built.lines.join('\n')).toEqual([expect.stringContaining(message)]);
    });
});

describe('number-out-of-range in scenarios', () => {
    const files = {
        'types.contract': 'datatype Battery {float level = 100.0, float voltage = 24.0};',
        'bat.contract': 'import "types.contract";\nasynchronous module BAT { event flows { out :0 Battery battery; out :1 int count; out :2 float level; } }',
    };
    it('a value out of its type is a diagnostic of the scenario, which does not run', async () => {
        const built = await build(files, services);
        const index = indexModels([...built.docs.values()].map((d) => d.parseResult.value as Model));
        const parsed = parseScenario([
            't=1ms BAT:0 battery = {1e308, -1e308}',
            't=2ms BAT:0 battery = {1e400, 24}',
            `t=3ms BAT:1 count = ${INT_MAX}`,
            't=4ms BAT:1 count = 9223372036854775808',
            't=5ms BAT:2 level = 99999999999999999999',
            't=6ms BAT:2 level = 1e-400',
        ].join('\n'));
        expect(parsed.diagnostics).toEqual([]);
        const check = checkScenario(parsed.steps, index);
        expect(check.diagnostics.map((d) => `${d.line}:${d.column} ${d.severity} ${d.code} ${d.message}`)).toEqual([
            "2:24 error scenario-value-type The real 1e400 for field 'level' of Battery is too large for a float (a float is a C double, from -1.7976931348623157e+308 to 1.7976931348623157e+308): it would be infinite.",
            '4:21 error scenario-value-type The integer 9223372036854775808 for BAT:1 (int count) is too large for an int (an int is a C long, from -9223372036854775808 to 9223372036854775807).',
            '6:21 error scenario-value-type The real 1e-400 for BAT:2 (float level) is too close to 0 for a float (a float is a C double; its smallest value but 0 is 5e-324): it would be 0.',
        ]);
    });
});
