/*
 * test_ord.c — the scheduler core on a virtual clock: precedence in every cycle (diamond
 * A -> B, A -> C, B -> D, C -> D), data flows connected with their periodicity, absolute
 * release times, deadline miss (ORD:0) with an inclusive deadline, overrun skip, conflict
 * refusal (ORD:1), two schemas with different periods, deactivation.
 */
#include <stdio.h>
#include <string.h>

#include "fake_world.h"

#define MS 1000000LL
#define US 1000LL

static TestLog LOG;

static const long k_gain = 4;
static const ContractVar dia_params[] = {{"gain", &contract_type_long, 0, &k_gain}};
static const ContractAssign dia_b_p1[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_PARAM, 0, 0, &contract_type_long, NULL}}};
static const ContractParamSetting dia_b_settings[] = {{1, &contract_type_long, 1, dia_b_p1, NULL}};
static const ContractSchemaModule dia_modules[] = {
    {"A", 0, NULL}, {"B", 1, dia_b_settings}, {"C", 0, NULL}, {"D", 0, NULL}};
static const ContractPrecedence dia_prec[] = {{0, 1}, {0, 2}, {1, 3}, {2, 3}};
static const ContractDataFlow dia_flows[] = {{"A", 0, "D", 0, 2}, {"B", 0, "D", 1, 1}};
static const ContractSchema DIA = {"DIA", CONTRACT_SCHEMA_PERIODIC, 10 * MS, 6 * MS,
                                   1, dia_params, sizeof(long), 4, dia_modules, 4, dia_prec,
                                   2, dia_flows, 0, NULL};
