/*
 * report_tables.c — the report's example (§4.7 example 7, §8.1) written by hand as the
 * tables the generator emits in vocabulary.c: schemas schemaReceptionMessage (event),
 * schemaCommande1/2 (periodic), supervisor SUP (function action, rules FIRST, SECOND, THIRD,
 * FOURTH, RECEPTION), supervisor GLB (function mission, rule SINGLE), and ORD's tables.
 */
#include "report_tables.h"

#include <stddef.h>
#include <string.h>

#include "report_types.h"

TestLog *report_log;
int testit_result = 1;

/* ---- types -------------------------------------------------------------------------- */
static const TypeA contract_default_TypeA = {0.0, 0.0, 0.0};
static const TypeB contract_default_TypeB = {{1.0, 1.0, 1.0}, 1};
static const TypeC contract_default_TypeC = {"", 0, {0.0, 0.0, 0.0}};
static const TypeD contract_default_TypeD = {"", 0};
CONTRACT_DEFINE_TYPE(TypeA, &contract_default_TypeA)
CONTRACT_DEFINE_TYPE(TypeB, &contract_default_TypeB)
CONTRACT_DEFINE_TYPE(TypeC, &contract_default_TypeC)
CONTRACT_DEFINE_TYPE(TypeD, &contract_default_TypeD)
const ContractType *const report_type_TypeA = &contract_type_TypeA;
const ContractType *const report_type_TypeC = &contract_type_TypeC;
const ContractType *const report_type_TypeD = &contract_type_TypeD;

/* ---- user functions (SharedFunctiontestit.h / SharedFunctiondoit.h) ------------------ */
static int testit(char *arg1, TypeA *arg2) {
    if (report_log) log_add(report_log, "testit(%s,{%g,%g,%g})", arg1, arg2->i, arg2->j, arg2->k);
    return testit_result;
}
static void doit(char *argfirst, double *argsecond) {
    if (report_log) log_add(report_log, "compute doit(%s,%g)", argfirst, *argsecond);
}
static int call_testit(void **a) { return testit((char *)a[0], (TypeA *)a[1]); }
static int call_doit(void **a) { doit((char *)a[0], (double *)a[1]); return 0; }
static const ContractType *const testit_args[] = {&contract_type_string, &contract_type_TypeA};
static const ContractType *const doit_args[] = {&contract_type_string, &contract_type_double};
static const ContractUserFunction fn_testit = {"testit", 1, 2, testit_args, call_testit};
static const ContractUserFunction fn_doit = {"doit", 0, 2, doit_args, call_doit};

/* ---- constants ------------------------------------------------------------------------ */
static const char k_disconnected[256] = "disconnected";
static const char k_dedede[256] = "dedede";
static const char k_commutation[256] = "commutation";
static const char k_124[256] = "1.24";
static const TypeA k_param_reception = {27.12, 0.0, 0.04};
static const TypeA k_consigne_zero = {0.0, 0.0, 0.0};

#define REF(kind, index, offset, type, constant) {kind, index, offset, type, constant}
#define CONST_REF(type, ptr) REF(CONTRACT_REF_CONST, 0, 0, type, ptr)

/* ---- schemas -------------------------------------------------------------------------- */

/* event schema schemaReceptionMessage(TypeA param = {27.12,0.0,0.04})
     modules { MAA (param :0); MAB (); }  communications { MAA:0 =* MAB:0; } */
static const ContractVar recep_params[] = {{"param", &contract_type_TypeA, 0, &k_param_reception}};
static const ContractAssign recep_maa_p0[] = {
    {0, 0, &contract_type_TypeA, REF(CONTRACT_REF_PARAM, 0, 0, &contract_type_TypeA, NULL)}};
