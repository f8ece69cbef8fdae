// vocabulary.c of supervisor SUP (generated whole from its Cactal description; format: contract/vocabulary.h)
#include <stddef.h>
#include <contract/vocabulary.h>
#include "suptypes.h"
#include "SharedFunctiondoit.h"
#include "SharedFunctiontestit.h"
#include "SharedTypeA.h"
#include "SharedTypeC.h"
#include "SharedTypeD.h"

static const TypeA contract_default_TypeA = { 0.0, 0.0, 0.0 };
static const ContractField contract_fields_TypeA[] = {
    {"i", offsetof(TypeA, i), &contract_type_double},
    {"j", offsetof(TypeA, j), &contract_type_double},
    {"k", offsetof(TypeA, k), &contract_type_double}};
CONTRACT_DEFINE_TYPE_FIELDS(TypeA, &contract_default_TypeA, 3, contract_fields_TypeA)
static const TypeC contract_default_TypeC = { "\0", 0, { 0.0, 0.0, 0.0 } };
static const ContractField contract_fields_TypeC[] = {
    {"message", offsetof(TypeC, message), &contract_type_string},
    {"messagetype", offsetof(TypeC, messagetype), &contract_type_long},
    {"value", offsetof(TypeC, value), &contract_type_TypeA}};
CONTRACT_DEFINE_TYPE_FIELDS(TypeC, &contract_default_TypeC, 3, contract_fields_TypeC)
static const TypeD contract_default_TypeD = { "\0", 0 };
static const ContractField contract_fields_TypeD[] = {
    {"dataname", offsetof(TypeD, dataname), &contract_type_string},
    {"datavalue", offsetof(TypeD, datavalue), &contract_type_long}};
CONTRACT_DEFINE_TYPE_FIELDS(TypeD, &contract_default_TypeD, 2, contract_fields_TypeD)

static const ContractEventPort in_ports[] = {
    {1, "message_received", &contract_type_TypeC, NULL},
    {2, "connection_status", &contract_type_string, NULL},
    {3, "failure", &contract_type_TypeD, NULL}};
static const ContractEventPort out_ports[] = {
    {1, "failure_message_type", &contract_type_string, NULL}};
typedef struct action_params_t {
    TypeA consigne;
} action_params_t;
static const ContractVar action_params[] = {
    {"consigne", &contract_type_TypeA, offsetof(action_params_t, consigne), NULL}};
typedef struct action_locals_t {
    TypeC temp_message;
    char temp_mess_type[256];
    TypeD failure_data;
    TypeA temp_consigne;
} action_locals_t;
static const ContractVar action_locals[] = {
    {"temp_message", &contract_type_TypeC, offsetof(action_locals_t, temp_message), NULL},
    {"temp_mess_type", &contract_type_string, offsetof(action_locals_t, temp_mess_type), NULL},
    {"failure_data", &contract_type_TypeD, offsetof(action_locals_t, failure_data), NULL},
    {"temp_consigne", &contract_type_TypeA, offsetof(action_locals_t, temp_consigne), NULL}};
static const ContractAssign action_local_inits[] = {
    {3, 0, &contract_type_TypeA, {CONTRACT_REF_PARAM, 0, 0, &contract_type_TypeA, NULL}}};
