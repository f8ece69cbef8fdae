/*
 * test_sim.c — the simulator's harness (runtime/sim/, docs/simulation.md) driven through its
 * line protocol with the report's hand-written tables: the §4.7 story as JSON records, a failed
 * expectation with its expected and actual state, determinism (the same lines twice give the
 * same bytes), an overrun that makes ORD emit ORD:0, the data a virtual module posts on the
 * flows ORD connected, a module whose code returns (finish), and hostile lines answered by error
 * records.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "harness.h"
#include "report_tables.h"
#include "sim_protocol.h"

static const ContractSupervisorVocabulary *const SUPS[] = {&SUP_VOCAB, &GLB_VOCAB};

/** Runs `lines` (one step per string, NULL-terminated) and returns the records (malloc'd). */
static char *run_lines(const char *const *lines) {
    char *buf = NULL;
    size_t len = 0;
    FILE *out = open_memstream(&buf, &len);
    if (!out) return NULL;
    char err[256] = "";
    SimSession *s = sim_session_create(SUPS, 2, &REPORT_ORD_VOCAB, out, -1, err, sizeof err);
    CHECK(s != NULL);
    if (s) {
        for (int i = 0; lines[i]; i++) {
            char *copy = strdup(lines[i]);
            if (!copy) break;
            int end = sim_session_line(s, copy);
            free(copy);
            if (end) break;
        }
        sim_session_destroy(s);
    }
    fclose(out);
    return buf;
}

/** The seq of the item of `rec` holding `needle` (its `"seq":N` is just before it); -1: not found. */
static long seq_of(const char *rec, const char *needle) {
    const char *at = strstr(rec, needle), *q = NULL;
    for (const char *p = rec; at && (p = strstr(p, "\"seq\":")) != NULL && p < at; p++) q = p;
    return q ? strtol(q + 6, NULL, 10) : -1;
}

/** Removes every `"seq":N,` of a record (the items' order, checked with seq_of on the raw line). */
static void strip_seq(char *s) {
    for (char *w; (w = strstr(s, "\"seq\":")) != NULL;) {
        char *e = w + 6;
        while (*e >= '0' && *e <= '9') e++;
        if (*e == ',') e++;
        memmove(w, e, strlen(e) + 1);
    }
}

/** The n-th record (0-based) of the output, with its items' seq, in a static buffer ("" when absent). */
static const char *raw_record(const char *out, int n) {
    static char line[65536];
    line[0] = '\0';
    const char *p = out;
    for (int i = 0; p && i < n; i++) {
        p = strchr(p, '\n');
        if (p) p++;
    }
    if (!p || !*p) return line;
    const char *e = strchr(p, '\n');
    size_t l = e ? (size_t)(e - p) : strlen(p);
    if (l >= sizeof line) l = sizeof line - 1;
    memcpy(line, p, l);
    line[l] = '\0';
    return line;
}

/** The n-th record without its items' seq (the order is checked with seq_of on raw_record). */
static const char *record(const char *out, int n) {
    static char line[65536];
    snprintf(line, sizeof line, "%s", raw_record(out, n));
    strip_seq(line);
    return line;
}

#define HAS(rec, s) CHECK(strstr((rec), (s)) != NULL)

static const char *const STORY[] = {
    "0\t1\tstart\tSUP\taction\tconsigne={1.0,2.0,3.0}",
    "1000000\t2\texpect-rule\tSUP\taction\tFIRST\t1",
    "300000000\t3\tevent\tMAA\t2\t\"disconnected\"",
    "300000000\t4\texpect-rule\tSUP\taction\tSECOND\t1",
    "300000000\t5\texpect-schema\tschemaCommande1\t1",
    "1000000000\t6\tevent\tMSC\t1\t",
    "1000000000\t7\texpect-rule\tSUP\taction\tFOURTH\t1",
    "1000000000\t8\texpect-rule\tSUP\taction\tSECOND\t1",
    "5000000000\t0\tend",
    NULL};

