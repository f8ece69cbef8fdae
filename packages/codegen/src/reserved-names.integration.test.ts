/**
 * A project that `check` accepts generates C that compiles (docs/language-reference.md, "Reserved
 * names"): random valid projects whose names are drawn also from C library, POSIX, libmodule and
 * generated-code identifiers, C keywords and names whose generated headers would coincide are either
 * refused by `check` with a name-collision code, or generate (regions at their defaults) a tree that gcc compiles with -Werror.
 */
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import fc from 'fast-check';
import { EmptyFileSystem, URI, type LangiumDocument } from 'langium';
import { createCactalServices, type CactalServices, type Model } from '@contract-studio/language';
import { beforeAll, describe, expect, it } from 'vitest';
import { generateFiles } from './generators/generate-files.js';
import { architectureFromModels } from './model/from-langium.js';
import { tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, STRICT_CFLAGS, run } from './test-support/c-toolchain.js';

/** The codes by which `check` refuses a name that would collide in the generated C. */
const COLLISION_CODES = ['identifier-c-reserved', 'identifier-c-keyword', 'identifier-generated-clash'];

/**
 * Risky names, written here independently of the language's lists: the issue's, C library and
 * POSIX names (declared by the included headers or not, gcc built-ins, macros, tags), libmodule
 * and runtime names, variables and tables of the generated C, C keywords that Cactal accepts as names.
 */
const RISKY = [
    'time', 'productionTime', 'receptionTime', 'MODULE_NAME', 'IUSE', 'stateindex', 'printf', 'exit', 'ModuleMain',
    'read', 'write', 'signal', 'index', 'sleep', 'select', 'log', 'abs', 'sin', 'y0', 'errno', 'EOF', 'NULL', 'stdin',
    'stdout', 'FILE', 'size_t', 'tm', 'timespec', 'clock', 'main', 'malloc', 'free', 'strlen', 'memcpy', 'open', 'close',
    'kill', 'random', 'rand', 'getenv', 'system', 'remove', 'rename', 'stat', 'access', 'socket', 'poll', 'BUFSIZ',
    'GetData', 'PostData', 'SendAck', 'RTIME', 'ModuleUse', 'RequestMessage', 'REQ_START', 'ACK_START', 'IPRODUCE',
    'MODULE_PRIORITY', 'get_int', 'fill_string', 'extract_float', 'increment_until_markerfound', 'ControlMain',
    'ContractLog', 'contract_type_long', 'CONTRACT_OK', 'g_rt',
    'receivedMessage', 'registered', 'subscription', 'end', 'state', 'interact', 'argc', 'argv', 'parameterport',
    'sendermodule', 'arg', 'arg1', 'arg2', 'buffer', 'size', 'tmp', 'res', 'symbol', 'description', 'sizeread', 'a',
    'in_ports', 'out_ports', 'functions', 'k_0', 'PARAMS', 'ORD_VOCABULARY', 'SUP_VOCABULARY', 'schema_ps', 'fn_check',
    'call_check', 'get', 'params', 'get_params', 'serialize_Pose', 'SHARED_POSE_H', 'Pose', 'check',
    // common/ headers: the same include guard as datatype TypeT1, the same file as function vfn1
    'TYPET1', 'Functionvfn1', 'FUNCTION_VFN1', 'typeT2',
    'double', 'switch', 'struct', 'while', 'return', 'static', 'volatile', 'goto', 'unsigned',
    // extension types: locals of enumeration headers and array parsers, an enumeration member's C name
    // (`increment` + `until_markerfound` = tools.h's increment_until_markerfound), loop variables
    'i', 'm', 'n', 'next', 'value', 'names', 'dst', 'i0', 'increment', 'until_markerfound', 'type_long',
    // named constants are macros in every module.c: members of the request loop's messages, gcc attributes
    'Type', 'Param', 'WantedAck', 'fallthrough', 'x',
];

