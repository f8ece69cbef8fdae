// vocabulary.c of supervisor DRV (generated whole from its Cactal description; format: contract/vocabulary.h)
#include <stddef.h>
#include <contract/vocabulary.h>
#include "suptypes.h"
#include "SharedDriveMode.h"
#include "SharedPose.h"
#include "SharedTwist.h"

static const ContractEnumMember contract_members_DriveMode[] = {{"TELEOP", DriveMode_TELEOP}, {"AUTO", DriveMode_AUTO}, {"SAFESTOP", DriveMode_SAFESTOP}};
static const ContractType contract_type_DriveMode = CONTRACT_ENUM_TYPE(DriveMode, contract_members_DriveMode, 3, NULL);
static const Pose contract_default_Pose = { 0.0, 0.0, 0.0 };
static const ContractField contract_fields_Pose[] = {
    {"x", offsetof(Pose, x), &contract_type_double},
    {"y", offsetof(Pose, y), &contract_type_double},
    {"theta", offsetof(Pose, theta), &contract_type_double}};
CONTRACT_DEFINE_TYPE_FIELDS(Pose, &contract_default_Pose, 3, contract_fields_Pose)
static const Twist contract_default_Twist = { 0.0, 0.0 };
static const ContractField contract_fields_Twist[] = {
    {"v", offsetof(Twist, v), &contract_type_double},
    {"w", offsetof(Twist, w), &contract_type_double}};
CONTRACT_DEFINE_TYPE_FIELDS(Twist, &contract_default_Twist, 2, contract_fields_Twist)

static const ContractEventPort in_ports[] = {
    {0, "joystick", &contract_type_Twist, NULL},
    {1, "nav_cmd", &contract_type_Twist, NULL}};
typedef struct teleop_locals_t {
    Twist cmd;
} teleop_locals_t;
static const ContractVar teleop_locals[] = {
    {"cmd", &contract_type_Twist, offsetof(teleop_locals_t, cmd), NULL}};
static const ContractEvent teleop_LOOP_pre_c0_events[] = {
    {.kind = CONTRACT_EV_ELAPSED, .time_ns = 1000000, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause teleop_LOOP_pre_clauses[] = {
    {1, teleop_LOOP_pre_c0_events}};
typedef struct schema_velocityLoop_params_t {
    Twist setpoint;
    DriveMode mode;
} schema_velocityLoop_params_t;
static const Twist k_0 = { 0.0, 0.0 };
static const DriveMode k_1 = DriveMode_TELEOP;
static const ContractVar schema_velocityLoop_params[] = {
    {"setpoint", &contract_type_Twist, offsetof(schema_velocityLoop_params_t, setpoint), &k_0},
    {"mode", &contract_type_DriveMode, offsetof(schema_velocityLoop_params_t, mode), &k_1}};
static const ContractAssign schema_velocityLoop_VEL_p0[] = {
    {0, 0, &contract_type_Twist, {CONTRACT_REF_PARAM, 0, 0, &contract_type_Twist, NULL}}};
static const ContractAssign schema_velocityLoop_VEL_p1[] = {
    {0, 0, &contract_type_DriveMode, {CONTRACT_REF_PARAM, 1, 0, &contract_type_DriveMode, NULL}}};
static const ContractParamSetting schema_velocityLoop_VEL_settings[] = {
    {0, &contract_type_Twist, 1, schema_velocityLoop_VEL_p0, "setpoint"},
    {1, &contract_type_DriveMode, 1, schema_velocityLoop_VEL_p1, "mode"}};
static const ContractSchemaModule schema_velocityLoop_modules[] = {
    {"WHL", 0, NULL},
    {"ODO", 0, NULL},
    {"VEL", 2, schema_velocityLoop_VEL_settings},
    {"MOT", 0, NULL}};
static const ContractPrecedence schema_velocityLoop_precedences[] = {
    {0, 1},
    {1, 2},
    {2, 3}};
static const ContractDataFlow schema_velocityLoop_data_flows[] = {
    {"WHL", 0, "ODO", 0, 1},
    {"ODO", 0, "VEL", 0, 1},
    {"VEL", 0, "MOT", 0, 1},
    {"ODO", 1, "MOT", 1, 50},
    {"MOT", 0, "WHL", 0, 1}};
static const ContractSchema schema_velocityLoop = {
    "velocityLoop", CONTRACT_SCHEMA_PERIODIC, 10000000, 10000000,
    2, schema_velocityLoop_params, sizeof(schema_velocityLoop_params_t),
    4, schema_velocityLoop_modules, 3, schema_velocityLoop_precedences, 5, schema_velocityLoop_data_flows, 0, NULL};
static const ContractAssign teleop_LOOP_a1_assigns[] = {
    {1, 0, &contract_type_DriveMode, {CONTRACT_REF_CONST, 0, 0, &contract_type_DriveMode, &k_1}}};
static const ContractAction teleop_LOOP_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "TEL", .src_port = 0, .in_port = 0, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_velocityLoop, .nassigns = 1, .assigns = teleop_LOOP_a1_assigns}};
static const double k_2 = 100.0;
static const ContractTest teleop_LOOP_post_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_GT, {CONTRACT_REF_IN_PORT, 0, offsetof(Twist, v), &contract_type_double, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k_2}, NULL, 0, NULL}};
static const ContractTestClause teleop_LOOP_post_c0_e0_tests[] = {
    {1, teleop_LOOP_post_c0_e0_t0_tests}};
