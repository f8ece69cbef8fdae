/*
 * istuck.c — the supervisor SKS of the stuck-module scenario (itest_stuck.c):
 *   SKS.go:
 *     W:  [elapsed=10ms] activate schema SLW() [ ]
 *     T1: [elapsed=10ms | endof(T2)] activate schema FST(), parameterize STK(7 :0)
 *         [ORD:0<(ord_schema == "FST")>]
 *     T2: [endof(T1)] [duration(T2)=20ms]
 * as a supervisor that recovers from a deadline miss by deactivating the schema and activating
 * it again (the mobile robot's DRV and MIS do so on ORD:0). Once STK is stuck in its release,
 * every activation of FST is held for it and misses its deadline: SKS toggles FST every ~30 ms,
 * and each activation makes ORD send STK a parameter request (gain) that STK never reads, and
 * SKS send it one of its own: SKS keeps those for STK's full mailbox and goes on (it used to wait
 * 2 s for room at each, toggling FST once per 2 s: the mobile robot's DRV parameterizing VEL).
 *   SKS.crash:
 *     C:  [elapsed=10ms] activate schema CRH() [ ]
 * for the crashed-module scenario: CRS is killed in its 5th release of CRH.
 *   SKS.busy:
 *     A:  [elapsed=10ms] activate resttime module AMS [duration(A)=400ms]
 *     P:  [elapsed=10ms | endof(Q)] parameterize AMS(1 :0) [duration(P)=5ms]
 *     Q:  [endof(P)] [duration(Q)=5ms]
 * for the kept-stop scenario: AMS, busy 5 s in its own code from its START, reads nothing, so
 * P's values fill its mailbox; A's undo, the STOP of AMS, is kept behind them and fails 2 s later.
 *   SKS.flood:
 *     F:  [elapsed=10ms] activate schema FLD() [ ]
 * for the output-flood scenario: FLM takes 3 ms a release of FLD (1 ms): ORD misses every deadline.
 *   SKS.evflood:
 *     E:  [elapsed=10ms] activate schema EVF() [duration(E)=600ms]
 *     R:  [elapsed=300ms] activate resttime module AMC, parameterize AMC(5 :0) [duration(R)=100ms]
 *   with event schema EVF { modules { AMC (); AMF (); } communications { AMF:0 =* AMC:0; } }
 * for the event-flood scenario: AMF posts as fast as AMC, 5 ms an event, takes them, so AMC's
 * mailbox is always full; R's priority change and parameter, and E's undo (the STOP of AMC),
 * are requests to the flooded AMC.
 */
#include "../engine_executable.h"

ENGINE_EXECUTABLE("SKS", 90, "engines integration test supervisor (stuck module)")

#include "itables.h"

static const char k_fst[256] = "FST";
ELAPSED(c10, 10 * ITEST_MS)
static const ContractAction w_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_SLW}};
static const ContractEvent t1_again[] = {{.kind = CONTRACT_EV_ENDOF, .rule = 2}};
static const ContractClause t1_pre[] = {{1, c10_ev}, {1, t1_again}};
static const long k_gain = 7;
static const ContractAssign stk_gain[] = {{0, 0, &contract_type_long, {CONTRACT_REF_CONST, 0, 0, &contract_type_long, &k_gain}}};
static const ContractParamSetting stk_settings[] = {{0, &contract_type_long, 1, stk_gain, "gain"}};
static const ContractAction t1_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_FST},
                                            {.kind = CONTRACT_ACT_PARAMETERIZE, .module = "STK", .nsettings = 1,
                                             .settings = stk_settings}};
static const ContractTest miss_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_ORD_SCHEMA, 0, 0, &contract_type_string, NULL},
     {CONTRACT_REF_CONST, 0, 0, &contract_type_string, k_fst}, NULL, 0, NULL}};
static const ContractTestClause miss_tc[] = {{1, miss_tests}};
static const ContractEvent miss_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "ORD", .port = 0, .in_port = -1, .ntest_clauses = 1,
     .test_clauses = miss_tc}};
static const ContractClause t1_post[] = {{1, miss_ev}};
static const ContractEvent t2_start[] = {{.kind = CONTRACT_EV_ENDOF, .rule = 1}};
static const ContractClause t2_pre[] = {{1, t2_start}};
static const ContractEvent t2_end[] = {{.kind = CONTRACT_EV_DURATION, .rule = 2, .time_ns = 20 * ITEST_MS}};
static const ContractClause t2_post[] = {{1, t2_end}};
static const ContractRule go_rules[] = {{"W", {1, c10}, 1, w_actions, {0, NULL}},
                                        {"T1", {2, t1_pre}, 2, t1_actions, {1, t1_post}},
                                        {"T2", {1, t2_pre}, 0, NULL, {1, t2_post}}};
