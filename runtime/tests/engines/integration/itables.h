/* itables.h — the integration test's periodic schemas, included by iord.c and the supervisors
 * that activate them (isup.c, ireactivate.c; one TU each).
 *   ISC (20 ms, critical delay 15 ms): IMA (gain :0) -> IMB, IMA -> IMC; IMA:0 -> IMB:0 * 1,
 *       IMA:0 -> IMC:0 * 2.          ICF: IMB alone (conflicts with ISC).
 *   RSC (20 ms, critical delay 15 ms): RMA -> RMB -> RMC (RMB is slow in its 4th activation).
 *   PSC (20 ms, critical delay 15 ms): UMA alone (activated by UPA and USM: undo scenario).
 *   FST (10 ms, critical delay 10 ms): STK (gain :0), which never finishes its 5th release;
 *   SLW (20 ms, critical delay 15 ms): OKM alone (stuck-module scenario).
 *   CRH (20 ms, critical delay 15 ms): CRS alone, killed in its 5th release (crashed-module scenario).
 *   FLD (1 ms, critical delay 1 ms): FLM alone, 3 ms a release: every cycle misses its deadline and
 *       overruns (output-flood scenario). */
#ifndef ITEST_TABLES_H
#define ITEST_TABLES_H
#include <contract/vocabulary.h>

#define ITEST_MS 1000000LL
/* `name`: the precondition or postcondition [elapsed=t] */
#define ELAPSED(name, t)                                                                   \
    static const ContractEvent name##_ev[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = (t)}}; \
    static const ContractClause name[] = {{1, name##_ev}};
static const long itest_gain_default = 3;
static const ContractVar isc_params[] = {{"gain", &contract_type_long, 0, &itest_gain_default}};
static const ContractAssign isc_ima_p0[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_PARAM, 0, 0, &contract_type_long, NULL}}};
static const ContractParamSetting isc_ima_settings[] = {{0, &contract_type_long, 1, isc_ima_p0, "gain"}};
static const ContractSchemaModule isc_modules[] = {
    {"IMA", 1, isc_ima_settings}, {"IMB", 0, NULL}, {"IMC", 0, NULL}};
static const ContractPrecedence isc_prec[] = {{0, 1}, {0, 2}};
static const ContractDataFlow isc_flows[] = {{"IMA", 0, "IMB", 0, 1}, {"IMA", 0, "IMC", 0, 2}};
static const ContractSchema ITEST_ISC = {"ISC", CONTRACT_SCHEMA_PERIODIC, 20 * ITEST_MS, 15 * ITEST_MS,
                                         1, isc_params, sizeof(long), 3, isc_modules, 2, isc_prec,
                                         2, isc_flows, 0, NULL};
static const ContractSchemaModule icf_modules[] = {{"IMB", 0, NULL}};
static const ContractSchema ITEST_ICF = {"ICF", CONTRACT_SCHEMA_PERIODIC, 20 * ITEST_MS, 20 * ITEST_MS,
                                         0, NULL, 0, 1, icf_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractSchemaModule rsc_modules[] = {{"RMA", 0, NULL}, {"RMB", 0, NULL}, {"RMC", 0, NULL}};
static const ContractPrecedence rsc_prec[] = {{0, 1}, {1, 2}};
static const ContractSchema ITEST_RSC = {"RSC", CONTRACT_SCHEMA_PERIODIC, 20 * ITEST_MS, 15 * ITEST_MS,
                                         0, NULL, 0, 3, rsc_modules, 2, rsc_prec, 0, NULL, 0, NULL};
static const ContractSchemaModule psc_modules[] = {{"UMA", 0, NULL}};
static const ContractSchema ITEST_PSC = {"PSC", CONTRACT_SCHEMA_PERIODIC, 20 * ITEST_MS, 15 * ITEST_MS,
                                         0, NULL, 0, 1, psc_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractSchemaModule fst_modules[] = {{"STK", 1, isc_ima_settings}};
static const ContractSchema ITEST_FST = {"FST", CONTRACT_SCHEMA_PERIODIC, 10 * ITEST_MS, 10 * ITEST_MS,
                                         1, isc_params, sizeof(long), 1, fst_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractSchemaModule slw_modules[] = {{"OKM", 0, NULL}};
static const ContractSchema ITEST_SLW = {"SLW", CONTRACT_SCHEMA_PERIODIC, 20 * ITEST_MS, 15 * ITEST_MS,
                                         0, NULL, 0, 1, slw_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractSchemaModule crh_modules[] = {{"CRS", 0, NULL}};
static const ContractSchema ITEST_CRH = {"CRH", CONTRACT_SCHEMA_PERIODIC, 20 * ITEST_MS, 15 * ITEST_MS,
                                         0, NULL, 0, 1, crh_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractSchemaModule fld_modules[] = {{"FLM", 0, NULL}};
static const ContractSchema ITEST_FLD = {"FLD", CONTRACT_SCHEMA_PERIODIC, 1 * ITEST_MS, 1 * ITEST_MS,
                                         0, NULL, 0, 1, fld_modules, 0, NULL, 0, NULL, 0, NULL};
#endif
