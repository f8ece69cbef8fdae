/*
 * test_sup_report.c — the report's SUP.action (rules FIRST, SECOND, THIRD, FOURTH, RECEPTION)
 * driven by a scripted MAA/MSC on a virtual clock; asserts the exact sequence of rule
 * activations, actions and undos. And GLB.mission activating SUP.action and stopping it on
 * SUP:1 (nested supervisors), through a bus that delivers like separate processes.
 */
#include <string.h>

#include "fake_world.h"
#include "report_tables.h"
#include "report_types.h"

#define MS 1000000LL

static TestLog LOG;

static SupCore *make_sup(FakeWorld *w, const ContractSupervisorVocabulary *v, const char *name) {
    return fake_make_sup(w, &LOG, v, name);
}

static void send_string(SupCore *c, int64_t t, const char *m, int port, const char *s) {
    char buf[256] = {0};
    strncpy(buf, s, sizeof buf - 1);
    sup_core_module_event(c, t, m, port, -1, buf, sizeof buf);
}

void test_report_sup_full_sequence(void) {
    log_clear(&LOG);
    report_log = &LOG;
    testit_result = 1;
    FakeWorld w;
    SupCore *c = make_sup(&w, &SUP_VOCAB, NULL);
    CHECK(c != NULL);
    if (!c) return;
    w.log_actions = 1; /* the event schema's activation and undo, the compute, in their place */
    TypeA consigne = {1.0, 2.0, 3.0};
    CHECK(sup_core_start_function(c, 0, "action", &consigne, sizeof consigne) == 0);

    /* before elapsed=1ms: nothing */
    sup_core_advance(c, 1 * MS - 1);
    CHECK(sup_core_rule_active(c, "action", "FIRST") == 0);
    /* MAA:2 before FIRST subscribed is ignored (no subscription) */
    send_string(c, 1 * MS - 1, "MAA", 2, "disconnected");
    sup_core_advance(c, 1 * MS);
    CHECK(sup_core_rule_active(c, "action", "FIRST") == 1);

    /* MAA:0: RECEPTION activated and at once deactivated; MAA (started by the event schema)
       gets the resttime priority, then its priority back, and keeps running */
    TypeC msg = {"hello", 7, {4.0, 5.0, 6.0}};
    sup_core_module_event(c, 2 * MS, "MAA", 0, -1, &msg, sizeof msg);
    CHECK(fake_is_running(&w, "MAA"));
    const TypeC *tm = sup_core_local(c, "action", "temp_message");
    CHECK(tm && strcmp(tm->message, "hello") == 0 && tm->value.k == 6.0);

    /* MAA:2 "disconnected": ends FIRST and starts SECOND (same event, states taken before it) */
    send_string(c, 3 * MS, "MAA", 2, "disconnected");
    CHECK(sup_core_rule_active(c, "action", "FIRST") == 0);
    CHECK(sup_core_rule_active(c, "action", "SECOND") == 1);
    CHECK(!fake_is_running(&w, "MAA"));

    /* MSC:1 (one-shot): SECOND ends with its extractions; THIRD and FOURTH start on endof */
    TypeD fail = {"overheat", 42};
    sup_core_module_event(c, 4 * MS, "MSC", 1, -1, &fail, sizeof fail);
    const TypeD *fd = sup_core_local(c, "action", "failure_data");
    CHECK(fd && strcmp(fd->dataname, "overheat") == 0 && fd->datavalue == 42);
    CHECK(strcmp(sup_core_local(c, "action", "temp_mess_type"), "commutation") == 0);
    CHECK(sup_core_rule_active(c, "action", "THIRD") == 0);
    CHECK(sup_core_rule_active(c, "action", "FOURTH") == 1);
    /* the one-shot subscription is spent: a second MSC:1 is ignored */
    sup_core_module_event(c, 5 * MS, "MSC", 1, -1, &fail, sizeof fail);

    CHECK(sup_core_stop_function(c, 6 * MS, "action") == 0);
    CHECK(!sup_core_function_running(c, "action"));

    CHECK_LOG(&LOG,
              "function action(consigne = {24 bytes}) started",
              "ignored: event MAA:2 (no active subscription)",
              "rule action.FIRST active",
              "subscribe MAA:2 =* :2",
              "subscribe MAA:0 =* :1",
              "activate schema schemaReceptionMessage(param = {24 bytes}) (event schema)",
              "setparam MAA:0 {27.12,0,0.04}",
              "start MAB prio 40", /* the consumer before its producer's flow and start */
              "connect MAA:0 =* MAB:0",
              "start MAA prio 40",
              /* MAA:0 */
              "rule action.RECEPTION active",
              "setparam MSC:0 {4,5,6}",
              "priority MAA 5 (was 40)",
              "rule action.RECEPTION inactive",
              "priority MAA 40 (was 5)",
              /* MAA:2: FIRST's postcondition, then SECOND's precondition (testit called) */
              "testit(dedede,{1,2,3})",
              "rule action.FIRST inactive",
              "unsubscribe MAA:2 :2",
              "unsubscribe MAA:0 :1",
              "undo: deactivate schema schemaReceptionMessage (event schema)",
              "disconnect MAA:0 =* MAB:0",
              "stop MAA",
              "stop MAB",
              "rule action.SECOND active",
              "subscribe MSC:1 => :3",
              "ORD activate schemaCommande1 consigne={1,2,3}",
              /* MSC:1 */
              "rule action.SECOND inactive",
              "unsubscribe MSC:1 :3",
              "ORD deactivate schemaCommande1",
              "rule action.THIRD active",
              "notify :1 commutation",
              "rule action.FOURTH active",
              "compute doit(1.24,3)",
              "compute doit",
              "ORD activate schemaCommande2 consigne={1,2,3}",
              "rule action.THIRD inactive",
              "ignored: event MSC:1 (no active subscription)",
              /* stop */
              "rule action.FOURTH inactive",
              "ORD deactivate schemaCommande2",
              "function action stopped");
    report_log = NULL;
    sup_core_destroy(c);
}