static const ContractEvent action_FIRST_pre_c0_events[] = {
    {.kind = CONTRACT_EV_ELAPSED, .time_ns = 1000000, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause action_FIRST_pre_clauses[] = {
    {1, action_FIRST_pre_c0_events}};
typedef struct schema_schemaReceptionMessage_params_t {
    TypeA param;
} schema_schemaReceptionMessage_params_t;
static const TypeA k_0 = { 27.12, 0.0, 0.04 };
static const ContractVar schema_schemaReceptionMessage_params[] = {
    {"param", &contract_type_TypeA, offsetof(schema_schemaReceptionMessage_params_t, param), &k_0}};
static const ContractAssign schema_schemaReceptionMessage_MAA_p0[] = {
    {0, 0, &contract_type_TypeA, {CONTRACT_REF_PARAM, 0, 0, &contract_type_TypeA, NULL}}};
static const ContractParamSetting schema_schemaReceptionMessage_MAA_settings[] = {
    {0, &contract_type_TypeA, 1, schema_schemaReceptionMessage_MAA_p0, "param"}};
static const ContractSchemaModule schema_schemaReceptionMessage_modules[] = {
    {"MAA", 1, schema_schemaReceptionMessage_MAA_settings},
    {"MAB", 0, NULL}};
static const ContractEventFlow schema_schemaReceptionMessage_event_flows[] = {
    {"MAA", 0, "MAB", 0, CONTRACT_CONTINUOUS}};
static const ContractSchema schema_schemaReceptionMessage = {
    "schemaReceptionMessage", CONTRACT_SCHEMA_EVENT, 0, 0,
    1, schema_schemaReceptionMessage_params, sizeof(schema_schemaReceptionMessage_params_t),
    2, schema_schemaReceptionMessage_modules, 0, NULL, 0, NULL, 1, schema_schemaReceptionMessage_event_flows};
static const ContractAction action_FIRST_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "MAA", .src_port = 2, .in_port = 2, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "MAA", .src_port = 0, .in_port = 1, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_schemaReceptionMessage, .nassigns = 0, .assigns = NULL}};
static const char k_1[256] = "disconnected";
static const ContractTest action_FIRST_post_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_IN_PORT, 2, 0, &contract_type_string, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_string, &k_1}, NULL, 0, NULL}};
static const ContractTestClause action_FIRST_post_c0_e0_tests[] = {
    {1, action_FIRST_post_c0_e0_t0_tests}};
static const ContractEvent action_FIRST_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "MAA", .port = 2, .in_port = 2, .ntest_clauses = 1, .test_clauses = action_FIRST_post_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractClause action_FIRST_post_clauses[] = {
    {1, action_FIRST_post_c0_events}};
static const char k_2[256] = "dedede";
static const ContractType *const fnargs_testit[] = {&contract_type_string, &contract_type_TypeA};
static int call_testit(void **a) { return testit((char *)a[0], (TypeA *)a[1]); }
static const ContractUserFunction fn_testit = {"testit", 1, 2, fnargs_testit, call_testit};
static const ContractRef action_SECOND_pre_c0_e0_t0_args[] = {
    {CONTRACT_REF_CONST, 0, 0, &contract_type_string, &k_2},
    {CONTRACT_REF_LOCAL, 3, 0, &contract_type_TypeA, NULL}};
static const ContractTest action_SECOND_pre_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_IN_PORT, 2, 0, &contract_type_string, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_string, &k_1}, NULL, 0, NULL},
    {CONTRACT_TEST_CALL, {0}, {0}, &fn_testit, 2, action_SECOND_pre_c0_e0_t0_args}};
static const ContractTestClause action_SECOND_pre_c0_e0_tests[] = {
    {2, action_SECOND_pre_c0_e0_t0_tests}};
static const ContractEvent action_SECOND_pre_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "MAA", .port = 2, .in_port = 2, .ntest_clauses = 1, .test_clauses = action_SECOND_pre_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL},
    {.kind = CONTRACT_EV_STARTED, .rule = 0, .persist = CONTRACT_PERSIST_INFINITE}};
static const ContractClause action_SECOND_pre_clauses[] = {
    {2, action_SECOND_pre_c0_events}};
typedef struct schema_schemaCommande1_params_t {
    TypeA consigne;
} schema_schemaCommande1_params_t;
static const TypeA k_3 = { 0.0, 0.0, 0.0 };
static const ContractVar schema_schemaCommande1_params[] = {
    {"consigne", &contract_type_TypeA, offsetof(schema_schemaCommande1_params_t, consigne), &k_3}};
static const ContractAssign schema_schemaCommande1_MSC_p0[] = {
    {0, 0, &contract_type_TypeA, {CONTRACT_REF_PARAM, 0, 0, &contract_type_TypeA, NULL}}};
static const ContractParamSetting schema_schemaCommande1_MSC_settings[] = {
    {0, &contract_type_TypeA, 1, schema_schemaCommande1_MSC_p0, "param"}};
static const ContractSchemaModule schema_schemaCommande1_modules[] = {
    {"MSA", 0, NULL},
    {"MSC", 1, schema_schemaCommande1_MSC_settings},
    {"MSD", 0, NULL}};
static const ContractPrecedence schema_schemaCommande1_precedences[] = {
    {0, 1},
    {1, 2}};
