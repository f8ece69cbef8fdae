/*
 * iord.c — the scheduler executable of the integration test, written as the generator writes
 * ORD_mod (module.c binding + vocabulary.c tables): schema ISC (period 20 ms, critical delay
 * 15 ms): IMA (gain :0) -> IMB, IMA -> IMC; IMA:0 -> IMB:0 * 1, IMA:0 -> IMC:0 * 2; schema ICF
 * uses IMB too (conflict); schema RSC: RMA -> RMB -> RMC (tables: itables.h). Supervisors to
 * notify: ISU, RSU (each scenario runs one of them: ORD:0/ORD:1 to the other is not delivered).
 */
#include "../engine_executable.h"

ENGINE_EXECUTABLE("ORD", 80, "engines integration test scheduler")

#include "itables.h"

static const ContractOrdModule modules[] = {{"IMA", 50, 300000}, {"IMB", 50, 300000}, {"IMC", 50, 300000},
                                            {"RMA", 50, 300000}, {"RMB", 50, 300000}, {"RMC", 50, 300000}};
static const ContractSchema *const schemas[] = {&ITEST_ISC, &ITEST_ICF, &ITEST_RSC};
static const char *const supervisors[] = {"ISU", "RSU"};
static const ContractOrdVocabulary ORD_VOCABULARY = {CONTRACT_VOCABULARY_VERSION, 6, modules, 3,
                                                     schemas, 2, supervisors};

int ModuleMain(int argc, const char *argv[]) { return contract_ord_main(&ORD_VOCABULARY, argc, argv); }