static const ContractSchemaModule oth_modules[] = {{"B", 0, NULL}, {"F", 0, NULL}};
static const ContractSchema OTH = {"OTH", CONTRACT_SCHEMA_PERIODIC, 10 * MS, 10 * MS,
                                   0, NULL, 0, 2, oth_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractSchemaModule fst_modules[] = {{"E", 0, NULL}};
static const ContractSchema FST = {"FST", CONTRACT_SCHEMA_PERIODIC, 3 * MS, 3 * MS,
                                   0, NULL, 0, 1, fst_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractSchemaModule slw_modules[] = {{"G", 0, NULL}};
static const ContractSchema SLW = {"SLW", CONTRACT_SCHEMA_PERIODIC, 200 * MS, 200 * MS,
                                   0, NULL, 0, 1, slw_modules, 0, NULL, 0, NULL, 0, NULL};
static const ContractSchema *const schemas[] = {&DIA, &OTH, &FST, &SLW};
static const ContractOrdModule modules[] = {{"A", 50, 0}, {"B", 50, 0}, {"C", 50, 0}, {"D", 50, 0},
                                            {"E", 60, 0}, {"F", 50, 0}, {"G", 50, 0}};
static const char *const sups[] = {"SUP"};
static const ContractOrdVocabulary VOC = {CONTRACT_VOCABULARY_VERSION, 7, modules, 4, schemas, 1, sups};

/* A core over a fresh fake world; `fact` (NULL: none) gets its typed facts. */
static OrdCore *make_with_facts(FakeWorld *w, void (*fact)(void *ctx, int64_t t, const OrdFact *f)) {
    log_clear(&LOG);
    memset(w, 0, sizeof *w);
    w->log = &LOG;
    OrdIo io = fake_ord_io(w);
    io.fact = fact;
    char err[256] = "";
    OrdCore *c = ord_core_create(&VOC, &io, err, sizeof err);
    if (!c) fprintf(stderr, "  %s\n", err);
    return c;
}

static OrdCore *make(FakeWorld *w) { return make_with_facts(w, NULL); }

static const char *const SCHED[] = {"release", "deadline", "overrun", "missed", NULL};

/* runs one diamond cycle at tick: A 1ms, then B and C in parallel (C ends first), D after both */
static void diamond_cycle(OrdCore *c, int64_t tick, int64_t d_end) {
    ord_core_module_finished(c, tick + 1 * MS, "A");
    ord_core_module_finished(c, tick + 2 * MS, "C");
    ord_core_module_finished(c, tick + 3 * MS, "B");
    ord_core_module_finished(c, tick + d_end, "D");
}

void test_ord_precedence_every_cycle(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    long gain = 9;
    CHECK(ord_core_activate(c, 0, "DIA", &gain, sizeof gain, "SUP", 1) == 0);
    for (int k = 0; k < 5; k++) diamond_cycle(c, k * 10 * MS, 4 * MS);
    ord_core_advance(c, 49 * MS);
    static char exp[64][LOG_LINE];
    const char *expp[65];
    int n = 0;
    for (int k = 0; k < 5; k++) {
        long base = k * 10000;
        snprintf(exp[n++], LOG_LINE, "%ldus release A (DIA)", base);
        snprintf(exp[n++], LOG_LINE, "%ldus release B (DIA)", base + 1000);
        snprintf(exp[n++], LOG_LINE, "%ldus release C (DIA)", base + 1000);
        snprintf(exp[n++], LOG_LINE, "%ldus release D (DIA)", base + 3000);
    }
    for (int i = 0; i < n; i++) expp[i] = exp[i];
    expp[n] = NULL;
    check_log_filtered(&LOG, SCHED, expp, __FILE__, __LINE__);
    /* parameterised and connected before the first release, with periodicities */
    CHECK_LOG(&LOG, "setparam B:1 <8 bytes>", "connect A:0 -> D:0 * 2", "connect B:0 -> D:1 * 1",
              "0us activate DIA (activation #1 from SUP)", "ack SUP #1 done", "0us release A (DIA)", "1000us release B (DIA)",
              "1000us release C (DIA)", "3000us release D (DIA)", "10000us release A (DIA)",
              "11000us release B (DIA)", "11000us release C (DIA)", "13000us release D (DIA)",
              "20000us release A (DIA)", "21000us release B (DIA)", "21000us release C (DIA)",
              "23000us release D (DIA)", "30000us release A (DIA)", "31000us release B (DIA)",
              "31000us release C (DIA)", "33000us release D (DIA)", "40000us release A (DIA)",
              "41000us release B (DIA)", "41000us release C (DIA)", "43000us release D (DIA)");
    OrdSchemaStats st;
    CHECK(ord_core_stats(c, "DIA", &st) == 0);
    CHECK(st.cycles == 5 && st.completed == 5 && st.deadline_misses == 0 && st.overruns == 0);
    CHECK(st.max_response_ns == 4 * MS);
    ord_core_destroy(c);
}

void test_ord_deadline_miss_is_inclusive_and_emits_ord0(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "DIA", NULL, 0, "SUP", 1);
    diamond_cycle(c, 0, 6 * MS);          /* finishes exactly at tick + CRITICAL_DELAY: in time */
    diamond_cycle(c, 10 * MS, 6 * MS + 1); /* 1 ns late: ORD:0 at tick + 6ms */
    ord_core_advance(c, 19 * MS);
    CHECK(log_find(&LOG, "6000us deadline miss: DIA cycle 0 (ORD:0)", 0) < 0);
    int i = log_find(&LOG, "16000us deadline miss: DIA cycle 1 (ORD:0)", 0);
    CHECK(i >= 0);
    CHECK(i >= 0 && log_find(&LOG, "emit ORD:0 DIA", i) == i + 1);
    OrdSchemaStats st;
    ord_core_stats(c, "DIA", &st);
    CHECK(st.deadline_misses == 1 && st.completed == 2);
    ord_core_destroy(c);
}

/* A slow set-up: DIA's parameter and two connections take 2 ms each (a loaded machine, ORD at a nice
   level), 6 ms in all, DIA's whole CRITICAL_DELAY. Tick 0 is when the set-up is done, so that cycle 0
   has its 6 ms: finished 4 ms after its release, it misses nothing (with tick 0 at the request, it
   missed at 6 ms, before its modules had any time: the field test's spurious ORD:0). */
void test_ord_slow_setup_not_counted_against_cycle_0(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_destroy(c);
    OrdIo io = fake_ord_io(&w);
    io.setup_done_at = fake_setup_done_at;
    char err[256] = "";
    c = ord_core_create(&VOC, &io, err, sizeof err);
    if (!c) { CHECK(0); return; }
    ord_core_set_skip_late_ticks(c, 1); /* as the real ORD runs */
    w.ord_clock = 0;
    w.ord_request_ns = 2 * MS;
    long gain = 9;
    CHECK(ord_core_activate(c, 0, "DIA", &gain, sizeof gain, "SUP", 1) == 0);
    CHECK(w.ord_clock == 6 * MS);
    diamond_cycle(c, 6 * MS, 4 * MS); /* cycle 0 released at 6 ms, finished at 10 ms */
    diamond_cycle(c, 16 * MS, 4 * MS); /* cycle 1 at tick 0 + PERIOD */
    ord_core_advance(c, 25 * MS);
    CHECK_LOG(&LOG, "setparam B:1 <8 bytes>", "connect A:0 -> D:0 * 2", "connect B:0 -> D:1 * 1",
              "6000us activate DIA (activation #1 from SUP)", "ack SUP #1 done", "6000us release A (DIA)",
              "7000us release B (DIA)", "7000us release C (DIA)", "9000us release D (DIA)", "16000us release A (DIA)",
              "17000us release B (DIA)", "17000us release C (DIA)", "19000us release D (DIA)");
    CHECK(log_find(&LOG, "emit ORD:0 DIA", 0) < 0);
    OrdSchemaStats st;
    CHECK(ord_core_stats(c, "DIA", &st) == 0);
    CHECK(st.cycles == 2 && st.completed == 2 && st.deadline_misses == 0 && st.late_releases == 0);
    CHECK(st.max_response_ns == 4 * MS);
    ord_core_destroy(c);
}

/* one diamond cycle released at `at` whose modules take 800 us in all (A, C, B, D 200 us apart) */
static void diamond_fast_cycle(OrdCore *c, int64_t at) {
    ord_core_module_finished(c, at + 200 * US, "A");
    ord_core_module_finished(c, at + 400 * US, "C");
    ord_core_module_finished(c, at + 600 * US, "B");
    ord_core_module_finished(c, at + 800 * US, "D");
}

/* Real time: ORD itself woke 7 ms after DIA's tick of 10 ms (a loaded machine), past its 6 ms
   CRITICAL_DELAY but before the next tick, and released the cycle then: its modules had no time, the
   miss is ORD's. No ORD:0 (a supervisor's rule on it would take out a schema whose modules did nothing
   wrong), its own line instead; a cycle released late but with time left still misses with ORD:0. */
void test_ord_cycle_released_past_its_critical_delay_is_ords_miss(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_set_skip_late_ticks(c, 1);
    ord_core_activate(c, 0, "DIA", NULL, 0, "SUP", 1);
    diamond_fast_cycle(c, 0);
    ord_core_advance(c, 17 * MS); /* the 10 ms tick, ORD running at 17 ms: 7 ms late */
    diamond_fast_cycle(c, 17 * MS);
    ord_core_advance(c, 26 * MS); /* the 20 ms tick at 26 ms: 6 ms late, exactly its delay */
    diamond_fast_cycle(c, 26 * MS);
    ord_core_advance(c, 35 * MS); /* the 30 ms tick at 35 ms: 5 ms late, 1 ms left */
    diamond_cycle(c, 35 * MS, 4 * MS); /* ...which its modules overrun: their miss */
    ord_core_advance(c, 39 * MS);
    CHECK(log_find(&LOG, "16000us late release: DIA cycle 1 released 7000 us after its tick, past CRITICAL_DELAY 6000 us (ORD late, no ORD:0)", 0) >= 0);
    CHECK(log_find(&LOG, "26000us late release: DIA cycle 2 released 6000 us after its tick, past CRITICAL_DELAY 6000 us (ORD late, no ORD:0)", 0) >= 0);
    CHECK(log_find(&LOG, "deadline miss: DIA cycle 1", 0) < 0 && log_find(&LOG, "deadline miss: DIA cycle 2", 0) < 0);
    int i = log_find(&LOG, "36000us deadline miss: DIA cycle 3 (ORD:0)", 0);
    CHECK(i >= 0 && log_find(&LOG, "emit ORD:0 DIA", 0) == i + 1);
    CHECK(log_find(&LOG, "emit ORD:0 DIA", i + 2) < 0);
    OrdSchemaStats st;
    CHECK(ord_core_stats(c, "DIA", &st) == 0);
    CHECK(st.cycles == 4 && st.completed == 4 && st.deadline_misses == 1 && st.late_releases == 2);
    ord_core_destroy(c);
}

void test_ord_overrun_skips_release(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "DIA", NULL, 0, "SUP", 1);
    diamond_cycle(c, 0, 12 * MS); /* still running at the 10ms tick */
    ord_core_advance(c, 20 * MS);
    check_log_filtered(&LOG, SCHED,
                       (const char *const[]){"0us release A (DIA)", "1000us release B (DIA)",
                                             "1000us release C (DIA)", "3000us release D (DIA)",
                                             "6000us deadline miss: DIA cycle 0 (ORD:0)",
                                             "10000us overrun: DIA cycle still running (D), release skipped",
                                             "20000us release A (DIA)", NULL},
                       __FILE__, __LINE__);
    OrdSchemaStats st;
    ord_core_stats(c, "DIA", &st);
    CHECK(st.overruns == 1 && st.cycles == 2 && st.completed == 1);
    ord_core_destroy(c);
}