static const ContractEvent teleop_LOOP_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "TEL", .port = 0, .in_port = 0, .ntest_clauses = 1, .test_clauses = teleop_LOOP_post_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractClause teleop_LOOP_post_clauses[] = {
    {1, teleop_LOOP_post_c0_events}};
static const ContractAssign teleop_FOLLOW_pre_c0_e0_extractions[] = {
    {0, 0, &contract_type_Twist, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_Twist, NULL}}};
static const ContractEvent teleop_FOLLOW_pre_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "TEL", .port = 0, .in_port = 0, .ntest_clauses = 0, .test_clauses = NULL, .persist = CONTRACT_PERSIST_NONE, .nextractions = 1, .extractions = teleop_FOLLOW_pre_c0_e0_extractions}};
static const ContractClause teleop_FOLLOW_pre_clauses[] = {
    {1, teleop_FOLLOW_pre_c0_events}};
static const ContractAssign teleop_FOLLOW_a0_p0[] = {
    {0, 0, &contract_type_Twist, {CONTRACT_REF_LOCAL, 0, 0, &contract_type_Twist, NULL}}};
static const ContractParamSetting teleop_FOLLOW_a0_settings[] = {
    {0, &contract_type_Twist, 1, teleop_FOLLOW_a0_p0, "setpoint"}};
static const ContractAction teleop_FOLLOW_actions[] = {
    {.kind = CONTRACT_ACT_PARAMETERIZE, .module = "VEL", .nsettings = 1, .settings = teleop_FOLLOW_a0_settings}};
