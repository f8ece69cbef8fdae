/* bsup.c — the benchmark's supervisor: BSU.run: R: [elapsed=1ms] activate schema BEN() [ ]. */
#include "../engine_executable.h"

ENGINE_EXECUTABLE("BSU", 90, "engines benchmark supervisor")

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