void test_ord_conflict_refused_with_ord1(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    CHECK(ord_core_activate(c, 0, "DIA", NULL, 0, "SUP", 1) == 0);
    CHECK(ord_core_activate(c, 1 * MS, "OTH", NULL, 0, "SUP", 2) == -1);     /* shares B */
    CHECK(ord_core_activate(c, 1 * MS, "DIA", NULL, 0, "GLB", 3) == -1);     /* itself */
    CHECK(ord_core_deactivate(c, 2 * MS, "DIA", "GLB", 3) == -1); /* the refused one's undo */
    CHECK(ord_core_schema_active(c, "DIA") && !ord_core_schema_active(c, "OTH"));
    CHECK(log_find(&LOG, "emit ORD:1 OTH", 0) >= 0);
    CHECK(log_find(&LOG, "ack SUP #2 refused", 0) >= 0);
    CHECK(log_find(&LOG, "emit ORD:1 DIA", 0) >= 0);
    CHECK(ord_core_activate(c, 3 * MS, "NOPE", NULL, 0, "SUP", 4) == -1);
    CHECK(ord_core_deactivate(c, 4 * MS, "DIA", "SUP", 1) == 0);
    CHECK(ord_core_activate(c, 5 * MS, "OTH", NULL, 0, "SUP", 5) == 0);      /* now free */
    ord_core_destroy(c);
}

void test_ord_two_periods_and_deactivation(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "DIA", NULL, 0, "SUP", 1);
    ord_core_activate(c, 0, "FST", NULL, 0, "SUP", 2);
    for (int ms = 0; ms <= 40; ms++) { /* scripted in time order, 1 ms steps */
        int64_t t = ms * MS;
        if (ms < 14) {
            static const char *const order[] = {NULL, "A", "C", "B", "D"};
            if (ms % 10 >= 1 && ms % 10 <= 4) ord_core_module_finished(c, t, order[ms % 10]);
        }
        if (ms % 3 == 1) ord_core_module_finished(c, t, "E");
        if (ms == 14) CHECK(ord_core_deactivate(c, t + 500000, "DIA", "SUP", 1) == 0);
        ord_core_advance(c, t);
    }
    static const char *const rel[] = {"release", NULL};
    int e = 0, dia = 0, last_dia = -1;
    for (int i = 0; i < LOG.n; i++) {
        if (strstr(LOG.lines[i], "release E")) e++;
        if (strstr(LOG.lines[i], "release A (DIA)")) { dia++; last_dia = i; }
    }
    (void)rel;
    CHECK(e == 14);  /* 0, 3, ..., 39 ms */
    CHECK(dia == 2); /* 0 and 10 ms, nothing after the deactivation */
    CHECK(last_dia >= 0 && strcmp(LOG.lines[last_dia], "10000us release A (DIA)") == 0);
    CHECK(log_find(&LOG, "disconnect A:0 -> D:0", 0) >= 0);
    /* the activate and deactivate lines name the activation they serve, as SUP numbered it */
    CHECK(log_find(&LOG, "0us activate FST (activation #2 from SUP)", 0) >= 0);
    CHECK(log_find(&LOG, "14500us deactivate DIA (activation #1 from SUP)", 0) >= 0);
    CHECK(log_find(&LOG, "3000us release E (FST)", 0) >= 0);
    CHECK(log_find(&LOG, "39000us release E (FST)", 0) >= 0);
    int64_t d;
    CHECK(ord_core_next_deadline(c, &d) == 1 && d == 42 * MS);
    ord_core_destroy(c);
}

void test_ord_cyclic_graph_refused(void) {
    static const ContractSchemaModule m2[] = {{"A", 0, NULL}, {"B", 0, NULL}};
    static const ContractPrecedence cyc[] = {{0, 1}, {1, 0}};
    static const ContractSchema CYC = {"CYC", CONTRACT_SCHEMA_PERIODIC, MS, MS, 0, NULL, 0, 2, m2,
                                       2, cyc, 0, NULL, 0, NULL};
    static const ContractSchema *const s[] = {&CYC};
    ContractOrdVocabulary v = {CONTRACT_VOCABULARY_VERSION, 0, NULL, 1, s, 0, NULL};
    char err[256] = "";
    CHECK(ord_core_create(&v, NULL, err, sizeof err) == NULL);
    CHECK(strstr(err, "CYC") && strstr(err, "cycle"));
}

void test_ord_schema_module_not_in_configuration_refused(void) {
    static const ContractSchema *const s[] = {&DIA};
    static const ContractOrdModule only_a[] = {{"A", 50, 0}};
    ContractOrdVocabulary v = {CONTRACT_VOCABULARY_VERSION, 1, only_a, 1, s, 0, NULL};
    char err[256] = "";
    CHECK(ord_core_create(&v, NULL, err, sizeof err) == NULL);
    CHECK(strstr(err, "schema DIA uses module B, which the scheduler configuration does not list") != NULL);
}

