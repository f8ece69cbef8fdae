// vocabulary.c of ORD (generated whole from the scheduler configuration; format: contract/vocabulary.h)
#include <stddef.h>
#include <contract/vocabulary.h>
#include "schedtypes.h"
#include "SharedTypeA.h"

static const TypeA contract_default_TypeA = { 0.0, 0.0, 0.0 };
static const ContractField contract_fields_TypeA[] = {
    {"i", offsetof(TypeA, i), &contract_type_double},
    {"j", offsetof(TypeA, j), &contract_type_double},
    {"k", offsetof(TypeA, k), &contract_type_double}};
CONTRACT_DEFINE_TYPE_FIELDS(TypeA, &contract_default_TypeA, 3, contract_fields_TypeA)

typedef struct schema_schemaCommande1_params_t {
    TypeA consigne;
} schema_schemaCommande1_params_t;
static const TypeA k_0 = { 0.0, 0.0, 0.0 };
static const ContractVar schema_schemaCommande1_params[] = {
    {"consigne", &contract_type_TypeA, offsetof(schema_schemaCommande1_params_t, consigne), &k_0}};
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
static const ContractOrdModule ord_modules[] = {
    {"MSA", 84, 500000},
    {"MSB", 84, 500000},
    {"MSC", 84, 1000000},
    {"MSD", 84, 1000000}};
static const ContractSchema *const ord_schemas[] = {
    &schema_schemaCommande1,
    &schema_schemaCommande2};
static const char *const ord_supervisors[] = {
    "SUP",
    "GLB"};
const ContractOrdVocabulary ORD_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, 4, ord_modules, 2, ord_schemas, 2, ord_supervisors};
