/* bord.c — the benchmark's scheduler executable (generated-style ORD module.c + tables). */
#include <contract/vocabulary.h>
#include <libmodule/libmodule.h>

MODULE_DESCRIPTION("engines benchmark scheduler");
MODULE_AUTHOR("engines bench");
char MODULE_NAME[] = "ORD";
int MODULE_PRIORITY = 80;
ModuleUse IUSE[] = {IUSE_TERM};
ModuleProduce IPRODUCE[] = {IPRODUCE_TERM};
ModuleReact IREACT[] = {IREACT_TERM};
ModuleDetect IDETECT[] = {IDETECT_TERM};
size_t PARAM_SIZE_IN[] = {PARAM_SIZE_TERM};
size_t PARAM_SIZE_OUT[] = {PARAM_SIZE_TERM};

#include "btables.h"

static const ContractOrdModule modules[] = {{"BMA", 50, 20000}, {"BMB", 50, 20000}, {"BMC", 50, 20000}};
static const ContractSchema *const schemas[] = {&BENCH_BEN};
static const char *const supervisors[] = {"BSU"};
static const ContractOrdVocabulary ORD_VOCABULARY = {CONTRACT_VOCABULARY_VERSION, 3, modules, 1,
                                                     schemas, 1, supervisors};

int ModuleMain(int argc, const char *argv[]) { return contract_ord_main(&ORD_VOCABULARY, argc, argv); }
