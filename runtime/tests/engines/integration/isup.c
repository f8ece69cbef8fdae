/*
 * isup.c — the supervisor executable of the integration test (module.c binding +
 * vocabulary.c tables, as generated): ISU.go:
 *   local { int g = 7; }
 *   R1: [elapsed=10ms] activate schema ISC(gain = g) [elapsed=300ms]
 *   R2: [elapsed=50ms] activate schema ICF() [ ]              (conflicts with ISC: ORD:1)
 *   R3: [ORD:1<(ord_schema == "ICF")>] [ ]
 */
#include "../engine_executable.h"

ENGINE_EXECUTABLE("ISU", 90, "engines integration test supervisor")

#include "itables.h"

static const long k7 = 7;
static const char k_icf[256] = "ICF";
static const ContractVar go_locals[] = {{"g", &contract_type_long, 0, &k7}};
static const ContractEvent e10[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 10 * ITEST_MS}};
static const ContractEvent e50[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 50 * ITEST_MS}};
static const ContractEvent e300[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 300 * ITEST_MS}};
static const ContractClause c10[] = {{1, e10}}, c50[] = {{1, e50}}, c300[] = {{1, e300}};
static const ContractAssign r1_params[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_LOCAL, 0, 0, &contract_type_long, NULL}}};
static const ContractAction r1_actions[] = {
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_ISC, .nassigns = 1, .assigns = r1_params}};
static const ContractAction r2_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_ICF}};
static const ContractTest r3_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_ORD_SCHEMA, 0, 0, &contract_type_string, NULL},
     {CONTRACT_REF_CONST, 0, 0, &contract_type_string, k_icf}, NULL, 0, NULL}};
static const ContractTestClause r3_tc[] = {{1, r3_tests}};
static const ContractEvent r3_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "ORD", .port = 1, .in_port = -1, .ntest_clauses = 1,
     .test_clauses = r3_tc}};
static const ContractClause r3_pre[] = {{1, r3_ev}};
static const ContractRule go_rules[] = {
    {"R1", {1, c10}, 1, r1_actions, {1, c300}},
    {"R2", {1, c50}, 1, r2_actions, {0, NULL}},
    {"R3", {1, r3_pre}, 0, NULL, {0, NULL}}};
static const ContractFunction functions[] = {
    {"go", 0, NULL, 0, 1, go_locals, sizeof(long), 0, NULL, 3, go_rules}};
static const ContractSupervisorVocabulary ISU_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "ISU", 90, 40, 5, 70, 0, NULL, 0, NULL, 1, functions};

int ModuleMain(int argc, const char *argv[]) {
    return contract_supervisor_main(&ISU_VOCABULARY, argc, argv);
}