void test_report_sup_test_function_false_keeps_first(void) {
    log_clear(&LOG);
    testit_result = 0;
    FakeWorld w;
    SupCore *c = make_sup(&w, &SUP_VOCAB, NULL);
    if (!c) { CHECK(0); return; }
    CHECK(sup_core_start_function(c, 0, "action", NULL, 0) == 0);
    sup_core_advance(c, 1 * MS);
    send_string(c, 2 * MS, "MAA", 2, "disconnected");
    /* FIRST ends (its test has no testit), SECOND's test fails: MAA:2 is not significant */
    CHECK(sup_core_rule_active(c, "action", "FIRST") == 0);
    CHECK(sup_core_rule_active(c, "action", "SECOND") == 0);
    /* a status other than "disconnected" would not even end FIRST */
    testit_result = 1;
    sup_core_destroy(c);

    log_clear(&LOG);
    c = make_sup(&w, &SUP_VOCAB, NULL);
    if (!c) { CHECK(0); return; }
    sup_core_start_function(c, 0, "action", NULL, 0);
    sup_core_advance(c, 1 * MS);
    send_string(c, 2 * MS, "MAA", 2, "connected");
    CHECK(sup_core_rule_active(c, "action", "FIRST") == 1);
    CHECK(sup_core_rule_active(c, "action", "SECOND") == 0);
    /* the port variable holds the last notified value even when not significant */
    CHECK(strcmp(sup_core_in_port_value(c, 2), "connected") == 0);
    sup_core_destroy(c);
}

void test_report_sup_second_activation_refused(void) {
    log_clear(&LOG);
    FakeWorld w;
    SupCore *c = make_sup(&w, &SUP_VOCAB, NULL);
    if (!c) { CHECK(0); return; }
    CHECK(sup_core_start_function(c, 0, "action", NULL, 0) == 0);
    CHECK(sup_core_start_function(c, 10, "action", NULL, 0) == -1);
    CHECK(log_find(&LOG, "refused: function action already running", 0) >= 0);
    CHECK(sup_core_start_function(c, 10, "nosuch", NULL, 0) == -1);
    /* stop then start again: all rules inactive, clock restarted */
    CHECK(sup_core_stop_function(c, 20, "action") == 0);
    CHECK(sup_core_start_function(c, 5 * MS, "action", NULL, 0) == 0);
    sup_core_advance(c, 6 * MS - 1);
    CHECK(sup_core_rule_active(c, "action", "FIRST") == 0);
    sup_core_advance(c, 6 * MS);
    CHECK(sup_core_rule_active(c, "action", "FIRST") == 1);
    sup_core_destroy(c);
}

