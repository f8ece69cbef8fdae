/*
 * inest.c — two supervisors of the integration test, built twice (-DINEST_TOP for GLT):
 *   GLT.top:  T1: [elapsed=5ms] subscribe SLV:0 => :0; activate supervisor SLV.work(n = 2)
 *                 [SLV:0<(done == "finished")>]
 *   SLV.work(int n): local { int ln; int step = n; }
 *             W1: [elapsed=5ms] subscribe AMX:0 =* :0; activate schema EVS(step = step)
 *                 [AMX:0<(ev > 5)>(ln = ev)]
 *             W2: [endof(W1)] notify :0(done = "finished") [ ]
 *   event schema EVS(int step = 1) { modules { AMX (step :0); } }
 * AMX posts step, 2*step, ... every 10 ms: with step 2, W1 ends on 6, EVS is undone (AMX
 * stopped), W2 notifies GLT, whose T1 ends and stops SLV.work.
 */
#include <stddef.h>

#include "../engine_executable.h"

#ifdef INEST_TOP
ENGINE_EXECUTABLE("GLT", 95, "engines integration test supervisor")
#else
ENGINE_EXECUTABLE("SLV", 92, "engines integration test supervisor")
#endif

#define MS 1000000LL
static const char k_finished[256] = "finished";
static const ContractEvent e5[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 5 * MS}};
static const ContractClause c5[] = {{1, e5}};
static const ContractVar work_params[] = {{"n", &contract_type_long, 0, NULL}};

#ifdef INEST_TOP
static const long k2 = 2;
static const ContractEventPort in_ports[] = {{0, "done", &contract_type_string, NULL}};
static const ContractFunctionSignature sig_work = {"SLV", "work", 1, work_params, sizeof(long)};
static const ContractAssign t1_params[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_CONST, 0, 0, &contract_type_long, &k2}}};
static const ContractAction t1_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "SLV", .src_port = 0, .in_port = 0, .mode = CONTRACT_ONESHOT},
    {.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_work, .nassigns = 1, .assigns = t1_params}};
static const ContractTest t1_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_string, NULL},
     {CONTRACT_REF_CONST, 0, 0, &contract_type_string, k_finished}, NULL, 0, NULL}};
static const ContractTestClause t1_tc[] = {{1, t1_tests}};
static const ContractEvent t1_post_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "SLV", .port = 0, .in_port = 0, .ntest_clauses = 1, .test_clauses = t1_tc}};
static const ContractClause t1_post[] = {{1, t1_post_ev}};
static const ContractRule rules[] = {{"T1", {1, c5}, 2, t1_actions, {1, t1_post}}};
static const ContractFunction functions[] = {{"top", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, rules}};
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "GLT", 95, 40, 5, 70, 1, in_ports, 0, NULL, 1, functions};
#else
static const long k1 = 1, k5 = 5;
typedef struct WorkLocals { long ln; long step; } WorkLocals;
static const ContractEventPort in_ports[] = {{0, "ev", &contract_type_long, NULL}};
static const ContractEventPort out_ports[] = {{0, "done", &contract_type_string, NULL}};
static const ContractVar work_locals[] = {
    {"ln", &contract_type_long, offsetof(WorkLocals, ln), NULL},
    {"step", &contract_type_long, offsetof(WorkLocals, step), NULL}};
static const ContractAssign work_inits[] = {
    {1, 0, &contract_type_long, {CONTRACT_REF_PARAM, 0, 0, &contract_type_long, NULL}}};
static const ContractVar evs_params[] = {{"step", &contract_type_long, 0, &k1}};
static const ContractAssign evs_amx_p0[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_PARAM, 0, 0, &contract_type_long, NULL}}};
static const ContractParamSetting evs_amx_settings[] = {{0, &contract_type_long, 1, evs_amx_p0, NULL}};
static const ContractSchemaModule evs_modules[] = {{"AMX", 1, evs_amx_settings}};
static const ContractSchema EVS = {"EVS", CONTRACT_SCHEMA_EVENT, 0, 0, 1, evs_params, sizeof(long),
                                   1, evs_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractAssign w1_schema_params[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_LOCAL, 1, 0, &contract_type_long, NULL}}};
static const ContractAction w1_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "AMX", .src_port = 0, .in_port = 0, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &EVS, .nassigns = 1, .assigns = w1_schema_params}};
static const ContractTest w1_tests[] = {
    {CONTRACT_TEST_GT, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_long, NULL},
     {CONTRACT_REF_CONST, 0, 0, &contract_type_long, &k5}, NULL, 0, NULL}};
static const ContractTestClause w1_tc[] = {{1, w1_tests}};
static const ContractAssign w1_extr[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_long, NULL}}};
static const ContractEvent w1_post_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "AMX", .port = 0, .in_port = 0, .ntest_clauses = 1,
     .test_clauses = w1_tc, .nextractions = 1, .extractions = w1_extr}};
static const ContractClause w1_post[] = {{1, w1_post_ev}};
static const ContractEvent w2_pre_ev[] = {{.kind = CONTRACT_EV_ENDOF, .rule = 0}};
static const ContractClause w2_pre[] = {{1, w2_pre_ev}};
static const ContractAssign w2_notify[] = {
    {0, 0, &contract_type_string, {CONTRACT_REF_CONST, 0, 0, &contract_type_string, k_finished}}};
static const ContractAction w2_actions[] = {
    {.kind = CONTRACT_ACT_NOTIFY, .out_port = 0, .nassigns = 1, .assigns = w2_notify}};
static const ContractRule rules[] = {
    {"W1", {1, c5}, 2, w1_actions, {1, w1_post}},
    {"W2", {1, w2_pre}, 1, w2_actions, {0, NULL}}};
static const ContractFunction functions[] = {
    {"work", 1, work_params, sizeof(long), 2, work_locals, sizeof(WorkLocals), 1, work_inits, 2, rules}};
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "SLV", 92, 40, 5, 70, 1, in_ports, 1, out_ports, 1, functions};
#endif

int ModuleMain(int argc, const char *argv[]) { return contract_supervisor_main(&VOCABULARY, argc, argv); }
