import { defineCodes } from './code-table.js';

/** docs/language-reference.md §4: periodic and event schemas, their communications and timing analysis. */
export const { area: schemasArea, codes: SchemaCodes } = defineCodes('Schemas', 'language-reference.md §4', {
    'schema-name-duplicate': {
        severity: 'error',
        description: 'Schema names are unique among all schemas of the project, periodic and event schemas together.',
        example: '// a.contract\nevent schema s() { }\n// b.contract\nevent schema s() { }'
    },
    'schema-name-too-long': {
        severity: 'error',
        description: 'A schema name has at most 63 characters: the requests that activate it carry the name in a field of 64 bytes (ORD would refuse a longer one as an unknown schema).',
        example: `periodic schema ${'s'.repeat(64)}() { realtime { PERIOD=1s; CRITICAL_DELAY=1s; } modules { MSA (); } }`
    },
    'schema-parameter-duplicate': {
        severity: 'error',
        description: 'The parameter names of a schema are unique within it (an activation sets parameters by name).',
        example: 'event schema s(int a, float a) { }'
    },
    'schema-block-order': {
        severity: 'error',
        description: 'Schema blocks come in the order `realtime`, `modules`, `scheduling graph`, `communications` (each at most once).',
        example: 'periodic schema s() { modules { MSA (); } realtime { PERIOD=1s; CRITICAL_DELAY=1s; } }'
    },
    'schema-block-duplicate': {
        severity: 'error',
        description: 'A block appears twice in one schema: merge them.',
        example: 'event schema s() { modules { MAA (); } modules { MAB (); } }'
    },
    'schema-event-forbidden-block': {
        severity: 'error',
        description: 'An event schema is not scheduled: it has no `realtime` and no `scheduling graph` block.',
        example: 'event schema s() { realtime { PERIOD=1s; CRITICAL_DELAY=1s; } modules { MAA (); } }'
    },
    'schema-realtime-missing': {
        severity: 'error',
        description: 'A periodic schema needs a `realtime` block giving `PERIOD` (its activation period) and `CRITICAL_DELAY` (the latest end of each cycle after its tick).',
        example: 'periodic schema s() { modules { MSA (); } }'
    },
    'schema-realtime-property': {
        severity: 'error',
        description: 'The `realtime` block holds `PERIOD` and `CRITICAL_DELAY`, each once; any other name is an error.',
        example: 'periodic schema s() { realtime { PERIOD=1s; DEADLINE=1s; } }'
    },
    'schema-module-kind': {
        severity: 'error',
        description: 'Periodic schemas assemble synchronous modules only (ORD schedules them); event schemas assemble asynchronous modules only.',
        example: 'periodic schema s() { realtime { PERIOD=1s; CRITICAL_DELAY=1s; } modules { MAA (); } }   // MAA is asynchronous'
    },
    'schema-module-duplicate': {
        severity: 'error',
        description: 'A module appears at most once in the `modules` block of a schema.',
        example: 'event schema s() { modules { MAA (); MAA (); } }'
    },
    'parameterisation-port-duplicate': {
        severity: 'error',
        description: 'A parameterisation `(v :N, ...)` (in a schema\'s `modules` block or a supervisor\'s `parameterize`) sets each parameter port at most once.',
        example: 'event schema s() { modules { MAA ({1.0,2.0,3.0} :0, {4.0,5.0,6.0} :0); } }'
    },
    'schema-foreign-module': {
        severity: 'error',
        description: 'The scheduling graph and the communications of a schema only name modules listed in its `modules` block.',
        example: 'periodic schema s() { realtime { PERIOD=1s; CRITICAL_DELAY=1s; } modules { MSA (); } scheduling graph { MSA -> MSB; } }'
    },
    'schema-graph-cycle': {
        severity: 'error',
        description: 'The scheduling graph (precedences `A -> B`: A runs before B in each cycle) must be acyclic; the message lists the cycle.',
        example: 'scheduling graph { MSA -> MSB; MSB -> MSA; }'
    },
    'schema-communication-kind': {
        severity: 'error',
        description: 'A periodic schema connects data ports (`A:o -> B:i * k`); an event schema connects event ports (`A:o =* B:i` continuous, `A:o => B:i` one shot).',
        example: 'periodic schema s() { ... communications { MSA:1 =* MSB:0; } }'
    },
    'schema-communication-type': {
        severity: 'error',
        description: 'The two ports of a communication carry the same type (data travels as the raw bytes of the port variable); the message shows both types.',
        example: 'communications { MSC:1 -> MSD:2 * 1; }   // MSC:1 is TypeB, MSD:2 is TypeA'
    },
    'schema-periodicity': {
        severity: 'error',
        description: 'The periodicity `k` of a data communication `A:o -> B:i * k` is an integer >= 1: B receives what A posts on every k-th activation of A.',
        example: 'communications { MSA:0 -> MSC:0 * 0; }'
    },
    'schema-input-multiple-producers': {
        severity: 'error',
        description: 'An input port (data or event) has at most one producer in a schema: two communications cannot target the same input port.',
        example: 'communications { MSA:0 -> MSC:0 * 1; MSB:0 -> MSC:0 * 1; }'
    },
    'schema-timing-delay-exceeds-period': {
        severity: 'warning',
        description: 'Timing analysis: `CRITICAL_DELAY` is greater than `PERIOD`, so a late cycle would still be running at the next tick (ORD skips that release and counts an overrun) before the lateness is ever reported.',
        example: 'realtime { PERIOD=1ms; CRITICAL_DELAY=2ms; }'
    },
    'schema-timing-critical-path': {
        severity: 'warning',
        description: 'Timing analysis: the longest path of summed `C` through the precedence graph (modules without precedences are paths of their own) exceeds `CRITICAL_DELAY`, so every cycle is expected to be late. The message shows the path. Hover on a schema shows its utilisation (sum of C / PERIOD) and critical path.',
        example: 'realtime { PERIOD=1ms; CRITICAL_DELAY=1ms; } modules { MSA (); MSB (); } scheduling graph { MSA -> MSB; }   // C=600us each'
    }
});