/* Issue 4 (seen in the mobile robot under load): the schema is deactivated while B and C of
   its cycle still run, and activated again 1 ms later. The new activation's first cycle must
   not release any module while a release of the old one is outstanding (the module would run
   the old START and then the new one: twice in the new cycle), and the old releases' acks
   must not complete the new cycle: acks are matched to their release by id. */
void test_ord_late_ack_of_deactivated_cycle_does_not_complete_new_one(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "DIA", NULL, 0, "SUP", 1);
    uint32_t a0 = fake_last_release(&w, "A");
    ord_core_release_finished(c, 1 * MS, "A", a0);
    uint32_t b0 = fake_last_release(&w, "B"), c0 = fake_last_release(&w, "C");
    CHECK(a0 && b0 && c0 && b0 != c0);
    CHECK(ord_core_deactivate(c, 2 * MS, "DIA", "SUP", 1) == 0);
    CHECK(ord_core_activate(c, 3 * MS, "DIA", NULL, 0, "SUP", 2) == 0); /* cycle held: B, C run */
    ord_core_release_finished(c, 4 * MS, "B", b0);   /* old B: frees B, C still runs */
    ord_core_release_finished(c, 4 * MS, "B", b0);   /* duplicate: matches nothing */
    ord_core_release_finished(c, 5 * MS, "C", c0);   /* old C: the held cycle releases A */
    uint32_t a1 = fake_last_release(&w, "A");
    CHECK(a1 != a0);
    ord_core_release_finished(c, 6 * MS, "A", a0);   /* a stale id of A: ignored */
    ord_core_release_finished(c, 7 * MS, "A", a1);
    uint32_t b1 = fake_last_release(&w, "B"), c1 = fake_last_release(&w, "C");
    CHECK(b1 != b0 && c1 != c0);
    ord_core_release_finished(c, 8 * MS, "C", c0);   /* the old C again: must not finish C now */
    ord_core_release_finished(c, 8 * MS, "B", b1);
    ord_core_advance(c, 8 * MS + 500000);
    CHECK(log_find(&LOG, "8000us release D (DIA)", 0) < 0); /* D waits for the new C */
    ord_core_release_finished(c, 9 * MS, "C", c1);
    ord_core_release_finished(c, 10 * MS, "D", fake_last_release(&w, "D"));
    ord_core_advance(c, 12 * MS); /* the next tick is 13 ms (activation 3 ms + 10 ms) */
    check_log_filtered(&LOG, (const char *const[]){"release", "held", "resumed", "late ack", "ignored", NULL},
                       (const char *const[]){
                           "0us release A (DIA)", "1000us release B (DIA)", "1000us release C (DIA)",
                           "3000us cycle of DIA held: B still runs a release of an earlier activation",
                           "4000us late ack: B finished release #2 of an earlier cycle of DIA (not counted)",
                           "4000us ignored: B finished outside a cycle (release #2 is not outstanding)",
                           "5000us late ack: C finished release #3 of an earlier cycle of DIA (not counted)",
                           "5000us cycle of DIA resumed", "5000us release A (DIA)",
                           "6000us ignored: A finished outside a cycle (release #1 is not outstanding)",
                           "7000us release B (DIA)", "7000us release C (DIA)",
                           "8000us ignored: C finished outside a cycle (release #3 is not outstanding)",
                           "9000us release D (DIA)", NULL},
                       __FILE__, __LINE__);
    /* every module exactly once in the new activation's first cycle */
    for (int i = 0; i < LOG.n; i++) CHECK(strstr(LOG.lines[i], "overrun") == NULL);
    OrdSchemaStats st;
    ord_core_stats(c, "DIA", &st);
    CHECK(st.cycles == 2 && st.completed == 1 && st.held_cycles == 1 && st.late_acks == 2);
    CHECK(st.max_response_ns == 7 * MS); /* tick 3 ms -> D finished at 10 ms */
    ord_core_destroy(c);
}

/* Within one activation: a duplicate ack of the previous cycle's release of E must not
   complete the next cycle's E (the cycle stays open: overrun at the next tick). */
void test_ord_ack_matched_to_its_cycle_by_release_id(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "FST", NULL, 0, "SUP", 1);
    uint32_t e0 = fake_last_release(&w, "E");
    ord_core_release_finished(c, 1 * MS, "E", e0);
    ord_core_advance(c, 3 * MS);
    uint32_t e1 = fake_last_release(&w, "E");
    CHECK(e1 != e0);
    ord_core_release_finished(c, 4 * MS, "E", e0); /* late duplicate of cycle 0 */
    ord_core_release_finished(c, 4 * MS, "F", 99); /* unknown module and id */
    ord_core_advance(c, 6 * MS);
    ord_core_release_finished(c, 7 * MS, "E", e1);
    ord_core_advance(c, 9 * MS);
    check_log_filtered(&LOG, (const char *const[]){"release", "overrun", "ignored", "deadline", NULL},
                       (const char *const[]){
                           "0us release E (FST)", "3000us release E (FST)",
                           "4000us ignored: E finished outside a cycle (release #1 is not outstanding)",
                           "4000us ignored: F finished outside a cycle (release #99 is not outstanding)",
                           "6000us deadline miss: FST cycle 1 (ORD:0)",
                           "6000us overrun: FST cycle still running (E), release skipped",
                           "9000us release E (FST)", NULL},
                       __FILE__, __LINE__);
    OrdSchemaStats st;
    ord_core_stats(c, "FST", &st);
    CHECK(st.cycles == 3 && st.completed == 2 && st.overruns == 1 && st.late_acks == 0);
    ord_core_destroy(c);
}

/* A held cycle waits at most 1 s: E, released before the deactivation, never answers
   (stopped by someone else, or crashed). Until then every tick is an overrun; at the first tick
   1 s after the held cycle's, ORD forgets that release and the cycle starts afresh; the old ack,
   if it comes at last, completes nothing. E's release, 1 s old before that, is reported stuck. */
