// vocabulary.c of ORD (generated whole from the scheduler configuration; format: contract/vocabulary.h)
#include <stddef.h>
#include <contract/vocabulary.h>
#include "schedtypes.h"
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
typedef struct schema_localisationLoop_params_t {
    Pose goal;
} schema_localisationLoop_params_t;
static const Pose k_2 = { 4.0, 2.0, 0.0 };
static const ContractVar schema_localisationLoop_params[] = {
    {"goal", &contract_type_Pose, offsetof(schema_localisationLoop_params_t, goal), &k_2}};
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
static const ContractSchemaModule schema_obstacleWatch_modules[] = {
    {"OBS", 0, NULL}};
static const ContractSchema schema_obstacleWatch = {
    "obstacleWatch", CONTRACT_SCHEMA_PERIODIC, 100000000, 50000000,
    0, NULL, 0,
    1, schema_obstacleWatch_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractOrdModule ord_modules[] = {
    {"WHL", 84, 100000},
    {"ODO", 84, 100000},
    {"VEL", 84, 200000},
    {"MOT", 84, 100000},
    {"LOC", 83, 1000000},
    {"NAV", 83, 1000000},
    {"OBS", 83, 500000}};
static const ContractSchema *const ord_schemas[] = {
    &schema_velocityLoop,
    &schema_localisationLoop,
    &schema_obstacleWatch};
static const char *const ord_supervisors[] = {
    "DRV",
    "MIS"};
const ContractOrdVocabulary ORD_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, 7, ord_modules, 3, ord_schemas, 2, ord_supervisors};