static const ContractParamSetting recep_maa_settings[] = {{0, &contract_type_TypeA, 1, recep_maa_p0, "param"}};
static const ContractSchemaModule recep_modules[] = {{"MAA", 1, recep_maa_settings}, {"MAB", 0, NULL}};
static const ContractEventFlow recep_flows[] = {{"MAA", 0, "MAB", 0, CONTRACT_CONTINUOUS}};
const ContractSchema schema_schemaReceptionMessage = {
    "schemaReceptionMessage", CONTRACT_SCHEMA_EVENT, 0, 0,
    1, recep_params, sizeof(TypeA), 2, recep_modules, 0, NULL, 0, NULL, 1, recep_flows};

/* periodic schema schemaCommande1(TypeA consigne = {0,0,0}) PERIOD=1s CRITICAL_DELAY=1s
     modules { MSA (); MSC (consigne:0); MSD (); }  MSA -> MSC; MSC -> MSD;
     MSA:0 -> MSC:0 * 1; MSC:1 -> MSD:2 * 2; */
static const ContractVar cmd_params[] = {{"consigne", &contract_type_TypeA, 0, &k_consigne_zero}};
static const ContractAssign cmd_msc_p0[] = {
    {0, 0, &contract_type_TypeA, REF(CONTRACT_REF_PARAM, 0, 0, &contract_type_TypeA, NULL)}};
static const ContractParamSetting cmd_msc_settings[] = {{0, &contract_type_TypeA, 1, cmd_msc_p0, "param"}};
static const ContractSchemaModule cmd1_modules[] = {
    {"MSA", 0, NULL}, {"MSC", 1, cmd_msc_settings}, {"MSD", 0, NULL}};
static const ContractPrecedence cmd_prec[] = {{0, 1}, {1, 2}};
static const ContractDataFlow cmd1_flows[] = {{"MSA", 0, "MSC", 0, 1}, {"MSC", 1, "MSD", 2, 2}};
const ContractSchema schema_schemaCommande1 = {
    "schemaCommande1", CONTRACT_SCHEMA_PERIODIC, 1000000000, 1000000000,
    1, cmd_params, sizeof(TypeA), 3, cmd1_modules, 2, cmd_prec, 2, cmd1_flows, 0, NULL};

/* periodic schema schemaCommande2(TypeA consigne): MSB -> MSC -> MSD */
static const ContractSchemaModule cmd2_modules[] = {
    {"MSB", 0, NULL}, {"MSC", 1, cmd_msc_settings}, {"MSD", 0, NULL}};
static const ContractDataFlow cmd2_flows[] = {{"MSB", 0, "MSC", 0, 1}, {"MSC", 1, "MSD", 2, 1}};
const ContractSchema schema_schemaCommande2 = {
    "schemaCommande2", CONTRACT_SCHEMA_PERIODIC, 1000000000, 1000000000,
    1, cmd_params, sizeof(TypeA), 3, cmd2_modules, 2, cmd_prec, 2, cmd2_flows, 0, NULL};

static const ContractSchema *const ord_schemas[] = {&schema_schemaCommande1, &schema_schemaCommande2};
static const ContractOrdModule ord_modules[] = {
    {"MSA", 60, 500000}, {"MSB", 60, 500000}, {"MSC", 60, 1000000}, {"MSD", 60, 1000000}};
static const char *const ord_supervisors[] = {"GLB", "SUP"};
const ContractOrdVocabulary REPORT_ORD_VOCAB = {
    CONTRACT_VOCABULARY_VERSION, 4, ord_modules, 2, ord_schemas, 2, ord_supervisors};

/* ---- supervisor SUP ------------------------------------------------------------------- */
/* event flows { in :1 TypeC message_received; in :2 string connection_status;
                 in :3 TypeD failure; out :1 string failure_message_type; } */
static const ContractEventPort sup_in[] = {
    {1, "message_received", &contract_type_TypeC, NULL},
    {2, "connection_status", &contract_type_string, NULL},
    {3, "failure", &contract_type_TypeD, NULL}};
static const ContractEventPort sup_out[] = {{1, "failure_message_type", &contract_type_string, NULL}};

