// vocabulary.c of supervisor MIS (generated whole from its Cactal description; format: contract/vocabulary.h)
#include <stddef.h>
#include <contract/vocabulary.h>
#include "suptypes.h"
#include <stdbool.h>
#include "SharedLaserScan.h"
#include "SharedPose.h"

static const Pose contract_default_Pose = { 0.0, 0.0, 0.0 };
static const ContractField contract_fields_Pose[] = {
    {"x", offsetof(Pose, x), &contract_type_double},
    {"y", offsetof(Pose, y), &contract_type_double},
    {"theta", offsetof(Pose, theta), &contract_type_double}};
CONTRACT_DEFINE_TYPE_FIELDS(Pose, &contract_default_Pose, 3, contract_fields_Pose)
static const ContractType contract_array_float_180 = CONTRACT_ARRAY_TYPE("float[180]", double[180], contract_type_double, 180, NULL);
static const LaserScan contract_default_LaserScan = { { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 }, false };
static const ContractField contract_fields_LaserScan[] = {
    {"ranges", offsetof(LaserScan, ranges), &contract_array_float_180},
    {"blocked", offsetof(LaserScan, blocked), &contract_type_bool}};
CONTRACT_DEFINE_TYPE_FIELDS(LaserScan, &contract_default_LaserScan, 2, contract_fields_LaserScan)

static const ContractEventPort in_ports[] = {
    {0, "request", &contract_type_string, NULL},
    {1, "distance", &contract_type_double, NULL},
    {2, "scan", &contract_type_LaserScan, NULL}};
typedef struct mission_locals_t {
    char missed[256];
    double ahead;
} mission_locals_t;
static const ContractVar mission_locals[] = {
    {"missed", &contract_type_string, offsetof(mission_locals_t, missed), NULL},
    {"ahead", &contract_type_double, offsetof(mission_locals_t, ahead), NULL}};
static const ContractEvent mission_LINK_pre_c0_events[] = {
    {.kind = CONTRACT_EV_ELAPSED, .time_ns = 1000000, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause mission_LINK_pre_clauses[] = {
    {1, mission_LINK_pre_c0_events}};
static const ContractSchemaModule schema_obstacleWatch_modules[] = {
    {"OBS", 0, NULL}};
static const ContractSchema schema_obstacleWatch = {
    "obstacleWatch", CONTRACT_SCHEMA_PERIODIC, 100000000, 50000000,
    0, NULL, 0,
    1, schema_obstacleWatch_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractAction mission_LINK_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "TEL", .src_port = 1, .in_port = 0, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "OBS", .src_port = 0, .in_port = 1, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "OBS", .src_port = 1, .in_port = 2, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_obstacleWatch, .nassigns = 0, .assigns = NULL},
    {.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "TEL"}};
static const char k_0[256] = "shutdown";
static const ContractTest mission_LINK_post_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_string, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_string, &k_0}, NULL, 0, NULL}};
static const ContractTestClause mission_LINK_post_c0_e0_tests[] = {
    {1, mission_LINK_post_c0_e0_t0_tests}};
static const ContractEvent mission_LINK_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "TEL", .port = 1, .in_port = 0, .ntest_clauses = 1, .test_clauses = mission_LINK_post_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractClause mission_LINK_post_clauses[] = {
    {1, mission_LINK_post_c0_events}};
static const ContractEvent mission_TELEOP_pre_c0_events[] = {
    {.kind = CONTRACT_EV_STARTED, .rule = 0, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause mission_TELEOP_pre_clauses[] = {
    {1, mission_TELEOP_pre_c0_events}};
static const ContractFunctionSignature sig_DRV_teleop = {"DRV", "teleop", 0, NULL, 0};
static const ContractAction mission_TELEOP_actions[] = {
    {.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_DRV_teleop, .nassigns = 0, .assigns = NULL}};
static const char k_1[256] = "auto";
static const ContractTest mission_TELEOP_post_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_string, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_string, &k_1}, NULL, 0, NULL}};
static const ContractTestClause mission_TELEOP_post_c0_e0_tests[] = {
    {1, mission_TELEOP_post_c0_e0_t0_tests}};
static const ContractEvent mission_TELEOP_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "TEL", .port = 1, .in_port = 0, .ntest_clauses = 1, .test_clauses = mission_TELEOP_post_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractClause mission_TELEOP_post_clauses[] = {
    {1, mission_TELEOP_post_c0_events}};
static const ContractTest mission_AUTO_pre_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_string, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_string, &k_1}, NULL, 0, NULL}};
static const ContractTestClause mission_AUTO_pre_c0_e0_tests[] = {
    {1, mission_AUTO_pre_c0_e0_t0_tests}};
static const ContractEvent mission_AUTO_pre_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "TEL", .port = 1, .in_port = 0, .ntest_clauses = 1, .test_clauses = mission_AUTO_pre_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractEvent mission_AUTO_pre_c1_events[] = {
    {.kind = CONTRACT_EV_ENDOF, .rule = 3, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause mission_AUTO_pre_clauses[] = {
    {1, mission_AUTO_pre_c0_events},
    {1, mission_AUTO_pre_c1_events}};
typedef struct sig_DRV_autonomous_params_t {
    Pose goal;
} sig_DRV_autonomous_params_t;
static const Pose k_2 = { 4.0, 2.0, 0.0 };
static const ContractVar sig_DRV_autonomous_params[] = {
    {"goal", &contract_type_Pose, offsetof(sig_DRV_autonomous_params_t, goal), &k_2}};
static const ContractFunctionSignature sig_DRV_autonomous = {"DRV", "autonomous", 1, sig_DRV_autonomous_params, sizeof(sig_DRV_autonomous_params_t)};
static const ContractAction mission_AUTO_actions[] = {
    {.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_DRV_autonomous, .nassigns = 0, .assigns = NULL}};
static const double k_3 = 0.5;
static const ContractTest mission_AUTO_post_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_LT, {CONTRACT_REF_IN_PORT, 1, 0, &contract_type_double, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k_3}, NULL, 0, NULL}};
static const ContractTestClause mission_AUTO_post_c0_e0_tests[] = {
    {1, mission_AUTO_post_c0_e0_t0_tests}};