/** Every place a project below takes a name (plain names `v<slot>` unless a run overrides a few). */
const SLOTS = [
    'T1', 'T2', 'f1a', 'f1b', 'f1c', 'f2a', 'f2b', 'fn1', 'fn2', 'a1', 'a2', 'b1', 'p0', 'p1', 'p2', 'q0', 'q1', 'q2',
    'r0', 'r1', 'r2', 'r3', 'PS', 'ES', 'sp', 'ep', 's0', 's1', 'sf', 'fp', 'l0', 'l1', 'R', 'E1', 'em1', 'em2', 'f1d', 'K'
] as const;
type Names = Record<(typeof SLOTS)[number], string>;

/** A valid project using every kind of name: datatypes, functions, modules, schemas, scheduler, supervisor. */
function project(n: Names): Record<string, string> {
    const imp = (...files: string[]) => files.map((f) => `import "${f}.contract";\n`).join('');
    return {
        'types.contract': `enum ${n.E1} {${n.em1}, ${n.em2}};\nconst int ${n.K} = 1;\n` +
            `datatype ${n.T1} {float ${n.f1a} = 0.0, string ${n.f1b}, int ${n.f1c} = ${n.K}, ${n.E1}[2] ${n.f1d} = {${n.E1}.${n.em2}, ${n.E1}.${n.em1}}};\n` +
            `datatype ${n.T2} {${n.T1} ${n.f2a}, int ${n.f2b}};\n` +
            `function bool ${n.fn1}(${n.T1} ${n.a1}, int ${n.a2});\nfunction void ${n.fn2}(string ${n.b1});\n`,
        'msa.contract': `${imp('types')}synchronous module MSA {\n    scheduling { C=1ms; }\n` +
            `    data flows { out :0 ${n.T1} ${n.p0}; out :1 int ${n.p1}; }\n    event flows { out :0 string ${n.p2}; }\n}\n`,
        'msb.contract': `${imp('types')}synchronous module MSB {\n    scheduling { C=1ms; }\n` +
            `    data flows { in :0 ${n.T1} ${n.q0}; in :1 int ${n.q1}; out :0 float ${n.q2}; }\n}\n`,
        'maa.contract': `${imp('types')}asynchronous module MAA {\n    parameters { ${n.T2} ${n.r0} :0; int ${n.r1} = 0 :1; }\n` +
            `    event flows { in :0 string ${n.r2}; out :0 ${n.T1} ${n.r3}; }\n}\n`,
        'ps.contract': `${imp('msa', 'msb')}periodic schema ${n.PS}(int ${n.sp} = 1) {\n    realtime { PERIOD=10ms; CRITICAL_DELAY=5ms; }\n` +
            `    modules { MSA (); MSB (); }\n    scheduling graph { MSA -> MSB; }\n    communications { MSA:0 -> MSB:0 * 1; }\n}\n`,
        'es.contract': `${imp('maa')}event schema ${n.ES}(int ${n.ep} = 1) {\n    modules { MAA (${n.ep} :1); }\n}\n`,
        'sched.contract': `${imp('msa', 'msb', 'ps')}scheduler configuration {\n    modules { MSA; MSB; }\n    schemas { ${n.PS}; }\n}\n`,
        'sup.contract': `${imp('types', 'msa', 'maa', 'ps', 'es', 'sched')}supervisor SUP {\n` +
            `    event flows { in :0 string ${n.s0}; in :1 ${n.T1} ${n.s1}; }\n` +
            `    ${n.sf}(int ${n.fp} = 0) {\n        local { ${n.T1} ${n.l0}; int ${n.l1} = ${n.fp}; }\n        rules {\n` +
            `            ${n.R}: [elapsed=1ms]\n                subscribe MSA:0 =* :0; subscribe MAA:0 =* :1; activate schema ${n.PS}(${n.sp} = ${n.l1}); ` +
            `activate schema ${n.ES}(); compute ${n.fn2}("x")\n` +
            `                [MSA:0<${n.s0} == "a" | ${n.fn1}(${n.l0}, ${n.l1}) | ${n.s1}.${n.f1d}[1] == ${n.E1}.${n.em2}>]\n        }\n    }\n}\n`
    };
}

const plainNames = (): Names => Object.fromEntries(SLOTS.map((s) => [s, s.startsWith('T') ? `Type${s}` : s === 'E1' ? 'Mode' : s === 'K' ? 'NK' : `v${s}`])) as Names;