/* action(TypeA consigne) local { TypeC temp_message; string temp_mess_type; TypeD failure_data;
                                  TypeA temp_consigne = consigne; } */
typedef struct ActionLocals { TypeC temp_message; char temp_mess_type[256]; TypeD failure_data; TypeA temp_consigne; } ActionLocals;
enum { L_TEMP_MESSAGE, L_TEMP_MESS_TYPE, L_FAILURE_DATA, L_TEMP_CONSIGNE };
enum { R_FIRST, R_SECOND, R_THIRD, R_FOURTH, R_RECEPTION };
static const ContractVar action_params[] = {{"consigne", &contract_type_TypeA, 0, NULL}};
static const ContractVar action_locals[] = {
    {"temp_message", &contract_type_TypeC, offsetof(ActionLocals, temp_message), NULL},
    {"temp_mess_type", &contract_type_string, offsetof(ActionLocals, temp_mess_type), NULL},
    {"failure_data", &contract_type_TypeD, offsetof(ActionLocals, failure_data), NULL},
    {"temp_consigne", &contract_type_TypeA, offsetof(ActionLocals, temp_consigne), NULL}};
static const ContractAssign action_inits[] = {
    {L_TEMP_CONSIGNE, 0, &contract_type_TypeA, REF(CONTRACT_REF_PARAM, 0, 0, &contract_type_TypeA, NULL)}};

/* FIRST:[elapsed=1ms] subscribe MAA:2 ==* :2; subscribe MAA:0 ==* :1;
         activate schema schemaReceptionMessage() [MAA:2<connection_status == "disconnected">] */
static const ContractEvent first_pre_ev[] = {
    {.kind = CONTRACT_EV_ELAPSED, .time_ns = 1000000, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause first_pre[] = {{1, first_pre_ev}};
static const ContractAction first_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "MAA", .src_port = 2, .in_port = 2, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "MAA", .src_port = 0, .in_port = 1, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_schemaReceptionMessage}};
static const ContractTest first_post_tests[] = {
    {CONTRACT_TEST_EQ, REF(CONTRACT_REF_IN_PORT, 2, 0, &contract_type_string, NULL),
     CONST_REF(&contract_type_string, k_disconnected), NULL, 0, NULL}};
static const ContractTestClause first_post_tc[] = {{1, first_post_tests}};
static const ContractEvent first_post_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "MAA", .port = 2, .in_port = 2, .ntest_clauses = 1,
     .test_clauses = first_post_tc}};
static const ContractClause first_post[] = {{1, first_post_ev}};

/* SECOND:[(MAA:2<(connection_status == "disconnected" & testit("dedede",temp_consigne))>
            and started(FIRST){infinite})]
          subscribe MSC:1=>:3; activate schema schemaCommande1(consigne = temp_consigne)
          [MSC:1(failure_data = failure, temp_mess_type = "commutation")] */
static const ContractRef second_testit_args[] = {
    CONST_REF(&contract_type_string, k_dedede),
    REF(CONTRACT_REF_LOCAL, L_TEMP_CONSIGNE, 0, &contract_type_TypeA, NULL)};
static const ContractTest second_tests[] = {
    {CONTRACT_TEST_EQ, REF(CONTRACT_REF_IN_PORT, 2, 0, &contract_type_string, NULL),
     CONST_REF(&contract_type_string, k_disconnected), NULL, 0, NULL},
    {CONTRACT_TEST_CALL, {0, 0, 0, NULL, NULL}, {0, 0, 0, NULL, NULL}, &fn_testit, 2, second_testit_args}};
static const ContractTestClause second_tc[] = {{2, second_tests}};
static const ContractEvent second_pre_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "MAA", .port = 2, .in_port = 2, .ntest_clauses = 1,
     .test_clauses = second_tc},
    {.kind = CONTRACT_EV_STARTED, .rule = R_FIRST, .persist = CONTRACT_PERSIST_INFINITE}};