void test_sim_report_story_records(void) {
    report_log = NULL;
    testit_result = 1;
    char *out = run_lines(STORY);
    CHECK(out != NULL);
    if (!out) return;
    HAS(record(out, 0), "\"line\":1,\"timeNs\":0,\"verb\":\"start\",\"ok\":true");
    HAS(record(out, 1), "\"rule\":\"FIRST\",\"active\":true,\"cause\":\"elapsed=1000000ns\"");
    HAS(record(out, 1), "\"schemas\":[\"schemaReceptionMessage\"]");
    HAS(record(out, 2), "\"delivered\":1");
    HAS(record(out, 2), "\"rule\":\"SECOND\",\"active\":true,\"cause\":\"MAA:2 value=\\\"disconnected\\\"\"");
    HAS(record(out, 2), "activate schema schemaCommande1");
    /* a notified value as sent (SUP:1 "commutation"); a parameterized one as its type prints
       (these hand-written tables give TypeA no field table: its size) */
    HAS(out, "\"who\":\"SUP\",\"what\":\"notify :1 (string) = \\\"commutation\\\"\"");
    HAS(record(out, 1), "\"who\":\"SUP\",\"what\":\"parameterize MAA:0 param (24 bytes) = {24 bytes}\"");
    HAS(record(out, 4), "\"ok\":true");
    HAS(record(out, 4), "\"schemas\":[\"schemaCommande1\"]");
    HAS(record(out, 5), "\"rule\":\"FOURTH\",\"active\":true,\"cause\":\"endof(SECOND)\"");
    HAS(record(out, 6), "\"ok\":true");
    /* a wrong expectation: SECOND ended at 1 s */
    HAS(record(out, 7), "\"line\":8,\"timeNs\":1000000000,\"verb\":\"expect-rule\",\"ok\":false");
    HAS(record(out, 7), "\"expected\":\"rule SUP.action.SECOND active\",\"actual\":\"inactive\"");
    /* schemaCommande2's cycles of 1 s run to the end: releases in the end record's log */
    HAS(record(out, 8), "\"end\":true");
    HAS(record(out, 8), "release MSB (schemaCommande2)");
    /* the typed records of the same facts, as a real run's CSV logs hold them */
    HAS(record(out, 2), "{\"timeNs\":300000000,\"module\":\"SUP\",\"kind\":\"event_received\",\"peer\":\"MAA\",\"port\":");
    /* as sup_main.c writes it: when the engine took it, the rule changes it made (FIRST inactive,
       SECOND active) and its value as the rules' causes write it */
    HAS(record(out, 2), "\"kind\":\"event_received\",\"peer\":\"MAA\",\"port\":2,\"detail\":\"from_port=2 latency_ns=0 taken_ns=300000000 rules=2 value=\\\"disconnected\\\"\"");
    HAS(record(out, 5), "\"module\":\"ORD\",\"kind\":\"ord_release\",\"peer\":\"MSB\",\"detail\":\"schema=schemaCommande2 cycle=0 tick_ns=1000000000 release_ns=1000000000 release=");
    HAS(record(out, 5), "\"module\":\"MSB\",\"kind\":\"run_started\",\"peer\":\"ORD\",\"detail\":\"activation=1\"");
    HAS(record(out, 8), "\"module\":\"ORD\",\"kind\":\"ord_release\",\"peer\":\"MSB\",\"detail\":\"schema=schemaCommande2 cycle=3 tick_ns=4000000000 release_ns=4000000000 release=");
    HAS(record(out, 8), "\"kind\":\"run_finished\",\"peer\":\"\",\"detail\":\"activation=4 cpu_ns=500000 ACK_FINISHED\"");
    HAS(record(out, 8), "\"kind\":\"ord_complete\",\"peer\":\"\",\"detail\":\"schema=schemaCommande2 cycle=3 tick_ns=4000000000 response_ns=");
    /* the holds of schemaReceptionMessage's modules and flow, as a run's engines write them:
       taken at 1 ms (after their action lines), the last (only) holder's undo at 300 ms */
    HAS(record(out, 1), "\"module\":\"SUP\",\"kind\":\"flow_hold\",\"peer\":\"flow-MAA-0-MAB-0\",\"detail\":\"hold taken\"");
    HAS(record(out, 1), "\"module\":\"SUP\",\"kind\":\"module_hold\",\"peer\":\"MAA\",\"detail\":\"hold taken (started it)\"");
    HAS(record(out, 2), "\"kind\":\"flow_hold\",\"peer\":\"flow-MAA-0-MAB-0\",\"detail\":\"last hold dropped (disconnected)\"");
    HAS(record(out, 2), "\"kind\":\"module_hold\",\"peer\":\"MAB\",\"detail\":\"last hold dropped (stopped)\"");
    const char *r1 = raw_record(out, 1);
    CHECK(seq_of(r1, "\"what\":\"start module MAA") < seq_of(r1, "\"peer\":\"MAA\",\"detail\":\"hold taken (started it)\""));
    /* the four lists in one order (seq): at 300 ms FIRST inactive, its undo, SECOND active, its
       activation of schemaCommande1, then MAA's event_received (written once the rules have seen
       it, as sup_main.c writes it), ORD's release of MSA */
    const char *r2 = raw_record(out, 2);
    long order[] = {seq_of(r2, "\"rule\":\"FIRST\",\"active\":false"),
                    seq_of(r2, "\"what\":\"undo: deactivate schema schemaReceptionMessage"),
                    seq_of(r2, "\"rule\":\"SECOND\",\"active\":true"),
                    seq_of(r2, "\"what\":\"activate schema schemaCommande1"),
                    seq_of(r2, "\"kind\":\"event_received\",\"peer\":\"MAA\""),
                    seq_of(r2, "\"kind\":\"ord_release\",\"peer\":\"MSA\"")};
    for (size_t i = 0; i < sizeof order / sizeof order[0]; i++) {
        CHECK(order[i] >= 0);
        if (i > 0 && !(order[i - 1] < order[i])) {
            fprintf(stderr, "  item %zu: seq %ld after %ld\n", i, order[i], order[i - 1]);
            CHECK(0);
        }
    }
    free(out);
}

