/** Cross-file linking through direct imports, ports by index, members, variables and field paths. */
import { AstUtils, EmptyFileSystem, type AstNode, type Reference } from 'langium';
import { beforeAll, describe, expect, it } from 'vitest';
import { createCactalServices, type CactalServices } from '../src/cactal-module.js';
import { isModule, isPort, isSchema, isSupervisor, type Model, type Supervisor } from '../src/generated/ast.js';
import { build, TYPES, type Built } from './helpers.js';

const FILES = {
    'common/types.contract': TYPES,
    'modules/msc.contract': `import "../common/types.contract";
synchronous module MSC {
    parameters { TypeA param = {2.1,6.98,5.34} :0; }
    scheduling { C=1ms; }
    data flows { in :0 TypeA in_coordinates; out :1 TypeB out_cmd; }
    event flows { out :1 TypeD failing_data; }
}`,
    'modules/msd.contract': `import "../common/types.contract";
synchronous module MSD { scheduling { C=1ms; } data flows { in :2 TypeB in_cmd; out :1 TypeA in_cmd_copy; } }`,
    'modules/maa.contract': `import "../common/types.contract";
asynchronous module MAA { event flows { out :0 TypeC note; out :2 string status; } }`,
    'schemas/s1.contract': `import "../common/types.contract";
import "../modules/msc.contract";
import "../modules/msd.contract";
periodic schema s1(TypeA consigne = {0.0, 0.0, 0.0}) {
    realtime { PERIOD=1s; CRITICAL_DELAY=1s; }
    modules { MSC (consigne:0); MSD (); }
    scheduling graph { MSC -> MSD; }
    communications { MSC:1 -> MSD :2 * 2; }
}`,
    'sched.contract': `import "modules/msc.contract";
import "modules/msd.contract";
import "schemas/s1.contract";
scheduler configuration { modules { MSC; MSD; } schemas { s1; } }`,
    'sup.contract': `import "common/types.contract";
import "modules/msc.contract";
import "modules/maa.contract";
import "schemas/s1.contract";
supervisor SUP {
    event flows { in :1 TypeC message_received; in :2 string status; in :3 TypeD failure; out :1 string out_status; }
    action(TypeA consigne) {
        local { TypeC temp_message; TypeA temp = consigne; TypeD fd; }
        rules {
            FIRST: [elapsed=1ms]
                subscribe MAA:2 =* :2; subscribe MAA:0 =* :1; subscribe MSC:1 => :3
                [MAA:2<status == "disconnected">]
            SECOND: [(MAA:0<(temp_message.value.i > 3)>(temp_message = message_received) and started(FIRST){infinite})]
                activate schema s1(consigne = temp);
                parameterize MSC(temp_message.value :0);
                notify :1 (out_status = "x")
                [endof(FIRST)]
        }
    }
}`,
    'glb.contract': `import "common/types.contract";
import "sup.contract";
supervisor GLB { event flows { in :0 string s; } mission(TypeA c) { local { TypeA cc = c; } rules {
    ONLY: [elapsed=1ms] subscribe SUP:1 => :0; activate supervisor SUP.action(consigne = cc) [SUP:1<s == "x">]
} } }`
};

function refs(root: AstNode): Array<{ text: string; target?: AstNode; property: string; container: string }> {
    const out: Array<{ text: string; target?: AstNode; property: string; container: string }> = [];
    for (const node of AstUtils.streamAst(root)) {
        for (const info of AstUtils.streamReferences(node)) {
            const ref = info.reference as Reference;
            out.push({ text: ref.$refText, target: ref.ref, property: info.property, container: node.$type });
        }
    }
    return out;
}