void test_ord_held_cycle_gives_up_after_1s(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "FST", NULL, 0, "SUP", 1);
    uint32_t e0 = fake_last_release(&w, "E");
    CHECK(ord_core_deactivate(c, 1 * MS, "FST", "SUP", 1) == 0);
    CHECK(ord_core_activate(c, 2 * MS, "FST", NULL, 0, "SUP", 2) == 0);
    ord_core_advance(c, 1001 * MS);                /* ticks 5, 8, ..., 1001 ms: still held */
    CHECK(fake_last_release(&w, "E") == e0);
    ord_core_advance(c, 1002 * MS);                /* tick 1004 ms >= 2 ms + 1 s: not yet */
    ord_core_advance(c, 1004 * MS);
    uint32_t e1 = fake_last_release(&w, "E");
    CHECK(e1 != e0);
    ord_core_release_finished(c, 1005 * MS, "E", e0);
    ord_core_release_finished(c, 1005 * MS, "E", e1);
    ord_core_advance(c, 1007 * MS);
    check_log_filtered(&LOG, (const char *const[]){"release E", "held", "stuck", "gave up", "ignored", "late", "overrun", NULL},
                       (const char *const[]){
                           "0us release E (FST)",
                           "2000us cycle of FST held: E still runs a release of an earlier activation",
                           "5000us overrun: FST cycle still running (E), release skipped",
                           "1000000us stuck: E has not finished release #1 after 333 periods (its schema's new cycle "
                           "waits for it): does its exec region set *stateindex = -1? (FST)",
                           "stuck E #1 (FST) after 333 periods",
                           /* the held cycle's count, then the restart's own: 333 + 1, as counted */
                           "1004000us overrun: FST cycle ended after 333 skipped releases",
                           "1004000us overrun: FST cycle still held, restarted",
                           "1004000us gave up waiting for E release #1 (no ack within 1 s, FST)",
                           "1004000us release E (FST)",
                           "1005000us ignored: E finished outside a cycle (release #1 is not outstanding)",
                           "1007000us release E (FST)", NULL},
                       __FILE__, __LINE__);
    OrdSchemaStats st;
    ord_core_stats(c, "FST", &st);
    CHECK(st.overruns == 334 && st.held_cycles == 1 && st.completed == 1); /* 5..1001 ms: 333 */
    ord_core_destroy(c);
}

/* A cycle deactivated while it overran says how many releases it skipped, as one that finishes
   does: a reader of the trace counts ORD's overruns from its lines (`contract trace`, the Monitor,
   Save as scenario), and ORD traces only a cycle's first skipped release. */
void test_ord_deactivated_overrunning_cycle_tells_its_skipped_releases(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "SLW", NULL, 0, "SUP", 1);
    ord_core_advance(c, 700 * MS);                 /* ticks 200, 400, 600 ms skipped */
    CHECK(ord_core_deactivate(c, 700 * MS, "SLW", "SUP", 1) == 0);
    ord_core_release_finished(c, 750 * MS, "G", fake_last_release(&w, "G"));
    ord_core_activate(c, 800 * MS, "SLW", NULL, 0, "SUP", 2);
    ord_core_advance(c, 1100 * MS);                 /* one skipped (1000 ms): no count line */
    CHECK(ord_core_deactivate(c, 1100 * MS, "SLW", "SUP", 2) == 0);
    check_log_filtered(&LOG, (const char *const[]){"overrun", "activate", NULL},
                       (const char *const[]){
                           "0us activate SLW (activation #1 from SUP)",
                           "200000us overrun: SLW cycle still running (G), release skipped",
                           "700000us overrun: SLW cycle ended after 3 skipped releases",
                           "700000us deactivate SLW (activation #1 from SUP)",
                           "800000us activate SLW (activation #2 from SUP)",
                           "1000000us overrun: SLW cycle still running (G), release skipped",
                           "1100000us deactivate SLW (activation #2 from SUP)", NULL},
                       __FILE__, __LINE__);
    OrdSchemaStats st;
    ord_core_stats(c, "SLW", &st);
    CHECK(st.overruns == 4);
    /* ORD stopped with a cycle overrunning (the end of a run): its count too */
    ord_core_activate(c, 1200 * MS, "SLW", NULL, 0, "SUP", 3);
    ord_core_advance(c, 1900 * MS);                 /* held (G still runs #2's release): 1400, 1600, 1800 ms skipped */
    ord_core_stop(c);
    CHECK(log_find(&LOG, "1900000us overrun: SLW cycle ended after 3 skipped releases", 0) >= 0);
    ord_core_stats(c, "SLW", &st);
    CHECK(st.overruns == 7);
    ord_core_destroy(c);
}

/* activation ids are numbered by each supervisor: SUP's #1 and GLB's refused #1 are two
   activations, and GLB's undo must not deactivate SUP's schema */
void test_ord_undo_of_another_supervisors_activation_with_the_same_id(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    CHECK(ord_core_activate(c, 0, "DIA", NULL, 0, "SUP", 1) == 0);
    CHECK(ord_core_activate(c, 1 * MS, "DIA", NULL, 0, "GLB", 1) == -1); /* refused: ORD:1 */
    CHECK(ord_core_deactivate(c, 2 * MS, "DIA", "GLB", 1) == -1);        /* its undo */
    CHECK(ord_core_schema_active(c, "DIA"));
    CHECK(ord_core_deactivate(c, 3 * MS, "DIA", "SUP", 1) == 0);
    CHECK(!ord_core_schema_active(c, "DIA"));
    ord_core_destroy(c);
}

/* A synchronous module whose exec region never sets *stateindex = -1 never finishes its
   release (issue 18): after ORD_STUCK_PERIODS periods ORD names it once, with the likely cause,
   instead of an overrun line at every tick; the cycle's skipped ticks are still counted, and if
   the module ends at last, the schema goes on. */
