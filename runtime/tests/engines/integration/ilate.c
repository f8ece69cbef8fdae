/*
 * ilate.c — the supervisor PQS of the late-priority-answer scenario (itest_late.c): AMB (amod.c
 * with AMOD_BUSY_MS=300) runs 300 ms of its own code at each START, so it answers a priority
 * request only then; PQS does not wait for it.
 *   PQS.go:  S:  [elapsed=5ms]   activate critical module AMB  [ ]              (starts AMB)
 *            C1: [elapsed=40ms]  activate resttime module AMB  [elapsed=500ms]  (answered ~305 ms)
 *            C2: [elapsed=60ms]  activate critical module AMB  [elapsed=80ms]   (undone before its answer)
 *            T:  [elapsed=120ms] (no action)                   [ ]              (on time: ~120 ms)
 * Expected, in PQS's log: S's start priority; T active at ~120 ms; C1's and C2's claims recorded
 * when AMB answers (~305 ms); C2's undo done then (the latest claim: restores C1's priority);
 * C1's undo at 500 ms restores the priority AMB had before C1.
 */
#include <stddef.h>

#include "../engine_executable.h"
#include "itables.h"

ENGINE_EXECUTABLE("PQS", 90, "engines integration test supervisor (late priority answers)")

#define MS ITEST_MS

ELAPSED(at5, 5 * MS)
ELAPSED(at40, 40 * MS)
ELAPSED(at60, 60 * MS)
ELAPSED(at80, 80 * MS)
ELAPSED(at120, 120 * MS)
ELAPSED(at500, 500 * MS)
static const ContractAction critical[] = {{.kind = CONTRACT_ACT_CRITICAL_MODULE, .module = "AMB"}};
static const ContractAction resttime[] = {{.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "AMB"}};
static const ContractRule rules[] = {
    {"S", {1, at5}, 1, critical, {0, NULL}},
    {"C1", {1, at40}, 1, resttime, {1, at500}},
    {"C2", {1, at60}, 1, critical, {1, at80}},
    {"T", {1, at120}, 0, NULL, {0, NULL}}};
static const ContractFunction functions[] = {{"go", 0, NULL, 0, 0, NULL, 0, 0, NULL, 4, rules}};
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "PQS", 90, 40, 5, 70, 0, NULL, 0, NULL, 1, functions};

int ModuleMain(int argc, const char *argv[]) { return contract_supervisor_main(&VOCABULARY, argc, argv); }