async function check(services: CactalServices, files: Record<string, string>) {
    const shared = services.shared;
    const previous = shared.workspace.LangiumDocuments.all.map((d) => d.uri).toArray();
    if (previous.length) await shared.workspace.DocumentBuilder.update([], previous);
    const docs: LangiumDocument<Model>[] = [];
    for (const [file, text] of Object.entries(files)) {
        const doc = shared.workspace.LangiumDocumentFactory.fromString<Model>(text, URI.parse(`file:///ws/${file}`));
        shared.workspace.LangiumDocuments.addDocument(doc);
        docs.push(doc);
    }
    await shared.workspace.DocumentBuilder.build(docs, { validation: true });
    const errors = docs.flatMap((d) => (d.diagnostics ?? []).filter((x) => x.severity === 1).map((x) => ({ code: String(x.code), message: `${d.uri.path}:${x.range.start.line + 1} ${x.code} ${x.message}` })));
    return { docs, errors };
}

/** Generates the tree with regions at their defaults and compiles every C file with gcc -fsyntax-only -Werror (throws gcc's messages). */
function compileGenerated(docs: LangiumDocument<Model>[]): void {
    const { dir, cleanup } = tempDir('codegen-names-');
    try {
        const files = generateFiles(architectureFromModels(docs.map((d) => d.parseResult.value)));
        const sources: string[] = [];
        for (const f of files) {
            const path = join(dir, f.path);
            mkdirSync(dirname(path), { recursive: true });
            writeFileSync(path, f.content);
            if (path.endsWith('.c')) sources.push(path);
        }
        const arch = join(dir, 'generated', 'architecture');
        run('gcc', ['-fsyntax-only', ...STRICT_CFLAGS, `-I${RUNTIME_DIR}/include`, `-I${join(arch, 'common')}`, ...sources]);
    } finally {
        cleanup();
    }
}