static const ContractDataFlow schema_schemaCommande1_data_flows[] = {
    {"MSA", 0, "MSC", 0, 1},
    {"MSC", 1, "MSD", 2, 2}};
static const ContractSchema schema_schemaCommande1 = {
    "schemaCommande1", CONTRACT_SCHEMA_PERIODIC, 1000000000, 1000000000,
    1, schema_schemaCommande1_params, sizeof(schema_schemaCommande1_params_t),
    3, schema_schemaCommande1_modules, 2, schema_schemaCommande1_precedences, 2, schema_schemaCommande1_data_flows, 0, NULL};
static const ContractAssign action_SECOND_a1_assigns[] = {
    {0, 0, &contract_type_TypeA, {CONTRACT_REF_LOCAL, 3, 0, &contract_type_TypeA, NULL}}};
static const ContractAction action_SECOND_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "MSC", .src_port = 1, .in_port = 3, .mode = CONTRACT_ONESHOT},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_schemaCommande1, .nassigns = 1, .assigns = action_SECOND_a1_assigns}};
static const char k_4[256] = "commutation";
static const ContractAssign action_SECOND_post_c0_e0_extractions[] = {
    {2, 0, &contract_type_TypeD, {CONTRACT_REF_IN_PORT, 3, 0, &contract_type_TypeD, NULL}},
    {1, 0, &contract_type_string, {CONTRACT_REF_CONST, 0, 0, &contract_type_string, &k_4}}};
static const ContractEvent action_SECOND_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "MSC", .port = 1, .in_port = 3, .ntest_clauses = 0, .test_clauses = NULL, .persist = CONTRACT_PERSIST_NONE, .nextractions = 2, .extractions = action_SECOND_post_c0_e0_extractions}};
static const ContractClause action_SECOND_post_clauses[] = {
    {1, action_SECOND_post_c0_events}};