static const ContractEvent mission_AUTO_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "OBS", .port = 0, .in_port = 1, .ntest_clauses = 1, .test_clauses = mission_AUTO_post_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractAssign mission_AUTO_post_c1_e0_extractions[] = {
    {0, 0, &contract_type_string, {CONTRACT_REF_ORD_SCHEMA, 0, 0, &contract_type_string, NULL}}};
static const ContractEvent mission_AUTO_post_c1_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "ORD", .port = 0, .in_port = -1, .ntest_clauses = 0, .test_clauses = NULL, .persist = CONTRACT_PERSIST_NONE, .nextractions = 1, .extractions = mission_AUTO_post_c1_e0_extractions}};
static const ContractClause mission_AUTO_post_clauses[] = {
    {1, mission_AUTO_post_c0_events},
    {1, mission_AUTO_post_c1_events}};
static const ContractEvent mission_STOP_pre_c0_events[] = {
    {.kind = CONTRACT_EV_ENDOF, .rule = 2, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause mission_STOP_pre_clauses[] = {
    {1, mission_STOP_pre_c0_events}};
static const ContractFunctionSignature sig_DRV_safestop = {"DRV", "safestop", 0, NULL, 0};
static const ContractAction mission_STOP_actions[] = {
    {.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_DRV_safestop, .nassigns = 0, .assigns = NULL}};
static const double k_4 = 1.0;
static const ContractTest mission_STOP_post_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_GT, {CONTRACT_REF_IN_PORT, 1, 0, &contract_type_double, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k_4}, NULL, 0, NULL}};
static const ContractTestClause mission_STOP_post_c0_e0_tests[] = {
    {1, mission_STOP_post_c0_e0_t0_tests}};
static const ContractEvent mission_STOP_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "OBS", .port = 0, .in_port = 1, .ntest_clauses = 1, .test_clauses = mission_STOP_post_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractClause mission_STOP_post_clauses[] = {
    {1, mission_STOP_post_c0_events}};
static const ContractTest mission_AHEAD_pre_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_LT, {CONTRACT_REF_IN_PORT, 2, offsetof(LaserScan, ranges[90]), &contract_type_double, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k_3}, NULL, 0, NULL}};
static const ContractTestClause mission_AHEAD_pre_c0_e0_tests[] = {
    {1, mission_AHEAD_pre_c0_e0_t0_tests}};
static const ContractAssign mission_AHEAD_pre_c0_e0_extractions[] = {
    {1, 0, &contract_type_double, {CONTRACT_REF_IN_PORT, 2, offsetof(LaserScan, ranges[90]), &contract_type_double, NULL}}};
static const ContractEvent mission_AHEAD_pre_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "OBS", .port = 1, .in_port = 2, .ntest_clauses = 1, .test_clauses = mission_AHEAD_pre_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 1, .extractions = mission_AHEAD_pre_c0_e0_extractions}};
static const ContractClause mission_AHEAD_pre_clauses[] = {
    {1, mission_AHEAD_pre_c0_events}};
static const ContractTest mission_AHEAD_post_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_GT, {CONTRACT_REF_IN_PORT, 2, offsetof(LaserScan, ranges[90]), &contract_type_double, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k_4}, NULL, 0, NULL}};
static const ContractTestClause mission_AHEAD_post_c0_e0_tests[] = {
    {1, mission_AHEAD_post_c0_e0_t0_tests}};
static const ContractEvent mission_AHEAD_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "OBS", .port = 1, .in_port = 2, .ntest_clauses = 1, .test_clauses = mission_AHEAD_post_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractClause mission_AHEAD_post_clauses[] = {
    {1, mission_AHEAD_post_c0_events}};
static const ContractRule mission_rules[] = {
    {"LINK", {1, mission_LINK_pre_clauses}, 5, mission_LINK_actions, {1, mission_LINK_post_clauses}},
    {"TELEOP", {1, mission_TELEOP_pre_clauses}, 1, mission_TELEOP_actions, {1, mission_TELEOP_post_clauses}},
    {"AUTO", {2, mission_AUTO_pre_clauses}, 1, mission_AUTO_actions, {2, mission_AUTO_post_clauses}},
    {"STOP", {1, mission_STOP_pre_clauses}, 1, mission_STOP_actions, {1, mission_STOP_post_clauses}},
    {"AHEAD", {1, mission_AHEAD_pre_clauses}, 0, NULL, {1, mission_AHEAD_post_clauses}}};
static const ContractFunction functions[] = {
    {"mission", 0, NULL, 0, 2, mission_locals, sizeof(mission_locals_t), 0, NULL, 5, mission_rules}};
const ContractSupervisorVocabulary MIS_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "MIS", 99, 30, 10, 85,
    3, in_ports, 0, NULL, 1, functions};