void test_report_sup_start_with_text_parameters(void) {
    log_clear(&LOG);
    FakeWorld w;
    SupCore *c = make_sup(&w, &SUP_VOCAB, NULL);
    if (!c) { CHECK(0); return; }
    char err[256] = "";
    CHECK(sup_core_start_function_text(c, 0, "action", "consigne={1.5, 2.5, 3.5}", err, sizeof err) == 0);
    const TypeA *tc = sup_core_local(c, "action", "temp_consigne");
    CHECK(tc && tc->i == 1.5 && tc->j == 2.5 && tc->k == 3.5);
    /* a second start while it runs: refused, and told apart from a bad request (-2: the core traced it) */
    CHECK(sup_core_start_function_text(c, 0, "action", "consigne={1.5, 2.5, 3.5}", err, sizeof err) == -2);
    CHECK(strstr(err, "is already running") != NULL);
    CHECK(sup_core_stop_function(c, 1, "action") == 0);
    CHECK(sup_core_start_function_text(c, 2, "action", "consign={1,2,3}", err, sizeof err) == -1);
    CHECK(strstr(err, "no parameter 'consign'") != NULL);
    CHECK(sup_core_start_function_text(c, 2, "action", "consigne={1,2", err, sizeof err) == -1);
    CHECK(strstr(err, "cannot read a TypeA") != NULL);
    CHECK(sup_core_start_function_text(c, 2, "run", "", err, sizeof err) == -1);
    CHECK(strstr(err, "no supervision function 'run'") != NULL);
    sup_core_destroy(c);
}

/* GLB.mission: SINGLE:[elapsed=1ms] subscribe SUP:1 => :0;
   activate supervisor SUP.action(consigne=consigne_courante) [SUP:1<gdyegdyegdyge=="commutation">] */
void test_report_nested_glb_stops_sup_on_commutation(void) {
    log_clear(&LOG);
    report_log = NULL;
    testit_result = 1;
    FakeBus *bus = fake_bus_create();
    FakeWorld wg, ws;
    SupCore *glb = make_sup(&wg, &GLB_VOCAB, "GLB");
    SupCore *sup = make_sup(&ws, &SUP_VOCAB, "SUP");
    if (!glb || !sup || !bus) { CHECK(0); return; }
    wg.bus = ws.bus = bus;
    fake_bus_attach(bus, "GLB", glb);
    fake_bus_attach(bus, "SUP", sup);

    TypeA consigne = {7.0, 8.0, 9.0};
    CHECK(sup_core_start_function(glb, 0, "mission", &consigne, sizeof consigne) == 0);
    sup_core_advance(glb, 1 * MS);
    CHECK(fake_bus_deliver(bus, 1 * MS) == 2); /* the start to SUP, SUP's answer to GLB */
    CHECK(sup_core_function_running(sup, "action"));
    const TypeA *tc = sup_core_local(sup, "action", "temp_consigne");
    CHECK(tc && tc->i == 7.0 && tc->k == 9.0);
    sup_core_advance(sup, 2 * MS);           /* SUP.FIRST */
    send_string(sup, 3 * MS, "MAA", 2, "disconnected"); /* FIRST -> SECOND */
    TypeD fail = {"overheat", 1};
    sup_core_module_event(sup, 4 * MS, "MSC", 1, -1, &fail, sizeof fail); /* THIRD notifies */
    CHECK(sup_core_rule_active(glb, "mission", "SINGLE") == 1);
    CHECK(fake_bus_deliver(bus, 4 * MS + 100) == 2); /* SUP:1 to GLB, then GLB's stop to SUP */
    CHECK(sup_core_rule_active(glb, "mission", "SINGLE") == 0);
    CHECK(!sup_core_function_running(sup, "action"));

    static const char *const glb_only[] = {"GLB: ", NULL};
    check_log_filtered(&LOG, glb_only,
                       (const char *const[]){"GLB: function mission(consigne = {24 bytes}) started",
                                             "GLB: rule mission.SINGLE active",
                                             "GLB: subscribe SUP:1 => :0",
                                             "GLB: start SUP.action {7,8,9}",
                                             "GLB: rule mission.SINGLE inactive",
                                             "GLB: unsubscribe SUP:1 :0",
                                             "GLB: stop SUP.action", NULL},
                       __FILE__, __LINE__);
    /* SUP's side of the end: FOURTH (still active) undone by the stop */
    int n = log_find(&LOG, "SUP: notify :1 commutation", 0);
    CHECK(n >= 0);
    CHECK(log_find(&LOG, "SUP: rule action.FOURTH inactive", n) > n);
    CHECK(log_find(&LOG, "SUP: ORD deactivate schemaCommande2", n) > n);
    CHECK(log_find(&LOG, "SUP: function action stopped", n) > n);
    sup_core_destroy(glb);
    sup_core_destroy(sup);
    fake_bus_destroy(bus);
}

