/*
 * iundo.c — two supervisors of the undo scenario, built twice (-DIUNDO_TOP for UPA): each
 * undo must undo only what its own action did (docs/engines.md §4, "Undo and refusals").
 *   UPA.top:  S1: [elapsed=10ms]  activate schema PSC()          [elapsed=760ms]
 *             K1: [elapsed=20ms]  activate supervisor USM.aux()  [elapsed=720ms]
 *             F1: [elapsed=120ms] activate schema EVF()          [elapsed=450ms]
 *             K2: [elapsed=60ms]  activate supervisor USM.aux()  [elapsed=120ms]  (refused)
 *             P1: [elapsed=140ms] activate critical module AMX   [elapsed=380ms]
 *             P2: [elapsed=420ms] activate resttime module AMX   [elapsed=700ms]
 *   USM.aux:  A1: [elapsed=5ms]   activate schema EVA()          [ ]  (starts AMX)
 *             A2: [elapsed=5ms]   activate schema PSC()          [ORD:1]  (refused by ORD)
 *             A3: [elapsed=60ms]  activate schema EVG()          [elapsed=220ms]
 *             A4: [elapsed=220ms] activate resttime module AMX   [elapsed=520ms]
 *             B1: [elapsed=5ms]   subscribe AMX:0 => :0           [elapsed=100ms]  (spent at once)
 *             B2: [elapsed=90ms]  subscribe AMX:0 =* :0           [elapsed=260ms]
 *   aux starts ~20 ms after top, d ms more on a loaded host. The orders between the two
 *   supervisors the checks depend on, in top's time, with their margins (d widens "+ d"):
 *     USM's A1 starts AMX (~25 + d) before UPA's EVF shares it (120):            95 - d
 *     UPA's EVF uses AMX:0 =* AMY:0 (120) before EVG's undo (~240 + d):          120 + d
 *     AMX's claims: P1 (140) < A4 (~240 + d) < P1's undo (380):                 100 + d, 140 - d
 *                   P2 (420) < A4's undo (~540 + d) < P2's undo (700):          120 + d, 160 - d
 *   so all hold while aux starts up to ~90 ms late; every other order is within one process
 *   (or causal: USM's PSC follows UPA's, which UPA sent before starting aux). "+ d" margins are
 *   spent by UPA being late, e.g. waiting for AMX's status, which P1 asks before its claim: with
 *   AMX stopped (SIGSTOP) 80 ms from ~125 ms, A4 (then at aux 160) claimed AMX before P1 in 3
 *   runs of 3; now AMX may answer P1 up to ~100 ms late (passed 100 ms, failed 130). The first
 *   version had F1 at 40 ms: in a CI run of the full suite aux started over 15 ms late, UPA's EVF
 *   started AMX, and the counts of priority records per supervisor were swapped. Moving F1 to
 *   120 left EVG's undo (aux 150) 50 ms and A4's claim (aux 160) 40 ms after the UPA steps they
 *   must follow: A3 now ends and A4 begins at aux 220, and the later steps moved along.
 *   event schemas EVA { AMX }, EVF and EVG { AMX, AMY; AMX:0 =* AMY:0 }; periodic PSC { UMA }
 *   (itables.h). Expected: K2's undo leaves K1's run of aux; USM's undo of its refused PSC
 *   (same activation number as UPA's) leaves UPA's; EVG's undo leaves the flow that UPA's EVF
 *   still uses; P1's and A4's undos, each with a later change standing, change no priority;
 *   B1's undo leaves B2's subscription of the same port. B2 comes 85 ms after B1: AMX posts
 *   every 10 ms, so B1's one-shot is spent by then even when the host holds AMX for tens of ms
 *   (while a one-shot is pending, a second subscription of that port is refused, as documented).
 *   B2 lasts until aux 260: USM must receive an AMX event 40 ms or more after B1's undo (aux
 *   100), which leaves AMX 120 ms to post it (60 ms when B2 ended at aux 200).
 */
#include <stddef.h>

#include "../engine_executable.h"
#include "itables.h"

#ifdef IUNDO_TOP
ENGINE_EXECUTABLE("UPA", 95, "engines integration test supervisor")
#else
ENGINE_EXECUTABLE("USM", 92, "engines integration test supervisor")
#endif

#define MS ITEST_MS

static const ContractSchemaModule evf_modules[] = {{"AMX", 0, NULL}, {"AMY", 0, NULL}};
static const ContractEventFlow evf_flows[] = {{"AMX", 0, "AMY", 0, CONTRACT_CONTINUOUS}};

