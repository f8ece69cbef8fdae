import { defineCodes } from './code-table.js';

/** docs/language-reference.md §6: supervisors, supervision functions, rules, conditions and actions (report §4.7). */
export const { area: supervisorsArea, codes: SupervisorCodes } = defineCodes('Supervisors', 'language-reference.md §6', {
    'supervisor-function-name-too-long': {
        severity: 'error',
        description: 'A supervision function name has at most 63 characters: the start request carries it in a field of 64 bytes (a longer one could never be started).',
        example: `supervisor SUP { ${'f'.repeat(64)}() { } }`
    },
    'supervisor-function-duplicate': {
        severity: 'error',
        description: 'Supervision function names are unique within a supervisor (`activate supervisor SUP.fn` names them).',
        example: 'supervisor SUP { f() { } f() { } }'
    },
    'supervisor-parameter-duplicate': {
        severity: 'error',
        description: 'The parameters of a supervision function have unique names (callers set them by name).',
        example: 'supervisor SUP { f(int a, float a) { } }'
    },
    'supervisor-local-name-conflict': {
        severity: 'error',
        description: 'A local variable\'s name differs from the other locals, from the function\'s parameters and from the supervisor\'s event-port variables.',
        example: 'supervisor SUP { event flows { in :0 string status; } f() { local { string status; } } }'
    },
    'supervisor-rule-uses-parameter': {
        severity: 'error',
        description: 'Rules use the function\'s locals, the supervisor\'s event-port variables and constants, never the function\'s parameters: copy the parameter into a local (`local { TypeA c = consigne; }`) and use the local. When a local is initialised from exactly that parameter, the message names it and the diagnostic data holds it (`local`).',
        example: 'f(TypeA consigne) { rules { R: [elapsed=1ms] activate schema s(consigne = consigne) [elapsed=2ms] } }'
    },
    'supervisor-action-separator': {
        severity: 'error',
        description: 'The actions of a rule are separated by `;`. A missing one is read as if it were there (the rest of the rule and of the file is checked as meant, with no follow-on error), reported on the action it should come before; the quick fix inserts it.',
        example: 'rules { R: [elapsed=1ms] subscribe MAA:2 =* :2 subscribe MAA:0 =* :1 [elapsed=2ms] }'
    },
    'supervisor-label-duplicate': {
        severity: 'error',
        description: 'Rule labels are unique within a supervision function (`started(L)`, `endof(L)` and `duration(L)` name them). A label that is referenced but not defined is a `linking-error` listing the function\'s labels.',
        example: 'rules { R: [elapsed=1ms] [elapsed=2ms] R: [elapsed=3ms] [elapsed=4ms] }'
    },
    'supervisor-ord-port': {
        severity: 'error',
        description: 'The scheduler ORD emits two events: `ORD:0` (a schema cycle missed its critical delay) and `ORD:1` (a schema activation was refused); their data is the schema name, in the implicit string `ord_schema`.',
        example: 'R: [ORD:2] [elapsed=1ms]'
    },
    'supervisor-ord-schema-misuse': {
        severity: 'error',
        description: '`ord_schema` is the implicit string holding the schema name of an `ORD` event: it is only usable in the tests and extractions of an `ORD:0`/`ORD:1` event (and it is a reserved name).',
        example: 'R: [MAA:2<ord_schema == "s">] [elapsed=1ms]'
    },
    'supervisor-ord-schema-unknown': {
        severity: 'warning',
        description: 'A test `ord_schema == "name"` (or `!=`) in an `ORD:0`/`ORD:1` event compares with a schema name that no schema of the project has: ORD names the schema whose cycle missed its critical delay (ORD:0) or whose activation was refused (ORD:1), so the test is never true (`!=`: always). Often a typo or a schema renamed by hand; `contract rename` and the editor\'s rename of a schema rewrite these strings. The message names the closest schema.',
        example: 'R: [ORD:0<ord_schema == "pikLoop">] ...   // the schema is pickLoop'
    },
    'supervisor-test-type': {
        severity: 'error',
        description: 'Both operands of a test have the same type (int and float mix); structs and strings compare through the generated `eq_`/`diff_`/`inf_`/`sup_`/`infeq_`/`supeq_` functions.',
        example: 'MAA:2<connection_status == 3>   // connection_status is a string'
    },
    'supervisor-extraction-target': {
        severity: 'error',
        description: 'An extraction `(x = v)` assigns a local variable (or one of its fields); event-port variables are written by events, parameters are not used by rules.',
        example: 'MSC:1(failure = failure_data)   // failure is an event-port variable'
    },
    'supervisor-notify-target': {
        severity: 'error',
        description: '`notify :o (var = v, ...)` assigns the variable of the notified output event port `:o` (or its fields), which carries the event\'s data.',
        example: 'notify :1 (temp_mess_type = "x")   // the variable of port :1 is failure_message_type'
    },
    'supervisor-argument-duplicate': {
        severity: 'error',
        description: 'An activation (`activate schema S(p = v, ...)`, `activate supervisor SUP.fn(p = v, ...)`) or a notify sets each parameter or variable at most once.',
        example: 'activate schema s(consigne = a, consigne = b)'
    },
    'supervisor-module-not-async': {
        severity: 'error',
        description: '`activate resttime module M` and `activate critical module M` start an asynchronous module (a long computation) at that priority; synchronous modules are run by ORD through periodic schemas.',
        example: 'activate resttime module MSA   // MSA is synchronous'
    },
    'supervisor-subscribe-type': {
        severity: 'error',
        description: '`subscribe M:o =* :i` connects the output event port o of M to the supervisor\'s input event port i: both carry the same type (the message shows both).',
        example: 'subscribe MAA:2 =* :3   // MAA:2 is a string, :3 is TypeD'
    },
    'supervisor-subscribe-conflict': {
        severity: 'warning',
        description: 'An input event port has at most one producer at a time (language-reference.md §4). Two `subscribe` actions of the supervisor (in any of its functions: they share the ports) connect producers to the same input port: different ones, or the same one twice (the runtime refuses the second while the first holds the port: `port :i already subscribed`); whether their rules can be active at once is not decidable statically, so this is a warning: make sure they never are, or use one input port per producer (the same producer: one subscribe, in a rule active whenever either needs the events). Not warned: two rules of one function that the rules show are never active at once, one becoming active once at most and the other only after its end (on its `endof` without persistence, or through a chain of rules that start so: `B: [endof(A)]` after `A: [elapsed=1ms]`), or two rules taking turns, each on the `endof` of another, that one event occurring once at most starts (`A: [elapsed=1ms or endof(B)]`, `B: [endof(A)]`). Rules taking turns that may still be active at once (a second of them starting otherwise, a start that may come again, one end starting two) are warned with the reason.',
        example: 'A: [elapsed=1ms] subscribe MAA:2 =* :2 [...]  B: [elapsed=2ms] subscribe MAB:1 =* :2 [...]'
    },
    'supervisor-endof-own-postcondition': {
        severity: 'warning',
        description: 'Report §4.7: `endof(L)` in the postcondition of L itself can never be true: the postcondition defines when L becomes inactive, it cannot wait for an event that follows that deactivation.',
        example: 'REGLEA: [elapsed=1ms] compute doit("a", 1.0) [endof(REGLEA)]'
    },
    'supervisor-started-own-precondition': {
        severity: 'warning',
        description: 'Report §4.7: `started(L)` or `duration(L)` in the precondition of L itself can never be true: the precondition defines when L becomes active, it cannot wait for an event that follows that activation (at once for started, after a while for duration).',
        example: 'REGLEB: [started(REGLEB)] compute doit("a", 1.0) [elapsed=1ms]'
    },
    'supervisor-clause-transient': {
        severity: 'warning',
        description: 'Report §4.7: in a clause `(e1 and e2 ...)` all events but at most one need a persistence `{time}` or `{infinite}`: events are never simultaneous, so a clause with two transient events can never be true. The one transient event is necessarily the last one notified when the clause becomes true.',
        example: 'R: [(MAA:2 and elapsed=1ms)] ... [...]'
    },
    'supervisor-elapsed-once': {
        severity: 'warning',
        description: '`elapsed=t` occurs once in a run of the function, t after it started, whatever the rule: a rule that only `elapsed` ends, and that a rule sequence (`endof`, `started`, `duration` in its precondition) may make active again, never ends after its first activation, nor on one that comes after t. To end the rule t after each of its activations, write `duration(R)=t` (quick fix).',
        example: 'R2: [endof(R1)] activate schema watchB() [elapsed=60ms]   // R1: [elapsed=1ms or endof(R6)] ...'
    },
    'supervisor-event-not-subscribed': {
        severity: 'warning',
        description: 'A condition uses an event of a module or supervisor output port that the function never subscribes to (`subscribe M:o =* :i`): until it subscribes, every clause with this event is false (report §4.7). `ORD` events need no subscribe.',
        example: 'R: [MAA:2] compute doit("a", 1.0) [elapsed=1ms]   // no subscribe MAA:2 in this function'
    },
    'supervisor-event-variable': {
        severity: 'warning',
        description: 'A module event delivers its data into the supervisor input ports its subscribes connect it to (`subscribe MAA:2 =* :2` writes `:2`). A test of the event reads another input port\'s variable, or an extraction reads an input port that no module event of its clause writes: it would see that port\'s older value, not this event\'s data. When the function subscribes the module port to several input ports, the event waits for the deliveries into the one whose variable it reads; one that reads the variables of several of them is warned too: an occurrence comes in on one port and writes that one only (write one event per port: `MAA:2<a == "x"> or MAA:2<b == "y">`).',
        example: 'R: [elapsed=1ms] subscribe MAA:2 =* :2 [MAA:2<failure.datavalue == 3>]   // failure is the variable of :3'
    },
    'supervisor-activation-cycle': {
        severity: 'error',
        description: 'Supervisors that activate each other (`activate supervisor`) form a cycle; the supervisor hierarchy must be a tree or a DAG (it also fixes their priorities). The message lists the cycle.',
        example: '// SUP activates GLB.mission and GLB activates SUP.action'
    },
    'supervisor-schema-conflict': {
        severity: 'warning',
        description: 'ORD refuses to activate a periodic schema that shares a module with an active one and emits `ORD:1` (data: the refused schema). One rule, or two rules that become active together (one\'s precondition has `started` of the other, without persistence, or both start on the same event), activate periodic schemas that share a module (or the same schema twice): the second activation is refused every time. `endof(L)` does not count: L\'s schemas are deactivated before `endof(L)` occurs. The diagnostic data holds the other schema (`conflictsWith`) and the shared modules (`modules`).',
        example: 'R: [elapsed=1ms] activate schema track(); activate schema hold() [elapsed=1s]   // both use EST and CTL'
    }
});
