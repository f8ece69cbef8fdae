/** docs/language-reference.md §4: every schema diagnostic code, raised and not raised by a near-identical case. */
import { describe, expect, it } from 'vitest';
import { architecture } from './architecture-fixture.js';
import { describeCodeCases, type CodeCase } from './code-cases.js';
import { build } from './helpers.js';

const periodic = (body: string, params = 'TypeA consigne = {0.0, 0.0, 0.0}') => architecture({ 'sc1.contract': `periodic schema sc1(${params}) { ${body} }` });
const event = (body: string) => architecture({ 'ev.contract': `event schema ev(TypeA param) { ${body} }` });
const RT = 'realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; }';
const MODS = 'modules { MSA (); MSC (consigne:0); MSD (); }';
const GRAPH = 'scheduling graph { MSA -> MSC; MSC -> MSD; }';

const CASES: Record<string, CodeCase> = {
    'schema-name-duplicate': {
        raise: architecture({ 'ev2.contract': 'event schema ev() { modules { MAB (); } }' }),
        clean: architecture({ 'ev2.contract': 'event schema ev2() { modules { MAB (); } }' }),
        message: "Schema 'ev' is defined more than once (also in"
    },
    'schema-name-too-long': {
        raise: architecture({ 'ev9.contract': `event schema ${'e'.repeat(64)}(TypeA param) { modules { MAA (); } }` }),
        clean: architecture({ 'ev9.contract': `event schema ${'e'.repeat(63)}(TypeA param) { modules { MAA (); } }` })
    },
    'schema-parameter-duplicate': {
        raise: periodic(`${RT} ${MODS}`, 'TypeA consigne, int consigne'),
        clean: periodic(`${RT} ${MODS}`, 'TypeA consigne, int mode')
    },
    'schema-block-order': {
        raise: periodic(`${MODS} ${RT}`),
        clean: periodic(`${RT} ${MODS}`),
        message: "Block 'realtime' must come before 'modules': the order is realtime, modules, scheduling graph, communications."
    },
    'schema-block-duplicate': {
        raise: periodic(`${RT} modules { MSA (); } modules { MSC (consigne:0); }`),
        clean: periodic(`${RT} modules { MSA (); MSC (consigne:0); }`)
    },
    'schema-event-forbidden-block': {
        raise: event('realtime { PERIOD=1s; CRITICAL_DELAY=1s; } modules { MAA (); MAB (); }'),
        clean: event('modules { MAA (); MAB (); }'),
        message: "Event schema ev is not scheduled: remove the 'realtime' block"
    },
    'schema-realtime-missing': {
        raise: periodic(MODS),
        clean: periodic(`${RT} ${MODS}`)
    },
    'schema-realtime-property': {
        raise: periodic(`realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; DEADLINE=1ms; } ${MODS}`),
        clean: periodic(`realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; } ${MODS}`)
    },
    'schema-module-kind': {
        raise: periodic(`${RT} modules { MSA (); MAA (); }`),
        clean: periodic(`${RT} modules { MSA (); MSB (); }`),
        message: 'Module MAA is asynchronous: a periodic schema assembles synchronous modules only'
    },
    'schema-module-duplicate': {
        raise: periodic(`${RT} modules { MSA (); MSA (); }`),
        clean: periodic(`${RT} modules { MSA (); MSB (); }`)
    },
    'parameterisation-port-duplicate': {
        raise: periodic(`${RT} modules { MSC (consigne:0, {1.0, 2.0, 3.0}:0); }`),
        clean: periodic(`${RT} modules { MSC (consigne:0); }`)
    },
    'schema-foreign-module': {
        raise: periodic(`${RT} modules { MSA (); MSC (consigne:0); } scheduling graph { MSA -> MSC; MSC -> MSD; }`),
        clean: periodic(`${RT} ${MODS} ${GRAPH}`),
        message: 'Module MSD is not in the modules of schema sc1 (MSA, MSC)'
    },
    'schema-graph-cycle': {
        raise: periodic(`${RT} ${MODS} scheduling graph { MSA -> MSC; MSC -> MSD; MSD -> MSA; }`),
        clean: periodic(`${RT} ${MODS} scheduling graph { MSA -> MSC; MSC -> MSD; MSA -> MSD; }`),
        message: 'has a cycle: MSA -> MSC -> MSD -> MSA.'
    },
    'schema-communication-kind': {
        raise: event('modules { MAA (); MAB (); } communications { MAA:0 -> MAB:0 * 1; }'),
        clean: event('modules { MAA (); MAB (); } communications { MAA:0 =* MAB:0; }')
    },
    'schema-communication-type': {
        raise: periodic(`${RT} ${MODS} ${GRAPH} communications { MSA:0 -> MSC:0 * 1; MSA:0 -> MSD:2 * 1; }`),
        clean: periodic(`${RT} ${MODS} ${GRAPH} communications { MSA:0 -> MSC:0 * 1; MSC:1 -> MSD:2 * 1; }`),
        message: 'Port MSA:0 is an output data port of type TypeA; MSD:2 expects TypeB'
    },
    'schema-periodicity': {
        raise: periodic(`${RT} ${MODS} ${GRAPH} communications { MSA:0 -> MSC:0 * 0; }`),
        clean: periodic(`${RT} ${MODS} ${GRAPH} communications { MSA:0 -> MSC:0 * 3; }`)
    },
    'schema-input-multiple-producers': {
        raise: periodic(`${RT} modules { MSA (); MSB (); MSC (consigne:0); } communications { MSA:0 -> MSC:0 * 1; MSB:0 -> MSC:0 * 1; }`),
        clean: periodic(`${RT} modules { MSA (); MSB (); MSC (consigne:0); } communications { MSA:0 -> MSC:0 * 1; }`),
        message: 'Input data port MSC:0 already has a producer in this schema (MSA:0)'
    },
    'schema-timing-delay-exceeds-period': {
        raise: periodic(`realtime { PERIOD=10ms; CRITICAL_DELAY=20ms; } ${MODS} ${GRAPH}`),
        clean: periodic(`realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; } ${MODS} ${GRAPH}`),
        message: 'CRITICAL_DELAY (20ms) exceeds PERIOD (10ms)'
    },
    'schema-timing-critical-path': {
        raise: periodic(`realtime { PERIOD=10ms; CRITICAL_DELAY=2ms; } ${MODS} ${GRAPH}`),
        clean: periodic(`realtime { PERIOD=10ms; CRITICAL_DELAY=2500us; } ${MODS} ${GRAPH}`),
        message: 'takes 2500us (MSA -> MSC -> MSD, summed C), more than CRITICAL_DELAY (2ms)'
    }
};

