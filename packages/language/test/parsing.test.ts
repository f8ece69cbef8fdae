import { describe, expect, it } from 'vitest';
import {
    isActivateModule, isActivateSchema, isActivateSupervisor, isCompute, isDataCommunication, isDataType,
    isDurationEvent, isElapsedEvent, isEndofEvent, isEqualityTest, isEventCommunication, isFunctionPrototype,
    isFunctionTest, isIntLiteral, isModule, isModuleEvent, isNotify, isParameterize, isRealLiteral,
    isRelationalTest, isSchedulerConfiguration, isSchema, isStartedEvent, isStringLiteral, isStructValue,
    isSubscribe, isSupervisor, isVariableRef,
    type DataType, type Module, type Schema, type Supervisor
} from '../src/generated/ast.js';
import { parse } from './helpers.js';

function parseOk(text: string) {
    const r = parse(text);
    expect(r.errors).toEqual([]);
    return r.model;
}

describe('parsing: files, imports, datatypes, values, functions (§2.1, §2.2)', () => {
    it('parses imports, comments and datatypes with every value form', () => {
        const model = parseOk(`
            import "a.contract"; import "dir/b.contract"
            // line comment
            /* block
               comment */
            datatype T {int a = -3, float b = -1.5, float c = 2., float d = 1e-3, float e = .5, string s = "x\\"y", int z};
            datatype U {T t = {1, 2.0, 3., 4e2, 0.5, "s", 0}, T u};
        `);
        expect(model.imports.map((i) => i.path)).toEqual(['a.contract', 'dir/b.contract']);
        const [t, u] = model.elements as DataType[];
        expect(t!.fields.map((f) => f.name)).toEqual(['a', 'b', 'c', 'd', 'e', 's', 'z']);
        const values = t!.fields.map((f) => f.value);
        expect(isIntLiteral(values[0]) && values[0].value).toBe(-3);
        expect(isRealLiteral(values[1]) && values[1].value).toBe(-1.5);
        expect(isRealLiteral(values[2]) && values[2].value).toBe(2);
        expect(isRealLiteral(values[3]) && values[3].value).toBe(0.001);
        expect(isRealLiteral(values[4]) && values[4].value).toBe(0.5);
        expect(isStringLiteral(values[5]) && values[5].value).toBe('x"y');
        expect(values[6]).toBeUndefined();
        const nested = u!.fields[0]!.value;
        expect(isStructValue(nested) && nested.elements.length).toBe(7);
        expect(u!.fields[0]!.type.datatype?.$refText).toBe('T');
    });

    it('parses function prototypes with primitive and datatype arguments', () => {
        const model = parseOk('function bool testit(string arg1, TypeA arg2);\nfunction void doit();');
        const [f, g] = model.elements;
        expect(isFunctionPrototype(f) && f.returnType.primitive).toBe('bool');
        expect(isFunctionPrototype(f) && f.args.map((a) => a.type.primitive ?? a.type.datatype?.$refText)).toEqual(['string', 'TypeA']);
        expect(isFunctionPrototype(g) && g.args).toEqual([]);
    });
});

describe('parsing: modules (§2.3)', () => {
    it('parses a synchronous module with all blocks and time literals', () => {
        const model = parseOk(`synchronous module MSC {
            parameters { TypeA param = {2.1,6.98,5.34} :0; int gain :1; }
            scheduling { C=500us; }
            data flows { in :0 TypeA in_coordinates; out :1 TypeB out_cmd = {{1.0,1.0,1.0}, 1}; }
            event flows { out :1 TypeD failing_data; }
        }`);
        const m = model.elements[0] as Module;
        expect(m.kind).toBe('synchronous');
        expect(m.blocks.map((b) => b.$type)).toEqual(['ParametersBlock', 'SchedulingBlock', 'DataFlowsBlock', 'EventFlowsBlock']);
        const ports = m.blocks.flatMap((b) => ('ports' in b ? b.ports : []));
        expect(ports.map((p) => `${p.direction}:${p.index}:${p.name}`)).toEqual(['in:0:in_coordinates', 'out:1:out_cmd', 'out:1:failing_data']);
        const sched = m.blocks[1]!;
        expect('properties' in sched && sched.properties[0]!.value.text).toBe('500us');
    });

    it('parses blocks in any order and asynchronous modules with forbidden blocks (reported by validation)', () => {
        const model = parseOk(`asynchronous module MAA {
            event flows { in :0 string controlevent; out :0 TypeC notif; }
            data flows { out :0 int x; }
            scheduling { C=1.5ms; }
            parameters { TypeA param = {22.12,6.98,897.34} :0; }
        }`);
        expect((model.elements[0] as Module).blocks.map((b) => b.$type)).toEqual(['EventFlowsBlock', 'DataFlowsBlock', 'SchedulingBlock', 'ParametersBlock']);
    });

    it('accepts ORD and lower-case names syntactically (validation reports them)', () => {
        const model = parseOk('synchronous module ORD { scheduling { C=1s; } }\nsupervisor abc { }');
        expect(isModule(model.elements[0]) && model.elements[0].name).toBe('ORD');
        expect(isSupervisor(model.elements[1]) && model.elements[1].name).toBe('abc');
    });
});

