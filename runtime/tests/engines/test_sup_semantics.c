/*
 * test_sup_semantics.c — supervisor semantics edge cases on a small hand-written supervisor
 * TST (in :0 int a, in :1 int b, in :2 float x; out :0 int o), one function per scenario.
 * Rule 0 of every function subscribes X:0/X:1/X:2 at elapsed=1ms, so scenarios start at 1ms.
 */
#include <string.h>

#include "fake_world.h"

#define MS 1000000LL
#define T0 (1 * MS)

static TestLog LOG;

static const long k3 = 3;
static const double k2_5 = 2.5;
static const long k100 = 100;

static const ContractEventPort tst_in[] = {
    {0, "a", &contract_type_long, NULL}, {1, "b", &contract_type_long, NULL},
    {2, "x", &contract_type_double, NULL}};
static const ContractEventPort tst_out[] = {{0, "o", &contract_type_long, NULL}};
static const ContractVar tst_locals[] = {{"la", &contract_type_long, 0, NULL},
                                         {"lx", &contract_type_double, 8, NULL}};

/* S: [elapsed=1ms] subscribe X:0 =* :0; subscribe X:1 =* :1; subscribe X:2 =* :2 [] */
static const ContractEvent ev_elapsed_1ms[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 1 * MS}};
static const ContractClause cl_elapsed_1ms[] = {{1, ev_elapsed_1ms}};
static const ContractAction subs_actions[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "X", .src_port = 0, .in_port = 0},
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "X", .src_port = 1, .in_port = 1},
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "X", .src_port = 2, .in_port = 2}};
#define RULE_S {"S", {1, cl_elapsed_1ms}, 3, subs_actions, {0, NULL}}

#define EV_A(persist_kind, ns) \
    {.kind = CONTRACT_EV_MODULE, .module = "X", .port = 0, .in_port = 0, .persist = persist_kind, .persist_ns = ns}
#define EV_B {.kind = CONTRACT_EV_MODULE, .module = "X", .port = 1, .in_port = 1}

/* window: W1: [(X:0{10ms} and X:1)]  W2: [(X:0{infinite} and X:1)]  W3: [(X:0 and X:1)] */
static const ContractEvent w1_ev[] = {EV_A(CONTRACT_PERSIST_TIME, 10 * MS), EV_B};
static const ContractClause w1_cl[] = {{2, w1_ev}};
static const ContractEvent w2_ev[] = {EV_A(CONTRACT_PERSIST_INFINITE, 0), EV_B};
static const ContractClause w2_cl[] = {{2, w2_ev}};
static const ContractEvent w3_ev[] = {EV_A(CONTRACT_PERSIST_NONE, 0), EV_B};
static const ContractClause w3_cl[] = {{2, w3_ev}};
static const ContractRule window_rules[] = {
    RULE_S, {"W1", {1, w1_cl}, 0, NULL, {0, NULL}}, {"W2", {1, w2_cl}, 0, NULL, {0, NULL}},
    {"W3", {1, w3_cl}, 0, NULL, {0, NULL}}};

/* transient: T: [(X:1 and X:0{10ms})] — the transient event written first */
static const ContractEvent t_ev[] = {EV_B, EV_A(CONTRACT_PERSIST_TIME, 10 * MS)};
static const ContractClause t_cl[] = {{2, t_ev}};
static const ContractRule transient_rules[] = {RULE_S, {"T", {1, t_cl}, 0, NULL, {0, NULL}}};

/* extract: E: [(X:0<(a > 3)>{10ms}(la = a) and X:1)]
            F: [X:2<(x > 2.5) | (x == 100)>(lx = x)]   (int constant against a float port) */
static const ContractTest e_tests[] = {
    {CONTRACT_TEST_GT, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_long, NULL},
     {CONTRACT_REF_CONST, 0, 0, &contract_type_long, &k3}, NULL, 0, NULL}};
static const ContractTestClause e_tc[] = {{1, e_tests}};
static const ContractAssign e_extr[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_IN_PORT, 0, 0, &contract_type_long, NULL}}};
static const ContractEvent e_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "X", .port = 0, .in_port = 0, .ntest_clauses = 1,
     .test_clauses = e_tc, .persist = CONTRACT_PERSIST_TIME, .persist_ns = 10 * MS,
     .nextractions = 1, .extractions = e_extr},
    EV_B};
static const ContractClause e_cl[] = {{2, e_ev}};
static const ContractTest f_t1[] = {
    {CONTRACT_TEST_GT, {CONTRACT_REF_IN_PORT, 2, 0, &contract_type_double, NULL},
     {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k2_5}, NULL, 0, NULL}};
static const ContractTest f_t2[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_IN_PORT, 2, 0, &contract_type_double, NULL},
     {CONTRACT_REF_CONST, 0, 0, &contract_type_long, &k100}, NULL, 0, NULL}};