/* Runs are deterministic (docs/semantics.md "Supervisors: event order"): the same inputs at the same times give the same effects. */
static void scripted_run(TestLog *out) {
    FakeWorld w;
    memset(&w, 0, sizeof w);
    w.log = out;
    report_log = out;
    SupIo io = fake_sup_io(&w);
    char err[256];
    SupCore *c = sup_core_create(&SUP_VOCAB, &io, err, sizeof err);
    if (!c) return;
    sup_core_start_function(c, 0, "action", NULL, 0);
    for (int k = 1; k <= 40; k++) {
        int64_t t = k * MS / 2;
        if (k % 7 == 0) {
            TypeC msg = {"m", k, {k, k, k}};
            sup_core_module_event(c, t, "MAA", 0, -1, &msg, sizeof msg);
        } else if (k % 11 == 0) {
            send_string(c, t, "MAA", 2, k % 2 ? "disconnected" : "connected");
        } else if (k % 13 == 0) {
            TypeD d = {"x", k};
            sup_core_module_event(c, t, "MSC", 1, -1, &d, sizeof d);
        } else {
            sup_core_advance(c, t);
        }
    }
    sup_core_stop_function(c, 30 * MS, "action");
    sup_core_destroy(c);
    report_log = NULL;
}

void test_report_sup_runs_are_deterministic(void) {
    static TestLog a, b;
    log_clear(&a);
    log_clear(&b);
    testit_result = 1;
    scripted_run(&a);
    scripted_run(&b);
    CHECK(a.n > 20 && a.n == b.n);
    for (int i = 0; i < a.n && i < b.n; i++) CHECK(strcmp(a.lines[i], b.lines[i]) == 0);
    CHECK(log_find(&a, "rule action.SECOND active", 0) >= 0);
}

/* SupIo.rule: every rule change of the report's sequence with the event that caused it
   (docs/runtime-api.md "Trace records") */
static TestLog CAUSES;
static void rule_to_log(void *ctx, int64_t t, const char *function, const char *rule, int active,
                        const char *cause) {
    (void)ctx;
    log_add(&CAUSES, "%lldus %s.%s %s cause=%s", (long long)(t / 1000), function, rule,
            active ? "active" : "inactive", cause);
}

void test_report_sup_rule_changes_carry_their_cause(void) {
    log_clear(&LOG);
    log_clear(&CAUSES);
    report_log = &LOG;
    testit_result = 1;
    FakeWorld w;
    memset(&w, 0, sizeof w);
    w.log = &LOG;
    SupIo io = fake_sup_io(&w);
    io.rule = rule_to_log;
    char err[256] = "";
    SupCore *c = sup_core_create(&SUP_VOCAB, &io, err, sizeof err);
    CHECK(c != NULL);
    if (!c) return;
    TypeA consigne = {1.0, 2.0, 3.0};
    CHECK(sup_core_start_function(c, 0, "action", &consigne, sizeof consigne) == 0);
    sup_core_advance(c, 1 * MS);
    TypeC msg = {"hello", 7, {4.0, 5.0, 6.0}};
    sup_core_module_event(c, 2 * MS, "MAA", 0, -1, &msg, sizeof msg);
    send_string(c, 3 * MS, "MAA", 2, "disconnected");
    TypeD fail = {"overheat", 42};
    sup_core_module_event(c, 4 * MS, "MSC", 1, -1, &fail, sizeof fail);
    CHECK(sup_core_stop_function(c, 6 * MS, "action") == 0);
    char typec[64], typed[64];
    snprintf(typec, sizeof typec, "2000us action.RECEPTION active cause=MAA:0 value={%zu bytes}", sizeof(TypeC));
    snprintf(typed, sizeof typed, "4000us action.SECOND inactive cause=MSC:1 value={%zu bytes}", sizeof(TypeD));
    CHECK_LOG(&CAUSES,
              "1000us action.FIRST active cause=elapsed=1000000ns",
              typec,
              "2000us action.RECEPTION inactive cause=started(RECEPTION)",
              "3000us action.FIRST inactive cause=MAA:2 value=\"disconnected\"",
              "3000us action.SECOND active cause=MAA:2 value=\"disconnected\"",
              typed,
              "4000us action.THIRD active cause=endof(SECOND)",
              "4000us action.FOURTH active cause=endof(SECOND)",
              "4000us action.THIRD inactive cause=started(THIRD)",
              "6000us action.FOURTH inactive cause=stop");
    report_log = NULL;
    sup_core_destroy(c);
}
