/**
 * Every diagnostic code of docs/language-reference.md §1–3 (and the syntax/linking codes): a case that raises it and
 * a near-identical case that does not.
 */
import { describe, expect, it } from 'vitest';
import { describeCodeCases, type CodeCase } from './code-cases.js';
import { build, TYPES } from './helpers.js';

const sync = (body: string, name = 'MSA') => `synchronous module ${name} { ${body} }`;
const sup = (rule: string) => ({
    't.contract': TYPES,
    's.contract': `import "t.contract";\nsupervisor SUP { f() { local { TypeA t; } rules { R: [elapsed=1ms] ${rule} [elapsed=2ms] } } }`
});

export const CASES: Record<string, CodeCase> = {
    'lexing-error': { raise: { 'a.contract': 'datatype T {int a = 1 $};' }, clean: { 'a.contract': 'datatype T {int a = 1 };' } },
    'parsing-error': { raise: { 'a.contract': 'datatype T {int a = };' }, clean: { 'a.contract': 'datatype T {int a = 1};' } },
    'merge-conflict-marker': {
        raise: { 'a.contract': 'datatype T {\n<<<<<<< HEAD\nint a = 1\n=======\nint a = 2\n>>>>>>> eng-b\n};' },
        clean: { 'a.contract': 'datatype T {\nint a = 1\n};' }
    },
    'linking-error': {
        raise: { 'a.contract': sync('scheduling { C=1ms; }'), 's.contract': 'import "a.contract";\nperiodic schema s() { modules { MSA (); MSZ (); } }' },
        clean: { 'a.contract': sync('scheduling { C=1ms; }'), 's.contract': 'import "a.contract";\nperiodic schema s() { modules { MSA (); } }' }
    },
    'type-unknown': {
        raise: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :0 TypeZ x; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :0 int x; }') }
    },
    'import-missing-file': {
        raise: { 'sub/a.contract': 'import "b.contract";\ndatatype A {B x};', 'b.contract': 'datatype B {int y};' },
        data: { suggestion: '../b.contract' },
        clean: { 'a.contract': 'import "b.contract";\ndatatype A {B x};', 'b.contract': 'datatype B {int y};' }
    },
    'import-cycle': {
        raise: { 'a.contract': 'import "b.contract";\ndatatype A {B b};', 'b.contract': 'import "a.contract";\ndatatype B {int x};' },
        clean: { 'a.contract': 'import "b.contract";\ndatatype A {B b};', 'b.contract': 'datatype B {int x};' }
    },
    'import-unused': {
        raise: { 'a.contract': 'import "b.contract";\ndatatype A {int b};', 'b.contract': 'datatype B {int y};' },
        clean: { 'a.contract': 'import "b.contract";\ndatatype A {B b};', 'b.contract': 'datatype B {int y};' }
    },
    'import-not-imported': {
        raise: { 'a.contract': 'datatype A {B b};', 'b.contract': 'datatype B {int y};' },
        clean: { 'a.contract': 'import "b.contract";\ndatatype A {B b};', 'b.contract': 'datatype B {int y};' },
        data: { importPath: 'b.contract' }
    },
    'import-duplicate': {
        raise: { 'a.contract': 'import "b.contract";\nimport "./b.contract";\ndatatype A {B b};', 'b.contract': 'datatype B {int y};' },
        clean: { 'a.contract': 'import "b.contract";\ndatatype A {B b};', 'b.contract': 'datatype B {int y};' }
    },
    'import-self': {
        raise: { 'a.contract': 'import "a.contract";\ndatatype A {int b};' },
        clean: { 'a.contract': 'datatype A {int b};' }
    },
    'import-not-at-top': {
        raise: { 'a.contract': 'datatype A {B b};\nimport "b.contract";', 'b.contract': 'datatype B {int y};' },
        clean: { 'a.contract': 'import "b.contract";\ndatatype A {B b};', 'b.contract': 'datatype B {int y};' }
    },
    'file-mixed-content': {
        raise: { 'a.contract': `datatype T {int a};\n${sync('scheduling { C=1ms; } data flows { out :0 T x; }')}` },
        clean: { 'a.contract': 'datatype T {int a};', 'm.contract': `import "a.contract";\n${sync('scheduling { C=1ms; } data flows { out :0 T x; }')}` }
    },
    'type-duplicate-name': {
        raise: { 'a.contract': 'datatype T {int a};', 'b.contract': 'datatype T {float b};' },
        clean: { 'a.contract': 'datatype T {int a};', 'b.contract': 'datatype U {float b};' }
    },
    'type-duplicate-member': {
        raise: { 'a.contract': 'datatype T {int a, float a};' },
        clean: { 'a.contract': 'datatype T {int a, float b};' }
    },
    'type-recursive': {
        raise: { 'a.contract': 'datatype A {B b};\ndatatype B {A a};' },
        clean: { 'a.contract': 'datatype A {B b};\ndatatype B {int a};' }
    },
    'type-primitive-misuse': {
        raise: { 'a.contract': 'datatype T {void flag};' },
        clean: { 'a.contract': 'datatype T {bool flag};' }
    },
    'type-function-return': {
        raise: { 'a.contract': 'function int f(int a);' },
        clean: { 'a.contract': 'function bool f(int a);' }
    },
    'type-function-misuse': {
        raise: sup('compute testit("a", t)'),
        clean: sup('compute doit("a", t.i)')
    },
    'value-type-mismatch': {
        raise: { 'a.contract': 'datatype T {int a = 1.5};' },
        clean: { 'a.contract': 'datatype T {float a = 1};' }
    },
    'number-out-of-range': {
        raise: { 'a.contract': 'datatype T {int a = 9223372036854775808, float b = 1e400};' },
        clean: { 'a.contract': 'datatype T {int a = 9223372036854775807, float b = 1e308};' },
        message: "The real 1e400 for 'b' is too large for a float"
    },
    'value-struct-arity': {
        raise: { 'a.contract': 'datatype A {float i, float j};\ndatatype B {A a = {1.0}};' },
        clean: { 'a.contract': 'datatype A {float i, float j};\ndatatype B {A a = {1.0, 2}};' }
    },
    'value-string-too-long': {
        raise: { 'a.contract': `datatype T {string s = "${'é'.repeat(128)}"};` },
        clean: { 'a.contract': `datatype T {string s = "${'x'.repeat(255)}"};` }
    },
    'value-string-unknown-escape': {
        raise: { 'a.contract': 'const string ESC = "\\e[0m";' },
        clean: { 'a.contract': 'const string ESC = "\\\\e[0m\\n";' },
        message: "Unknown escape '\\e' in a string: it is read as 'e'."
    },
    'value-array-length': {
        raise: { 'a.contract': 'datatype T {float[3] v = {1.0, 2.0}};' },
        clean: { 'a.contract': 'datatype T {float[3] v = {1.0, 2.0, 3}};' },
        message: 'float[3] has 3 elements; this value has 2'
    },
    'enum-value-without-member': {
        raise: { 'a.contract': 'enum Mode {IDLE, AUTO};\ndatatype T {Mode m = Mode};' },
        clean: { 'a.contract': 'enum Mode {IDLE, AUTO};\ndatatype T {Mode m = Mode.AUTO};' },
        message: 'write one of its members (Mode.IDLE, Mode.AUTO)'
    },
    'enum-empty': {
        raise: { 'a.contract': 'enum Mode {};' },
        clean: { 'a.contract': 'enum Mode {IDLE};' }
    },
    'array-size-invalid': {
        raise: { 'a.contract': 'const int N = 0;\ndatatype T {float[N] v};' },
        clean: { 'a.contract': 'const int N = 2;\ndatatype T {float[N] v};' },
        message: "'N' is 0"
    },
    'array-index-invalid': {
        raise: { 'a.contract': 'const float[2] L = {1.0, 2.0};\ndatatype T {float a = L[2]};' },
        clean: { 'a.contract': 'const float[2] L = {1.0, 2.0};\ndatatype T {float a = L[1]};' },
        message: 'Index 2 is out of range'
    },
    'type-too-large': {
        raise: { 'a.contract': sync('scheduling { C=1ms; } event flows { out :0 float[4096] samples; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; } event flows { out :0 float[2048] samples; }') },
        message: "'samples' takes 32768 bytes"
    },
    'const-cycle': {
        raise: { 'a.contract': 'const int A = B;\nconst int B = A;' },
        clean: { 'a.contract': 'const int A = 1;\nconst int B = A;' },
        message: 'A -> B -> A'
    },
    'value-not-constant': {
        raise: { 'a.contract': 'datatype T {string s = ord_schema};' },
        clean: { 'a.contract': 'datatype T {string s = "ord_schema"};' }
    },
    'module-name-format': {
        raise: { 'a.contract': sync('scheduling { C=1ms; }', 'msa') },
        clean: { 'a.contract': sync('scheduling { C=1ms; }', 'MSA') },
        data: { suggestion: 'MSA' }
    },
    'module-name-reserved': {
        raise: { 'a.contract': sync('scheduling { C=1ms; }', 'ORD') },
        clean: { 'a.contract': sync('scheduling { C=1ms; }', 'ORE') }
    },
    'module-name-duplicate': {
        raise: { 'a.contract': sync('scheduling { C=1ms; }'), 'b.contract': 'supervisor MSA { }' },
        clean: { 'a.contract': sync('scheduling { C=1ms; }'), 'b.contract': 'supervisor MSB { }' }
    },
    'identifier-c-keyword': {
        raise: { 'a.contract': 'datatype T {int double};' },
        clean: { 'a.contract': 'datatype T {int double_};' }
    },
    'identifier-c-reserved': {
        raise: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :0 int time; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :0 int time_; }') },
        message: "'time' cannot name a port in the generated C",
        data: { suggestion: 'time_' }
    },
    'identifier-generated-clash': {
        raise: { 'a.contract': 'datatype Pose {float x};\ndatatype POSE {int y};' },
        clean: { 'a.contract': 'datatype Pose {float x};\ndatatype Pose2 {int y};' },
        message: "datatype 'POSE' and datatype 'Pose' would share the generated include guard SHARED_POSE_H",
        data: { suggestion: 'Pose_' }
    },
    'identifier-reserved-prefix': {
        raise: { 'a.contract': 'datatype T {int _a};' },
        clean: { 'a.contract': 'datatype T {int a_};' }
    },
    'module-block-order': {
        raise: { 'a.contract': sync('data flows { out :0 int x; } scheduling { C=1ms; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :0 int x; }') }
    },
    'module-block-duplicate': {
        raise: { 'a.contract': sync('scheduling { C=1ms; } scheduling { C=1ms; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; }') }
    },
    'module-scheduling-missing': {
        raise: { 'a.contract': sync('data flows { out :0 int x; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :0 int x; }') }
    },
    'module-scheduling-property': {
        raise: { 'a.contract': sync('scheduling { C=1ms; D=1ms; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; }') }
    },
    'module-async-forbidden-block': {
        raise: { 'a.contract': 'asynchronous module MAA { scheduling { C=1ms; } event flows { in :0 int e; } }' },
        clean: { 'a.contract': 'asynchronous module MAA { event flows { in :0 int e; } }' }
    },
    'module-sync-event-in': {
        raise: { 'a.contract': sync('scheduling { C=1ms; } event flows { in :0 int e; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; } event flows { out :0 int e; }') }
    },
    'port-index-duplicate': {
        raise: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :0 int a; out :0 int b; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :0 int a; in :0 int b; }') },
        data: { suggestedIndex: 1 }
    },
    'port-index-negative': {
        raise: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :-1 int a; }') },
        clean: { 'a.contract': sync('scheduling { C=1ms; } data flows { out :1 int a; }') }
    },
    'member-name-duplicate': {
        raise: { 'a.contract': sync('parameters { int a :0; } scheduling { C=1ms; } data flows { out :0 float a; }') },
        clean: { 'a.contract': sync('parameters { int a :0; } scheduling { C=1ms; } data flows { out :0 float b; }') }
    },
    'time-not-positive': {
        raise: { 'a.contract': sync('scheduling { C=0ms; }') },
        clean: { 'a.contract': sync('scheduling { C=1ns; }') }
    },
    'time-rounded': {
        raise: { 'a.contract': sync('scheduling { C=1.5ns; }') },
        clean: { 'a.contract': sync('scheduling { C=1.5us; }') }
    },
    'parameter-index-too-large': {
        raise: { 'a.contract': sync('parameters { int g :1024; } scheduling { C=1ms; }') },
        clean: { 'a.contract': sync('parameters { int g :1023; } scheduling { C=1ms; }') }
    },
    'identifier-too-long': {
        raise: { 't.contract': `datatype ${'T'.repeat(201)} {int v};\n` },
        clean: { 't.contract': `datatype ${'T'.repeat(200)} {int v};\n` }
    }
};

