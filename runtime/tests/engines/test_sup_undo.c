/*
 * test_sup_undo.c — an undo undoes only what its own action did (docs/engines.md §4, "Undo
 * and refusals"), on a virtual clock:
 *  - `activate supervisor`: PAR's K1 and K2 both activate SEM.aux; K2's activation is refused
 *    (aux already runs K1's), so K2's undo must not stop it — whether SEM's refusal reached PAR
 *    before the undo (no stop sent) or not (the stop names activation #2, SEM ignores it);
 *  - `activate resttime|critical module` on a running module changed again by another rule
 *    (of the same supervisor or another one) before its undo: the last undo restores the
 *    priority the module had before the first;
 *  - two active event schemas of one supervisor using the same event flow: the first undo
 *    keeps it connected, the last one disconnects it;
 *  - a spent one-shot subscription undone after another rule subscribed the same producer port
 *    to the same in port: the other rule's subscription stays.
 */
#include <string.h>

#include "fake_world.h"

#define MS 1000000LL

static TestLog LOG;

#define ELAPSED(name, ms)                                                                  \
    static const ContractEvent name##_ev[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = (ms)}}; \
    static const ContractClause name[] = {{1, name##_ev}};
ELAPSED(at1, 1 * MS)
ELAPSED(at2, 2 * MS)
ELAPSED(at3, 3 * MS)
ELAPSED(at4, 4 * MS)
ELAPSED(at5, 5 * MS)

/* ---- PAR.par: K1: [elapsed=1ms] activate supervisor SEM.aux() [elapsed=5ms]
                 K2: [elapsed=2ms] activate supervisor SEM.aux() [elapsed=3ms]
        SEM.aux(): no rules ---- */
static const ContractFunctionSignature sig_aux = {"SEM", "aux", 0, NULL, 0};
static const ContractAction k_actions[] = {{.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_aux}};
static const ContractRule par_rules[] = {{"K1", {1, at1}, 1, k_actions, {1, at5}},
                                         {"K2", {1, at2}, 1, k_actions, {1, at3}}};
static const ContractFunction par_functions[] = {{"par", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, par_rules}};
static const ContractSupervisorVocabulary PAR = {
    CONTRACT_VOCABULARY_VERSION, "PAR", 90, 40, 5, 70, 0, NULL, 0, NULL, 1, par_functions};
static const ContractFunction sem_functions[] = {{"aux", 0, NULL, 0, 0, NULL, 0, 0, NULL, 0, NULL}};
static const ContractSupervisorVocabulary SEM = {
    CONTRACT_VOCABULARY_VERSION, "SEM", 89, 40, 5, 70, 0, NULL, 0, NULL, 1, sem_functions};

/* ---- PRI.inorder:  P1: [elapsed=1ms] activate critical module MPR [elapsed=3ms]
                      P2: [elapsed=2ms] activate resttime module MPR [elapsed=4ms]
        PRI.reverse:  P1 until 4 ms, P2 until 3 ms
        PRI.flows:    F1: [elapsed=1ms] activate schema EF [elapsed=3ms]
                      F2: [elapsed=2ms] activate schema EG [elapsed=4ms]
        EF = {MFA, MFB} with MFA:0 =* MFB:0, EG = {MFA, MFC} with MFA:0 =* MFB:0 too ---- */
static const ContractAction crit_actions[] = {{.kind = CONTRACT_ACT_CRITICAL_MODULE, .module = "MPR"}};
static const ContractAction rest_actions[] = {{.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "MPR"}};
static const ContractRule inorder_rules[] = {{"P1", {1, at1}, 1, crit_actions, {1, at3}},
                                             {"P2", {1, at2}, 1, rest_actions, {1, at4}}};
static const ContractRule reverse_rules[] = {{"P1", {1, at1}, 1, crit_actions, {1, at4}},
                                             {"P2", {1, at2}, 1, rest_actions, {1, at3}}};
static const ContractSchemaModule ef_modules[] = {{"MFA", 0, NULL}, {"MFB", 0, NULL}};
static const ContractSchemaModule eg_modules[] = {{"MFA", 0, NULL}, {"MFC", 0, NULL}};
static const ContractEventFlow shared_flow[] = {{"MFA", 0, "MFB", 0, CONTRACT_CONTINUOUS}};
static const ContractSchema EF = {"EF", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 2, ef_modules,
                                  0, NULL, 0, NULL, 1, shared_flow};
static const ContractSchema EG = {"EG", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 2, eg_modules,
                                  0, NULL, 0, NULL, 1, shared_flow};
static const ContractAction ef_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &EF}};
static const ContractAction eg_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &EG}};
static const ContractRule flow_rules[] = {{"F1", {1, at1}, 1, ef_actions, {1, at3}},
                                          {"F2", {1, at2}, 1, eg_actions, {1, at4}}};