void test_ord_module_that_never_finishes_is_reported_once(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "SLW", NULL, 0, "SUP", 1);
    uint32_t g = fake_last_release(&w, "G");
    ord_core_advance(c, 5000 * MS);
    ord_core_release_finished(c, 5100 * MS, "G", g);
    ord_core_advance(c, 5200 * MS);
    char stuck[LOG_LINE], called[LOG_LINE], last[LOG_LINE];
    snprintf(stuck, sizeof stuck, "2000000us stuck: G has not finished release #%u after 10 periods: "
             "does its exec region set *stateindex = -1? (SLW)", g);
    snprintf(called, sizeof called, "stuck G #%u (SLW) after 10 periods", g);
    snprintf(last, sizeof last, "5100000us G finished release #%u at last (reported stuck, SLW)", g);
    check_log_filtered(&LOG, (const char *const[]){"release G", "overrun", "stuck", NULL},
                       (const char *const[]){
                           "0us release G (SLW)",
                           "200000us overrun: SLW cycle still running (G), release skipped",
                           stuck, called, last,
                           "5100000us overrun: SLW cycle ended after 25 skipped releases",
                           "5200000us release G (SLW)", NULL},
                       __FILE__, __LINE__);
    OrdSchemaStats st;
    ord_core_stats(c, "SLW", &st);
    CHECK(st.overruns == 25 && st.stuck_releases == 1 && st.completed == 1 && st.cycles == 2);
    ord_core_destroy(c);
}

/* A supervisor that deactivates the schema at each deadline miss and activates it again (field
   test: a gripper stuck in its exec region, a cell supervisor recovering on ORD:0): no cycle of
   an activation ever runs 10 periods, every new one is held for the stuck module. Its release is
   still reported stuck once, 10 periods after it was sent, and so when nothing is active at all
   (ORD's next deadline is that due time). */
void test_ord_stuck_release_outliving_its_activation_is_reported(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "SLW", NULL, 0, "SUP", 1);
    uint32_t g = fake_last_release(&w, "G");
    uint32_t id = 1;
    for (int64_t t = 201 * MS; t < 2600 * MS; t += 201 * MS) {
        CHECK(ord_core_deactivate(c, t, "SLW", "SUP", id) == 0);
        CHECK(ord_core_activate(c, t + 1 * MS, "SLW", NULL, 0, "SUP", ++id) == 0);
    }
    char stuck[LOG_LINE], called[LOG_LINE];
    snprintf(stuck, sizeof stuck, "2000000us stuck: G has not finished release #%u after 10 periods (its "
             "schema's new cycle waits for it): does its exec region set *stateindex = -1? (SLW)", g);
    snprintf(called, sizeof called, "stuck G #%u (SLW) after 10 periods", g);
    check_log_filtered(&LOG, (const char *const[]){"stuck", NULL}, (const char *const[]){stuck, called, NULL},
                       __FILE__, __LINE__);
    CHECK(fake_last_release(&w, "G") == g); /* never released again: every cycle was held */
    OrdSchemaStats st;
    ord_core_stats(c, "SLW", &st);
    CHECK(st.stuck_releases == 1 && st.held_cycles >= 10 && st.deadline_misses >= 10);
    ord_core_destroy(c);

    /* deactivated, nothing active: the due time wakes ORD; the late ack says it was reported */
    c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "SLW", NULL, 0, "SUP", 1);
    g = fake_last_release(&w, "G");
    ord_core_deactivate(c, 10 * MS, "SLW", "SUP", 1);
    int64_t next = 0;
    CHECK(ord_core_next_deadline(c, &next) == 1 && next == 2000 * MS);
    ord_core_advance(c, 2500 * MS);
    ord_core_release_finished(c, 3000 * MS, "G", g);
    CHECK(ord_core_next_deadline(c, &next) == 0);
    snprintf(stuck, sizeof stuck, "2000000us stuck: G has not finished release #%u after 10 periods (of a "
             "deactivated activation): does its exec region set *stateindex = -1? (SLW)", g);
    char late[LOG_LINE];
    snprintf(late, sizeof late, "3000000us late ack: G finished release #%u of an earlier cycle of SLW (not "
             "counted, reported stuck)", g);
    check_log_filtered(&LOG, (const char *const[]){"stuck", "late ack", NULL},
                       (const char *const[]){stuck, called, late, NULL}, __FILE__, __LINE__);
    ord_core_destroy(c);
}

/* A module that is no longer running (crashed, killed: OrdIo.module_gone) never finishes its
   release whatever its exec region does: its stuck report says so instead of the advice to set
   *stateindex = -1, in the trace line (ORD's CSV record `stuck: ...`, which contract trace and the
   IDE's Monitor show) as in the sentence of the stuck call (ORD's stderr line): one wording. A
   module running on still gets the advice. */
void test_ord_stuck_report_of_a_module_no_longer_running(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    fake_set_gone(&w, "G");
    ord_core_activate(c, 0, "SLW", NULL, 0, "SUP", 1);
    ord_core_activate(c, 0, "FST", NULL, 0, "SUP", 2);
    uint32_t g = fake_last_release(&w, "G"), e = fake_last_release(&w, "E");
    ord_core_deactivate(c, 10 * MS, "SLW", "SUP", 1);
    ord_core_advance(c, 2500 * MS);
    char said[LOG_LINE - 32], stuck[LOG_LINE], advice[LOG_LINE];
    snprintf(said, sizeof said, "G has not finished release #%u after 10 periods (of a deactivated activation): "
             "it is no longer running (it crashed or was killed)", g);
    snprintf(stuck, sizeof stuck, "2000000us stuck: %s (SLW)", said);
    snprintf(advice, sizeof advice, "1002000us stuck: E has not finished release #%u after 334 periods: does its "
             "exec region set *stateindex = -1? (FST)", e);
    check_log_filtered(&LOG, (const char *const[]){"1002000us stuck", "2000000us stuck", NULL},
                       (const char *const[]){advice, stuck, NULL}, __FILE__, __LINE__);
    if (strcmp(w.stuck_message, said) != 0) fprintf(stderr, "  the stuck call's sentence: %s\n", w.stuck_message);
    CHECK(strcmp(w.stuck_message, said) == 0);
    ord_core_destroy(c);
}

