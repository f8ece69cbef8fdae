/* bord.c — the benchmark's scheduler executable (generated-style ORD module.c + tables). */
#include "../engine_executable.h"

ENGINE_EXECUTABLE("ORD", 80, "engines benchmark scheduler")

#include "btables.h"

static const ContractOrdModule modules[] = {{"BMA", 50, 20000}, {"BMB", 50, 20000}, {"BMC", 50, 20000}};
static const ContractSchema *const schemas[] = {&BENCH_BEN};
static const char *const supervisors[] = {"BSU"};
static const ContractOrdVocabulary ORD_VOCABULARY = {CONTRACT_VOCABULARY_VERSION, 3, modules, 1,
                                                     schemas, 1, supervisors};

int ModuleMain(int argc, const char *argv[]) { return contract_ord_main(&ORD_VOCABULARY, argc, argv); }
