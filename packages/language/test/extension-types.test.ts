/**
 * The extension types of docs/language-reference.md (bool, fixed-size arrays, enumerations, named
 * constants): parsing, value model, type checks of tests and extractions in supervisors, reserved C
 * names of enumeration members, hover, completion after `Mode.`, formatting.
 */
import type { LangiumDocument } from 'langium';
import { EmptyFileSystem, URI } from 'langium';
import { describe, expect, it } from 'vitest';
import { createCactalServices } from '../src/cactal-module.js';
import { isConstant, isDataType, type Model } from '../src/generated/ast.js';
import type { CactalFormatter } from '../src/lsp/cactal-formatter.js';
import { cLayout, typeName, typeOf } from '../src/model/types.js';
import { constantValue, defaultValue, formatConstant } from '../src/model/values.js';
import { SemanticTokensDecoder, type AbstractSemanticTokenProvider } from 'langium/lsp';
import { build } from './helpers.js';
import { checkScenario, indexModels, parseScenario } from '../src/scenario/index.js';

const TYPES = `const int NJOINTS = 6;
const float SAFE = 0.3;
enum Mode { IDLE, TELEOP, AUTO }
enum Level { OK, WARN, STOP };
datatype Scan {float[180] ranges, Mode mode = Mode.AUTO, bool valid = true};
datatype Arm {float[NJOINTS] q = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5}, float[2][3] m, string[2] names = {"a", "b"}};
datatype Alarm {Level level, int code = NJOINTS};
const Arm HOME = {{0, 0, 0, 0, 0, 1}, {{1, 2, 3}, {4, 5, 6}}, {"x", "y"}};
`;

/** A supervisor of the types above, with `rules` in its function `watch`. */
const sup = (rules: string, locals = 'Level last = Level.OK; float d = 0.0; float[NJOINTS] q; bool stopped = false;') => `import "types.contract";
import "msa.contract";
supervisor SUP {
    event flows { in :1 Alarm alarm; in :2 Scan scan; in :3 Mode mode; out :4 float[NJOINTS] target; }
    watch() {
        local { ${locals} }
        rules { ${rules} }
    }
}
`;

/** The module whose event ports the supervisor's rules test. */
const MSA = `import "types.contract";
synchronous module MSA {
    scheduling { C=1ms; }
    event flows { out :1 Alarm alarm; out :2 Scan scan; out :3 Mode mode; }
}
`;

async function errorsOf(files: Record<string, string>): Promise<string[]> {
    const built = await build({ 'msa.contract': MSA, ...files });
    return built.diagnostics.filter((d) => d.severity === 'error').map((d) => `${d.code} ${d.message}`);
}

