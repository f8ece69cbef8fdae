/* report_tables.h — the report's example as hand-written engine tables (see report_tables.c). */
#ifndef ENGINES_TEST_REPORT_TABLES_H
#define ENGINES_TEST_REPORT_TABLES_H

#include "contract/vocabulary.h"
#include "harness.h"

extern const ContractSchema schema_schemaReceptionMessage;
extern const ContractSchema schema_schemaCommande1;
extern const ContractSchema schema_schemaCommande2;
extern const ContractOrdVocabulary REPORT_ORD_VOCAB;
extern const ContractSupervisorVocabulary SUP_VOCAB;
extern const ContractSupervisorVocabulary GLB_VOCAB;
extern const ContractType *const report_type_TypeA;
extern const ContractType *const report_type_TypeC;
extern const ContractType *const report_type_TypeD;

/** testit() returns this; calls of testit/doit are logged in report_log when set. */
extern int testit_result;
extern TestLog *report_log;

#endif