describe('names in the generated C', () => {
    let services: CactalServices;
    beforeAll(() => { services = createCactalServices(EmptyFileSystem).Cactal; });

    it('the plain project checks clean and compiles (the property starts from a valid project)', async () => {
        const { docs, errors } = await check(services, project(plainNames()));
        expect(errors.map((e) => e.message)).toEqual([]);
        compileGenerated(docs);
    }, 60_000);

    it('property: a project with risky names is refused with a collision code, or its generated C compiles', async () => {
        let accepted = 0;
        let refused = 0;
        const overrides = fc.uniqueArray(fc.tuple(fc.constantFrom(...SLOTS), fc.constantFrom(...RISKY)), { minLength: 1, maxLength: 4, selector: ([slot]) => slot })
            .filter((pairs) => new Set(pairs.map(([, name]) => name)).size === pairs.length);
        await fc.assert(fc.asyncProperty(overrides, async (pairs) => {
            const names = plainNames();
            for (const [slot, name] of pairs) names[slot] = name;
            const { docs, errors } = await check(services, project(names));
            if (errors.length > 0) {
                refused++;
                // only the names may be wrong: the project is otherwise valid
                expect(errors.filter((e) => !COLLISION_CODES.includes(e.code)).map((e) => e.message)).toEqual([]);
                return;
            }
            accepted++;
            compileGenerated(docs);
        }), { numRuns: 30 });
        // both outcomes occur at this size (about a third accepted): the compile side is exercised
        expect(accepted).toBeGreaterThan(0);
        expect(refused).toBeGreaterThan(0);
    }, 120_000);

    // the names of the issue: refused where they collide (module ports and parameters), kept where
    // the generated C keeps them apart (struct fields, locals, parameters), and then the tree compiles
    const ISSUE_NAMES = ['time', 'productionTime', 'receptionTime', 'MODULE_NAME', 'IUSE', 'stateindex', 'printf', 'exit', 'ModuleMain'] as const;
    const MEMBER_SLOTS = ['f1a', 'f2b', 'a2', 'b1', 'sp', 'l1', 'R'] as const;
    const PORT_SLOTS = ['p1', 'q1', 'r1'] as const;

    for (const name of ISSUE_NAMES) {
        it(`'${name}': refused as a module port or parameter, compiles as a field, argument, schema parameter, local, rule label`, async () => {
            for (const slot of PORT_SLOTS) {
                const names = plainNames();
                names[slot] = name;
                const { errors } = await check(services, project(names));
                expect(errors.map((e) => e.code), `${name} as ${slot}`).toEqual(['identifier-c-reserved']);
            }
            const names = plainNames();
            for (const slot of MEMBER_SLOTS) names[slot] = name;
            const { docs, errors } = await check(services, project(names));
            expect(errors.map((e) => e.message)).toEqual([]);
            compileGenerated(docs);
        }, 60_000);
    }

    it('enumerations: a member whose C name <Enum>_<member> is taken, or an enumeration named like a local of its functions, is refused; other members compile', async () => {
        for (const [over, code] of [[{ E1: 'increment', em1: 'until_markerfound' }, 'identifier-c-reserved'], [{ E1: 'm' }, 'identifier-c-reserved'], [{ E1: 'contract' }, 'identifier-c-reserved']] as const) {
            const { errors } = await check(services, project({ ...plainNames(), ...over }));
            expect(errors.map((e) => e.code), JSON.stringify(over)).toContain(code);
            expect(errors.filter((e) => !COLLISION_CODES.includes(e.code))).toEqual([]);
        }
        // members are prefixed in C (Mode_double, Mode_time): C keywords and library names are fine as members
        const { docs, errors } = await check(services, project({ ...plainNames(), em1: 'double', em2: 'time' }));
        expect(errors.map((e) => e.message)).toEqual([]);
        compileGenerated(docs);
    }, 60_000);

    it('a constant, a macro in every module.c, cannot take any name that a generated module.c writes after including it', async () => {
        const plain = await check(services, project(plainNames()));
        expect(plain.errors).toEqual([]);
        const words = new Set<string>();
        for (const f of generateFiles(architectureFromModels(plain.docs.map((d) => d.parseResult.value)))) {
            if (!f.path.endsWith('/module.c') || !f.content.includes('#include "constants.h"')) continue;
            const after = f.content.slice(f.content.indexOf('#include "constants.h"') + 22)
                .replace(/\/\*[\s\S]*?\*\//g, ' ').replace(/\/\/[^\n]*/g, ' ').replace(/"(?:\\.|[^"\\])*"/g, ' ');
            for (const m of after.matchAll(/\b[A-Za-z][A-Za-z0-9_]*\b/g)) words.add(m[0]);
        }
        expect(words.has('WantedAck') && words.has('stateindex') && words.has('vp0')).toBe(true);
        const cKeywords = new Set(['break', 'case', 'char', 'const', 'default', 'else', 'extern', 'if', 'int', 'return', 'sizeof', 'switch', 'void', 'while', 'double', 'long', 'unsigned', 'for', 'static']);
        const candidates = [...words].filter((w) => !cKeywords.has(w) && w !== plainNames().K).sort();
        const files = project(plainNames());
        files['types.contract'] += candidates.map((w) => `const int ${w} = 2;\n`).join('');
        const { errors } = await check(services, files);
        expect(errors.filter((e) => ![...COLLISION_CODES, 'type-duplicate-name'].includes(e.code)).map((e) => e.message)).toEqual([]);
        // every candidate is refused, as the constant or as the element whose name it takes
        const unrefused = candidates.filter((w) => !errors.some((e) => e.message.includes(`'${w}'`) || e.message.includes(`C name ${w},`)));
        expect(unrefused).toEqual([]);
    }, 60_000);

    it("vocabulary tables keep clear of the user's datatypes, functions and their generated functions", async () => {
        // a supervision function `get` has a parameter table `get_params`: the parser of datatype `params`;
        // a datatype and functions named like a supervisor's tables (`in_ports`, `functions`, `fn_<f>`)
        const names = { ...plainNames(), T1: 'params', T2: 'in_ports', sf: 'get', fn1: 'functions', fn2: 'fn_functions' };
        const { docs, errors } = await check(services, project(names));
        expect(errors.map((e) => e.message)).toEqual([]);
        compileGenerated(docs);
    }, 60_000);
});