static const ContractTestClause f_tc[] = {{1, f_t1}, {1, f_t2}};
static const ContractAssign f_extr[] = {
    {1, 0, &contract_type_double, {CONTRACT_REF_IN_PORT, 2, 0, &contract_type_double, NULL}}};
static const ContractEvent f_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "X", .port = 2, .in_port = 2, .ntest_clauses = 2,
     .test_clauses = f_tc, .nextractions = 1, .extractions = f_extr}};
static const ContractClause f_cl[] = {{1, f_ev}};
/* F ends on the next X:2 whatever its value, so it can start again */
static const ContractEvent f_post_ev[] = {{.kind = CONTRACT_EV_MODULE, .module = "X", .port = 2, .in_port = 2}};
static const ContractClause f_post[] = {{1, f_post_ev}};
static const ContractRule extract_rules[] = {
    RULE_S, {"E", {1, e_cl}, 0, NULL, {0, NULL}}, {"F", {1, f_cl}, 0, NULL, {1, f_post}}};

/* duration: D1: [elapsed=1ms] [duration(D1)=5ms]   D2: [duration(D1)=5ms] [X:0]
             D3: [elapsed=1ms] [X:1]                D4: [duration(D3)=5ms] [] 
             N:  [endof(D1)] notify :0(o = 100) [X:1]   (notify keeps the port value)        */
static const ContractEvent d1_post_ev[] = {{.kind = CONTRACT_EV_DURATION, .rule = 1, .time_ns = 5 * MS}};
static const ContractClause d1_post[] = {{1, d1_post_ev}};
static const ContractEvent d2_post_ev[] = {EV_A(CONTRACT_PERSIST_NONE, 0)};
static const ContractClause d2_post[] = {{1, d2_post_ev}};
static const ContractEvent d3_post_ev[] = {EV_B};
static const ContractClause d3_post[] = {{1, d3_post_ev}};
static const ContractEvent d4_pre_ev[] = {{.kind = CONTRACT_EV_DURATION, .rule = 3, .time_ns = 5 * MS}};
static const ContractClause d4_pre[] = {{1, d4_pre_ev}};
static const ContractEvent n_pre_ev[] = {{.kind = CONTRACT_EV_ENDOF, .rule = 1}};
static const ContractClause n_pre[] = {{1, n_pre_ev}};
static const ContractAssign n_notify[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_CONST, 0, 0, &contract_type_long, &k100}}};
static const ContractAction n_actions[] = {
    {.kind = CONTRACT_ACT_NOTIFY, .out_port = 0, .nassigns = 1, .assigns = n_notify}};
static const ContractRule duration_rules[] = {
    RULE_S,
    {"D1", {1, cl_elapsed_1ms}, 0, NULL, {1, d1_post}},
    {"D2", {1, d1_post}, 0, NULL, {1, d2_post}},
    {"D3", {1, cl_elapsed_1ms}, 0, NULL, {1, d3_post}},
    {"D4", {1, d4_pre}, 0, NULL, {0, NULL}},
    {"N", {1, n_pre}, 1, n_actions, {1, d3_post}}};

#define FN(name, rules) \
    {name, 0, NULL, 0, 2, tst_locals, 16, 0, NULL, (int)(sizeof rules / sizeof rules[0]), rules}
static const ContractFunction tst_functions[] = {
    FN("window", window_rules), FN("transient", transient_rules), FN("extract", extract_rules),
    FN("duration", duration_rules)};
static const ContractSupervisorVocabulary TST = {
    CONTRACT_VOCABULARY_VERSION, "TST", 90, 40, 5, 70, 3, tst_in, 1, tst_out, 4, tst_functions};

/* TST on a fresh world logging to LOG; `last_trace_time`: the binding's clock of its trace lines
   (NULL: the core's time, as in the simulator). NULL when it cannot be made (said). */
static SupCore *make_tst(FakeWorld *w, int64_t (*last_trace_time)(void *ctx)) {
    log_clear(&LOG);
    memset(w, 0, sizeof *w);
    w->log = &LOG;
    SupIo io = fake_sup_io(w);
    io.last_trace_time = last_trace_time;
    char err[256] = "";
    SupCore *c = sup_core_create(&TST, &io, err, sizeof err);
    if (!c) fprintf(stderr, "  %s\n", err);
    return c;
}

static SupCore *start(FakeWorld *w, const char *fn) {
    SupCore *c = make_tst(w, NULL);
    if (!c) return NULL;
    sup_core_start_function(c, 0, fn, NULL, 0);
    sup_core_advance(c, T0);
    return c;
}

static void send_long(SupCore *c, int64_t t, int port, long v) {
    sup_core_module_event(c, t, "X", port, -1, &v, sizeof v);
}