describe('extension types', () => {
    it('a types file with constants, enumerations, bools and arrays is valid, and its values follow the model', async () => {
        const built = await build({ 'types.contract': TYPES });
        expect(built.lines).toEqual([]);
        const model = built.docs.get('types.contract')!.parseResult.value as Model;
        const arm = model.elements.filter(isDataType).find((d) => d.name === 'Arm')!;
        expect(formatConstant(defaultValue({ kind: 'struct', datatype: arm })!)).toBe('{{0.0,0.1,0.2,0.3,0.4,0.5},{{0.0,0.0,0.0},{0.0,0.0,0.0}},{"a","b"}}');
        const scan = model.elements.filter(isDataType).find((d) => d.name === 'Scan')!;
        expect(formatConstant(defaultValue({ kind: 'struct', datatype: scan })!)).toMatch(/^\{\{0\.0(,0\.0){179}\},AUTO,true\}$/);
        expect(typeName(typeOf(arm.fields[1]!.type))).toBe('float[2][3]');
        expect(cLayout({ kind: 'struct', datatype: arm })).toEqual({ size: 48 + 48 + 512, align: 8 });
        expect(cLayout({ kind: 'struct', datatype: scan })).toEqual({ size: 1448, align: 8 }); // 1440 + enum 4 + bool 1, padded
        const home = model.elements.filter(isConstant).find((c) => c.name === 'HOME')!;
        expect(formatConstant(constantValue(home.value, typeOf(home.type))!)).toBe('{{0.0,0.0,0.0,0.0,0.0,1.0},{{1.0,2.0,3.0},{4.0,5.0,6.0}},{"x","y"}}');
    });

    it('accepts tests and extractions on array elements, enumeration values, bools and constants', async () => {
        const errors = await errorsOf({
            'types.contract': TYPES,
            'sup.contract': sup(`FIRST: [MSA:1<alarm.level == Level.STOP>(last = alarm.level, q[2] = HOME.q[5], d = SAFE)]
                notify :4 (target = q, target[0] = NJOINTS)
                [MSA:2<(scan.ranges[90] < SAFE) | (scan.valid == true & scan.mode != Mode.IDLE)>(stopped = scan.valid, d = scan.ranges[NJOINTS])]
              SECOND: [MSA:3<(mode >= Mode.TELEOP)>] [elapsed=1s]`)
        });
        expect(errors).toEqual([]);
    });

    it('type-checks tests: enumerations against their own members, no ordering of bools or whole arrays', async () => {
        const errors = await errorsOf({
            'types.contract': TYPES,
            'sup.contract': sup(`A: [MSA:1<alarm.level == Mode.AUTO | alarm.level == 2 | (scan.valid < true) | (scan.ranges > q)>] [elapsed=1s]`)
        });
        expect(errors).toEqual([
            "supervisor-test-type Cannot compare 'alarm.level' (Level) with 'Mode.AUTO' (Mode): both operands of a test have the same type (int and float mix).",
            "supervisor-test-type Cannot compare 'alarm.level' (Level) with the integer 2 (int): both operands of a test have the same type (int and float mix).",
            'supervisor-test-type Cannot order values of type bool with <: a bool is tested with == or !=.',
            'supervisor-test-type Cannot order values of type float[180] with >: compare one element (ranges[90]) or test the whole array with == / !=.',
        ]);
    });

    it('reports indexes out of range or on non-arrays, unknown members and wrong element types with clear messages', async () => {
        const errors = await errorsOf({
            'types.contract': TYPES,
            'sup.contract': sup(`A: [MSA:2<(scan.ranges[180] < 0.3) | scan.mode[0] == Mode.AUTO | scan.mode == Mode.FAST>(q = {1, 2}, stopped = 1)] [elapsed=1s]`)
        });
        expect(errors).toEqual([
            "linking-error 'FAST' is not a member of enumeration Mode; its members: IDLE, TELEOP, AUTO.",
            "array-index-invalid Index 180 is out of range: 'scan.ranges' is a float[180], its elements are [0] to [179].",
            "array-index-invalid 'scan.mode' is a Mode, not an array: only arrays have elements [i].",
            "value-array-length float[6] has 6 elements; this value has 2 for 'q'.",
            "value-type-mismatch Expected a bool (true or false) for 'stopped', found the integer 1 (write true or false).",
        ]);
    });

    it('refuses names clashing across datatypes, enumerations and constants, and enumeration members whose C name is taken', async () => {
        const built = await build({ 'a.contract': 'enum Pose {A};\ndatatype Pose {int x};\nconst int Pose = 1;\nenum increment {until_markerfound, fine};' });
        const errors = built.diagnostics.map((d) => `${d.code} ${d.message}`);
        expect(errors.filter((e) => e.startsWith('type-duplicate-name'))).toHaveLength(3);
        expect(errors).toContain("identifier-c-reserved Member 'until_markerfound' of enumeration increment becomes the C name increment_until_markerfound, which cannot be used: the C library, POSIX or runtime headers that the generated C includes already declare it. Choose another name (e.g. 'until_markerfound_').");
        expect(errors.filter((e) => e.includes("'fine'"))).toEqual([]);
    });

    it('hovers show sizes and the C layout; completion after `Mode.` offers the members', async () => {
        const text = TYPES + 'datatype T {Mode m = Mode.};\n';
        const ws = await build({ 'types.contract': text });
        const doc: LangiumDocument = ws.docs.get('types.contract')!;
        const hoverAt = async (needle: string, delta = 0) => {
            const hover = await ws.services.lsp.HoverProvider!.getHoverContent(doc, { textDocument: { uri: doc.uri.toString() }, position: doc.textDocument.positionAt(text.indexOf(needle) + delta) });
            return (hover?.contents as { value: string } | undefined)?.value ?? '';
        };
        const arm = await hoverAt('Arm {', 0);
        expect(arm).toContain('size: 608 bytes');
        expect(arm).toContain('- `m`: offset 48, 48 bytes');
        expect(arm).toContain('- `names`: offset 96, 512 bytes');
        expect(await hoverAt('Mode {', 0)).toContain('`Mode_AUTO` = 2; 4 bytes');
        expect(await hoverAt('ranges', 0)).toContain('offset 0 in `Scan`, 1,440 bytes (float[180])');
        const list = await ws.services.lsp.CompletionProvider!.getCompletion(doc, { textDocument: { uri: doc.uri.toString() }, position: doc.textDocument.positionAt(text.indexOf('Mode.}') + 5) });
        expect(list?.items.map((i) => `${i.label}: ${i.detail}`)).toEqual(['IDLE: Mode.IDLE (member 0 of Mode)', 'TELEOP: Mode.TELEOP (member 1 of Mode)', 'AUTO: Mode.AUTO (member 2 of Mode)']);
    });

    it('highlights enumerations, their members, constants and array sizes', async () => {
        const ws = await build({ 'types.contract': TYPES });
        const doc = ws.docs.get('types.contract')!;
        const provider = ws.services.lsp.SemanticTokenProvider as AbstractSemanticTokenProvider;
        const result = await provider.semanticHighlight(doc, { textDocument: { uri: doc.uri.toString() } });
        const list = SemanticTokensDecoder.decode(result, provider.tokenTypes, doc).map((t) => `${t.text}:${t.tokenType}`);
        expect(list).toEqual(expect.arrayContaining(['const:keyword', 'enum:keyword', 'Mode:enum', 'IDLE:enumMember', 'NJOINTS:variable', 'AUTO:enumMember', 'bool:type']));
        expect(list.filter((t) => t.startsWith('Mode:'))).toEqual(['Mode:enum', 'Mode:type', 'Mode:enum']);
    });

    it('scenarios (simulator) read bools and enumeration members, checked against the port types', async () => {
        const built = await build({ 'types.contract': TYPES, 'msa.contract': MSA });
        const index = indexModels([...built.docs.values()].map((d) => d.parseResult.value as Model));
        const parsed = parseScenario('t=1ms MSA:3 Mode.AUTO\nt=2ms MSA:3 Mode.FAST\nt=3ms MSA:3 Level.STOP\nt=4ms MSA:2 {{' + Array(180).fill('0.5').join(',') + '}, Mode.IDLE, false}\nt=5ms MSA:3 Gear.LOW');
        expect(parsed.diagnostics).toEqual([]);
        const check = checkScenario(parsed.steps, index);
        expect(check.diagnostics.map((d) => `${d.line} ${d.code} ${d.message}`)).toEqual([
            "2 scenario-value-type 'FAST' is not a member of enumeration Mode; its members: IDLE, TELEOP, AUTO",
            "3 scenario-value-type Expected a Mode value (Mode.IDLE, Mode.TELEOP, Mode.AUTO) for MSA:3 (Mode mode), found 'Level.STOP' of type Level.",
            "5 scenario-value-type no enumeration 'Gear' in the project (enumerations: Mode, Level)",
        ]);
    });

    it('renames enumerations, members and constants everywhere they are written, refusing clashes', async () => {
        const files = { 'types.contract': TYPES, 'msa.contract': MSA, 'sup.contract': sup('A: [MSA:1<alarm.level == Level.STOP>(d = SAFE)] [elapsed=1s]') };
        const ws = await build(files);
        const rename = ws.services.lsp.RenameProvider!;
        const types = ws.docs.get('types.contract')!;
        const at = (needle: string, delta = 0) => ({ textDocument: { uri: types.uri.toString() }, position: types.textDocument.positionAt(types.textDocument.getText().indexOf(needle) + delta) });
        const apply = (edit: { changes?: Record<string, Array<{ range: { start: { line: number; character: number }; end: { line: number; character: number } }; newText: string }>> }) => {
            const out: Record<string, string> = {};
            for (const [file, doc] of ws.docs) {
                let text = doc.textDocument.getText();
                for (const e of [...(edit.changes?.[doc.uri.toString()] ?? [])].sort((a, b) => doc.textDocument.offsetAt(b.range.start) - doc.textDocument.offsetAt(a.range.start))) {
                    text = text.slice(0, doc.textDocument.offsetAt(e.range.start)) + e.newText + text.slice(doc.textDocument.offsetAt(e.range.end));
                }
                out[file] = text;
            }
            return out;
        };
        const level = apply((await rename.rename(types, { ...at('Level {', 1), newName: 'Severity' }))!);
        expect(level['types.contract']).toContain('enum Severity { OK, WARN, STOP };');
        expect(level['types.contract']).toContain('datatype Alarm {Severity level');
        expect(level['sup.contract']).toContain('alarm.level == Severity.STOP');
        const stop = apply((await rename.rename(types, { ...at('STOP }', 1), newName: 'HALT' }))!);
        expect(stop['sup.contract']).toContain('alarm.level == Level.HALT');
        const safe = apply((await rename.rename(types, { ...at('SAFE =', 1), newName: 'MARGIN' }))!);
        expect(safe['sup.contract']).toContain('d = MARGIN');
        await expect(async () => rename.rename(types, { ...at('Level {', 1), newName: 'Scan' })).rejects.toThrow(/'Scan' already names a datatype/);
        await expect(async () => rename.rename(types, { ...at('STOP }', 1), newName: 'WARN' })).rejects.toThrow(/already used/);
    });

    it('lists enumerations with their members and constants in the outline', async () => {
        const ws = await build({ 'types.contract': TYPES });
        const symbols = await ws.services.lsp.DocumentSymbolProvider!.getSymbols(ws.docs.get('types.contract')!, { textDocument: { uri: 'file:///ws/types.contract' } });
        const outline = symbols.map((s) => `${s.name} ${s.detail}${s.children?.length ? ` [${s.children.map((c) => c.name).join(',')}]` : ''}`);
        expect(outline.slice(0, 4)).toEqual(['NJOINTS const int', 'SAFE const float', 'Mode enum [IDLE,TELEOP,AUTO]', 'Level enum [OK,WARN,STOP]']);
    });

    it('formats array sizes and indexes tight, and keeps the AST', () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        const doc = services.shared.workspace.LangiumDocumentFactory.fromString(
            'const int N=6;enum Mode{IDLE,AUTO};datatype D {float [ N ] q={1.0,2,3,4,5,6}, float[3] [3] m,bool b=true,Mode mode=Mode . AUTO};',
            URI.parse('file:///fmt/ext.contract'));
        expect((services.lsp.Formatter as CactalFormatter).formatText(doc)).toBe(
            'const int N = 6;\n\nenum Mode {IDLE, AUTO};\n\ndatatype D {float[N] q = {1.0, 2, 3, 4, 5, 6}, float[3][3] m, bool b = true, Mode mode = Mode.AUTO};\n');
    });
});
