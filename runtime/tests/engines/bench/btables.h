/* btables.h — the benchmark's schema BEN: 1 kHz (PERIOD = CRITICAL_DELAY = 1 ms), BMA -> BMB -> BMC,
 * BMA:0 -> BMB:0 * 1, BMB:0 -> BMC:0 * 1. Included by bord.c and bsup.c. */
#ifndef BENCH_TABLES_H
#define BENCH_TABLES_H
#include <contract/vocabulary.h>

#define BENCH_MS 1000000LL
static const ContractSchemaModule ben_modules[] = {{"BMA", 0, NULL}, {"BMB", 0, NULL}, {"BMC", 0, NULL}};
static const ContractPrecedence ben_prec[] = {{0, 1}, {1, 2}};
static const ContractDataFlow ben_flows[] = {{"BMA", 0, "BMB", 0, 1}, {"BMB", 0, "BMC", 0, 1}};
static const ContractSchema BENCH_BEN = {"BEN", CONTRACT_SCHEMA_PERIODIC, 1 * BENCH_MS, 1 * BENCH_MS,
                                         0, NULL, 0, 3, ben_modules, 2, ben_prec, 2, ben_flows, 0, NULL};
#endif