describe('parsing: schemas and scheduler configuration (§2.4, §2.5)', () => {
    it('parses a periodic schema with the report spellings', () => {
        const model = parseOk(`periodic schema schemaCommande1(TypeA consigne = {0.0, 0.0, 0.0}, int n) {
            realtime { PERIOD=1s; CRITICAL_DELAY=1s; }
            modules { MSA (); MSC (consigne:0, consigne.i :1, {1.0,2.0,3.0} :2); MSD (); }
            scheduling graph { MSA -> MSC; MSC -> MSD; }
            communications { MSA:0 -> MSC:0 * 1; MSC:1 -> MSD :2 * 2; MSA:1->MSD:3; }
        }`);
        const s = model.elements[0] as Schema;
        expect(s.kind).toBe('periodic');
        expect(s.parameters.map((p) => p.name)).toEqual(['consigne', 'n']);
        const comms = s.blocks.flatMap((b) => ('communications' in b ? b.communications : []));
        expect(comms.every(isDataCommunication)).toBe(true);
        expect(comms.map((c) => isDataCommunication(c) && `${c.source.$refText}:${c.sourcePort.$refText}->${c.target.$refText}:${c.targetPort.$refText}*${c.periodicity ?? 1}`))
            .toEqual(['MSA:0->MSC:0*1', 'MSC:1->MSD:2*2', 'MSA:1->MSD:3*1']);
        const instances = s.blocks.flatMap((b) => ('instances' in b ? b.instances : []));
        expect(instances[1]!.parameters.map((p) => p.port.$refText)).toEqual(['0', '1', '2']);
    });

    it('parses an event schema with all four event modes', () => {
        const model = parseOk(`event schema recv(TypeA param = {27.12,0.0,0.04}) {
            modules { MAA (param :0); MAB (); }
            communications { MAA:0 =* MAB:0; MAA:1 => MAB:1; MAA:2 ==* MAB:2; MAA:3 ==> MAB:3; }
        }`);
        const s = model.elements[0] as Schema;
        const comms = s.blocks.flatMap((b) => ('communications' in b ? b.communications : []));
        expect(comms.map((c) => isEventCommunication(c) && c.mode)).toEqual(['=*', '=>', '==*', '==>']);
    });

    it('parses the scheduler configuration', () => {
        const model = parseOk('scheduler configuration { modules { MSA; MSB; } schemas { s1; } }');
        const c = model.elements[0];
        expect(isSchedulerConfiguration(c) && c.blocks.map((b) => b.$type)).toEqual(['SchedulerModules', 'SchedulerSchemas']);
    });
});