void test_persistence_window_inclusive_end(void) {
    FakeWorld w;
    SupCore *c = start(&w, "window");
    if (!c) { CHECK(0); return; }
    send_long(c, T0 + 1 * MS, 0, 1);
    send_long(c, T0 + 11 * MS, 1, 1); /* exactly t + 10ms: still present */
    CHECK(sup_core_rule_active(c, "window", "W1") == 1);
    CHECK(sup_core_rule_active(c, "window", "W2") == 1);
    CHECK(sup_core_rule_active(c, "window", "W3") == 0);
    sup_core_destroy(c);
}

void test_persistence_window_just_outside(void) {
    FakeWorld w;
    SupCore *c = start(&w, "window");
    if (!c) { CHECK(0); return; }
    send_long(c, T0 + 1 * MS, 0, 1);
    send_long(c, T0 + 11 * MS + 1, 1, 1); /* 1 ns too late for {10ms}; {infinite} still there */
    CHECK(sup_core_rule_active(c, "window", "W1") == 0);
    CHECK(sup_core_rule_active(c, "window", "W2") == 1);
    sup_core_destroy(c);
}

void test_persistence_none_needs_same_event(void) {
    FakeWorld w;
    SupCore *c = start(&w, "window");
    if (!c) { CHECK(0); return; }
    /* two transient events at the same instant are still two events: W3 never holds */
    send_long(c, T0 + 1 * MS, 0, 1);
    send_long(c, T0 + 1 * MS, 1, 1);
    CHECK(sup_core_rule_active(c, "window", "W3") == 0);
    CHECK(sup_core_rule_active(c, "window", "W1") == 1);
    sup_core_destroy(c);
}

void test_transient_event_must_come_last(void) {
    FakeWorld w;
    SupCore *c = start(&w, "transient");
    if (!c) { CHECK(0); return; }
    send_long(c, T0 + 1 * MS, 1, 1); /* transient b first: forgotten */
    send_long(c, T0 + 2 * MS, 0, 1); /* a arrives: b is not present */
    CHECK(sup_core_rule_active(c, "transient", "T") == 0);
    send_long(c, T0 + 3 * MS, 1, 1); /* b last, a persists: true */
    CHECK(sup_core_rule_active(c, "transient", "T") == 1);
    sup_core_destroy(c);
}

void test_extraction_reads_the_occurrence_data(void) {
    FakeWorld w;
    SupCore *c = start(&w, "extract");
    if (!c) { CHECK(0); return; }
    send_long(c, T0 + 1 * MS, 0, 5); /* significant (5 > 3), recorded with its data */
    send_long(c, T0 + 2 * MS, 0, 1); /* not significant: not recorded, port variable a = 1 */
    send_long(c, T0 + 3 * MS, 1, 0);
    CHECK(sup_core_rule_active(c, "extract", "E") == 1);
    CHECK(*(const long *)sup_core_local(c, "extract", "la") == 5);
    CHECK(*(const long *)sup_core_in_port_value(c, 0) == 1);
    sup_core_destroy(c);
}

void test_tests_or_clauses_and_int_float_mix(void) {
    FakeWorld w;
    SupCore *c = start(&w, "extract");
    if (!c) { CHECK(0); return; }
    double x = 2.5; /* not > 2.5, not == 100 */
    sup_core_module_event(c, T0 + 1 * MS, "X", 2, -1, &x, sizeof x);
    CHECK(sup_core_rule_active(c, "extract", "F") == 0);
    x = 100.0; /* == 100 (int constant) through the second test clause */
    sup_core_module_event(c, T0 + 2 * MS, "X", 2, -1, &x, sizeof x);
    CHECK(sup_core_rule_active(c, "extract", "F") == 1);
    CHECK(*(const double *)sup_core_local(c, "extract", "lx") == 100.0);
    x = 0.0; /* ends F (postcondition), does not restart it (test fails) */
    sup_core_module_event(c, T0 + 3 * MS, "X", 2, -1, &x, sizeof x);
    CHECK(sup_core_rule_active(c, "extract", "F") == 0);
    x = 2.75;
    sup_core_module_event(c, T0 + 4 * MS, "X", 2, -1, &x, sizeof x);
    CHECK(sup_core_rule_active(c, "extract", "F") == 1);
    CHECK(*(const double *)sup_core_local(c, "extract", "lx") == 2.75);
    sup_core_destroy(c);
}