static const ContractClause second_pre[] = {{2, second_pre_ev}};
static const ContractAssign second_schema_params[] = {
    {0, 0, &contract_type_TypeA, REF(CONTRACT_REF_LOCAL, L_TEMP_CONSIGNE, 0, &contract_type_TypeA, NULL)}};
static const ContractAction second_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "MSC", .src_port = 1, .in_port = 3, .mode = CONTRACT_ONESHOT},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_schemaCommande1, .nassigns = 1,
     .assigns = second_schema_params}};
static const ContractAssign second_post_extr[] = {
    {L_FAILURE_DATA, 0, &contract_type_TypeD, REF(CONTRACT_REF_IN_PORT, 3, 0, &contract_type_TypeD, NULL)},
    {L_TEMP_MESS_TYPE, 0, &contract_type_string, CONST_REF(&contract_type_string, k_commutation)}};
static const ContractEvent second_post_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "MSC", .port = 1, .in_port = 3, .nextractions = 2,
     .extractions = second_post_extr}};
static const ContractClause second_post[] = {{1, second_post_ev}};

/* THIRD:[endof(SECOND)] notify :1(failure_message_type=temp_mess_type) [started(THIRD)] */
static const ContractEvent third_pre_ev[] = {{.kind = CONTRACT_EV_ENDOF, .rule = R_SECOND}};
static const ContractClause third_pre[] = {{1, third_pre_ev}};
static const ContractAssign third_notify[] = {
    {1, 0, &contract_type_string, REF(CONTRACT_REF_LOCAL, L_TEMP_MESS_TYPE, 0, &contract_type_string, NULL)}};
static const ContractAction third_actions[] = {
    {.kind = CONTRACT_ACT_NOTIFY, .out_port = 1, .nassigns = 1, .assigns = third_notify}};
static const ContractEvent third_post_ev[] = {{.kind = CONTRACT_EV_STARTED, .rule = R_THIRD}};
static const ContractClause third_post[] = {{1, third_post_ev}};

/* FOURTH:[endof(SECOND)] compute doit("1.24",temp_consigne.k);
          activate schema schemaCommande2(consigne = temp_consigne) [endof(FIRST)] */
static const ContractRef fourth_doit_args[] = {
    CONST_REF(&contract_type_string, k_124),
    REF(CONTRACT_REF_LOCAL, L_TEMP_CONSIGNE, offsetof(TypeA, k), &contract_type_double, NULL)};
static const ContractAction fourth_actions[] = {
    {.kind = CONTRACT_ACT_COMPUTE, .fn = &fn_doit, .nargs = 2, .args = fourth_doit_args},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_schemaCommande2, .nassigns = 1,
     .assigns = second_schema_params}};
static const ContractEvent fourth_post_ev[] = {{.kind = CONTRACT_EV_ENDOF, .rule = R_FIRST}};
static const ContractClause fourth_post[] = {{1, fourth_post_ev}};

/* RECEPTION:[MAA:0(temp_message=message_received)] parameterize MSC(temp_message.value :0);
             activate resttime module MAA [started(RECEPTION)] */
static const ContractAssign reception_extr[] = {
    {L_TEMP_MESSAGE, 0, &contract_type_TypeC, REF(CONTRACT_REF_IN_PORT, 1, 0, &contract_type_TypeC, NULL)}};
static const ContractEvent reception_pre_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "MAA", .port = 0, .in_port = 1, .nextractions = 1,
     .extractions = reception_extr}};
static const ContractClause reception_pre[] = {{1, reception_pre_ev}};
static const ContractAssign reception_msc_p0[] = {
    {0, 0, &contract_type_TypeA,
     REF(CONTRACT_REF_LOCAL, L_TEMP_MESSAGE, offsetof(TypeC, value), &contract_type_TypeA, NULL)}};
