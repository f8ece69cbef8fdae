// vocabulary.c of supervisor GLB (generated whole from its Cactal description; format: contract/vocabulary.h)
#include <stddef.h>
#include <contract/vocabulary.h>
#include "suptypes.h"
#include "SharedTypeA.h"

static const TypeA contract_default_TypeA = { 0.0, 0.0, 0.0 };
static const ContractField contract_fields_TypeA[] = {
    {"i", offsetof(TypeA, i), &contract_type_double},
    {"j", offsetof(TypeA, j), &contract_type_double},
    {"k", offsetof(TypeA, k), &contract_type_double}};
CONTRACT_DEFINE_TYPE_FIELDS(TypeA, &contract_default_TypeA, 3, contract_fields_TypeA)

static const ContractEventPort in_ports[] = {
    {0, "gdyegdyegdyge", &contract_type_string, NULL}};
typedef struct mission_params_t {
    TypeA consigne;
} mission_params_t;
static const ContractVar mission_params[] = {
    {"consigne", &contract_type_TypeA, offsetof(mission_params_t, consigne), NULL}};
typedef struct mission_locals_t {
    TypeA consigne_courante;
} mission_locals_t;
static const ContractVar mission_locals[] = {
    {"consigne_courante", &contract_type_TypeA, offsetof(mission_locals_t, consigne_courante), NULL}};
static const ContractAssign mission_local_inits[] = {
    {0, 0, &contract_type_TypeA, {CONTRACT_REF_PARAM, 0, 0, &contract_type_TypeA, NULL}}};
static const ContractEvent mission_SINGLE_pre_c0_events[] = {
    {.kind = CONTRACT_EV_ELAPSED, .time_ns = 1000000, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause mission_SINGLE_pre_clauses[] = {
    {1, mission_SINGLE_pre_c0_events}};
typedef struct sig_SUP_action_params_t {
    TypeA consigne;
} sig_SUP_action_params_t;
static const ContractVar sig_SUP_action_params[] = {
    {"consigne", &contract_type_TypeA, offsetof(sig_SUP_action_params_t, consigne), NULL}};
static const ContractFunctionSignature sig_SUP_action = {"SUP", "action", 1, sig_SUP_action_params, sizeof(sig_SUP_action_params_t)};
static const ContractAssign mission_SINGLE_a1_assigns[] = {
    {0, 0, &contract_type_TypeA, {CONTRACT_REF_LOCAL, 0, 0, &contract_type_TypeA, NULL}}};
static const ContractAction mission_SINGLE_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "SUP", .src_port = 1, .in_port = 0, .mode = CONTRACT_ONESHOT},
    {.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_SUP_action, .nassigns = 1, .assigns = mission_SINGLE_a1_assigns}};
static const char k_0[256] = "commutation";
static const ContractTest mission_SINGLE_post_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_string, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_string, &k_0}, NULL, 0, NULL}};
static const ContractTestClause mission_SINGLE_post_c0_e0_tests[] = {
    {1, mission_SINGLE_post_c0_e0_t0_tests}};
static const ContractEvent mission_SINGLE_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "SUP", .port = 1, .in_port = 0, .ntest_clauses = 1, .test_clauses = mission_SINGLE_post_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractClause mission_SINGLE_post_clauses[] = {
    {1, mission_SINGLE_post_c0_events}};
static const ContractRule mission_rules[] = {
    {"SINGLE", {1, mission_SINGLE_pre_clauses}, 2, mission_SINGLE_actions, {1, mission_SINGLE_post_clauses}}};
static const ContractFunction functions[] = {
    {"mission", 1, mission_params, sizeof(mission_params_t), 1, mission_locals, sizeof(mission_locals_t), 1, mission_local_inits, 1, mission_rules}};
const ContractSupervisorVocabulary GLB_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "GLB", 99, 30, 10, 85,
    1, in_ports, 0, NULL, 1, functions};