static const ContractEvent teleop_FOLLOW_post_c0_events[] = {
    {.kind = CONTRACT_EV_STARTED, .rule = 1, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause teleop_FOLLOW_post_clauses[] = {
    {1, teleop_FOLLOW_post_c0_events}};
static const ContractRule teleop_rules[] = {
    {"LOOP", {1, teleop_LOOP_pre_clauses}, 2, teleop_LOOP_actions, {1, teleop_LOOP_post_clauses}},
    {"FOLLOW", {1, teleop_FOLLOW_pre_clauses}, 1, teleop_FOLLOW_actions, {1, teleop_FOLLOW_post_clauses}}};
typedef struct autonomous_params_t {
    Pose goal;
} autonomous_params_t;
static const Pose k_3 = { 4.0, 2.0, 0.0 };
static const ContractVar autonomous_params[] = {
    {"goal", &contract_type_Pose, offsetof(autonomous_params_t, goal), &k_3}};
typedef struct autonomous_locals_t {
    Pose target;
    Twist cmd;
} autonomous_locals_t;
static const ContractVar autonomous_locals[] = {
    {"target", &contract_type_Pose, offsetof(autonomous_locals_t, target), NULL},
    {"cmd", &contract_type_Twist, offsetof(autonomous_locals_t, cmd), NULL}};
static const ContractAssign autonomous_local_inits[] = {
    {0, 0, &contract_type_Pose, {CONTRACT_REF_PARAM, 0, 0, &contract_type_Pose, NULL}}};
static const ContractEvent autonomous_LOOPS_pre_c0_events[] = {
    {.kind = CONTRACT_EV_ELAPSED, .time_ns = 1000000, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause autonomous_LOOPS_pre_clauses[] = {
    {1, autonomous_LOOPS_pre_c0_events}};
static const DriveMode k_4 = DriveMode_AUTO;
static const ContractAssign autonomous_LOOPS_a1_assigns[] = {
    {1, 0, &contract_type_DriveMode, {CONTRACT_REF_CONST, 0, 0, &contract_type_DriveMode, &k_4}}};
typedef struct schema_localisationLoop_params_t {
    Pose goal;
} schema_localisationLoop_params_t;
static const ContractVar schema_localisationLoop_params[] = {
    {"goal", &contract_type_Pose, offsetof(schema_localisationLoop_params_t, goal), &k_3}};
static const ContractAssign schema_localisationLoop_NAV_p0[] = {
    {0, 0, &contract_type_Pose, {CONTRACT_REF_PARAM, 0, 0, &contract_type_Pose, NULL}}};
static const ContractParamSetting schema_localisationLoop_NAV_settings[] = {
    {0, &contract_type_Pose, 1, schema_localisationLoop_NAV_p0, "goal"}};
static const ContractSchemaModule schema_localisationLoop_modules[] = {
    {"LOC", 0, NULL},
    {"NAV", 1, schema_localisationLoop_NAV_settings}};
static const ContractPrecedence schema_localisationLoop_precedences[] = {
    {0, 1}};
static const ContractDataFlow schema_localisationLoop_data_flows[] = {
    {"LOC", 0, "NAV", 0, 1},
    {"NAV", 0, "LOC", 0, 1}};
static const ContractSchema schema_localisationLoop = {
    "localisationLoop", CONTRACT_SCHEMA_PERIODIC, 100000000, 50000000,
    1, schema_localisationLoop_params, sizeof(schema_localisationLoop_params_t),
    2, schema_localisationLoop_modules, 1, schema_localisationLoop_precedences, 2, schema_localisationLoop_data_flows, 0, NULL};
static const ContractAssign autonomous_LOOPS_a2_assigns[] = {
    {0, 0, &contract_type_Pose, {CONTRACT_REF_LOCAL, 0, 0, &contract_type_Pose, NULL}}};
static const ContractAction autonomous_LOOPS_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "NAV", .src_port = 0, .in_port = 1, .mode = CONTRACT_CONTINUOUS},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_velocityLoop, .nassigns = 1, .assigns = autonomous_LOOPS_a1_assigns},
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_localisationLoop, .nassigns = 1, .assigns = autonomous_LOOPS_a2_assigns}};
static const ContractTest autonomous_LOOPS_post_c0_e0_t0_tests[] = {
    {CONTRACT_TEST_GT, {CONTRACT_REF_IN_PORT, 1, offsetof(Twist, v), &contract_type_double, NULL}, {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k_2}, NULL, 0, NULL}};
static const ContractTestClause autonomous_LOOPS_post_c0_e0_tests[] = {
    {1, autonomous_LOOPS_post_c0_e0_t0_tests}};
static const ContractEvent autonomous_LOOPS_post_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "NAV", .port = 0, .in_port = 1, .ntest_clauses = 1, .test_clauses = autonomous_LOOPS_post_c0_e0_tests, .persist = CONTRACT_PERSIST_NONE, .nextractions = 0, .extractions = NULL}};
static const ContractClause autonomous_LOOPS_post_clauses[] = {
    {1, autonomous_LOOPS_post_c0_events}};
static const ContractAssign autonomous_STEER_pre_c0_e0_extractions[] = {
    {1, 0, &contract_type_Twist, {CONTRACT_REF_IN_PORT, 1, 0, &contract_type_Twist, NULL}}};
