/*
 * ireactivate.c — the supervisor RSU of the reactivation scenario (itest_reactivate.c):
 *   RSU.go:
 *     R1: [elapsed=10ms] subscribe RMB:0 =* :0; activate schema RSC() [RMB:0]
 *     R2: [endof(R1)] activate schema RSC() [ ]
 * RMB posts RMB:0 when it begins its slow activation (then works 300 ms, 15 periods): R1 ends,
 * which deactivates RSC while RMB still runs that release, and R2 activates RSC again at once
 * (the same input: endof(R1) is processed before the next one).
 */
#include "../engine_executable.h"

ENGINE_EXECUTABLE("RSU", 90, "engines integration test supervisor (reactivation)")

#include "itables.h"

static const ContractEventPort in_ports[] = {{0, "slow", &contract_type_long, NULL}};
static const ContractEvent e10[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 10 * ITEST_MS}};
static const ContractClause c10[] = {{1, e10}};
static const ContractAction r1_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "RMB", .src_port = 0, .in_port = 0, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_RSC}};
static const ContractEvent r1_post_ev[] = {{.kind = CONTRACT_EV_MODULE, .module = "RMB", .port = 0, .in_port = 0}};
static const ContractClause r1_post[] = {{1, r1_post_ev}};
static const ContractEvent r2_pre_ev[] = {{.kind = CONTRACT_EV_ENDOF, .rule = 0}};
static const ContractClause r2_pre[] = {{1, r2_pre_ev}};
static const ContractAction r2_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_RSC}};
static const ContractRule go_rules[] = {{"R1", {1, c10}, 2, r1_actions, {1, r1_post}},
                                        {"R2", {1, r2_pre}, 1, r2_actions, {0, NULL}}};
static const ContractFunction functions[] = {{"go", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, go_rules}};
static const ContractSupervisorVocabulary RSU_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "RSU", 90, 40, 5, 70, 1, in_ports, 0, NULL, 1, functions};

int ModuleMain(int argc, const char *argv[]) { return contract_supervisor_main(&RSU_VOCABULARY, argc, argv); }