void test_duration_event(void) {
    FakeWorld w;
    SupCore *c = start(&w, "duration");
    if (!c) { CHECK(0); return; }
    int64_t d = 0;
    CHECK(sup_core_next_deadline(c, &d) == 1 && d == T0 + 5 * MS);
    send_long(c, T0 + 2 * MS, 1, 0); /* ends D3 before its duration: D4 never starts */
    sup_core_advance(c, T0 + 5 * MS - 1);
    CHECK(sup_core_rule_active(c, "duration", "D1") == 1);
    CHECK(sup_core_rule_active(c, "duration", "D2") == 0);
    sup_core_advance(c, T0 + 20 * MS);
    CHECK(sup_core_rule_active(c, "duration", "D1") == 0);
    CHECK(sup_core_rule_active(c, "duration", "D2") == 1);
    CHECK(sup_core_rule_active(c, "duration", "D4") == 0);
    CHECK(sup_core_rule_active(c, "duration", "N") == 1);
    static const char *const rules_only[] = {"rule ", "notify", NULL};
    check_log_filtered(&LOG, rules_only,
                       (const char *const[]){"rule duration.S active", "rule duration.D1 active",
                                             "rule duration.D3 active", "rule duration.D3 inactive",
                                             /* one duration event: D1's post, then D2's pre */
                                             "rule duration.D1 inactive", "rule duration.D2 active",
                                             /* then the queued endof(D1) */
                                             "rule duration.N active", "notify :0 100", NULL},
                       __FILE__, __LINE__);
    sup_core_destroy(c);
}

void test_stop_undoes_active_rules_in_order(void) {
    FakeWorld w;
    SupCore *c = start(&w, "window");
    if (!c) { CHECK(0); return; }
    CHECK(sup_core_stop_function(c, T0 + 1, "window") == 0);
    CHECK_LOG(&LOG, "function window() started", "rule window.S active", "subscribe X:0 =* :0",
              "subscribe X:1 =* :1", "subscribe X:2 =* :2", "rule window.S inactive",
              "unsubscribe X:0 :0", "unsubscribe X:1 :1", "unsubscribe X:2 :2",
              "function window stopped");
    /* events after the stop are not subscribed any more */
    send_long(c, T0 + 2, 0, 1);
    CHECK(log_find(&LOG, "ignored: event X:0 (no active subscription)", 0) >= 0);
    CHECK(sup_core_stop_function(c, T0 + 3, "window") == -1);
    sup_core_destroy(c);
}

/* the binding's clock when it writes a trace line: 0.4 ms past the time the START was read */
static int64_t late_trace_clock(void *ctx) {
    (void)ctx;
    return 400000;
}

void test_elapsed_counts_from_the_started_line(void) {
    FakeWorld w;
    SupCore *c = make_tst(&w, late_trace_clock);
    if (!c) { CHECK(0); return; }
    /* read at 0, its `function window started` line written at 0.4 ms: elapsed=1ms is due at
       1.4 ms (the time the trace shows + 1 ms), not at 1 ms */
    CHECK(sup_core_start_function(c, 0, "window", NULL, 0) == 0);
    int64_t d = 0;
    CHECK(sup_core_next_deadline(c, &d) == 1 && d == 1400000);
    sup_core_advance(c, 1399999);
    CHECK(sup_core_rule_active(c, "window", "S") == 0);
    sup_core_advance(c, 1400000);
    CHECK(sup_core_rule_active(c, "window", "S") == 1);
    sup_core_destroy(c);
}

void test_invalid_tables_are_refused_with_a_message(void) {
    static const ContractEvent bad_ev[] = {{.kind = CONTRACT_EV_STARTED, .rule = 7}};
    static const ContractClause bad_cl[] = {{1, bad_ev}};
    static const ContractRule bad_rules[] = {{"BAD", {1, bad_cl}, 0, NULL, {0, NULL}}};
    static const ContractFunction bad_fn[] = {{"f", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, bad_rules}};
    ContractSupervisorVocabulary v = {CONTRACT_VOCABULARY_VERSION, "BAD", 1, 1, 1, 1, 0, NULL, 0,
                                      NULL, 1, bad_fn};
    char err[256] = "";
    CHECK(sup_core_create(&v, NULL, err, sizeof err) == NULL);
    CHECK(strstr(err, "BAD.f rule BAD") && strstr(err, "rule 7 out of range"));
    v.version = 99;
    CHECK(sup_core_create(&v, NULL, err, sizeof err) == NULL);
    CHECK(strstr(err, "version 99") != NULL);

    /* a string local initialised from a float constant */
    static const double k1 = 1.0;
    static const ContractVar loc[] = {{"s", &contract_type_string, 0, NULL}};
    static const ContractAssign init[] = {
        {0, 0, &contract_type_string, {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k1}}};
    static const ContractFunction fn2[] = {{"g", 0, NULL, 0, 1, loc, 256, 1, init, 0, NULL}};
    ContractSupervisorVocabulary v2 = {CONTRACT_VOCABULARY_VERSION, "BAD", 1, 1, 1, 1, 0, NULL, 0,
                                       NULL, 1, fn2};
    CHECK(sup_core_create(&v2, NULL, err, sizeof err) == NULL);
    CHECK(strstr(err, "BAD.g") && strstr(err, "a string cannot take a float"));
}
