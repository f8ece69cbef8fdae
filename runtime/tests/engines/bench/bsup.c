/* bsup.c — the benchmark's supervisor: BSU.run: R: [elapsed=1ms] activate schema BEN() [ ]. */
#include <contract/vocabulary.h>
#include <libmodule/libmodule.h>

MODULE_DESCRIPTION("engines benchmark supervisor");
MODULE_AUTHOR("engines bench");
char MODULE_NAME[] = "BSU";
int MODULE_PRIORITY = 90;
ModuleUse IUSE[] = {IUSE_TERM};
ModuleProduce IPRODUCE[] = {IPRODUCE_TERM};
ModuleReact IREACT[] = {IREACT_TERM};
ModuleDetect IDETECT[] = {IDETECT_TERM};
size_t PARAM_SIZE_IN[] = {PARAM_SIZE_TERM};
size_t PARAM_SIZE_OUT[] = {PARAM_SIZE_TERM};

#include "btables.h"

static const ContractEvent e1[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 1 * BENCH_MS}};
static const ContractClause c1[] = {{1, e1}};
static const ContractAction actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &BENCH_BEN}};
static const ContractRule rules[] = {{"R", {1, c1}, 1, actions, {0, NULL}}};
static const ContractFunction functions[] = {{"run", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, rules}};
static const ContractSupervisorVocabulary BSU_VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "BSU", 90, 40, 5, 70, 0, NULL, 0, NULL, 1, functions};

int ModuleMain(int argc, const char *argv[]) {
    return contract_supervisor_main(&BSU_VOCABULARY, argc, argv);
}
