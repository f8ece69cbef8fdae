/** docs/language-reference.md §6: every supervisor diagnostic code, raised and not raised by a near-identical case. */
import { describe, expect, it } from 'vitest';
import { architecture, supervisor, type SupervisorOptions } from './architecture-fixture.js';
import { describeCodeCases, type CodeCase } from './code-cases.js';
import { build } from './helpers.js';

const sup = (rules: string, options: SupervisorOptions = {}) => architecture({ 'sup.contract': supervisor(rules, options) });
/** A rule subscribing to MAA:2 on :2, so that MAA:2 events are legitimate. */
const SUBSCRIBE = 'S0: [elapsed=1ms] subscribe MAA:2 =* :2 [elapsed=1s]';
const withSub = (rule: string) => sup(`${SUBSCRIBE}\n${rule}`);
/** A second periodic schema sharing MSC with sc1. */
const SC2 = {
    'sc2.contract': 'periodic schema sc2() { realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; } modules { MSB (); MSC (); } scheduling graph { MSB -> MSC; } }',
    'sched.contract': 'scheduler configuration { modules { MSA; MSB; MSC; MSD; } schemas { sc1; sc2; } }'
};

const CASES: Record<string, CodeCase> = {
    'supervisor-function-name-too-long': {
        raise: sup('', { more: `${'f'.repeat(64)}() { }` }),
        clean: sup('', { more: `${'f'.repeat(63)}() { }` })
    },
    'supervisor-function-duplicate': {
        raise: sup('', { more: 'action() { }' }),
        clean: sup('', { more: 'other() { }' })
    },
    'supervisor-parameter-duplicate': {
        raise: sup('', { params: 'TypeA consigne, int consigne' }),
        clean: sup('', { params: 'TypeA consigne, int mode' })
    },
    'supervisor-local-name-conflict': {
        raise: sup('', { locals: 'string connection_status;' }),
        clean: sup('', { locals: 'string connection_state;' }),
        message: "Local 'connection_status' has the name of the variable of input event port :2 of SUP"
    },
    'supervisor-rule-uses-parameter': {
        raise: sup('R: [elapsed=1ms] activate schema sc1(consigne = consigne) [elapsed=2ms]'),
        clean: sup('R: [elapsed=1ms] activate schema sc1(consigne = temp_consigne) [elapsed=2ms]'),
        message: "Rules cannot use the parameter 'consigne' of action: they use locals, event-port variables and constants. Use the local 'temp_consigne', initialised from it.",
        data: { local: 'temp_consigne' }
    },
    'supervisor-action-separator': {
        raise: sup('R: [elapsed=1ms] subscribe MAA:2 =* :2 subscribe MSC:1 => :3 [elapsed=2ms]'),
        clean: sup('R: [elapsed=1ms] subscribe MAA:2 =* :2; subscribe MSC:1 => :3 [elapsed=2ms]'),
        message: "Two actions are separated by ';': one is missing before 'subscribe'."
    },
    'supervisor-label-duplicate': {
        raise: sup('R: [elapsed=1ms] [elapsed=2ms]\nR: [elapsed=3ms] [elapsed=4ms]'),
        clean: sup('R: [elapsed=1ms] [elapsed=2ms]\nQ: [elapsed=3ms] [elapsed=4ms]')
    },
    'supervisor-ord-port': {
        raise: sup('R: [ORD:2] compute doit("late", 1.0) [elapsed=2ms]'),
        clean: sup('R: [ORD:1] compute doit("late", 1.0) [elapsed=2ms]')
    },
    'supervisor-ord-schema-misuse': {
        raise: withSub('R: [MAA:2<ord_schema == "sc1">] compute doit("late", 1.0) [elapsed=2ms]'),
        clean: withSub('R: [ORD:0<ord_schema == "sc1">] compute doit("late", 1.0) [elapsed=2ms]')
    },
    'supervisor-ord-schema-unknown': {
        raise: sup('R: [ORD:0<ord_schema == "sc">] compute doit("late", 1.0) [elapsed=2ms]'),
        clean: sup('R: [ORD:0<ord_schema == "sc1">] compute doit("late", 1.0) [elapsed=2ms]'),
        message: 'No schema is named "sc": ORD:0 names the schema whose cycle missed its critical delay, so this test is never true. Did you mean \'sc1\'?'
    },
    'supervisor-test-type': {
        raise: withSub('R: [MAA:2<connection_status == 3>] compute doit("x", 1.0) [elapsed=2ms]'),
        clean: withSub('R: [MAA:2<connection_status == "3">] compute doit("x", 1.0) [elapsed=2ms]'),
        message: "Cannot compare 'connection_status' (string) with the integer 3"
    },
    'supervisor-extraction-target': {
        raise: sup('R: [elapsed=1ms] subscribe MSC:1 => :3 [MSC:1(failure = failure_data)]'),
        clean: sup('R: [elapsed=1ms] subscribe MSC:1 => :3 [MSC:1(failure_data = failure)]')
    },
    'supervisor-notify-target': {
        raise: sup('R: [elapsed=1ms] notify :1 (temp_mess_type = "lost") [elapsed=2ms]'),
        clean: sup('R: [elapsed=1ms] notify :1 (failure_message_type = "lost") [elapsed=2ms]'),
        message: "notify :1 assigns the variable of that port, 'failure_message_type'"
    },
    'supervisor-argument-duplicate': {
        raise: sup('R: [elapsed=1ms] activate schema sc1(consigne = temp_consigne, consigne = temp_consigne) [elapsed=2ms]'),
        clean: sup('R: [elapsed=1ms] activate schema sc1(consigne = temp_consigne) [elapsed=2ms]')
    },
    'supervisor-module-not-async': {
        raise: sup('R: [elapsed=1ms] activate resttime module MSA [elapsed=2ms]'),
        clean: sup('R: [elapsed=1ms] activate resttime module MAA [elapsed=2ms]')
    },
    'supervisor-subscribe-type': {
        raise: sup('R: [elapsed=1ms] subscribe MAA:2 =* :3 [elapsed=2ms]'),
        clean: sup('R: [elapsed=1ms] subscribe MAA:2 =* :2 [elapsed=2ms]'),
        message: 'Port MAA:2 is an output event port of type string; input event port :3 (failure) expects TypeD'
    },
    'supervisor-subscribe-conflict': {
        raise: sup('A: [elapsed=1ms] subscribe MAA:2 =* :2 [elapsed=2ms]\nB: [elapsed=3ms] subscribe MAB:1 =* :2 [elapsed=4ms]'),
        clean: sup('A: [elapsed=1ms] subscribe MAA:2 =* :2 [elapsed=2ms]\nB: [elapsed=3ms] compute doit("y", 1.0) [elapsed=4ms]'),
        message: 'Input event port :2 (connection_status) is also subscribed to MAA:2 (rule A)'
    },
    'supervisor-endof-own-postcondition': {
        raise: sup('A: [elapsed=1ms] compute doit("x", 1.0) [endof(A)]\nB: [elapsed=3ms] compute doit("y", 1.0) [elapsed=4ms]'),
        clean: sup('A: [elapsed=1ms] compute doit("x", 1.0) [endof(B)]\nB: [elapsed=3ms] compute doit("y", 1.0) [elapsed=4ms]')
    },
    'supervisor-started-own-precondition': {
        raise: sup('A: [started(A)] compute doit("x", 1.0) [elapsed=2ms]\nB: [elapsed=3ms] compute doit("y", 1.0) [elapsed=4ms]'),
        clean: sup('A: [started(B)] compute doit("x", 1.0) [elapsed=2ms]\nB: [elapsed=3ms] compute doit("y", 1.0) [elapsed=4ms]')
    },
    'supervisor-elapsed-once': {
        raise: sup('A: [elapsed=1ms or endof(B)] compute doit("x", 1.0) [elapsed=5ms]\nB: [endof(A)] compute doit("y", 1.0) [duration(B)=4ms]'),
        clean: sup('A: [elapsed=1ms or endof(B)] compute doit("x", 1.0) [duration(A)=5ms]\nB: [endof(A)] compute doit("y", 1.0) [duration(B)=4ms]'),
        message: 'elapsed=5ms occurs once, 5ms after the function started: A becomes active on endof(B), which may come again, and a later A (or one that starts after 5ms) is never ended by it. To end A 5ms after each of its activations, write duration(A)=5ms.'
    },
    'supervisor-clause-transient': {
        raise: withSub('R: [(MAA:2 and elapsed=1ms)] compute doit("x", 1.0) [elapsed=2ms]'),
        clean: withSub('R: [(MAA:2 and elapsed=1ms{infinite})] compute doit("x", 1.0) [elapsed=2ms]')
    },
    'supervisor-event-not-subscribed': {
        raise: sup('R: [MAA:2] compute doit("x", 1.0) [elapsed=2ms]'),
        clean: withSub('R: [MAA:2] compute doit("x", 1.0) [elapsed=2ms]'),
        message: 'Function action never subscribes to MAA:2'
    },
    'supervisor-event-variable': {
        raise: sup('R: [elapsed=1ms] subscribe MAA:2 =* :2 [MAA:2<failure.dataname == "x">]'),
        clean: sup('R: [elapsed=1ms] subscribe MAA:2 =* :2 [MAA:2<connection_status == "x">]'),
        message: "MAA:2 is delivered to :2 connection_status; 'failure.dataname' is the variable of input port :3, which this event does not write"
    },
    'supervisor-activation-cycle': {
        raise: architecture({
            'sup.contract': 'import "glb.contract";\n' + supervisor('R: [elapsed=1ms] activate supervisor GLB.mission() [elapsed=2ms]'),
            'glb.contract': 'import "sup.contract";\nsupervisor GLB { mission() { rules { R: [elapsed=1ms] activate supervisor SUP.action() [elapsed=2ms] } } }'
        }),
        clean: architecture({
            'sup.contract': supervisor('R: [elapsed=1ms] compute doit("x", 1.0) [elapsed=2ms]'),
            'glb.contract': 'import "sup.contract";\nsupervisor GLB { mission() { rules { R: [elapsed=1ms] activate supervisor SUP.action() [elapsed=2ms] } } }'
        }),
        message: 'Supervisors activate each other: SUP -> GLB -> SUP.'
    },
    'supervisor-schema-conflict': {
        raise: architecture({ ...SC2, 'sup.contract': supervisor('R: [elapsed=1ms] activate schema sc1(); activate schema sc2() [elapsed=2ms]') }),
        clean: architecture({ ...SC2, 'sup.contract': supervisor('R: [elapsed=1ms] activate schema sc1() [elapsed=2ms]\nQ: [elapsed=3ms] activate schema sc2() [elapsed=4ms]') }),
        message: 'Rule R activates periodic schemas sc1 and sc2, which share module MSC',
        data: { conflictsWith: 'sc1', modules: ['MSC'] }
    }
};

