/*
 * itoggle.c — two supervisors that toggle event schemas sharing the asynchronous AMX as fast
 * as their timers go, concurrently (itest_toggles.c), built twice (-DITOGGLE_TOP for HTA):
 *   HTA.main: M: [elapsed=1ms] activate supervisor HTA.flip() [elapsed=700ms]
 *             N: [elapsed=1ms] activate supervisor HTB.flip() [elapsed=700ms]
 *   HTA.flip: T1: [elapsed=5ms | endof(T2)] activate schema EVA [duration(T1)=3ms]
 *             T2: [endof(T1)] [duration(T2)=2ms]
 *   HTB.flip: T1: [elapsed=5ms | endof(T2)] activate schema EVB [duration(T1)=2ms]
 *             T2: [endof(T1)] [duration(T2)=2ms]
 *   event schemas EVA, EVB { modules { AMX; } }
 * Periods of ~5 ms and ~4 ms drift against each other, so one supervisor's last-hold drop
 * (stop AMX) often meets the other's "AMX runs: share it" decision. At 700 ms HTA.main stops
 * both flips (their active T1 undone): AMX must end stopped, well before the launcher stops
 * the architecture.
 */
#include <stddef.h>

#include "../engine_executable.h"

#ifdef ITOGGLE_TOP
#define SUP_NAME "HTA"
#define SUP_PRIO 95
#define ON_MS 3
#define SCHEMA_NAME "EVA"
#else
#define SUP_NAME "HTB"
#define SUP_PRIO 92
#define ON_MS 2
#define SCHEMA_NAME "EVB"
#endif
ENGINE_EXECUTABLE(SUP_NAME, SUP_PRIO, "engines integration test supervisor (hold toggles)")
#define OFF_MS 2
#define MS 1000000LL

static const ContractSchemaModule amx_only[] = {{"AMX", 0, NULL}};
static const ContractSchema EV = {SCHEMA_NAME, CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 1, amx_only,
                                  0, NULL, 0, NULL, 0, NULL};
static const ContractEvent t1_first[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 5 * MS}};
static const ContractEvent t1_again[] = {{.kind = CONTRACT_EV_ENDOF, .rule = 1}};
static const ContractClause t1_pre[] = {{1, t1_first}, {1, t1_again}};
static const ContractEvent t1_end[] = {{.kind = CONTRACT_EV_DURATION, .rule = 0, .time_ns = ON_MS * MS}};
static const ContractClause t1_post[] = {{1, t1_end}};
static const ContractAction t1_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &EV}};
static const ContractEvent t2_start[] = {{.kind = CONTRACT_EV_ENDOF, .rule = 0}};
static const ContractClause t2_pre[] = {{1, t2_start}};
static const ContractEvent t2_end[] = {{.kind = CONTRACT_EV_DURATION, .rule = 1, .time_ns = OFF_MS * MS}};
static const ContractClause t2_post[] = {{1, t2_end}};
static const ContractRule flip_rules[] = {{"T1", {2, t1_pre}, 1, t1_actions, {1, t1_post}},
                                          {"T2", {1, t2_pre}, 0, NULL, {1, t2_post}}};

#ifdef ITOGGLE_TOP
static const ContractEvent e1[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 1 * MS}};
static const ContractEvent e700[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 700 * MS}};
static const ContractClause c1[] = {{1, e1}}, c700[] = {{1, e700}};
static const ContractFunctionSignature sig_own = {"HTA", "flip", 0, NULL, 0};
static const ContractFunctionSignature sig_other = {"HTB", "flip", 0, NULL, 0};
static const ContractAction m_actions[] = {{.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_own}};
static const ContractAction n_actions[] = {{.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_other}};
static const ContractRule main_rules[] = {{"M", {1, c1}, 1, m_actions, {1, c700}},
                                          {"N", {1, c1}, 1, n_actions, {1, c700}}};
static const ContractFunction functions[] = {{"main", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, main_rules},
                                              {"flip", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, flip_rules}};
#else
static const ContractFunction functions[] = {{"flip", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, flip_rules}};
#endif
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, SUP_NAME, SUP_PRIO, 40, 5, 70, 0, NULL, 0, NULL,
    (int)(sizeof functions / sizeof functions[0]), functions};

int ModuleMain(int argc, const char *argv[]) { return contract_supervisor_main(&VOCABULARY, argc, argv); }
