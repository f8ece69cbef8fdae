/*
 * icross.c — the two supervisors of the crossed-claims scenario (itest_cross.c), built twice
 * (-DICROSS_TOP for DLA). AMD and AME (amod.c, 250 ms of their own code at START and after
 * each post) answer requests late. DLA starts AMD and DLB starts AME (each holds its own: a
 * claim on it needs no status query); then each claims its own module, then the other's:
 *   DLA.go:  S:  [elapsed=5ms]   activate critical module AMD; activate supervisor DLB.go()  [ ]
 *            A1: [elapsed=100ms] activate resttime module AMD   (its lock until AMD answers, ~255 ms)
 *            A2: [elapsed=110ms] activate resttime module AME   (status query, answered ~260 ms)
 *            T:  [elapsed=900ms] (no action)
 *   DLB.go:  S:  [elapsed=5ms]   activate critical module AME
 *            B1: [elapsed=95ms]  activate resttime module AME   (its lock until AME answers, ~260 ms)
 *            B2: [elapsed=105ms] activate resttime module AMD   (status query, answered ~255 ms)
 *            T:  [elapsed=900ms] (no action)
 * At ~255 ms DLB wants AMD's lock, which DLA keeps for an answer that only DLA can read, and DLA
 * (out of its status query at ~260 ms) wants AME's, which DLB keeps the same way: each would wait
 * for the other forever unless it first settles its own answers (prio_requests_settle).
 */
#include <stddef.h>

#include "../engine_executable.h"
#include "itables.h"

#ifdef ICROSS_TOP
ENGINE_EXECUTABLE("DLA", 90, "engines integration test supervisor (crossed claims)")
#else
ENGINE_EXECUTABLE("DLB", 89, "engines integration test supervisor (crossed claims)")
#endif

#define MS ITEST_MS

static const ContractAction on_amd[] = {{.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "AMD"}};
static const ContractAction on_ame[] = {{.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "AME"}};
ELAPSED(at900, 900 * MS)

#ifdef ICROSS_TOP
ELAPSED(at5, 5 * MS)
ELAPSED(at100, 100 * MS)
ELAPSED(at110, 110 * MS)
static const ContractFunctionSignature sig_dlb = {"DLB", "go", 0, NULL, 0};
static const ContractAction s_actions[] = {{.kind = CONTRACT_ACT_CRITICAL_MODULE, .module = "AMD"},
                                           {.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_dlb}};
static const ContractRule rules[] = {
    {"S", {1, at5}, 2, s_actions, {0, NULL}},
    {"A1", {1, at100}, 1, on_amd, {0, NULL}},
    {"A2", {1, at110}, 1, on_ame, {0, NULL}},
    {"T", {1, at900}, 0, NULL, {0, NULL}}};
static const ContractFunction functions[] = {{"go", 0, NULL, 0, 0, NULL, 0, 0, NULL, 4, rules}};
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "DLA", 90, 40, 5, 70, 0, NULL, 0, NULL, 1, functions};
#else
ELAPSED(at5, 5 * MS)
ELAPSED(at95, 95 * MS)
ELAPSED(at105, 105 * MS)
static const ContractAction s_actions[] = {{.kind = CONTRACT_ACT_CRITICAL_MODULE, .module = "AME"}};
static const ContractRule rules[] = {
    {"S", {1, at5}, 1, s_actions, {0, NULL}},
    {"B1", {1, at95}, 1, on_ame, {0, NULL}},
    {"B2", {1, at105}, 1, on_amd, {0, NULL}},
    {"T", {1, at900}, 0, NULL, {0, NULL}}};
static const ContractFunction functions[] = {{"go", 0, NULL, 0, 0, NULL, 0, 0, NULL, 4, rules}};
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "DLB", 89, 40, 5, 70, 0, NULL, 0, NULL, 1, functions};
#endif

int ModuleMain(int argc, const char *argv[]) { return contract_supervisor_main(&VOCABULARY, argc, argv); }