const MY_AREAS = ['Syntax and references', 'Files and imports', 'Data types, values and functions', 'Modules and identifiers'];

describeCodeCases('diagnostic codes of §2.1–2.3: raised and not raised', MY_AREAS, CASES);

describe('messages say what is wrong and what would be right', () => {
    it('names the expected block order', async () => {
        const built = await build(CASES['module-block-order']!.raise);
        expect(built.lines.join('\n')).toContain('the order is parameters, scheduling, data flows, event flows');
    });
    it('shows the datatype cycle', async () => {
        const built = await build(CASES['type-recursive']!.raise);
        expect(built.lines.join('\n')).toContain('A -> B -> A');
    });
    it('shows the import cycle on the import to remove, and on no other file of the cycle', async () => {
        const built = await build(CASES['import-cycle']!.raise);
        const cycle = built.diagnostics.filter((d) => d.code === 'import-cycle');
        expect(cycle.map((d) => [d.file, d.line, d.message])).toEqual([[
            'b.contract', 1, 'Import cycle: b.contract -> a.contract -> b.contract, and nothing from "a.contract" is used in this file: remove this import (imports are not transitive: a file imports only the files whose names it uses).'
        ]]);
    });
    it('says no import cycle for files that use each other\'s names (each must import the other)', async () => {
        const built = await build({
            'a.contract': 'import "b.contract";\ndatatype A {B b};\ndatatype A2 {int x};',
            'b.contract': 'import "a.contract";\ndatatype B {A2 y};'
        });
        expect(built.lines.join('\n')).not.toContain('Import cycle');
        expect(built.lines.join('\n')).not.toContain('import-');
    });
    it('lists the available ports when a port index does not resolve', async () => {
        const built = await build({
            't.contract': TYPES,
            'm.contract': `import "t.contract";\n${sync('scheduling { C=1ms; } data flows { in :0 TypeA a; out :1 TypeB b; }', 'MSC')}`,
            'n.contract': `import "t.contract";\n${sync('scheduling { C=1ms; } data flows { in :2 TypeB c; }', 'MSD')}`,
            's.contract': 'import "m.contract";\nimport "n.contract";\nperiodic schema s() { realtime { PERIOD=1s; CRITICAL_DELAY=1s; } modules { MSC (); MSD (); } communications { MSC:0 -> MSD:2 * 1; } }'
        });
        expect(built.lines.join('\n')).toContain('MSC has no output data port 0; its output data ports: :1 b.');
    });
    it('accepts an int literal for a float, rejects a real for an int', async () => {
        const built = await build({ 'a.contract': 'datatype T {float f = 1, int i = 2.5};' });
        expect(built.diagnostics.map((d) => d.message)).toEqual(["Expected an int (integer literal) for 'i', found the real 2.5 (a real cannot be an int)."]);
    });
});