/** Removes the end record's `,"wallNs":N` (the only figure of the host's clock). */
static void strip_wall(char *s) {
    char *w = s ? strstr(s, ",\"wallNs\":") : NULL;
    if (!w) return;
    char *e = w + 10;
    while (*e >= '0' && *e <= '9') e++;
    memmove(w, e, strlen(e) + 1);
}

void test_sim_same_lines_same_bytes(void) {
    report_log = NULL;
    testit_result = 1;
    char *a = run_lines(STORY);
    char *b = run_lines(STORY);
    strip_wall(a);
    strip_wall(b);
    CHECK(a && b && strcmp(a, b) == 0);
    CHECK(a && strstr(a, "\"end\":true,\"eventsProcessed\":") != NULL);
    free(a);
    free(b);
}

void test_sim_overrun_makes_ord_emit_deadline_miss(void) {
    report_log = NULL;
    testit_result = 1;
    static const char *const lines[] = {
        "0\t1\tstart\tSUP\taction\tconsigne={1.0,2.0,3.0}",
        "0\t2\texec\tMSC\t1500000000\tonce",
        "300000000\t3\tevent\tMAA\t2\t\"disconnected\"",
        "2000000000\t0\tend",
        NULL};
    char *out = run_lines(lines);
    CHECK(out != NULL);
    if (!out) return;
    /* schemaCommande1 (period and critical delay 1 s) released at 300 ms; MSC takes 1.5 s */
    HAS(record(out, 3), "ORD:0 \\\"schemaCommande1\\\" (deadline miss)");
    HAS(record(out, 3), "\"timeNs\":1300000000,\"who\":\"ORD\",\"what\":\"ORD:0");
    /* the same miss typed, on cycle 0; MSC, released after MSA's 0.5 ms, answered 1.5 s later (its run_finished says
       its simulated work time, the scenario's 1.5 s, as its CPU time) */
    HAS(record(out, 3), "{\"timeNs\":1300000000,\"module\":\"ORD\",\"kind\":\"ord_deadline_miss\",\"peer\":\"\",\"detail\":\"schema=schemaCommande1 cycle=0 tick_ns=300000000 critical_delay_ns=1000000000\"}");
    HAS(record(out, 3), "{\"timeNs\":1800500000,\"module\":\"MSC\",\"kind\":\"run_finished\",\"peer\":\"\",\"detail\":\"activation=1 cpu_ns=1500000000 ACK_FINISHED\"}");
    HAS(record(out, 3), "\"kind\":\"ord_finished\",\"peer\":\"MSC\",\"detail\":\"schema=schemaCommande1 cycle=0 release=");
    HAS(record(out, 3), " response_ns=1500500000\"}");
    HAS(record(out, 3), "\"kind\":\"ord_complete\",\"peer\":\"\",\"detail\":\"schema=schemaCommande1 cycle=0 tick_ns=300000000 response_ns=1501500000\"}");
    free(out);
}