describe('parsing: supervisors, conditions and actions (§2.6)', () => {
    const text = `supervisor SUP {
        event flows { in :2 string connection_status; in :3 TypeD failure; out :1 string failure_message_type; }
        action(TypeA consigne, int n = 3) {
            local { string temp_mess_type; TypeD failure_data; TypeA temp_consigne = consigne; }
            rules {
                FIRST: [elapsed=1ms]
                    subscribe MAA:2 ==* :2; subscribe MAA:0 ==> :1; subscribe MSC:1=>:3; subscribe MSC:2 =* :4;
                    activate schema schemaReceptionMessage()
                    [MAA:2<connection_status == "disconnected">]
                SECOND: [(MAA:2<(connection_status == "disconnected" & testit("dedede", temp_consigne))> and started(FIRST){infinite})]
                    activate schema schemaCommande1(consigne = temp_consigne, n = 2);
                    [MSC:1(failure_data = failure, temp_mess_type = "commutation")]
                THIRD: [endof(SECOND){10ms} or duration(FIRST)=2s{infinite} or ORD:0<ord_schema != "x">]
                    notify :1(failure_message_type=temp_mess_type);
                    compute doit("1.24", temp_consigne.k);
                    parameterize MSC(temp_consigne.i :0, {1.0,2.0,3.0} :1);
                    activate resttime module MAA; activate critical module MAB;
                    activate supervisor GLB.mission(consigne = temp_consigne)
                    [MSC:1<(failure.datavalue > 3) | (failure.datavalue <= 1) | failure.dataname != "a">{5ms}(failure_data = failure) or elapsed=1s]
                EMPTY: [elapsed=1ms] [elapsed=2ms]
            }
        }
        other() { rules { } }
    }`;

    it('parses every condition and action form', () => {
        const model = parseOk(text);
        const sup = model.elements[0] as Supervisor;
        expect(sup.functions.map((f) => f.name)).toEqual(['action', 'other']);
        const fn = sup.functions[0]!;
        expect(fn.parameters.map((p) => p.name)).toEqual(['consigne', 'n']);
        const rules = fn.rules[0]!.rules;
        expect(rules.map((r) => r.name)).toEqual(['FIRST', 'SECOND', 'THIRD', 'EMPTY']);
        const [first, second, third, empty] = rules;

        expect(first!.actions.map((a) => isSubscribe(a) ? a.mode : a.$type)).toEqual(['==*', '==>', '=>', '=*', 'ActivateSchema']);
        expect(isElapsedEvent(first!.precondition.clauses[0]!.events[0]) ).toBe(true);

        const clause = second!.precondition.clauses[0]!;
        expect(clause.events.length).toBe(2);
        const me = clause.events[0]!;
        expect(isModuleEvent(me) && me.tests[0]!.tests.map((t) => t.$type)).toEqual(['EqualityTest', 'FunctionTest']);
        expect(isStartedEvent(clause.events[1]) && clause.events[1].persistence?.infinite).toBe(true);
        const post = second!.postcondition.clauses[0]!.events[0]!;
        expect(isModuleEvent(post) && post.extractions.map((e) => isVariableRef(e.target) && e.target.variable?.$refText)).toEqual(['failure_data', 'temp_mess_type']);

        const thirdPre = third!.precondition.clauses.map((c) => c.events[0]!);
        expect(isEndofEvent(thirdPre[0]) && thirdPre[0].persistence?.time?.text).toBe('10ms');
        expect(isDurationEvent(thirdPre[1]) && thirdPre[1].time.text).toBe('2s');
        expect(isModuleEvent(thirdPre[2]) && thirdPre[2].ord && thirdPre[2].ordPort).toBe(0);
        const ordTest = isModuleEvent(thirdPre[2]) ? thirdPre[2].tests[0]!.tests[0]! : undefined;
        expect(isEqualityTest(ordTest) && isVariableRef(ordTest.left) && ordTest.left.ordSchema).toBe(true);
        expect(third!.actions.map((a) => a.$type)).toEqual(['Notify', 'Compute', 'Parameterize', 'ActivateModule', 'ActivateModule', 'ActivateSupervisor']);
        const [notify, compute, parameterize, rest, crit, activate] = third!.actions;
        expect(isNotify(notify) && notify.port.$refText).toBe('1');
        expect(isCompute(compute) && compute.args.length).toBe(2);
        expect(isParameterize(parameterize) && parameterize.parameters.map((p) => p.port.$refText)).toEqual(['0', '1']);
        expect(isActivateModule(rest) && rest.priority).toBe('resttime');
        expect(isActivateModule(crit) && crit.priority).toBe('critical');
        expect(isActivateSupervisor(activate) && `${activate.supervisor.$refText}.${activate.function.$refText}`).toBe('GLB.mission');
        const thirdPost = third!.postcondition.clauses[0]!.events[0]!;
        const tests = isModuleEvent(thirdPost) ? thirdPost.tests : [];
        expect(tests.length).toBe(3);
        expect(isRelationalTest(tests[0]!.tests[0]) && tests[0]!.tests[0].operator).toBe('>');
        expect(isRelationalTest(tests[1]!.tests[0]) && tests[1]!.tests[0].operator).toBe('<=');
        expect(isModuleEvent(thirdPost) && thirdPost.persistence?.time?.text).toBe('5ms');
        expect(empty!.actions).toEqual([]);
        expect(isActivateSchema(second!.actions[0])).toBe(true);
        expect(isFunctionTest(isModuleEvent(me) ? me.tests[0]!.tests[1] : undefined)).toBe(true);
    });

    it('accepts keywords of other contexts as variable and field names', async () => {
        const model = parseOk(`datatype Traj {float duration, int data, string event, float in};
            supervisor SUP { event flows { in :0 Traj started; } f(Traj elapsed) {
                local { Traj local = elapsed; float out = 1.0; }
                rules { R: [MAA:0<(started.duration > 2.5)>(local = started, out = started.in)] [elapsed=1s] }
            } }`);
        const dt = model.elements[0] as DataType;
        expect(dt.fields.map((f) => f.name)).toEqual(['duration', 'data', 'event', 'in']);
        const sup = model.elements[1] as Supervisor;
        expect(sup.functions[0]!.locals[0]!.variables.map((v) => v.name)).toEqual(['local', 'out']);
    });

    it('reports a syntax error (not a crash) for malformed input and keeps the rest', () => {
        const r = parse('datatype T {int a = };\ndatatype U {int b};');
        expect(r.errors.length).toBeGreaterThan(0);
        expect(r.model.elements.some((e) => isDataType(e) && e.name === 'U')).toBe(true);
    });

    it('rejects a time without unit where a time is expected', () => {
        expect(parse('synchronous module MSA { scheduling { C=5; } }').errors.length).toBeGreaterThan(0);
    });

    it('parses schemas with an out-of-order realtime block', () => {
        const model = parseOk('periodic schema s() { modules { MSA (); } realtime { PERIOD=1s; } }');
        expect(isSchema(model.elements[0]) && model.elements[0].blocks.map((b) => b.$type)).toEqual(['ModulesBlock', 'RealtimeBlock']);
    });
});
