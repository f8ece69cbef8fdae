/*
 * iord.c — the scheduler executable of the integration test, written as the generator writes
 * ORD_mod (module.c binding + vocabulary.c tables): schema ISC (period 20 ms, critical delay
 * 15 ms): IMA (gain :0) -> IMB, IMA -> IMC; IMA:0 -> IMB:0 * 1, IMA:0 -> IMC:0 * 2; schema ICF
 * uses IMB too (conflict); supervisor to notify: ISU. Built with -DIORD_RSC (as rsc/ORD) for
 * the reactivation scenario: schema RSC: RMA -> RMB -> RMC, supervisor RSU (tables: itables.h).
 * Built with -DIORD_UNDO (as undo/ORD) for the undo scenario: schema PSC: UMA, supervisors UPA
 * and USM. Built with -DIORD_STK (as stk/ORD) for the stuck- and crashed-module scenarios:
 * schemas FST (STK), SLW (OKM), CRH (CRS) and FLD (FLM), supervisor SKS.
 */
#include "../engine_executable.h"

ENGINE_EXECUTABLE("ORD", 80, "engines integration test scheduler")

#include "itables.h"

#if defined(IORD_STK)
static const ContractOrdModule modules[] = {{"STK", 50, 300000}, {"OKM", 50, 300000}, {"CRS", 50, 300000},
                                            {"FLM", 50, 300000}};
static const ContractSchema *const schemas[] = {&ITEST_FST, &ITEST_SLW, &ITEST_CRH, &ITEST_FLD};
static const char *const supervisors[] = {"SKS"};
#elif defined(IORD_UNDO)
static const ContractOrdModule modules[] = {{"UMA", 50, 300000}};
static const ContractSchema *const schemas[] = {&ITEST_PSC};
static const char *const supervisors[] = {"UPA", "USM"};
#elif defined(IORD_RSC)
static const ContractOrdModule modules[] = {{"RMA", 50, 300000}, {"RMB", 50, 300000}, {"RMC", 50, 300000}};
static const ContractSchema *const schemas[] = {&ITEST_RSC};
static const char *const supervisors[] = {"RSU"};
#else
static const ContractOrdModule modules[] = {{"IMA", 50, 300000}, {"IMB", 50, 300000}, {"IMC", 50, 300000}};
static const ContractSchema *const schemas[] = {&ITEST_ISC, &ITEST_ICF};
static const char *const supervisors[] = {"ISU"};
#endif
static const ContractOrdVocabulary ORD_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, (int)(sizeof modules / sizeof modules[0]), modules,
    (int)(sizeof schemas / sizeof schemas[0]), schemas, (int)(sizeof supervisors / sizeof supervisors[0]), supervisors};

int ModuleMain(int argc, const char *argv[]) { return contract_ord_main(&ORD_VOCABULARY, argc, argv); }