static int count_in(const char *s, const char *text) {
    int n = 0;
    for (const char *p = s ? strstr(s, text) : NULL; p; p = strstr(p + 1, text)) n++;
    return n;
}

void test_sim_virtual_modules_post_on_connected_flows(void) {
    report_log = NULL;
    testit_result = 1;
    /* schemaCommande1 (MSA:0 -> MSC:0 * 1, MSC:1 -> MSD:2 * 2; period 1 s) from 300 ms: five
       cycles by 4.5 s; then SECOND ends on MSC:1 and its flows are disconnected */
    static const char *const lines[] = {
        "0\t1\tstart\tSUP\taction\tconsigne={1.0,2.0,3.0}",
        "300000000\t2\tevent\tMAA\t2\t\"disconnected\"",
        "4500000000\t3\tevent\tMSC\t1\t",
        "9000000000\t0\tend",
        NULL};
    char *out = run_lines(lines);
    CHECK(out != NULL);
    if (!out) return;
    const char *msa = "\"module\":\"MSA\",\"kind\":\"data_posted\",\"peer\":\"MSC\",\"port\":0,\"detail\":\"to_port=0\"";
    const char *msc = "\"module\":\"MSC\",\"kind\":\"data_posted\",\"peer\":\"MSD\",\"port\":1,\"detail\":\"to_port=2\"";
    /* every run of MSA reaches MSC; MSC reaches MSD on its 2nd and 4th runs only (* 2) */
    CHECK(count_in(record(out, 2), msa) == 5);
    CHECK(count_in(record(out, 2), msc) == 2);
    /* a post comes at the end of its run, before the run's run_finished */
    HAS(record(out, 2), "{\"timeNs\":1300500000,\"module\":\"MSA\",\"kind\":\"data_posted\"");
    /* disconnected with schemaCommande1 at 4.5 s; schemaCommande2 (FOURTH) connects MSB:0 -> MSC:0
       and MSC:1 -> MSD:2 again, * 1 this time: MSC reaches MSD at every run from then on */
    const char *msb = "\"module\":\"MSB\",\"kind\":\"data_posted\",\"peer\":\"MSC\",\"port\":0,\"detail\":\"to_port=0\"";
    int runs = count_in(record(out, 3), "\"module\":\"MSC\",\"kind\":\"run_finished\"");
    CHECK(count_in(record(out, 3), msa) == 0 && runs >= 4);
    CHECK(count_in(record(out, 3), msc) == runs && count_in(record(out, 3), msb) == runs);
    free(out);
}

void test_sim_hostile_lines_get_error_records(void) {
    report_log = NULL;
    static const char *const lines[] = {
        "garbage",
        "10\t1\tfrobnicate\tx",
        "20\t2\tstart\tNOPE\tf\t",
        "30\t3\tstart\tSUP\taction\tconsigne={1.0,",
        "40\t4\tevent\tMAA\t99999999999\tx",
        "50\t5\texpect-rule\tSUP\taction",
        "5\t6\texpect-schema\tS\t1",
        "60\t7\texpect-local\tSUP\taction\ttemp_consigne\t{1.0,2.0,3.0}",
        "61\t8\texpect-count\tNOPE\tdeadline-misses\t0",
        "62\t9\texpect-count\tschemaCommande1\toverruns\t-3",
        "63\t10\texpect-count\tschemaCommande1\toverruns",
        "64\t11\texpect-count\tschemaCommande1\tmisses\t0",
        "70\t0\tend",
        NULL};
    char *out = run_lines(lines);
    CHECK(out != NULL);
    if (!out) return;
    HAS(record(out, 0), "\"ok\":false,\"error\":\"expected TIME_NS<TAB>LINE<TAB>VERB...\"");
    HAS(record(out, 1), "unknown verb 'frobnicate'");
    HAS(record(out, 2), "no supervisor NOPE");
    HAS(record(out, 3), "\"line\":3,");
    HAS(record(out, 3), "cannot read a TypeA for parameter 'consigne'");
    HAS(record(out, 4), "bad port");
    HAS(record(out, 5), "expect-rule takes 4 arguments");
    HAS(record(out, 6), "is before the simulation's");
    HAS(record(out, 7), "\"actual\":\"SUP.action is not running (no local temp_consigne)\"");
    HAS(record(out, 8), "\"ok\":false");
    HAS(record(out, 8), "\"actual\":\"no periodic schema NOPE\"");
    HAS(record(out, 9), "bad count '-3'");
    HAS(record(out, 10), "expect-count takes 3 arguments");
    HAS(record(out, 11), "bad count kind 'misses'");
    HAS(record(out, 12), "\"end\":true");
    free(out);
}