/* What ORD saw of the module tells the cause of a stuck release (ord_stuck_cause.h): it looks at
   the module half way to the report (1 s) and at it (2 s). A module that ran 97% of that second,
   or more CPU time than its 200 ms period, is asked whether its exec region loops; one that ran 3% while ready to run 90% of it is
   starved; one that ran 3% and waited for a CPU 2% slept: it waits, whatever its state at the
   last look. One look at each point, not one per tick. */
static void stuck_writing(char state, int64_t cpu_step_ns, int64_t wait_step_ns, const char *wchan, int64_t written_step,
                          const char *cause) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    fake_set_activity(&w, "G", state, cpu_step_ns, wait_step_ns);
    fake_set_waiting_in(&w, "G", wchan);
    fake_set_written(&w, "G", written_step);
    ord_core_activate(c, 0, "SLW", NULL, 0, "SUP", 1);
    uint32_t g = fake_last_release(&w, "G");
    ord_core_advance(c, 1900 * MS);
    CHECK(fake_activity_looks(&w, "G") == 1);
    ord_core_advance(c, 3000 * MS);
    char said[400], stuck[LOG_LINE]; /* the log keeps LOG_LINE - 1 characters of a line, as stuck */
    snprintf(said, sizeof said, "G has not finished release #%u after 10 periods: %s", g, cause);
    char full[450];
    snprintf(full, sizeof full, "2000000us stuck: %s (SLW)", said);
    snprintf(stuck, sizeof stuck, "%.*s", (int)sizeof stuck - 1, full);
    check_log_filtered(&LOG, (const char *const[]){"stuck:", NULL}, (const char *const[]){stuck, NULL}, __FILE__,
                       __LINE__);
    if (strcmp(w.stuck_message, said) != 0) fprintf(stderr, "  the stuck call's sentence: %s\n", w.stuck_message);
    CHECK(strcmp(w.stuck_message, said) == 0);
    CHECK(fake_activity_looks(&w, "G") == 2);
    ord_core_destroy(c);
}

static void stuck_waiting_in(char state, int64_t cpu_step_ns, int64_t wait_step_ns, const char *wchan, const char *cause) {
    stuck_writing(state, cpu_step_ns, wait_step_ns, wchan, -1, cause);
}

static void stuck_with_activity(char state, int64_t cpu_step_ns, int64_t wait_step_ns, const char *cause) {
    stuck_waiting_in(state, cpu_step_ns, wait_step_ns, "", cause);
}

#define LOOPS                                                                                                  \
    "does its exec region loop, or never set *stateindex = -1? (its thread got 97% of a CPU in the last 1.0 s, " \
    "more than a period needs; a loaded machine gives it less)"
#define LOOPS_HELD                                                                                             \
    "does its exec region loop, or never set *stateindex = -1? (its thread got 30% of a CPU in the last 1.0 s, " \
    "more than a period needs; a loaded machine gives it less)"
#define WRITING                                                                                                \
    "it is blocked writing its output: the pipe is full (it prints faster than the run's output is read): does " \
    "its exec region print too much?"
#define STARVED                                                                                                   \
    "it wanted the CPU but got only 3% of it in the last 1.0 s: do processes at real-time priority or an "      \
    "overloaded machine starve it, or does its exec region loop?"
#define WAITS "it is waiting, not running (a sleep, a read, a lock or a send to a full mailbox in its exec region?)"

void test_ord_stuck_report_says_what_the_module_was_doing(void) {
    stuck_with_activity('R', 970 * MS, 20 * MS, LOOPS);
    stuck_with_activity('S', 970 * MS, -1, LOOPS); /* asleep at the last look, but it ran */
    /* held under half a CPU (a loaded machine, the real-time budget), but 300 ms of CPU is more
       than a 200 ms period: a release that finishes in time would have */
    stuck_with_activity('R', 300 * MS, 650 * MS, LOOPS_HELD);
    stuck_with_activity('R', 30 * MS, 900 * MS, STARVED);
    stuck_with_activity('R', 30 * MS, -1, STARVED); /* no wait known: ready to run at the last look */
    stuck_with_activity('R', 30 * MS, 20 * MS, WAITS); /* runnable at the last look, asleep nearly all along */
    stuck_with_activity('S', 30 * MS, -1, WAITS);
    stuck_with_activity('D', 0, 0, WAITS);
    stuck_with_activity('T', 0, 0, "it is stopped (by SIGSTOP, or a debugger holds it)");
    stuck_with_activity('Z', 0, 0, "it is no longer running (it crashed or was killed)");
    /* a printf flood: asleep in a write to a full pipe (wchan), whatever CPU it got printing */
    stuck_waiting_in('S', 970 * MS, -1, "anon_pipe_write", WRITING);
    stuck_waiting_in('S', 300 * MS, 650 * MS, "pipe_write", WRITING);
    stuck_waiting_in('D', 30 * MS, -1, "pipe_wait_writable", WRITING);
    /* asleep elsewhere, or running, or an older kernel's pipe_wait (reads and writes alike): not said so */
    stuck_waiting_in('S', 970 * MS, -1, "pipe_wait", LOOPS);
    stuck_waiting_in('S', 30 * MS, -1, "hrtimer_nanosleep", WAITS);
    stuck_waiting_in('R', 970 * MS, 20 * MS, "anon_pipe_write", LOOPS);
    /* a flood whose pipe had room at the look: 12 MiB written between the looks (1 s) */
    stuck_writing('R', 970 * MS, 20 * MS, "", 12 * 1024 * 1024,
                  "it prints without end (12.0 MiB written in the last 1.0 s): does its exec region print too much, or "
                  "loop printing?");
    /* a period's printf (4 KiB) is no flood: still a loop */
    stuck_writing('R', 970 * MS, 20 * MS, "", 4096, LOOPS);
}

/* Short periods: a loaded machine may hold a module for a few periods; it is declared stuck only
   after ORD_STUCK_MIN_NS (1 s), i.e. 334 periods of 3 ms. */