describeCodeCases('supervisor diagnostics: each code raised by its case, not by a near-identical one', 'Supervisors', CASES);

describe('supervisors: more behaviour', () => {
    const errorsAndWarnings = async (files: Record<string, string>) =>
        (await build(files)).diagnostics.filter((d) => d.severity === 'error' || d.severity === 'warning').map((d) => `${d.code}: ${d.message}`);

    it('accepts the report-style SUP with GLB above it', async () => {
        const rules = `FIRST: [elapsed=1ms]
                subscribe MAA:2 ==* :2; subscribe MAA:0 ==* :1; activate schema ev()
                [MAA:2<connection_status == "disconnected">]
            SECOND: [(MAA:2<(connection_status == "disconnected" & testit("dedede", temp_consigne))> and started(FIRST){infinite})]
                subscribe MSC:1=>:3; activate schema sc1(consigne = temp_consigne)
                [MSC:1(failure_data = failure, temp_mess_type = "commutation")]
            THIRD: [endof(SECOND)] notify :1(failure_message_type=temp_mess_type) [started(THIRD)]
            FOURTH: [endof(SECOND)] compute doit("1.24",temp_consigne.k) [endof(FIRST)]
            RECEPTION: [MAA:0(temp_message=message_received)]
                parameterize MSC(temp_message.value :0); activate resttime module MAA
                [started(RECEPTION)]
            LATE: [ORD:0<ord_schema == "sc1">(temp_mess_type = ord_schema)] notify :1(failure_message_type = temp_mess_type) [duration(LATE)=1s]`;
        expect(await errorsAndWarnings(architecture({
            'sup.contract': supervisor(rules),
            'glb.contract': `import "sup.contract";\nsupervisor GLB { event flows { in :0 string s; } mission(TypeA consigne) { local { TypeA c = consigne; } rules {
                SINGLE: [elapsed=1ms] subscribe SUP:1 => :0; activate supervisor SUP.action(consigne = c) [SUP:1<s == "commutation">]
            } } }`
        }))).toEqual([]);
    });

    it('the same producer subscribed twice to one input port is the same warning: the runtime refuses the second while the first holds the port', async () => {
        const built = await build(sup('A: [elapsed=1ms] subscribe MAA:2 =* :2 [elapsed=2ms]\nB: [elapsed=3ms] subscribe MAA:2 =* :2 [elapsed=4ms]'));
        const warned = built.diagnostics.filter((d) => d.code === 'supervisor-subscribe-conflict').map((d) => d.message);
        expect(warned).toEqual(['Input event port :2 (connection_status) is also subscribed to MAA:2 by rule A: an input port takes one subscribe at a time, the same producer\'s too (the second is refused while the first holds it: `port :2 already subscribed`). Make sure these rules are never active at once, or subscribe once in a rule active whenever either needs the events.']);
    });

    it('subscribes to one input port in rules never active together are not a conflict: one rule starts only after the end of the other, which is active once', async () => {
        const conflicts = async (rules: string, more?: string) =>
            (await build(sup(rules, more ? { more } : {}))).diagnostics.filter((d) => d.code === 'supervisor-subscribe-conflict').map((d) => d.message);
        const HOLD = 'HOLD: [elapsed=1ms] subscribe MAA:2 =* :2 [elapsed=2ms]';
        // the field test's HOLD and LAND, the same producer or another, and a chain after LAND
        expect(await conflicts(`${HOLD}\nLAND: [endof(HOLD)] subscribe MAA:2 =* :2 [elapsed=5ms]`)).toEqual([]);
        expect(await conflicts(`${HOLD}\nLAND: [endof(HOLD)] subscribe MAB:1 =* :2 [MAB:1]`)).toEqual([]);
        expect(await conflicts(`${HOLD}\nLAND: [endof(HOLD)] compute doit("x", 1.0) [duration(LAND)=1ms]\nTAXI: [endof(LAND) or started(LATER)] subscribe MAA:2 =* :2 [elapsed=9ms]\nLATER: [endof(LAND)] compute doit("y", 1.0) [elapsed=9ms]`)).toEqual([]);
        // either written first
        expect(await conflicts(`LAND: [endof(HOLD)] subscribe MAA:2 =* :2 [elapsed=5ms]\n${HOLD}`)).toEqual([]);
        const warned = 'Input event port :2 (connection_status) is also subscribed to MAA:2 by rule HOLD';
        // HOLD may become active again while LAND is: on each MAA:0 event, or at 1 ms and again at 3 ms
        for (const pre of ['MAA:0', 'elapsed=1ms or elapsed=3ms', 'elapsed=1ms{1s}']) {
            const rules = `HOLD: [${pre}] subscribe MAA:2 =* :2 [elapsed=2ms]\nLAND: [endof(HOLD)] subscribe MAA:2 =* :2 [elapsed=5ms]`;
            expect((await conflicts(rules))[0], pre).toContain(warned);
        }
        // LAND may start otherwise than at HOLD's end: another clause, an endof that persists, started(HOLD)
        for (const pre of ['endof(HOLD) or elapsed=1500us', 'endof(HOLD){1s}', 'started(HOLD)']) {
            expect((await conflicts(`${HOLD}\nLAND: [${pre}] subscribe MAA:2 =* :2 [elapsed=5ms]`))[0], pre).toContain(warned);
        }
        // one rule subscribing twice, and rules of two functions (they may run at once), are still warned
        expect(await conflicts('HOLD: [elapsed=1ms] subscribe MAA:2 =* :2; subscribe MAA:2 =* :2 [elapsed=2ms]')).toHaveLength(1);
        expect(await conflicts(HOLD, 'other() { rules { LAND: [elapsed=1ms] subscribe MAA:2 =* :2 [elapsed=5ms] } }')).toHaveLength(1);
    });

    it('rules ending each other in turn (A on endof(B), B on endof(A)) are not a subscribe conflict when one event, once, starts the first; they are warned, saying why, when the turn may hold two', async () => {
        const conflicts = async (rules: string) =>
            (await build(sup(rules))).diagnostics.filter((d) => d.code === 'supervisor-subscribe-conflict').map((d) => d.message);
        const sub = 'subscribe MAA:2 =* :2';
        const post = '[MAA:2<connection_status == "done">]';
        // the usual alternation: A first at 1 ms, then each on the end of the other
        expect(await conflicts(`A: [elapsed=1ms or endof(B)] ${sub} ${post}\nB: [endof(A)] ${sub} ${post}`)).toEqual([]);
        // three in a ring, and the first started by the end of a rule active once
        expect(await conflicts(`A: [endof(C) or endof(HOLD)] ${sub} ${post}\nB: [endof(A)] ${sub} ${post}\nC: [endof(B)] ${sub} ${post}\nHOLD: [elapsed=1ms] compute doit("x", 1.0) [elapsed=2ms]`)).toEqual([]);
        // an endof that persists or a module event beside the turn's endof does not start a second one
        expect(await conflicts(`A: [elapsed=1ms or (endof(B) and MAA:0{1s})] ${sub} ${post}\nB: [endof(A)] ${sub} ${post}`)).toEqual([]);
        // no rule of the turn ever starts
        expect(await conflicts(`A: [endof(B)] ${sub} ${post}\nB: [endof(A)] ${sub} ${post}`)).toEqual([]);

        const warned = 'Input event port :2 (connection_status) is also subscribed to MAA:2 by rule A';
        const cases: Array<[string, string]> = [
            // B starts at 2 ms whatever A is doing: A (from 1 ms) may still be active
            [`A: [elapsed=1ms or endof(B)] ${sub} ${post}\nB: [elapsed=2ms or endof(A)] ${sub} ${post}`,
                'They may be active at once: B and A take turns on the endof of another rule, but 2 of their clauses start one otherwise, so one may start while another is active: A on elapsed=1ms, B on elapsed=2ms.'],
            // A starts again on each MAA:0, while B may be active
            [`A: [MAA:0 or endof(B)] ${sub} ${post}\nB: [endof(A)] ${sub} ${post}`,
                'They may be active at once: B and A take turns on the endof of another rule, but A also starts on MAA:0, which may come again while another of their turn is active.'],
            // the end of A starts B and C: both become active at once
            [`A: [elapsed=1ms or endof(C)] compute doit("x", 1.0) ${post}\nB: [endof(A)] ${sub} ${post}\nC: [endof(A)] ${sub} ${post}`,
                'They may be active at once: C and B take turns on the endof of another rule, but endof(A) starts 2 of them (B, C).']
        ];
        for (const [rules, why] of cases) {
            const found = await conflicts(rules);
            expect(found, rules).toHaveLength(1);
            expect(found[0], rules).toContain(rules.includes('C: [endof(A)]') ? warned.replace('rule A', 'rule B') : warned);
            expect(found[0], rules).toContain(why);
        }
    });

    it('an alternation is no schema conflict (their activations never meet), and a turn that may hold two is not claimed certain', async () => {
        const sc2 = { 'sc2.contract': 'periodic schema sc2(TypeA consigne) { realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; } modules { MSC (consigne:0); MSD (); } scheduling graph { MSC -> MSD; } }',
            'sched.contract': 'scheduler configuration { modules { MSA; MSB; MSC; MSD; } schemas { sc1; sc2; } }' };
        const schemaConflicts = async (rules: string) => (await build(architecture({ ...sc2, 'sup.contract': supervisor(rules) })))
            .diagnostics.filter((d) => d.code === 'supervisor-schema-conflict');
        const a = 'activate schema sc1(consigne = temp_consigne)';
        const b = 'activate schema sc2(consigne = temp_consigne)';
        expect(await schemaConflicts(`A: [elapsed=1ms or endof(B)] ${a} [elapsed=5ms]\nB: [endof(A)] ${b} [duration(B)=1ms]`)).toEqual([]);
        expect(await schemaConflicts(`A: [elapsed=1ms or endof(B)] ${a} [duration(A)=1ms]\nB: [elapsed=2ms or endof(A)] ${b} [duration(B)=1ms]`)).toEqual([]);
    });

    it('an event reading the variables of two input ports it is delivered to is warned: an occurrence writes one', async () => {
        const ports = 'in :2 string connection_status; in :4 string status2; out :1 string failure_message_type;';
        const rules = (post: string) => `HOLD: [elapsed=1ms] subscribe MAA:2 =* :2 [elapsed=2ms]\nLAND: [endof(HOLD)] subscribe MAA:2 =* :4 [${post}]`;
        const warnings = async (post: string) => (await build(sup(rules(post), { ports, locals: 'string last;' }))).diagnostics.filter((d) => d.severity === 'warning').map((d) => `${d.code}: ${d.message}`);
        expect(await warnings('MAA:2<status2 == "landed">(last = status2)')).toEqual([]);
        expect(await warnings('MAA:2<status2 == "landed"> or MAA:2<connection_status == "lost">')).toEqual([]);
        expect(await warnings('MAA:2<status2 == "landed" | connection_status == "lost">')).toEqual([
            'supervisor-event-variable: MAA:2 is delivered to :2 connection_status, :4 status2 (one subscribe each), and this event reads the variables of :4 status2, :2 connection_status: an occurrence comes in on one of them and writes that one only, so what it reads of the others is older. Read one input port per event; to wait for either, write one event per port: MAA:2<status2 ...> or MAA:2<connection_status ...>.'
        ]);
        expect(await warnings('MAA:2<status2 == "landed">(last = connection_status)')).toHaveLength(1);
    });

    it('a label referenced but not defined is a linking error listing the labels', async () => {
        const built = await build(sup('A: [endof(NOPE)] compute doit("x", 1.0) [elapsed=2ms]'));
        const found = built.diagnostics.filter((d) => d.code === 'linking-error');
        expect(found.map((d) => [d.severity, d.message])).toEqual([['error', "No rule labelled 'NOPE' in function action; its labels: A."]]);
    });

    it('an extraction may read the port of any module event of its clause, not others', async () => {
        const rule = (extract: string) => `A: [elapsed=1ms] subscribe MAA:2 =* :2; subscribe MSC:1 => :3 [elapsed=1s]
            B: [(MAA:2{infinite} and MSC:1(${extract}))] compute doit("x", 1.0) [duration(B)=2s]`;
        const codesOf = async (extract: string) => (await build(sup(rule(extract)))).diagnostics.filter((d) => d.severity !== 'hint').map((d) => d.code);
        expect(await codesOf('temp_mess_type = connection_status, failure_data = failure')).toEqual([]);
        expect(await codesOf('temp_message = message_received')).toEqual(['supervisor-event-variable']);
    });

    it('ORD events need no subscribe', async () => {
        const built = await build(sup('R: [ORD:0] compute doit("late", 1.0) [elapsed=2ms]'));
        expect(built.diagnostics.filter((d) => d.code === 'supervisor-event-not-subscribed')).toEqual([]);
    });

    it('type-checks activation arguments, parameterize, extraction values and notify values', async () => {
        const rules = `R: [elapsed=1ms]
                subscribe MSC:1 => :3;
                activate schema sc1(consigne = temp_mess_type);
                parameterize MSC(failure_data :0);
                notify :1 (failure_message_type = 2)
                [MSC:1(temp_mess_type = failure)]`;
        const messages = (await build(sup(rules))).diagnostics.filter((d) => d.code === 'value-type-mismatch').map((d) => d.message).sort();
        expect(messages).toEqual([
            "Expected a TypeA value {i, j, k} for parameter 'consigne' of schema sc1, found 'temp_mess_type' of type string.",
            "Expected a TypeA value {i, j, k} for parameter port :0 'param' of MSC, found 'failure_data' of type TypeD.",
            "Expected a string (\"...\") for 'failure_message_type', found the integer 2.",
            "Expected a string (\"...\") for 'temp_mess_type', found 'failure' of type TypeD."
        ]);
    });

    it('a test mixing int and float is fine; a struct literal takes the type of the other operand', async () => {
        const ok = await errorsAndWarnings(sup('R: [elapsed=1ms] subscribe MSC:1 => :3 [MSC:1<(failure.datavalue > 2.5) | failure == {"x", 1}>]'));
        expect(ok).toEqual([]);
        const bad = await errorsAndWarnings(sup('R: [elapsed=1ms] subscribe MSC:1 => :3 [MSC:1<failure == {"x"}>]'));
        expect(bad).toEqual(['value-struct-arity: TypeD has 2 fields (dataname, datavalue); this value has 1 element for this comparison.']);
    });

    it('an ORD test names a schema of the project, periodic or event, on either side of == or !=', async () => {
        const unknown = async (rule: string) => (await build(sup(rule))).diagnostics.filter((d) => d.code === 'supervisor-ord-schema-unknown').map((d) => d.message);
        expect(await unknown('R: [ORD:1<"sc2" != ord_schema>] compute doit("x", 1.0) [elapsed=2ms]'))
            .toEqual(['No schema is named "sc2": ORD:1 names the schema whose activation was refused, so this test is always true. Did you mean \'sc1\'?']);
        expect(await unknown('R: [ORD:0<ord_schema == "nothingLike">] compute doit("x", 1.0) [elapsed=2ms]'))
            .toEqual(['No schema is named "nothingLike": ORD:0 names the schema whose cycle missed its critical delay, so this test is never true.']);
        for (const named of ['"ev" == ord_schema', 'ord_schema == "sc1"', 'ord_schema != "ev"']) expect(await unknown(`R: [ORD:1<${named}>] compute doit("x", 1.0) [elapsed=2ms]`), named).toEqual([]);
        // only a test of ord_schema itself: a local holding it is another string
        expect(await unknown('R: [ORD:0(temp_mess_type = ord_schema)] compute doit("x", 1.0) [(ORD:0<temp_mess_type == "nothingLike">)]')).toEqual([]);
    });

    it('a supervisor activating itself is a cycle', async () => {
        const built = await build(sup('R: [elapsed=1ms] activate supervisor SUP.action() [elapsed=2ms]'));
        expect(built.diagnostics.filter((d) => d.code === 'supervisor-activation-cycle').map((d) => d.message))
            .toEqual(['Supervisors activate each other: SUP -> SUP. The supervisor hierarchy must be a tree or a DAG (a supervisor activates only supervisors below it).']);
    });

    it('does not crash on unresolved names in rules', async () => {
        const rules = `R: [(MZZ:4<((nothing.x > 1) & nofn(2))>(ghost = what) and started(GHOST){infinite})]
                subscribe MZZ:1 =* :9; activate schema nosuch(p = q); activate supervisor NOP.fn(a = b);
                activate critical module MZZ; parameterize MZZ(x :0); compute nofn(1); notify :7 (z = 1)
                [ORD:9<ord_schema == 1>]`;
        const built = await build(sup(rules));
        expect(built.diagnostics.filter((d) => d.code === 'parsing-error')).toEqual([]);
        expect(built.diagnostics.filter((d) => d.code === 'linking-error').length).toBeGreaterThan(10);
        expect(built.diagnostics.filter((d) => d.code === 'supervisor-ord-port').length).toBe(1);
        expect(built.diagnostics.filter((d) => d.code === 'supervisor-test-type').map((d) => d.message))
            .toEqual(["Cannot compare 'ord_schema' (string) with the integer 1 (int): both operands of a test have the same type (int and float mix)."]);
    });
});