static const ContractAction c_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_CRH}};
static const ContractRule crash_rules[] = {{"C", {1, c10}, 1, c_actions, {0, NULL}}};
ELAPSED(c10b, 10 * ITEST_MS)
static const long k_one = 1;
static const ContractAssign ams_step[] = {{0, 0, &contract_type_long, {CONTRACT_REF_CONST, 0, 0, &contract_type_long, &k_one}}};
static const ContractParamSetting ams_settings[] = {{0, &contract_type_long, 1, ams_step, "step"}};
static const ContractAction a_actions[] = {{.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "AMS"}};
static const ContractEvent a_end[] = {{.kind = CONTRACT_EV_DURATION, .rule = 0, .time_ns = 400 * ITEST_MS}};
static const ContractClause a_post[] = {{1, a_end}};
static const ContractAction p_actions[] = {{.kind = CONTRACT_ACT_PARAMETERIZE, .module = "AMS", .nsettings = 1, .settings = ams_settings}};
static const ContractEvent p_again[] = {{.kind = CONTRACT_EV_ENDOF, .rule = 2}};
static const ContractClause p_pre[] = {{1, c10b_ev}, {1, p_again}};
static const ContractEvent p_end[] = {{.kind = CONTRACT_EV_DURATION, .rule = 1, .time_ns = 5 * ITEST_MS}};
static const ContractClause p_post[] = {{1, p_end}};
static const ContractEvent q_start[] = {{.kind = CONTRACT_EV_ENDOF, .rule = 1}};
static const ContractClause q_pre[] = {{1, q_start}};
static const ContractEvent q_end[] = {{.kind = CONTRACT_EV_DURATION, .rule = 2, .time_ns = 5 * ITEST_MS}};
static const ContractClause q_post[] = {{1, q_end}};
static const ContractRule busy_rules[] = {{"A", {1, c10b}, 1, a_actions, {1, a_post}},
                                          {"P", {2, p_pre}, 1, p_actions, {1, p_post}},
                                          {"Q", {1, q_pre}, 0, NULL, {1, q_post}}};
static const ContractAction f_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_FLD}};
static const ContractRule flood_rules[] = {{"F", {1, c10}, 1, f_actions, {0, NULL}}};
static const ContractSchemaModule evf_modules[] = {{"AMC", 0, NULL}, {"AMF", 0, NULL}};
static const ContractEventFlow evf_flows[] = {{"AMF", 0, "AMC", 0, CONTRACT_CONTINUOUS}};
static const ContractSchema EVF = {"EVF", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 2, evf_modules, 0, NULL, 0, NULL, 1, evf_flows};
static const ContractAction e_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &EVF}};
static const ContractEvent e_end[] = {{.kind = CONTRACT_EV_DURATION, .rule = 0, .time_ns = 600 * ITEST_MS}};
static const ContractClause e_post[] = {{1, e_end}};
ELAPSED(c300, 300 * ITEST_MS)
static const long k_five = 5;
static const ContractAssign amc_step[] = {{0, 0, &contract_type_long, {CONTRACT_REF_CONST, 0, 0, &contract_type_long, &k_five}}};
static const ContractParamSetting amc_settings[] = {{0, &contract_type_long, 1, amc_step, "step"}};
static const ContractAction r_actions[] = {{.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "AMC"},
                                           {.kind = CONTRACT_ACT_PARAMETERIZE, .module = "AMC", .nsettings = 1, .settings = amc_settings}};
static const ContractEvent r_end[] = {{.kind = CONTRACT_EV_DURATION, .rule = 1, .time_ns = 100 * ITEST_MS}};
static const ContractClause r_post[] = {{1, r_end}};
static const ContractRule evflood_rules[] = {{"E", {1, c10}, 1, e_actions, {1, e_post}},
                                             {"R", {1, c300}, 2, r_actions, {1, r_post}}};
static const ContractFunction functions[] = {{"go", 0, NULL, 0, 0, NULL, 0, 0, NULL, 3, go_rules},
                                             {"crash", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, crash_rules},
                                             {"busy", 0, NULL, 0, 0, NULL, 0, 0, NULL, 3, busy_rules},
                                             {"flood", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, flood_rules},
                                             {"evflood", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, evflood_rules}};
static const ContractSupervisorVocabulary SKS_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "SKS", 90, 40, 5, 70, 0, NULL, 0, NULL, 5, functions};

int ModuleMain(int argc, const char *argv[]) { return contract_supervisor_main(&SKS_VOCABULARY, argc, argv); }