/* `finish M`: the asynchronous module's code returns: its run ends as libmodule logs it (no STOP,
   no peer), it no longer runs; a second finish, or one of a module never started, is an error */
void test_sim_finish_ends_an_asynchronous_run(void) {
    report_log = NULL;
    testit_result = 1;
    static const char *const lines[] = {
        "0\t1\tstart\tSUP\taction\tconsigne={1.0,2.0,3.0}",
        "1000000\t2\texpect-module\tMAA\t1",
        "2000000\t3\tfinish\tMAA",
        "2000000\t4\texpect-module\tMAA\t0",
        "2000000\t5\tfinish\tMAA",
        "2000000\t6\tfinish\tNOPE",
        "2000000\t7\tfinish",
        "3000000\t0\tend",
        NULL};
    char *out = run_lines(lines);
    CHECK(out != NULL);
    if (!out) return;
    HAS(record(out, 1), "\"ok\":true");
    HAS(record(out, 1), "\"module\":\"MAA\",\"kind\":\"run_started\",\"peer\":\"SUP\",\"detail\":\"activation=1\"");
    HAS(record(out, 2), "\"verb\":\"finish\",\"ok\":true");
    HAS(record(out, 2), "{\"timeNs\":2000000,\"module\":\"MAA\",\"kind\":\"run_finished\",\"peer\":\"\",\"detail\":\"activation=1 cpu_ns=0\"}");
    HAS(record(out, 3), "\"ok\":true");
    HAS(record(out, 4), "\"ok\":false,\"error\":\"MAA is not running: it has no run to finish\"");
    HAS(record(out, 5), "\"error\":\"NOPE is not running: it has no run to finish\"");
    HAS(record(out, 6), "finish takes 1 arguments");
    HAS(record(out, 7), "\"end\":true");
    free(out);
}

/* `finish-after M NS`: each run of M started from then on ends NS after its start, by its own code
   (run_finished with no STOP); a run stopped before that time is not ended again */
void test_sim_finish_after_ends_each_run(void) {
    report_log = NULL;
    testit_result = 1;
    static const char *const lines[] = {
        "0\t1\tfinish-after\tMAB\t500000\talways",
        "0\t2\tstart\tSUP\taction\tconsigne={1.0,2.0,3.0}",
        "1000000\t3\texpect-module\tMAB\t1",
        "2000000\t4\texpect-module\tMAB\t0",
        "2000000\t5\tfinish-after\tMAB\tsoon\talways",
        "3000000\t0\tend",
        NULL};
    char *out = run_lines(lines);
    CHECK(out != NULL);
    if (!out) return;
    HAS(record(out, 0), "\"verb\":\"finish-after\",\"ok\":true");
    HAS(record(out, 2), "\"module\":\"MAB\",\"kind\":\"run_started\",\"peer\":\"SUP\",\"detail\":\"activation=1\"");
    HAS(record(out, 2), "\"ok\":true");
    HAS(record(out, 3), "{\"timeNs\":1500000,\"module\":\"MAB\",\"kind\":\"run_finished\",\"peer\":\"\",\"detail\":\"activation=1 cpu_ns=0\"}");
    HAS(record(out, 3), "\"ok\":true");
    HAS(record(out, 4), "bad time 'soon'");
    HAS(record(out, 5), "\"end\":true");
    free(out);
}
