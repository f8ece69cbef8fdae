/**
 * Names the generated C declares itself, next to the Cactal names it uses as they are
 * (docs/codegen.md; docs/language-reference.md, "Reserved names"). Each list says where the
 * generator writes them, so that a change there is mirrored here; the codegen property test
 * (packages/codegen/src/reserved-names.integration.test.ts) compiles random projects to keep them honest.
 */

/** Globals of every `modules/<M>_mod/module.c` (module-source.ts), in scope of the module's ports and datatypes. */
export const MODULE_GLOBALS: readonly string[] = [
    'MODULE_NAME', 'MODULE_PRIORITY', 'IUSE', 'IPRODUCE', 'IREACT', 'IDETECT', 'PARAM_SIZE_IN', 'PARAM_SIZE_OUT',
    'productionTime', 'receptionTime', 'ModuleMain'
];

/**
 * Locals of ModuleMain and parameters of the user functions of module.c (`_exec_module_state(int *
 * stateindex)`, `_react_to_event(...)`, `_react_to_parameterizing(...)`): a port of that name would be
 * hidden there (ModuleMain copies parameters into `&<port>`, the regions read the ports).
 */
export const MODULE_LOCALS: readonly string[] = [
    'receivedMessage', 'registered', 'subscription', 'end', 'state', 'interact', 'cycleRunning', 'argc', 'argv',
    'stateindex', 'receiverport', 'senderport', 'sendermodule', 'eventProductionTime', 'eventReceptionTime', 'parameterport'
];

/**
 * Other identifiers that every generated module.c writes after `#include "constants.h"`: the members
 * of libmodule's `RequestMessage` that the request loop reads (module-source.ts) and gcc's
 * `fallthrough` attribute. A named constant, a macro there, may not take them.
 */
export const MODULE_SOURCE_WORDS: readonly string[] = [
    'Type', 'Param', 'Start', 'Stop', 'Kil', 'Event', 'SetParam', 'Subscribe', 'Unsubscribe', 'SubscribeEvent',
    'UnsubscribeEvent', 'SubscribeUser', 'UnsubscribeUser', 'SubscribeUserToEvent', 'UnsubscribeUserToEvent',
    'SubscribeVariables', 'UnsubscribeVariables', 'WantedAck', 'ModAck', 'AckID', 'Periodicity', 'Port', 'SourcePort',
    'TargetModule', 'TargetPort', 'isContextual', 'sourceModule', 'sourcePort', 'targetModule', 'targetPort', 'mode', 'fallthrough'
];

/**
 * Parameters and locals of the functions of `common/Shared<T>.h` (shared-type-header.ts): a datatype
 * of that name would be hidden by them inside its own functions (`eq_arg1(arg1 * arg1, arg1 * arg2)`).
 */
export const TYPE_HEADER_LOCALS: readonly string[] = [
    'arg', 'arg1', 'arg2', 'buffer', 'description', 'size', 'sizeread', 'res', 'symbol', 'tmp',
    // enumeration headers (shared-enum-header.ts) and the control tools' array parsers (extension types)
    'i', 'm', 'n', 'next', 'value', 'names', 'dst'
];

/**
 * File-scope names of the files that include the `common/` headers next to the generated tables:
 * the control tools (`main`, `PARAMS`, control-tool.ts), ORD's vocabulary and ORD's headers
 * (ord-module.ts), and `a`, the parameter of the user-function adapters of vocabulary.c
 * (table-builder.ts: `static int call_f(void **a) { return f((long *)a[0]); }`).
 */
export const TOOL_AND_VOCABULARY_NAMES: readonly string[] = [
    'main', 'PARAMS', 'ORD_VOCABULARY', 'SCHEDTYPES_H', 'SCHEDMESSAGES_H', 'ORD_MOD_TOOLS_H', 'ORD_EVENT_DEADLINE_MISS',
    'ORD_EVENT_CONFLICT', 'a'
];

/**
 * Name spaces of the runtime (contract/vocabulary.h, libmodule: `contract_type_T`,
 * `ContractModuleDescription`, ...) and the parsers of the control tools (libmodule/control.h:
 * CONTROL_DEFINE_PARSER(get_T, T) defines `control_get_T`).
 */
export const RUNTIME_PREFIXES: readonly string[] = ['contract_', 'Contract', 'CONTRACT_', 'control_get_'];

/** Functions of `common/Shared<T>.h` for datatype T (shared-type-header.ts): `<prefix>_<T>`. */
export const TYPE_FUNCTION_PREFIXES: readonly string[] = [
    'serialize', 'deserialize', 'diff', 'eq', 'inf', 'sup', 'infeq', 'supeq', 'set', 'get', 'print'
];

/** Names built from a supervisor's name S (three upper-case letters): its table and its header guard. */
export const SUPERVISOR_DERIVED = /^(?:[A-Z]{3}_VOCABULARY|SUPTYPES_[A-Z]{3}_H)$/;

/** Header guards of the `common/` headers (shared-type-header.ts, shared-function-header.ts). */
export const SHARED_GUARD = /^SHARED_\w*_H$/;

/**
 * What a datatype or function prototype writes into `common/` (shared-type-header.ts,
 * shared-function-header.ts): its header file and the header's include guard. Two elements must
 * not share either (`Pose` and `POSE` share SHARED_POSE_H; datatype `FunctionStep` and function
 * `Step` both write SharedFunctionStep.h). File names compare without case: checkouts on
 * case-insensitive file systems would merge them.
 */
export function commonHeaderKeys(kind: 'datatype' | 'function', name: string): { file: string; guard: string } {
    return kind === 'datatype'
        ? { file: `Shared${name}.h`, guard: `SHARED_${name.toUpperCase()}_H` }
        : { file: `SharedFunction${name}.h`, guard: `SHARED_FUNCTION_${name.toUpperCase()}_H` };
}