/* crit: P1 alone (1 ms -> 3 ms), rest: P2 alone (2 ms -> 4 ms), run by two supervisors */
/* PRI.resub (in port :0 long):  O1: [elapsed=1ms] subscribe MSB:0 => :0 [elapsed=3ms]
                                 O2: [elapsed=2ms] subscribe MSB:0 =* :0 [elapsed=4ms]
   (MSB:0 arrives at 1.5 ms and spends O1's one-shot subscription) */
static const ContractEventPort pri_in[] = {{0, "v", &contract_type_long, NULL}};
static const ContractAction o1_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "MSB", .src_port = 0, .in_port = 0, .mode = CONTRACT_ONESHOT}};
static const ContractAction o2_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "MSB", .src_port = 0, .in_port = 0, .mode = CONTRACT_CONTINUOUS}};
static const ContractRule resub_rules[] = {{"O1", {1, at1}, 1, o1_actions, {1, at3}},
                                           {"O2", {1, at2}, 1, o2_actions, {1, at4}}};

static const ContractFunction pri_functions[] = {
    {"inorder", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, inorder_rules},
    {"reverse", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, reverse_rules},
    {"flows", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, flow_rules},
    {"crit", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, inorder_rules},
    {"rest", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, inorder_rules + 1},
    {"resub", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, resub_rules}};
static const ContractSupervisorVocabulary PRI = {
    CONTRACT_VOCABULARY_VERSION, "PRI", 90, 40, 5, 70, 1, pri_in, 0, NULL, 6, pri_functions};

static SupCore *make_sup(FakeWorld *w, const ContractSupervisorVocabulary *v, const char *name) {
    return fake_make_sup(w, &LOG, v, name);
}

static void run_par_sem(int answer_before_undo) {
    log_clear(&LOG);
    FakeBus *bus = fake_bus_create();
    FakeWorld wp, ws;
    SupCore *par = make_sup(&wp, &PAR, "PAR"), *sem = make_sup(&ws, &SEM, "SEM");
    if (!bus || !par || !sem) { CHECK(0); return; }
    wp.bus = ws.bus = bus;
    fake_bus_attach(bus, "PAR", par);
    fake_bus_attach(bus, "SEM", sem);
    sup_core_start_function(par, 0, "par", NULL, 0);
    sup_core_advance(par, 1 * MS);
    fake_bus_deliver(bus, 1 * MS);          /* K1's activation accepted */
    CHECK(sup_core_function_running(sem, "aux"));
    sup_core_advance(par, 2 * MS);          /* K2's: refused by SEM */
    if (answer_before_undo) fake_bus_deliver(bus, 2 * MS);
    sup_core_advance(par, 3 * MS);          /* K2 undone */
    fake_bus_deliver(bus, 3 * MS);
    CHECK(sup_core_function_running(sem, "aux")); /* still K1's run */
    sup_core_advance(par, 5 * MS);          /* K1 undone: its own run ends */
    fake_bus_deliver(bus, 5 * MS);
    CHECK(!sup_core_function_running(sem, "aux"));
    CHECK(log_find(&LOG, "SEM: refused: function aux already running", 0) >= 0);
    const char *const par_stops[] = {"PAR: stop", "PAR: activation", NULL};
    if (answer_before_undo)
        check_log_filtered(&LOG, par_stops,
                           (const char *const[]){"PAR: activation #2 of SEM.aux refused: its undo stops nothing",
                                                 "PAR: stop SEM.aux", NULL},
                           __FILE__, __LINE__);
    else
        CHECK(log_find(&LOG, "SEM: ignored: stop of aux for activation #2 of PAR (it runs activation #1 of PAR)", 0) >= 0);
    sup_core_destroy(par);
    sup_core_destroy(sem);
    fake_bus_destroy(bus);
}