static const ContractEvent action_THIRD_pre_c0_events[] = {
    {.kind = CONTRACT_EV_ENDOF, .rule = 1, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause action_THIRD_pre_clauses[] = {
    {1, action_THIRD_pre_c0_events}};
static const ContractAssign action_THIRD_a0_assigns[] = {
    {1, 0, &contract_type_string, {CONTRACT_REF_LOCAL, 1, 0, &contract_type_string, NULL}}};
static const ContractAction action_THIRD_actions[] = {
    {.kind = CONTRACT_ACT_NOTIFY, .out_port = 1, .nassigns = 1, .assigns = action_THIRD_a0_assigns}};
static const ContractEvent action_THIRD_post_c0_events[] = {
    {.kind = CONTRACT_EV_STARTED, .rule = 2, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause action_THIRD_post_clauses[] = {
    {1, action_THIRD_post_c0_events}};
static const ContractEvent action_FOURTH_pre_c0_events[] = {
    {.kind = CONTRACT_EV_ENDOF, .rule = 1, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause action_FOURTH_pre_clauses[] = {
    {1, action_FOURTH_pre_c0_events}};
static const char k_5[256] = "1.24";
static const ContractType *const fnargs_doit[] = {&contract_type_string, &contract_type_double};
static int call_doit(void **a) { doit((char *)a[0], (double *)a[1]); return 0; }
static const ContractUserFunction fn_doit = {"doit", 0, 2, fnargs_doit, call_doit};
static const ContractRef action_FOURTH_a0_args[] = {
    {CONTRACT_REF_CONST, 0, 0, &contract_type_string, &k_5},
    {CONTRACT_REF_LOCAL, 3, offsetof(TypeA, k), &contract_type_double, NULL}};
typedef struct schema_schemaCommande2_params_t {
    TypeA consigne;
} schema_schemaCommande2_params_t;
static const ContractVar schema_schemaCommande2_params[] = {
    {"consigne", &contract_type_TypeA, offsetof(schema_schemaCommande2_params_t, consigne), NULL}};
static const ContractAssign schema_schemaCommande2_MSC_p0[] = {
    {0, 0, &contract_type_TypeA, {CONTRACT_REF_PARAM, 0, 0, &contract_type_TypeA, NULL}}};
static const ContractParamSetting schema_schemaCommande2_MSC_settings[] = {
    {0, &contract_type_TypeA, 1, schema_schemaCommande2_MSC_p0, "param"}};
static const ContractSchemaModule schema_schemaCommande2_modules[] = {
    {"MSB", 0, NULL},
    {"MSC", 1, schema_schemaCommande2_MSC_settings},
    {"MSD", 0, NULL}};
static const ContractPrecedence schema_schemaCommande2_precedences[] = {
    {0, 1},
    {1, 2}};
static const ContractDataFlow schema_schemaCommande2_data_flows[] = {
    {"MSB", 0, "MSC", 0, 1},
    {"MSC", 1, "MSD", 2, 1}};
static const ContractSchema schema_schemaCommande2 = {
    "schemaCommande2", CONTRACT_SCHEMA_PERIODIC, 1000000000, 1000000000,
    1, schema_schemaCommande2_params, sizeof(schema_schemaCommande2_params_t),
    3, schema_schemaCommande2_modules, 2, schema_schemaCommande2_precedences, 2, schema_schemaCommande2_data_flows, 0, NULL};
static const ContractAssign action_FOURTH_a1_assigns[] = {
    {0, 0, &contract_type_TypeA, {CONTRACT_REF_LOCAL, 3, 0, &contract_type_TypeA, NULL}}};
static const ContractAction action_FOURTH_actions[] = {
    {.kind = CONTRACT_ACT_COMPUTE, .fn = &fn_doit, .nargs = 2, .args = action_FOURTH_a0_args},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_schemaCommande2, .nassigns = 1, .assigns = action_FOURTH_a1_assigns}};
static const ContractEvent action_FOURTH_post_c0_events[] = {
    {.kind = CONTRACT_EV_ENDOF, .rule = 0, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause action_FOURTH_post_clauses[] = {
    {1, action_FOURTH_post_c0_events}};
static const ContractAssign action_RECEPTION_pre_c0_e0_extractions[] = {
    {0, 0, &contract_type_TypeC, {CONTRACT_REF_IN_PORT, 1, 0, &contract_type_TypeC, NULL}}};
static const ContractEvent action_RECEPTION_pre_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "MAA", .port = 0, .in_port = 1, .ntest_clauses = 0, .test_clauses = NULL, .persist = CONTRACT_PERSIST_NONE, .nextractions = 1, .extractions = action_RECEPTION_pre_c0_e0_extractions}};
static const ContractClause action_RECEPTION_pre_clauses[] = {
    {1, action_RECEPTION_pre_c0_events}};
static const ContractAssign action_RECEPTION_a0_p0[] = {
    {0, 0, &contract_type_TypeA, {CONTRACT_REF_LOCAL, 0, offsetof(TypeC, value), &contract_type_TypeA, NULL}}};
static const ContractParamSetting action_RECEPTION_a0_settings[] = {
    {0, &contract_type_TypeA, 1, action_RECEPTION_a0_p0, "param"}};
static const ContractAction action_RECEPTION_actions[] = {
    {.kind = CONTRACT_ACT_PARAMETERIZE, .module = "MSC", .nsettings = 1, .settings = action_RECEPTION_a0_settings},
    {.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "MAA"}};
static const ContractEvent action_RECEPTION_post_c0_events[] = {
    {.kind = CONTRACT_EV_STARTED, .rule = 4, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause action_RECEPTION_post_clauses[] = {
    {1, action_RECEPTION_post_c0_events}};
static const ContractRule action_rules[] = {
    {"FIRST", {1, action_FIRST_pre_clauses}, 3, action_FIRST_actions, {1, action_FIRST_post_clauses}},
    {"SECOND", {1, action_SECOND_pre_clauses}, 2, action_SECOND_actions, {1, action_SECOND_post_clauses}},
    {"THIRD", {1, action_THIRD_pre_clauses}, 1, action_THIRD_actions, {1, action_THIRD_post_clauses}},
    {"FOURTH", {1, action_FOURTH_pre_clauses}, 2, action_FOURTH_actions, {1, action_FOURTH_post_clauses}},
    {"RECEPTION", {1, action_RECEPTION_pre_clauses}, 2, action_RECEPTION_actions, {1, action_RECEPTION_post_clauses}}};
static const ContractFunction functions[] = {
    {"action", 1, action_params, sizeof(action_params_t), 4, action_locals, sizeof(action_locals_t), 1, action_local_inits, 5, action_rules}};
const ContractSupervisorVocabulary SUP_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "SUP", 98, 30, 10, 85,
    3, in_ports, 1, out_ports, 1, functions};
