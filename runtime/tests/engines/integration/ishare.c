/*
 * ishare.c — two supervisors sharing the asynchronous AMX through event schemas (docs/semantics.md
 * "Event schemas: undo and shared modules", across supervisors), built twice (-DISHARE_TOP for SHA):
 *   SHA.top:  A1: [elapsed=5ms]  activate schema EVA   [elapsed=150ms]
 *             A2: [elapsed=20ms] activate supervisor SHB.use() [ ]
 *   SHB.use:  B1: [elapsed=10ms] activate schema EVB   [elapsed=300ms]
 *   event schemas EVA, EVB { modules { AMX; } }
 * SHA starts AMX at 5 ms; SHB finds it running at ~30 ms (status query) and does not start it
 * again; SHA's A1 ends at 150 ms but AMX keeps running (SHB still uses it); SHB's B1 ends at
 * ~320 ms and, as the last user of a module a supervisor started, stops AMX.
 */
#include <stddef.h>

#include "../engine_executable.h"

#ifdef ISHARE_TOP
ENGINE_EXECUTABLE("SHA", 95, "engines integration test supervisor (shared module)")
#else
ENGINE_EXECUTABLE("SHB", 92, "engines integration test supervisor (shared module)")
#endif

#define MS 1000000LL
static const ContractSchemaModule amx_only[] = {{"AMX", 0, NULL}};

#ifdef ISHARE_TOP
static const ContractSchema EVA = {"EVA", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 1, amx_only, 0, NULL, 0, NULL, 0, NULL};
static const ContractEvent e5[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 5 * MS}};
static const ContractEvent e20[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 20 * MS}};
static const ContractEvent e150[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 150 * MS}};
static const ContractClause c5[] = {{1, e5}}, c20[] = {{1, e20}}, c150[] = {{1, e150}};
static const ContractFunctionSignature sig_use = {"SHB", "use", 0, NULL, 0};
static const ContractAction a1_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &EVA}};
static const ContractAction a2_actions[] = {{.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_use}};
static const ContractRule rules[] = {{"A1", {1, c5}, 1, a1_actions, {1, c150}},
                                     {"A2", {1, c20}, 1, a2_actions, {0, NULL}}};
static const ContractFunction functions[] = {{"top", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, rules}};
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "SHA", 95, 40, 5, 70, 0, NULL, 0, NULL, 1, functions};
#else
static const ContractSchema EVB = {"EVB", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 1, amx_only, 0, NULL, 0, NULL, 0, NULL};
static const ContractEvent e10[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 10 * MS}};
static const ContractEvent e300[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 300 * MS}};
static const ContractClause c10[] = {{1, e10}}, c300[] = {{1, e300}};
static const ContractAction b1_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &EVB}};
static const ContractRule rules[] = {{"B1", {1, c10}, 1, b1_actions, {1, c300}}};
static const ContractFunction functions[] = {{"use", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, rules}};
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "SHB", 92, 40, 5, 70, 0, NULL, 0, NULL, 1, functions};
#endif

int ModuleMain(int argc, const char *argv[]) { return contract_supervisor_main(&VOCABULARY, argc, argv); }