#ifdef IUNDO_TOP
ELAPSED(at10, 10 * MS)
ELAPSED(at20, 20 * MS)
ELAPSED(at60, 60 * MS)
ELAPSED(at120, 120 * MS)
ELAPSED(at140, 140 * MS)
ELAPSED(at380, 380 * MS)
ELAPSED(at420, 420 * MS)
ELAPSED(at450, 450 * MS)
ELAPSED(at700, 700 * MS)
ELAPSED(at720, 720 * MS)
ELAPSED(at760, 760 * MS)
static const ContractSchema EVF = {"EVF", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 2, evf_modules,
                                   0, NULL, 0, NULL, 1, evf_flows};
static const ContractFunctionSignature sig_aux = {"USM", "aux", 0, NULL, 0};
static const ContractAction s1_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_PSC}};
static const ContractAction k_actions[] = {{.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_aux}};
static const ContractAction f1_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &EVF}};
static const ContractAction p1_actions[] = {{.kind = CONTRACT_ACT_CRITICAL_MODULE, .module = "AMX"}};
static const ContractAction p2_actions[] = {{.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "AMX"}};
static const ContractRule rules[] = {
    {"S1", {1, at10}, 1, s1_actions, {1, at760}},
    {"K1", {1, at20}, 1, k_actions, {1, at720}},
    {"F1", {1, at120}, 1, f1_actions, {1, at450}},
    {"K2", {1, at60}, 1, k_actions, {1, at120}},
    {"P1", {1, at140}, 1, p1_actions, {1, at380}},
    {"P2", {1, at420}, 1, p2_actions, {1, at700}}};
static const ContractFunction functions[] = {{"top", 0, NULL, 0, 0, NULL, 0, 0, NULL, 6, rules}};
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "UPA", 95, 40, 5, 70, 0, NULL, 0, NULL, 1, functions};
#else
ELAPSED(at5, 5 * MS)
ELAPSED(at60, 60 * MS)
ELAPSED(at90, 90 * MS)
ELAPSED(at100, 100 * MS)
ELAPSED(at220, 220 * MS)
ELAPSED(at260, 260 * MS)
ELAPSED(at520, 520 * MS)
static const ContractSchemaModule eva_modules[] = {{"AMX", 0, NULL}};
static const ContractSchema EVA = {"EVA", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 1, eva_modules,
                                   0, NULL, 0, NULL, 0, NULL};
static const ContractSchema EVG = {"EVG", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 2, evf_modules,
                                   0, NULL, 0, NULL, 1, evf_flows};
static const ContractEvent ord1_ev[] = {{.kind = CONTRACT_EV_MODULE, .module = "ORD", .port = 1, .in_port = -1}};
static const ContractClause ord1[] = {{1, ord1_ev}};
static const ContractAction a1_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &EVA}};
static const ContractAction a2_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &ITEST_PSC}};
static const ContractAction a3_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &EVG}};
static const ContractAction a4_actions[] = {{.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "AMX"}};
static const ContractAction b1_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "AMX", .src_port = 0, .in_port = 0, .mode = CONTRACT_ONESHOT}};
static const ContractAction b2_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "AMX", .src_port = 0, .in_port = 0, .mode = CONTRACT_CONTINUOUS}};
static const ContractEventPort in_ports[] = {{0, "v", &contract_type_long, NULL}};
static const ContractRule rules[] = {
    {"A1", {1, at5}, 1, a1_actions, {0, NULL}},
    {"A2", {1, at5}, 1, a2_actions, {1, ord1}},
    {"A3", {1, at60}, 1, a3_actions, {1, at220}},
    {"A4", {1, at220}, 1, a4_actions, {1, at520}},
    {"B1", {1, at5}, 1, b1_actions, {1, at100}},
    {"B2", {1, at90}, 1, b2_actions, {1, at260}}};
static const ContractFunction functions[] = {{"aux", 0, NULL, 0, 0, NULL, 0, 0, NULL, 6, rules}};
static const ContractSupervisorVocabulary VOCABULARY = {
    CONTRACT_VOCABULARY_VERSION, "USM", 92, 40, 5, 70, 1, in_ports, 0, NULL, 1, functions};
#endif

int ModuleMain(int argc, const char *argv[]) { return contract_supervisor_main(&VOCABULARY, argc, argv); }