void test_undo_refused_supervisor_activation_answered_stops_nothing(void) { run_par_sem(1); }

void test_undo_refused_supervisor_activation_not_yet_answered_is_ignored_by_callee(void) {
    run_par_sem(0);
}

/* a run started by a control tool is not a caller's: a refused activation's undo leaves it;
   a stop with no activation (a control tool's) ends any run */
void test_undo_leaves_a_function_a_control_tool_started(void) {
    log_clear(&LOG);
    FakeWorld ws;
    SupCore *sem = make_sup(&ws, &SEM, "SEM");
    if (!sem) { CHECK(0); return; }
    CHECK(sup_core_start_function(sem, 0, "aux", NULL, 0) == 0);
    CHECK(sup_core_start_function_for(sem, 1 * MS, "aux", NULL, 0, "PAR", 7) == -2); /* already running */
    CHECK(sup_core_start_function_for(sem, 1 * MS, "nope", NULL, 0, "PAR", 8) == -1);   /* no such function */
    CHECK(sup_core_stop_function_for(sem, 2 * MS, "aux", "PAR", 7) == -1);
    CHECK(sup_core_function_running(sem, "aux"));
    CHECK(log_find(&LOG, "SEM: ignored: stop of aux for activation #7 of PAR (started by a control tool)", 0) >= 0);
    CHECK(sup_core_stop_function_for(sem, 3 * MS, "aux", "CTL", 0) == 0);
    CHECK(!sup_core_function_running(sem, "aux"));
    sup_core_destroy(sem);
}

static int prio_of(const FakeWorld *w, const char *m) {
    for (int i = 0; i < w->nrunning; i++)
        if (strcmp(w->running[i], m) == 0) return w->prio[i];
    return -1;
}

void test_undo_priority_changed_again_by_another_rule(void) {
    static const char *const prio_lines[] = {"priority", "kept", NULL};
    for (int reverse = 0; reverse <= 1; reverse++) {
        log_clear(&LOG);
        FakeWorld w;
        SupCore *c = make_sup(&w, &PRI, NULL);
        if (!c) { CHECK(0); return; }
        fake_set_running(&w, "MPR", 33);
        sup_core_start_function(c, 0, reverse ? "reverse" : "inorder", NULL, 0);
        sup_core_advance(c, 10 * MS);
        CHECK(prio_of(&w, "MPR") == 33);
        if (!reverse) /* P1 undone while P2's change stands: nothing applied, P2 restores 33 */
            check_log_filtered(&LOG, prio_lines,
                               (const char *const[]){"priority MPR 70 (was 33)", "priority MPR 5 (was 70)",
                                                     "kept: priority of MPR (a later change by this supervisor stands)",
                                                     "priority MPR 33 (was 5)", NULL},
                               __FILE__, __LINE__);
        else /* the latest undone first: each restores the one before it */
            check_log_filtered(&LOG, prio_lines,
                               (const char *const[]){"priority MPR 70 (was 33)", "priority MPR 5 (was 70)",
                                                     "priority MPR 70 (was 5)", "priority MPR 33 (was 70)", NULL},
                               __FILE__, __LINE__);
        sup_core_destroy(c);
    }
}

void test_undo_event_flow_used_by_two_active_schemas(void) {
    log_clear(&LOG);
    FakeWorld w;
    SupCore *c = make_sup(&w, &PRI, NULL);
    if (!c) { CHECK(0); return; }
    sup_core_start_function(c, 0, "flows", NULL, 0);
    sup_core_advance(c, 10 * MS);
    static const char *const flow_lines[] = {"connect", "disconnect", "kept", "rule", NULL};
    check_log_filtered(&LOG, flow_lines,
                       (const char *const[]){"rule flows.F1 active", "connect MFA:0 =* MFB:0",
                                             "rule flows.F2 active", "connect MFA:0 =* MFB:0",
                                             "rule flows.F1 inactive",
                                             "kept: event flow MFA:0 -> MFB:0 (used by 1 other active schema(s))",
                                             "rule flows.F2 inactive", "disconnect MFA:0 =* MFB:0", NULL},
                       __FILE__, __LINE__);
    CHECK(!fake_is_running(&w, "MFA") && !fake_is_running(&w, "MFB") && !fake_is_running(&w, "MFC"));
    sup_core_destroy(c);
}

