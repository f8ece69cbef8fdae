/**
 * Names that `check` accepted and gcc then rejected inside the generated C (docs/language-reference.md,
 * "Reserved names"): each is now an `identifier-c-reserved` error where it would collide, with a
 * rename quick fix, and stays accepted where the generated C keeps it out of the way.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { AstUtils } from 'langium';
import { describe, expect, it } from 'vitest';
import type { CodeAction, WorkspaceEdit } from 'vscode-languageserver-protocol';
import { renameProblem } from '../src/lsp/name-rules.js';
import { build, type Built } from './helpers.js';

const CODE = 'identifier-c-reserved';
const asyncModule = (param: string, port: string) =>
    `asynchronous module MAA {\n    parameters { int ${param} = 0 :0; }\n    event flows { in :0 int ${port}; out :0 float other; }\n}\n`;
const syncModule = (port: string) => `synchronous module MSA {\n    scheduling { C=1ms; }\n    data flows { out :0 int ${port}; in :0 float other; }\n}\n`;
const TYPES = 'datatype Pose {float x = 0.0, float y = 0.0};\nfunction bool near(Pose a, Pose b);\n';

function reserved(built: Built): string[] {
    return built.diagnostics.filter((d) => d.code === CODE).map((d) => `${d.file}:${d.line} ${d.message}`);
}

describe('names the generated C already takes', () => {
    // the names of the issue: libc, POSIX, libmodule and the generated module.c's own variables
    const ISSUE_NAMES = ['time', 'productionTime', 'receptionTime', 'MODULE_NAME', 'IUSE', 'stateindex', 'printf', 'exit', 'ModuleMain'];

    for (const name of ISSUE_NAMES) {
        it(`'${name}' as a module parameter or port is an error with a free suggestion`, async () => {
            const built = await build({ 'a.contract': asyncModule(name, `${name}In`), 's.contract': syncModule(name) });
            const found = built.diagnostics.filter((d) => d.code === CODE);
            expect(found.map((d) => `${d.file}:${d.line}`), built.lines.join('\n')).toEqual(['a.contract:2', 's.contract:3']);
            for (const d of found) {
                expect(d.severity).toBe('error');
                expect(d.message).toMatch(new RegExp(`^'${name}' cannot name a (parameter|port) in the generated C: .+\\. Choose another name \\(e\\.g\\. '${name}_'\\)\\.$`));
                expect(d.data).toMatchObject({ suggestion: `${name}_` });
            }
            const renamed = await build({ 'a.contract': asyncModule(`${name}_`, `${name}In`), 's.contract': syncModule(`${name}_`) });
            expect(renamed.diagnostics.filter((d) => d.severity === 'error'), renamed.lines.join('\n')).toEqual([]);
        });
    }

    it('says why: a header declaration, a macro, a generated variable, a hidden port, a library symbol', async () => {
        const built = await build({ 'a.contract': asyncModule('time', 'EOF'), 's.contract': syncModule('stateindex'), 'b.contract': syncModule('signal').replace('MSA', 'MSB') });
        const messages = reserved(built).join('\n');
        expect(messages).toContain("a.contract:2 'time' cannot name a parameter in the generated C: the C library, POSIX or runtime headers that the generated C includes already declare it.");
        expect(messages).toContain("'EOF' cannot name a port in the generated C: it is a macro of the C library or runtime headers");
        expect(messages).toContain("'stateindex' cannot name a port in the generated C: the generated module.c functions declare a variable of that name, which would hide the port");
        expect(messages).toContain("'signal' cannot name a port in the generated C: the runtime library defines or calls a global of that name");
    });

    it('checks datatypes, functions and their derived names at file scope', async () => {
        const built = await build({
            't.contract': `${TYPES}datatype tm {int a};\ndatatype arg1 {int a};\nfunction void printf(int a);\nfunction bool get_Pose(Pose a);\nfunction void contract_log(int a);\n`
        });
        const messages = reserved(built);
        expect(messages.map((m) => m.split(' ')[0] + ' ' + m.split("'")[1])).toEqual([
            't.contract:3 tm', 't.contract:4 arg1', 't.contract:5 printf', 't.contract:6 get_Pose', 't.contract:7 contract_log'
        ]);
        expect(messages[3]).toContain('it is the name of a function generated for datatype Pose (common/SharedPose.h)');
    });

    it('a datatype may not take the name of a ModuleMain local (sizeof(argv) would measure the parameter)', async () => {
        const built = await build({ 't.contract': 'datatype argv {int a};\ndatatype stateindex {int a};\ndatatype Argv {int a};\n' });
        const messages = reserved(built);
        expect(messages.map((m) => m.split("'")[1])).toEqual(['argv', 'stateindex']);
        expect(messages[0]).toContain('which would hide the type where the generated code takes its size (sizeof)');
    });

    it("the runtime's name spaces are reserved, names that only look alike are not", async () => {
        const built = await build({ 't.contract': `${TYPES}datatype ContractInfo {int a};\nfunction void control_get_Pose(Pose a);\nfunction void control_mode(Pose a);\nfunction void contracts(Pose a);\n` });
        expect(reserved(built).map((m) => m.split("'")[1])).toEqual(['ContractInfo', 'control_get_Pose']);
    });

    it('a port may not take the name of a datatype, an argument not the name of a datatype', async () => {
        const built = await build({ 't.contract': `${TYPES}function void move(Pose Pose, Pose to);\n`, 's.contract': `import "t.contract";\n${syncModule('Pose')}` });
        expect(reserved(built).map((m) => m.split(' ')[0]).sort()).toEqual(['s.contract:4', 't.contract:3']);
    });

    it('members only avoid macros: fields, locals and parameters named time or printf are fine', async () => {
        const clean = await build({
            't.contract': 'datatype Stamp {float time = 0.0, string printf, int exit = 0};\n',
            's.contract': 'import "t.contract";\nsupervisor SUP { f(int time = 0) { local { Stamp stateindex; int IUSE = 0; } rules { R: [elapsed=1ms] -> [elapsed=2ms] } } }\n',
            'p.contract': 'periodic schema s(int productionTime = 0) { realtime { PERIOD=10ms; } modules { } }\n'
        });
        expect(reserved(clean), clean.lines.join('\n')).toEqual([]);
        const macros = await build({ 't.contract': 'datatype Stamp {float EOF = 0.0, int NULL = 0};\n' });
        expect(reserved(macros).length).toBe(2);
    });

    it('the quick fix renames the element and its references to the suggestion', async () => {
        const ws = await build({ 'a.contract': syncModule('time'), 'b.contract': 'import "a.contract";\nperiodic schema s() { realtime { PERIOD=10ms; } modules { MSA(); } }\n' });
        const doc = ws.docs.get('a.contract')!;
        const diagnostics = (doc.diagnostics ?? []).filter((d) => d.code === CODE);
        const actions = (await ws.services.lsp.CodeActionProvider!.getCodeActions(doc, {
            textDocument: { uri: doc.uri.toString() }, range: diagnostics[0]!.range, context: { diagnostics }
        })) as CodeAction[];
        expect(actions.map((a) => a.title)).toEqual(["Rename 'time' to 'time_'"]);
        const fixed = applyEdit(ws, actions[0]!.edit!)['a.contract']!;
        expect(fixed).toBe(syncModule('time_'));
        const again = await build({ 'a.contract': fixed });
        expect(reserved(again)).toEqual([]);
    });

    it('the quick fix renames a datatype whose common/ header would clash', async () => {
        const ws = await build({ 't.contract': 'datatype Pose {float x};\ndatatype POSE {int y};\n' });
        const doc = ws.docs.get('t.contract')!;
        const diagnostics = (doc.diagnostics ?? []).filter((d) => d.code === 'identifier-generated-clash');
        const actions = (await ws.services.lsp.CodeActionProvider!.getCodeActions(doc, {
            textDocument: { uri: doc.uri.toString() }, range: diagnostics[1]!.range, context: { diagnostics: [diagnostics[1]!] }
        })) as CodeAction[];
        expect(actions.map((a) => a.title)).toEqual(["Rename 'POSE' to 'POSE_'"]);
        const again = await build({ 't.contract': applyEdit(ws, actions[0]!.edit!)['t.contract']! });
        expect(again.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
    });

    it('the quick fix skips a suggestion the rename rules refuse (a sibling already has it)', async () => {
        const ws = await build({ 'a.contract': 'synchronous module MSA {\n    scheduling { C=1ms; }\n    data flows { out :0 int time; out :1 int time_; }\n}\n' });
        const doc = ws.docs.get('a.contract')!;
        const diagnostics = (doc.diagnostics ?? []).filter((d) => d.code === CODE);
        const actions = (await ws.services.lsp.CodeActionProvider!.getCodeActions(doc, {
            textDocument: { uri: doc.uri.toString() }, range: diagnostics[0]!.range, context: { diagnostics }
        })) as CodeAction[];
        expect(actions.map((a) => a.title)).toEqual(["Rename 'time' to 'time_2'"]);
    });

    it('a rename to a reserved name is refused, with the reason', async () => {
        const ws = await build({ 'a.contract': syncModule('stamp') });
        const model = ws.docs.get('a.contract')!.parseResult.value;
        const node = AstUtils.streamAllContents(model).find((n) => (n as { name?: string }).name === 'stamp')!;
        const index = ws.services.shared.workspace.IndexManager;
        expect(renameProblem(node, 'time', ws.services.Grammar, index)).toBe(
            "'time' cannot name a port in the generated C: the C library, POSIX or runtime headers that the generated C includes already declare it.");
        expect(renameProblem(node, 'timestamp', ws.services.Grammar, index)).toBeUndefined();
    });

    it('a rename of a datatype or function to a name whose common/ header would clash is refused', async () => {
        const ws = await build({ 't.contract': 'datatype Pose {float x};\ndatatype Twist {float v};\nfunction void step(Pose p);\n' });
        const model = ws.docs.get('t.contract')!.parseResult.value;
        const twist = AstUtils.streamAllContents(model).find((n) => (n as { name?: string }).name === 'Twist')!;
        const index = ws.services.shared.workspace.IndexManager;
        expect(renameProblem(twist, 'POSE', ws.services.Grammar, index)).toBe("'POSE' would share the generated include guard SHARED_POSE_H with datatype 'Pose'.");
        expect(renameProblem(twist, 'Functionstep', ws.services.Grammar, index)).toBe("'Functionstep' would share the generated header file common/SharedFunctionstep.h with function 'step'.");
        expect(renameProblem(twist, 'Twist2', ws.services.Grammar, index)).toBeUndefined();
    });

    it('datatypes and functions whose common/ headers would share a file or an include guard', async () => {
        const built = await build({ 't.contract': 'datatype Pose {float x};\ndatatype POSE {int y};\ndatatype FunctionStep {int z};\nfunction void step(Pose p);\nfunction void Move(Pose p);\n' });
        const clashes = built.diagnostics.filter((d) => d.code === 'identifier-generated-clash').map((d) => `${d.line} ${d.message}`);
        expect(clashes).toEqual([
            "1 datatype 'Pose' and datatype 'POSE' would share the generated include guard SHARED_POSE_H: rename one of them (e.g. 'Pose_').",
            "2 datatype 'POSE' and datatype 'Pose' would share the generated include guard SHARED_POSE_H: rename one of them (e.g. 'POSE_').",
            "3 datatype 'FunctionStep' and function 'step' would share the generated header file common/SharedFunctionStep.h: rename one of them (e.g. 'FunctionStep_').",
            "4 function 'step' and datatype 'FunctionStep' would share the generated header file common/SharedFunctionstep.h: rename one of them (e.g. 'step_').",
        ]);
    });

    it('C23 and GNU C keywords are C keywords too (a build with another -std would break on them)', async () => {
        const built = await build({ 't.contract': 'datatype Stamp {int typeof, int nullptr, int asm, int alignas, int thread_local};\n' });
        expect(built.diagnostics.filter((d) => d.code === 'identifier-c-keyword').length).toBe(5);
    });

    it('the tutorial keeps every name of the report', async () => {
        // its names are the report's and its generated C is committed (codegen tests compare it byte for byte)
        const dir = new URL('../../../examples/tutorial/', import.meta.url);
        const files = Object.fromEntries(readdirSync(dir).filter((f) => f.endsWith('.contract')).map((f) => [f, readFileSync(new URL(f, dir), 'utf8')]));
        expect(reserved(await build(files))).toEqual([]);
    });
});

/** New texts of the files after a workspace edit. */
function applyEdit(ws: Built, edit: WorkspaceEdit): Record<string, string> {
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

describe('named constants: macros of common/constants.h in every module.c', () => {
    it('a constant may not take a name of the generated C, of the headers or of the request loop', async () => {
        const names = ['time', 'EOF', 'stateindex', 'MODULE_NAME', 'Type', 'WantedAck', 'fallthrough', 'arg', 'main', 'tm', 'get_Pose', 'near', 'SHARED_X_H', 'contract_k'];
        const built = await build({ 't.contract': TYPES + names.map((n) => `const int ${n} = 1;\n`).join('') });
        const messages = reserved(built).filter((m) => m.includes('cannot name a constant in the generated C: '));
        expect(messages.map((m) => m.split("'")[1])).toEqual(names);
        expect(messages[4]).toContain("'Type' cannot name a constant in the generated C: the generated module.c uses that name after the constants, which are macros there");
        expect(messages[11]).toContain("'near' cannot name a constant in the generated C: it names a function");
        // the function is refused too (either may be renamed)
        expect(reserved(built)).toContainEqual(expect.stringContaining("'near' cannot name a function in the generated C: a named constant has that name"));
    });

    it('a constant is a keyword-checked name; ordinary constant names are accepted', async () => {
        const built = await build({ 't.contract': 'const int double = 1;\nconst int NJOINTS = 6;\nconst float gain = 0.5;\nconst string FRAME = "map";\n' });
        expect(built.diagnostics.filter((d) => d.severity === 'error').map((d) => `${d.line} ${d.code}`)).toEqual(['1 identifier-c-keyword']);
    });

    it("a field, port, parameter, argument or enumeration member's C name that a constant takes is refused", async () => {
        const built = await build({
            't.contract': 'const int x = 1;\nconst int speed = 2;\nconst int gain = 3;\nconst int to = 4;\nconst int Mode_AUTO = 5;\n' +
                'datatype P {float x};\nfunction void move(P to);\nenum Mode { IDLE, AUTO }\n',
            'm.contract': 'import "t.contract";\nasynchronous module MAA {\n    parameters { int gain = 0 :0; }\n    event flows { in :0 int speed; }\n}\n'
        });
        const messages = reserved(built);
        expect(messages.map((m) => m.split(' ')[0]).sort()).toEqual(['m.contract:3', 'm.contract:4', 't.contract:6', 't.contract:7', 't.contract:8']);
        for (const m of messages) expect(m).toContain('a named constant has that name, and constants are macros in the generated C');
        expect(messages.find((m) => m.startsWith('t.contract:8'))).toContain("Member 'AUTO' of enumeration Mode becomes the C name Mode_AUTO");
    });
});

describe("enumeration members' C names (Mode_AUTO) against every other file-scope name", () => {
    const errors = (built: Built) => built.diagnostics.filter((d) => d.severity === 'error').map((d) => `${d.file}:${d.line} ${d.code} ${d.message}`);

    it("two members of two enumerations that make the same C constant (A_B + C and A + B_C) are both refused", async () => {
        const built = await build({ 't.contract': 'enum A_B { C, D }\nenum A { B_C, X }\n' });
        expect(errors(built)).toEqual([
            "t.contract:1 identifier-c-reserved Member 'C' of enumeration A_B becomes the C name A_B_C, which cannot be used: member B_C of enumeration A becomes the same C enumeration constant. Choose another name (e.g. 'C_').",
            "t.contract:2 identifier-c-reserved Member 'B_C' of enumeration A becomes the C name A_B_C, which cannot be used: member C of enumeration A_B becomes the same C enumeration constant. Choose another name (e.g. 'B_C_').",
        ]);
    });

    it('a datatype, an enumeration, a function or a module port or parameter named like a member\'s C name: refused, on both sides where both are names', async () => {
        const built = await build({
            't.contract': 'enum Mode { AUTO, MAN, IDLE }\ndatatype Mode_AUTO { int v };\nenum Mode_MAN { X }\nfunction void Mode_IDLE(int x);\n',
            'm.contract': 'import "t.contract";\nasynchronous module EEE { parameters { Mode p1 :0; int Mode_AUTO_ = 1 :1; } event flows { in :0 int Mode_MAN; } }\n',
        });
        const found = errors(built);
        expect(found.map((e) => e.split(' ').slice(0, 2).join(' ')).sort()).toEqual([
            'm.contract:2 identifier-c-reserved', // the port Mode_MAN
            't.contract:1 identifier-c-reserved', 't.contract:1 identifier-c-reserved', 't.contract:1 identifier-c-reserved', // AUTO, MAN (the port and the enumeration), IDLE
            't.contract:2 identifier-c-reserved', 't.contract:3 identifier-c-reserved', 't.contract:4 identifier-c-reserved',
        ]);
        expect(found).toContain("t.contract:2 identifier-c-reserved 'Mode_AUTO' cannot name a datatype in the generated C: member AUTO of enumeration Mode becomes the C enumeration constant Mode_AUTO, a file-scope name. Choose another name (e.g. 'Mode_AUTO_').");
        expect(found).toContain("t.contract:3 identifier-c-reserved 'Mode_MAN' cannot name an enumeration in the generated C: member MAN of enumeration Mode becomes the C enumeration constant Mode_MAN, a file-scope name. Choose another name (e.g. 'Mode_MAN_').");
        expect(found.find((e) => e.startsWith('m.contract:2'))).toContain("'Mode_MAN' cannot name a port in the generated C: member MAN of enumeration Mode becomes the C enumeration constant Mode_MAN");
        expect(found.find((e) => e.includes("Member 'IDLE'"))).toContain('a function has that name');
        // the member whose C name a port takes is refused too, not only the port
        const ports = await build({ 't.contract': 'enum Gear { LOW, HIGH }\n', 'm.contract': 'import "t.contract";\nasynchronous module EEE { parameters { Gear g :0; int Gear_LOW = 0 :1; } }\n' });
        expect(errors(ports).map((e) => e.split(' ').slice(0, 2).join(' ')).sort()).toEqual(['m.contract:2 identifier-c-reserved', 't.contract:1 identifier-c-reserved']);
        expect(errors(ports).find((e) => e.startsWith('t.contract'))).toContain("Member 'LOW' of enumeration Gear becomes the C name Gear_LOW, which cannot be used: a module port or parameter has that name");
    });

    it('a rename to a name that makes such a clash is refused, whichever side is renamed', async () => {
        const ws = await build({ 't.contract': 'enum Mode { AUTO, MAN }\nenum Gear { LOW }\ndatatype P { int v };\n', 'm.contract': `import "t.contract";\n${syncModule('speed')}` });
        const index = ws.services.shared.workspace.IndexManager;
        const find = (file: string, name: string) => AstUtils.streamAllContents(ws.docs.get(file)!.parseResult.value).find((n) => (n as { name?: string }).name === name)!;
        expect(renameProblem(find('m.contract', 'speed'), 'Mode_AUTO', ws.services.Grammar, index)).toContain('member AUTO of enumeration Mode becomes the C enumeration constant Mode_AUTO');
        expect(renameProblem(find('t.contract', 'P'), 'Gear_LOW', ws.services.Grammar, index)).toContain('member LOW of enumeration Gear');
        expect(renameProblem(find('t.contract', 'LOW'), 'AUTO', ws.services.Grammar, index)).toBeUndefined(); // Gear_AUTO is free
        expect(renameProblem(find('t.contract', 'P'), 'Mode_STOP', ws.services.Grammar, index)).toBeUndefined();
        expect(renameProblem(find('t.contract', 'MAN'), 'P', ws.services.Grammar, index)).toBeUndefined(); // Mode_P: free
    });
});

describe('names made into file names, parameter indexes and durations', () => {
    it('a name of more than 200 characters is refused (its common/ header file name would pass 255 bytes); 200 is fine', async () => {
        const built = await build({ 't.contract': `datatype ${'T'.repeat(201)} {int v};\nfunction void ${'f'.repeat(200)}(int x);\nenum E { ${'M'.repeat(201)} }\n` });
        expect(built.diagnostics.filter((d) => d.severity === 'error').map((d) => `${d.line} ${d.code}`)).toEqual(['1 identifier-too-long', '3 identifier-too-long']);
    });

    it('a parameter port index above 1023 is refused (PARAM_SIZE_IN has one entry per index); event ports may go to 2147483647', async () => {
        const built = await build({ 'm.contract': 'asynchronous module AAA { parameters { int big = 1 :1024; int ok = 1 :1023; } event flows { out :2147483647 int e; } }\n' });
        expect(built.diagnostics.filter((d) => d.severity === 'error').map((d) => `${d.code} ${d.message}`)).toEqual([
            'parameter-index-too-large Parameter port index :1024 is too large: at most 1023. The generated module.c gives the runtime a table of one size per parameter index up to the largest (PARAM_SIZE_IN), so :1024 would make it 1025 entries long.',
        ]);
    });

    it('a duration below the nanosecond is rounded, with a warning saying to what; one that rounds to 0ns is an error', async () => {
        const built = await build({
            'a.contract': 'synchronous module BBB { scheduling { C=1.5ns; } }\n', 'b.contract': 'synchronous module CCC { scheduling { C=0.4ns; } }\n',
            'c.contract': 'synchronous module DDD { scheduling { C=1.5us; } }\n',
        });
        expect(built.diagnostics.filter((d) => d.code.startsWith('time-')).map((d) => `${d.file} ${d.severity} ${d.code} ${d.message}`)).toEqual([
            'a.contract warning time-rounded Duration 1.5ns is not a whole number of nanoseconds: it is rounded to 2ns (durations are whole nanoseconds in the generated C and the runtime).',
            'b.contract error time-not-positive Duration 0.4ns is less than half a nanosecond: durations are whole nanoseconds, and it rounds to 0ns.',
        ]);
    });
});

describe('renames and named constants', () => {
    it('a rename of a constant to a name of the request loop, or of a port to a constant, is refused; a constant keeps its own name', async () => {
        const ws = await build({ 't.contract': 'const int NJOINTS = 6;\n', 'a.contract': `import "t.contract";\n${syncModule('stamp')}` });
        const index = ws.services.shared.workspace.IndexManager;
        const find = (file: string, name: string) => AstUtils.streamAllContents(ws.docs.get(file)!.parseResult.value).find((n) => (n as { name?: string }).name === name)!;
        const constant = find('t.contract', 'NJOINTS');
        expect(renameProblem(constant, 'Type', ws.services.Grammar, index)).toBe(
            "'Type' cannot name a constant in the generated C: the generated module.c uses that name after the constants, which are macros there.");
        expect(renameProblem(constant, 'NJOINTS', ws.services.Grammar, index)).toBeUndefined();
        expect(renameProblem(constant, 'NAXES', ws.services.Grammar, index)).toBeUndefined();
        expect(renameProblem(find('a.contract', 'stamp'), 'NJOINTS', ws.services.Grammar, index)).toContain(
            "'NJOINTS' cannot name a port in the generated C: a named constant has that name, and constants are macros in the generated C");
    });
});