static const ContractParamSetting reception_settings[] = {{0, &contract_type_TypeA, 1, reception_msc_p0, "param"}};
static const ContractAction reception_actions[] = {
    {.kind = CONTRACT_ACT_PARAMETERIZE, .module = "MSC", .nsettings = 1, .settings = reception_settings},
    {.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "MAA"}};
static const ContractEvent reception_post_ev[] = {{.kind = CONTRACT_EV_STARTED, .rule = R_RECEPTION}};
static const ContractClause reception_post[] = {{1, reception_post_ev}};

static const ContractRule action_rules[] = {
    {"FIRST", {1, first_pre}, 3, first_actions, {1, first_post}},
    {"SECOND", {1, second_pre}, 2, second_actions, {1, second_post}},
    {"THIRD", {1, third_pre}, 1, third_actions, {1, third_post}},
    {"FOURTH", {1, third_pre}, 2, fourth_actions, {1, fourth_post}},
    {"RECEPTION", {1, reception_pre}, 2, reception_actions, {1, reception_post}}};
static const ContractFunction sup_functions[] = {
    {"action", 1, action_params, sizeof(TypeA), 4, action_locals, sizeof(ActionLocals), 1,
     action_inits, 5, action_rules}};
const ContractSupervisorVocabulary SUP_VOCAB = {
    CONTRACT_VOCABULARY_VERSION, "SUP", 90, 40, 5, 70, 3, sup_in, 1, sup_out, 1, sup_functions};

/* ---- supervisor GLB ------------------------------------------------------------------- */
/* event flows { in :0 string gdyegdyegdyge; }
   mission(TypeA consigne) { local { TypeA consigne_courante = consigne; }
     SINGLE:[elapsed=1ms] subscribe SUP:1 => :0;
            activate supervisor SUP.action(consigne=consigne_courante)
            [SUP:1<gdyegdyegdyge=="commutation">] } */
static const ContractEventPort glb_in[] = {{0, "gdyegdyegdyge", &contract_type_string, NULL}};
static const ContractVar mission_params[] = {{"consigne", &contract_type_TypeA, 0, NULL}};
static const ContractVar mission_locals[] = {{"consigne_courante", &contract_type_TypeA, 0, NULL}};
static const ContractAssign mission_inits[] = {
    {0, 0, &contract_type_TypeA, REF(CONTRACT_REF_PARAM, 0, 0, &contract_type_TypeA, NULL)}};
static const ContractFunctionSignature sig_sup_action = {"SUP", "action", 1, action_params, sizeof(TypeA)};
static const ContractAssign single_call_params[] = {
    {0, 0, &contract_type_TypeA, REF(CONTRACT_REF_LOCAL, 0, 0, &contract_type_TypeA, NULL)}};
static const ContractAction single_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "SUP", .src_port = 1, .in_port = 0, .mode = CONTRACT_ONESHOT},
    {.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_sup_action, .nassigns = 1, .assigns = single_call_params}};
static const ContractTest single_tests[] = {
    {CONTRACT_TEST_EQ, REF(CONTRACT_REF_IN_PORT, 0, 0, &contract_type_string, NULL),
     CONST_REF(&contract_type_string, k_commutation), NULL, 0, NULL}};
static const ContractTestClause single_tc[] = {{1, single_tests}};
static const ContractEvent single_post_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "SUP", .port = 1, .in_port = 0, .ntest_clauses = 1,
     .test_clauses = single_tc}};
static const ContractClause single_post[] = {{1, single_post_ev}};
static const ContractRule mission_rules[] = {
    {"SINGLE", {1, first_pre}, 2, single_actions, {1, single_post}}};
static const ContractFunction glb_functions[] = {
    {"mission", 1, mission_params, sizeof(TypeA), 1, mission_locals, sizeof(TypeA), 1, mission_inits,
     1, mission_rules}};
const ContractSupervisorVocabulary GLB_VOCAB = {
    CONTRACT_VOCABULARY_VERSION, "GLB", 95, 40, 5, 70, 1, glb_in, 0, NULL, 1, glb_functions};