describeCodeCases('schema diagnostics: each code raised by its case, not by a near-identical one', 'Schemas', CASES);

describe('schemas: more behaviour', () => {
    it('the base fixture architecture has no error and no warning', async () => {
        const built = await build(architecture());
        expect(built.diagnostics.filter((d) => d.severity === 'error' || d.severity === 'warning')).toEqual([]);
    });

    it('type-checks a parameterisation from a schema parameter with a field path', async () => {
        const wrong = await build(periodic(`${RT} modules { MSA (); MSC (consigne.i:0); MSD (); }`));
        expect(wrong.diagnostics.map((d) => d.message)).toContain("Expected a TypeA value {i, j, k} for parameter port :0 'param' of MSC, found 'consigne.i' of type float.");
        const right = await build(periodic(`${RT} modules { MSA (); MSC ({consigne.i, 2, consigne.k}:0); MSD (); }`, 'TypeA consigne'));
        expect(right.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
    });

    it('reports an event communication to an input port of another type', async () => {
        const built = await build(architecture({
            'mab.contract': 'asynchronous module MAB { event flows { in :0 string message_type_notification; out :1 string link_status; } }'
        }));
        expect(built.diagnostics.filter((d) => d.code === 'schema-communication-type').map((d) => d.message))
            .toEqual(['Port MAA:0 is an output event port of type TypeC; MAB:0 expects string: connected ports carry the same type.']);
    });

    it('does not crash on unresolved modules and ports', async () => {
        const built = await build(periodic(`${RT} modules { MSX (); MSC (nothing:7); } scheduling graph { MSX -> MSC; MSC -> MSY; } communications { MSX:0 -> MSC:9 * 1; MSC:1 -> MSQ:2; }`));
        expect(built.diagnostics.some((d) => d.code === 'linking-error')).toBe(true);
        expect(built.diagnostics.filter((d) => d.code.startsWith('schema-'))).toEqual([]);
    });
});