/* the same with the two rules in two supervisors XA and XB acting on one module */
void test_undo_priority_changed_again_by_another_supervisor(void) {
    log_clear(&LOG);
    FakeWorld wa, wb;
    SupCore *xa = make_sup(&wa, &PRI, "XA"), *xb = make_sup(&wb, &PRI, "XB");
    if (!xa || !xb) { CHECK(0); return; }
    wb.modules = &wa; /* MPR and its claims, seen by both */
    fake_set_running(&wa, "MPR", 33);
    sup_core_start_function(xa, 0, "crit", NULL, 0);
    sup_core_start_function(xb, 0, "rest", NULL, 0);
    for (int ms = 1; ms <= 5; ms++) {
        sup_core_advance(xa, ms * MS);
        sup_core_advance(xb, ms * MS);
    }
    CHECK(prio_of(&wa, "MPR") == 33);
    static const char *const prio_lines[] = {"priority", "kept", NULL};
    check_log_filtered(&LOG, prio_lines,
                       (const char *const[]){"XA: priority MPR 70 (was 33)", "XB: priority MPR 5 (was 70)",
                                             "XA: kept: priority of MPR (a later change by XB stands)",
                                             "XB: priority MPR 33 (was 5)", NULL},
                       __FILE__, __LINE__);
    sup_core_destroy(xa);
    sup_core_destroy(xb);
}

void test_undo_spent_oneshot_subscription_made_again_by_another_rule(void) {
    log_clear(&LOG);
    FakeWorld w;
    SupCore *c = make_sup(&w, &PRI, NULL);
    if (!c) { CHECK(0); return; }
    sup_core_start_function(c, 0, "resub", NULL, 0);
    long v = 7;
    sup_core_module_event(c, 1 * MS + MS / 2, "MSB", 0, -1, &v, sizeof v); /* spends O1's */
    sup_core_advance(c, 10 * MS);
    static const char *const sub_lines[] = {"subscribe", "subscription", NULL};
    check_log_filtered(&LOG, sub_lines,
                       (const char *const[]){"subscribe MSB:0 => :0", "subscribe MSB:0 =* :0",
                                             "kept: subscription MSB:0 to :0 (made again since by another rule)",
                                             "unsubscribe MSB:0 :0", NULL},
                       __FILE__, __LINE__);
    sup_core_destroy(c);
}

/* PRI.flows again, MFA's run (started by F1's schema) ending by MFA's own code before F2's schema
   needs it: F2 starts it again (as a module not running), then the last undo stops it; while it
   still runs, F2 only shares F1's hold (one start: the test above) */
void test_held_module_whose_run_ended_is_started_again(void) {
    log_clear(&LOG);
    FakeWorld w;
    SupCore *c = make_sup(&w, &PRI, NULL);
    if (!c) { CHECK(0); return; }
    sup_core_start_function(c, 0, "flows", NULL, 0);
    sup_core_advance(c, 1500000);
    CHECK(fake_is_running(&w, "MFA"));
    fake_end_own_run(&w, "MFA");
    sup_core_advance(c, 10 * MS);
    static const char *const lines[] = {"start MFA", "stop MFA", "rule", NULL};
    check_log_filtered(&LOG, lines,
                       (const char *const[]){"rule flows.F1 active", "start MFA prio 40",
                                             "rule flows.F2 active", "start MFA prio 40",
                                             "rule flows.F1 inactive", "rule flows.F2 inactive", "stop MFA", NULL},
                       __FILE__, __LINE__);
    CHECK(!fake_is_running(&w, "MFA"));
    CHECK(w.unlocked_effects == 0);
    sup_core_destroy(c);
}