void test_ord_stuck_needs_at_least_1s_on_short_periods(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 0, "FST", NULL, 0, "SUP", 1);
    uint32_t e = fake_last_release(&w, "E");
    ord_core_advance(c, 999 * MS);
    OrdSchemaStats st;
    ord_core_stats(c, "FST", &st);
    CHECK(st.stuck_releases == 0 && st.overruns == 333);
    ord_core_advance(c, 3000 * MS);
    char called[LOG_LINE];
    snprintf(called, sizeof called, "stuck E #%u (FST) after 334 periods", e);
    check_log_filtered(&LOG, (const char *const[]){"stuck E", NULL}, (const char *const[]){called, NULL},
                       __FILE__, __LINE__);
    ord_core_stats(c, "FST", &st);
    CHECK(st.stuck_releases == 1 && st.overruns == 1000);
    ord_core_destroy(c);
}

/* Real-time mode: a module hogging the CPU makes ORD wake late, so every tick is overtaken by the
   next (missed, not an overrun). The stuck module is still reported, and the missed ticks of its
   cycle are one line, not one per tick, then their count when the cycle ends (the trace's missed
   ticks are ORD's count). */
void test_ord_stuck_reported_when_every_tick_is_missed(void) {
    FakeWorld w;
    OrdCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    ord_core_set_skip_late_ticks(c, 1);
    ord_core_activate(c, 0, "SLW", NULL, 0, "SUP", 1);
    uint32_t g = fake_last_release(&w, "G");
    for (int64_t t = 450 * MS; t <= 4500 * MS; t += 450 * MS) ord_core_advance(c, t);
    /* advancing to 2250 ms overtakes the 2000 ms tick: the report comes from a missed tick */
    char stuck[LOG_LINE], called[LOG_LINE];
    snprintf(stuck, sizeof stuck, "2000000us stuck: G has not finished release #%u after 10 periods: "
             "does its exec region set *stateindex = -1? (SLW)", g);
    snprintf(called, sizeof called, "stuck G #%u (SLW) after 10 periods", g);
    check_log_filtered(&LOG, (const char *const[]){"missed", "overrun", "stuck", NULL},
                       (const char *const[]){"200000us missed tick of SLW (cycle 1)",
                                             "400000us overrun: SLW cycle still running (G), release skipped",
                                             stuck, called, NULL},
                       __FILE__, __LINE__);
    OrdSchemaStats st;
    ord_core_stats(c, "SLW", &st);
    CHECK(st.stuck_releases == 1 && st.missed_ticks > 5);
    ord_core_release_finished(c, 4500 * MS, "G", g);
    char count[LOG_LINE];
    snprintf(count, sizeof count, "4500000us missed ticks: SLW cycle ended after %ld missed ticks", st.missed_ticks);
    CHECK(log_find(&LOG, count, 0) >= 0);
    ord_core_destroy(c);
}

/* OrdIo.fact: the typed timeline of docs/runtime-api.md "Trace records" */
static void fact_to_log(void *ctx, int64_t t, const OrdFact *f) {
    FakeWorld *w = ctx;
    static const char *const kinds[] = {"", "release", "finished", "complete", "deadline_miss"};
    log_add(w->log, "%lldus fact %s %s %s cycle=%ld tick=%lldus response=%lldus", (long long)(t / 1000),
            kinds[f->kind], f->schema, f->module ? f->module : "-", f->cycle, (long long)(f->tick / 1000),
            f->kind == ORD_FACT_FINISHED || f->kind == ORD_FACT_COMPLETE ? (long long)(f->response_ns / 1000) : 0LL);
}

/* OrdIo.fact: each fact as the record ORD's log holds ("ord_deadline_miss schema=..."), in the log */
static void fact_record_to_log(void *ctx, int64_t t, const OrdFact *f) {
    char detail[256];
    const char *kind = ord_fact_record(f, t, detail, sizeof detail);
    log_add(((FakeWorld *)ctx)->log, "%s %s", kind, detail);
}

/* the miss record carries the deadline it missed: a reader tells from it a cycle ORD released past
   CRITICAL_DELAY (ORD late) from a module that ran out of its time */
void test_ord_deadline_miss_record_says_its_critical_delay(void) {
    FakeWorld w;
    OrdCore *c = make_with_facts(&w, fact_record_to_log);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 5 * MS, "FST", NULL, 0, "SUP", 1); /* E every 3 ms, critical 3 ms */
    ord_core_advance(c, 8 * MS + 1);                        /* cycle 0 missed at 8 ms */
    CHECK(log_find(&LOG, "ord_deadline_miss schema=FST cycle=0 tick_ns=5000000 critical_delay_ns=3000000", 0) >= 0);
    ord_core_destroy(c);
}

void test_ord_facts_release_finished_complete_miss_with_cycle(void) {
    FakeWorld w;
    OrdCore *c = make_with_facts(&w, fact_to_log);
    if (!c) { CHECK(0); return; }
    ord_core_activate(c, 5 * MS, "FST", NULL, 0, "SUP", 1); /* E every 3 ms, critical 3 ms */
    ord_core_module_finished(c, 6 * MS, "E");               /* cycle 0: 1 ms */
    ord_core_advance(c, 8 * MS);                            /* cycle 1 released at 8 ms */
    ord_core_module_finished(c, 11 * MS + 500000, "E");     /* 3.5 ms: missed at 11 ms; the 11 ms tick overruns */
    const char *const facts[] = {"fact", NULL};
    check_log_filtered(&LOG, facts,
                       (const char *const[]){"5000us fact release FST E cycle=0 tick=5000us response=0us",
                                             "6000us fact finished FST E cycle=0 tick=5000us response=1000us",
                                             "6000us fact complete FST - cycle=0 tick=5000us response=1000us",
                                             "8000us fact release FST E cycle=1 tick=8000us response=0us",
                                             "11000us fact deadline_miss FST - cycle=1 tick=8000us response=0us",
                                             "11500us fact finished FST E cycle=1 tick=8000us response=3500us",
                                             "11500us fact complete FST - cycle=1 tick=8000us response=3500us",
                                             NULL},
                       __FILE__, __LINE__);
    ord_core_destroy(c);
}