static const ContractEvent autonomous_STEER_pre_c0_events[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "NAV", .port = 0, .in_port = 1, .ntest_clauses = 0, .test_clauses = NULL, .persist = CONTRACT_PERSIST_NONE, .nextractions = 1, .extractions = autonomous_STEER_pre_c0_e0_extractions}};
static const ContractClause autonomous_STEER_pre_clauses[] = {
    {1, autonomous_STEER_pre_c0_events}};
static const ContractAssign autonomous_STEER_a0_p0[] = {
    {0, 0, &contract_type_Twist, {CONTRACT_REF_LOCAL, 1, 0, &contract_type_Twist, NULL}}};
static const ContractParamSetting autonomous_STEER_a0_settings[] = {
    {0, &contract_type_Twist, 1, autonomous_STEER_a0_p0, "setpoint"}};
static const ContractAction autonomous_STEER_actions[] = {
    {.kind = CONTRACT_ACT_PARAMETERIZE, .module = "VEL", .nsettings = 1, .settings = autonomous_STEER_a0_settings}};
static const ContractEvent autonomous_STEER_post_c0_events[] = {
    {.kind = CONTRACT_EV_STARTED, .rule = 1, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause autonomous_STEER_post_clauses[] = {
    {1, autonomous_STEER_post_c0_events}};
static const ContractRule autonomous_rules[] = {
    {"LOOPS", {1, autonomous_LOOPS_pre_clauses}, 3, autonomous_LOOPS_actions, {1, autonomous_LOOPS_post_clauses}},
    {"STEER", {1, autonomous_STEER_pre_clauses}, 1, autonomous_STEER_actions, {1, autonomous_STEER_post_clauses}}};
typedef struct safestop_locals_t {
    Twist halt;
} safestop_locals_t;
static const ContractVar safestop_locals[] = {
    {"halt", &contract_type_Twist, offsetof(safestop_locals_t, halt), &k_0}};
static const ContractEvent safestop_HALT_pre_c0_events[] = {
    {.kind = CONTRACT_EV_ELAPSED, .time_ns = 1000000, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause safestop_HALT_pre_clauses[] = {
    {1, safestop_HALT_pre_c0_events}};
static const DriveMode k_5 = DriveMode_SAFESTOP;
static const ContractAssign safestop_HALT_a0_assigns[] = {
    {0, 0, &contract_type_Twist, {CONTRACT_REF_LOCAL, 0, 0, &contract_type_Twist, NULL}},
    {1, 0, &contract_type_DriveMode, {CONTRACT_REF_CONST, 0, 0, &contract_type_DriveMode, &k_5}}};
static const ContractAction safestop_HALT_actions[] = {
    {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_velocityLoop, .nassigns = 2, .assigns = safestop_HALT_a0_assigns}};
static const ContractEvent safestop_HALT_post_c0_events[] = {
    {.kind = CONTRACT_EV_DURATION, .rule = 0, .time_ns = 3600000000000, .persist = CONTRACT_PERSIST_NONE}};
static const ContractClause safestop_HALT_post_clauses[] = {
    {1, safestop_HALT_post_c0_events}};
static const ContractRule safestop_rules[] = {
    {"HALT", {1, safestop_HALT_pre_clauses}, 1, safestop_HALT_actions, {1, safestop_HALT_post_clauses}}};
static const ContractFunction functions[] = {
    {"teleop", 0, NULL, 0, 1, teleop_locals, sizeof(teleop_locals_t), 0, NULL, 2, teleop_rules},
    {"autonomous", 1, autonomous_params, sizeof(autonomous_params_t), 2, autonomous_locals, sizeof(autonomous_locals_t), 1, autonomous_local_inits, 2, autonomous_rules},
    {"safestop", 0, NULL, 0, 1, safestop_locals, sizeof(safestop_locals_t), 0, NULL, 1, safestop_rules}};
const ContractSupervisorVocabulary DRV_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "DRV", 98, 30, 10, 85,
    2, in_ports, 0, NULL, 3, functions};