describe('cross-file linking', () => {
    let built: Built;
    let services: CactalServices;
    beforeAll(async () => {
        services = createCactalServices(EmptyFileSystem).Cactal;
        built = await build(FILES, services);
    });

    it('resolves every reference of the project with no diagnostics', () => {
        expect(built.lines).toEqual([]);
        for (const doc of built.docs.values()) {
            const unresolved = refs(doc.parseResult.value).filter((r) => !r.target);
            expect(unresolved).toEqual([]);
        }
    });

    it('resolves port indexes in the context of module, kind and direction', () => {
        const schema = (built.docs.get('schemas/s1.contract')!.parseResult.value as Model).elements[0]!;
        expect(isSchema(schema)).toBe(true);
        const r = refs(schema);
        const src = r.find((x) => x.property === 'sourcePort')!.target;
        const dst = r.find((x) => x.property === 'targetPort')!.target;
        expect(isPort(src) && `${src.direction}:${src.index}:${src.name}`).toBe('out:1:out_cmd');
        expect(isPort(dst) && `${dst.direction}:${dst.index}:${dst.name}`).toBe('in:2:in_cmd');
        const param = r.find((x) => x.container === 'ParameterSetting')!.target as unknown as { name: string };
        expect(param.name).toBe('param');
        const variable = r.find((x) => x.container === 'VariableRef')!.target as { $type: string; name: string };
        expect(`${variable.$type}:${variable.name}`).toBe('SchemaParameter:consigne');
    });

    it('resolves supervisor references: ports, labels, locals, fields, schema and function parameters', () => {
        const sup = (built.docs.get('sup.contract')!.parseResult.value as Model).elements[0] as Supervisor;
        const r = refs(sup);
        const describe = (x: { target?: AstNode }) => {
            const t = x.target as AstNode & { name?: string; index?: number };
            const owner = AstUtils.getContainerOfType(t, (n): n is AstNode & { name: string } => isModule(n) || isSupervisor(n));
            return isPort(t) ? `${owner?.name}.${t.direction}:${t.index}` : `${t.$type}:${t.name}`;
        };
        const subscribes = r.filter((x) => x.container === 'Subscribe' && x.property !== 'source').map(describe);
        expect(subscribes).toEqual(['MAA.out:2', 'SUP.in:2', 'MAA.out:0', 'SUP.in:1', 'MSC.out:1', 'SUP.in:3']);
        expect(r.filter((x) => x.container === 'Notify').map(describe)).toEqual(['SUP.out:1']);
        expect(r.filter((x) => x.container === 'StartedEvent' || x.container === 'EndofEvent').map(describe)).toEqual(['Rule:FIRST', 'Rule:FIRST']);
        expect(r.filter((x) => x.container === 'FieldSegment').map(describe)).toEqual(['Field:value', 'Field:i', 'Field:value']);
        expect(r.filter((x) => x.container === 'SchemaArgument').map(describe)).toEqual(['SchemaParameter:consigne']);
        const vars = r.filter((x) => x.container === 'VariableRef').map(describe);
        expect(vars).toContain('SUP.in:2'); // status
        expect(vars).toContain('SUP.in:1'); // message_received
        expect(vars).toContain('LocalVariable:temp_message');
        expect(vars).toContain('FunctionParameter:consigne');
        const paramPort = r.find((x) => x.container === 'ParameterSetting')!;
        expect(describe(paramPort)).toBe('Parameter:param');
    });

    it('resolves a supervisor function and its parameters across files', () => {
        const glb = (built.docs.get('glb.contract')!.parseResult.value as Model).elements[0]!;
        const r = refs(glb);
        const names = r.map((x) => `${x.container}.${x.property}->${(x.target as { name?: string } | undefined)?.name}`);
        expect(names).toContain('ActivateSupervisor.supervisor->SUP');
        expect(names).toContain('ActivateSupervisor.function->action');
        expect(names).toContain('FunctionArgumentAssignment.parameter->consigne');
    });

    it('does not make imports transitive', async () => {
        const b = await build({
            'a.contract': 'datatype A {int x};',
            'b.contract': 'import "a.contract";\ndatatype B {A a};',
            'c.contract': 'import "b.contract";\ndatatype C {B b, A a};'
        }, services);
        const cDiags = b.diagnostics.filter((d) => d.file === 'c.contract');
        expect(cDiags.map((d) => d.code)).toEqual(['import-not-imported']);
        expect(cDiags[0]!.data).toMatchObject({ importPath: 'a.contract' });
    });

    it('computes import paths relative to the importing file for the quick fix', async () => {
        const b = await build({
            'common/types.contract': 'datatype A {int x};',
            'modules/m.contract': 'synchronous module MSA { scheduling { C=1ms; } data flows { out :0 A a; } }'
        }, services);
        expect(b.diagnostics.map((d) => [d.code, (d.data as { importPath?: string }).importPath])).toEqual([['import-not-imported', '../common/types.contract']]);
    });

    it('says that a supervisor named in an event schema is no module, and who receives its events', async () => {
        const b = await build({
            'm.contract': 'asynchronous module MAB { event flows { in :0 string note; } }',
            's.contract': 'supervisor SUP { event flows { out :1 string mode; } f() { rules { R: [elapsed=1ms] notify :1(mode = "x") [elapsed=2ms] } } }',
            'e.contract': 'import "m.contract";\nimport "s.contract";\nevent schema ES () { modules { MAB (); } communications { SUP:1 =* MAB:0; } }'
        }, services);
        const linking = b.lines.filter((l) => l.includes('linking-error'));
        expect(linking).toEqual([expect.stringContaining("linking-error 'SUP' is a supervisor, not a module: ")]);
        expect(linking[0]).toContain('reach only the supervisors that subscribe to them (subscribe SUP:o =* :i in a rule)');
        // an unknown name that is no supervisor keeps the message it had
        const other = await build({
            'm.contract': 'asynchronous module MAB { event flows { in :0 string note; } }',
            'e.contract': 'import "m.contract";\nevent schema ES () { modules { MAB (); } communications { ZZZ:1 =* MAB:0; } }'
        }, services);
        expect(other.lines.filter((l) => l.includes('linking-error'))).toEqual([expect.stringContaining("Unknown module 'ZZZ': no module of this name")]);
    });

    it('offers the closest name for a misspelt module, supervisor, parameter or rule label', async () => {
        const b = await build({
            'm.contract': 'asynchronous module MAB { event flows { out :0 string note; } }',
            's.contract': 'import "m.contract";\nsupervisor SUP { event flows { in :0 string n; } f(float speed = 1.0) { rules { R: [elapsed=1ms] subscribe MBA:0 =* :0 [endof(RR)] } } }',
            'g.contract': 'import "s.contract";\nsupervisor GLB { g() { rules { G: [elapsed=1ms] activate supervisor SUP.f(sped = 2.0) [elapsed=2ms] } } }'
        }, services);
        const linking = b.lines.filter((l) => l.includes('linking-error'));
        expect(linking).toEqual(expect.arrayContaining([
            expect.stringMatching(/Unknown module or supervisor 'MBA': .* Did you mean 'MAB'\?$/),
            expect.stringMatching(/No rule labelled 'RR' in function f; its labels: R\. Did you mean 'R'\?$/),
            expect.stringMatching(/Function f has no parameter 'sped'; its parameters: speed\. Did you mean 'speed'\?$/),
        ]));
    });

    it('offers the closest of the names valid where an unknown variable is, ord_schema in an ORD event', async () => {
        const b = await build({
            'm.contract': 'asynchronous module MAB { event flows { out :0 string note; } }',
            'c.contract': 'enum Mode { AUTO, MANUAL };\nconst int LIMIT = 3;',
            's.contract': `import "m.contract";
import "c.contract";
supervisor SUP {
    event flows { in :0 string status; out :1 string report; }
    f(string consigne = "x") {
        local { string late; string goal = consgine; }
        rules {
            R1: [ORD:0(late = ord_shema)] subscribe MAB:0 =* :0 [ORD:1<ord_shema == "s">]
            R2: [MAB:0<stauts == "x">] notify :1(reprot = late) [MAB:0(lat = status)]
            R3: [MAB:0<ord_shema == "x">] [MAB:0<status == LIMTI>]
            R4: [MAB:0<status == Mdoe.AUTO>] [elapsed=1ms]
        }
    }
}`
        }, services);
        const message = (written: string) => b.diagnostics.filter((d) => d.code === 'linking-error' && d.message.includes(`'${written}'`)).map((d) => d.message);
        const ord = "in this ORD event, also 'ord_schema' (the name of the schema it is about).";
        // in an ORD event's extracted value and its test: said, and suggested
        expect(message('ord_shema').slice(0, 2)).toEqual([
            `Unknown variable 'ord_shema': rules use the locals of f, the event-port variables of its supervisor and constants; ${ord} Did you mean 'ord_schema'?`,
            `Unknown variable 'ord_shema': rules use the locals of f, the event-port variables of its supervisor and constants; ${ord} Did you mean 'ord_schema'?`
        ]);
        // in another event: neither said nor suggested
        expect(message('ord_shema')[2]).toBe("Unknown variable 'ord_shema': rules use the locals of f, the event-port variables of its supervisor and constants.");
        // an event-port variable (two letters swapped), a constant, an enumeration, a parameter in a local's initial value
        expect(message('stauts')).toEqual([expect.stringMatching(/^Unknown variable 'stauts': rules use .*\. Did you mean 'status'\?$/)]);
        expect(message('LIMTI')).toEqual([expect.stringMatching(/\. Did you mean 'LIMIT'\?$/)]);
        expect(message('Mdoe')).toEqual([expect.stringMatching(/\. Did you mean 'Mode'\?$/)]);
        expect(message('consgine')).toEqual(["Unknown variable 'consgine': a local is initialised from constants and the parameters of f (consigne). Did you mean 'consigne'?"]);
        // an extraction's target is a local; a notify's, the variable of its port
        expect(message('lat')).toEqual(["Unknown variable 'lat': an extraction assigns a local of f (late, goal). Did you mean 'late'?"]);
        expect(message('reprot')).toEqual(["Unknown variable 'reprot': notify :1 assigns the variable of that port, 'report'. Did you mean 'report'?"]);
    });

    it('reports a port of the wrong direction as unresolved with the valid ports', async () => {
        const files = { ...FILES, 'schemas/s1.contract': FILES['schemas/s1.contract'].replace('MSC:1 -> MSD :2', 'MSC:0 -> MSD :2') };
        const b = await build(files, services);
        expect(b.lines.some((l) => l.includes('linking-error MSC has no output data port 0; its output data ports: :1 out_cmd.'))).toBe(true);
    });

    it('reports an unknown module once, not again for its port indexes', async () => {
        const b = await build({
            't.contract': TYPES,
            's.contract': 'import "t.contract";\nsupervisor SUX { event flows { in :0 TypeD a; } f() { local { TypeD l; } rules { R: [elapsed=1ms] subscribe MZZ:0 =* :0 [MZZ:0(l = a)] } } }'
        }, services);
        expect(b.diagnostics.map((d) => `${d.code} ${d.message}`)).toEqual([
            "linking-error Unknown module or supervisor 'MZZ': no module or supervisor of this name is defined in this file or in a file it imports.",
            "linking-error Unknown module or supervisor 'MZZ': no module or supervisor of this name is defined in this file or in a file it imports."
        ]);
    });
});
