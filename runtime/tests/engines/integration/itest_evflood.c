/*
 * itest_evflood.c — scenario 14: a consumer flooded with events still gets the supervisor's
 * requests at once (field test: a producer blocked in PostEvent takes every slot of its
 * consumer's mailbox the moment the consumer reads one, and a supervisor's request kept for the
 * full mailbox, tried again every 5 ms, waited behind the flood up to 2 s, then failed).
 * SKS.evflood activates the event schema EVF: AMF posts as fast as AMC takes its events (5 ms
 * each), so AMC's mailbox is full from AMF's first events to the end. Checks, from the CSV logs:
 *  (a) at the activation AMC's START comes before any event of EVF, soon after the activation;
 *  (b) R's priority change (resttime) and parameter to the flooded AMC, then E's undo (AMC's
 *      STOP), reach AMC within a small bound, not after ~2 s; no request of SKS is kept or fails;
 *  (c) AMF's posts that waited for room in AMC's mailbox are told by a few `event_waited` records.
 * The supervisors' requests travel on the receiver's control channel, read before its mailbox
 * (docs/runtime-api.md "Mailboxes and the control channel").
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "itest_scenarios.h"
#include "itest_support.h"

#define BOUND_NS 200000000LL /* generous: AMC takes an event in 5 ms, the flood's room is 10 of them */

/* mono_ns of the first record of csv holding text at or after time t (-1: none) */
static long long csv_time_from(const char *csv, long long t, const char *text) {
    if (t < 0) return -1;
    for (const char *at = csv; at && *at;) {
        long long x = csv_time_of(csv, at, text, &at);
        if (x < 0 || x >= t) return x;
    }
    return -1;
}

/* ms between two CSV times (-1 when either is missing) */
static double ms_between(long long from, long long to) { return from < 0 || to < 0 ? -1.0 : (double)(to - from) / 1e6; }

void scenario_event_flood(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "event-flood")) return;
    const char *const names[] = {"SKS", "AMC", "AMF", NULL};
    s.stop_first = "SKS";
    check(scenario_launch(&s, bin, launcher, "SKS.evflood()", "1", names), "event flood: architecture ran and stopped");
    char *sks = read_csv_log(&s, "SKS"), *amc = read_csv_log(&s, "AMC");
    char what[600];

    /* (a) the activation: AMC's START before its first event, soon after SKS's action */
    long long act = csv_time_of(sks, NULL, "activate schema EVF", NULL);
    long long start = csv_time_of(amc, NULL, ",START", NULL);
    long long first_event = csv_time_of(amc, NULL, ",EVENT from_port=0", NULL);
    int events = count_of(amc, ",EVENT from_port=0");
    snprintf(what, sizeof what,
             "activation: AMC's START %.1f ms after SKS activated EVF (at most 200), before its first event "
             "(%.1f ms after the activation); AMC received %d events (at least 50: flooded)",
             ms_between(act, start), ms_between(act, first_event), events);
    check(act >= 0 && start >= act && start - act < BOUND_NS && first_event > start && events >= 50, what);

    /* (b) R at 300 ms: its priority change and its parameter reach the flooded AMC at once */
    long long r_at = csv_time_of(sks, NULL, "set priority of AMC to 5", NULL);
    long long prio = csv_time_from(amc, r_at, ",priority_changed,SKS,");
    long long param = csv_time_from(amc, r_at, ",SETPARAM");
    long long r_undo = csv_time_of(sks, NULL, "undo: release priority claim #1 on AMC", NULL);
    long long back = csv_time_from(amc, r_undo, ",priority_changed,SKS,");
    snprintf(what, sizeof what,
             "mid-run: R's priority change reached the flooded AMC %.1f ms after R's action, its parameter %.1f ms "
             "after, R's undo (the priority back) %.1f ms after it (each at most 200, not ~2 s)",
             ms_between(r_at, prio), ms_between(r_at, param), ms_between(r_undo, back));
    check(r_at >= 0 && prio >= r_at && prio - r_at < BOUND_NS && param >= r_at && param - r_at < BOUND_NS &&
              r_undo >= 0 && back >= r_undo && back - r_undo < BOUND_NS,
          what);

    /* E's undo at ~610 ms: AMC's STOP */
    long long undo = csv_time_of(sks, NULL, "undo: deactivate schema EVF", NULL);
    long long stop = csv_time_of(amc, NULL, ",STOP", NULL);
    snprintf(what, sizeof what, "undo: AMC's STOP %.1f ms after SKS deactivated EVF (at most 200)", ms_between(undo, stop));
    check(undo >= 0 && stop >= undo && stop - undo < BOUND_NS, what);

    snprintf(what, sizeof what, "SKS kept no request for a full mailbox (%d requests_kept) and none failed (%d errors)",
             count_of(sks, ",requests_kept,"), count_of(sks, ",error,"));
    check(count_of(sks, ",requests_kept,") == 0 && count_of(sks, ",error,") == 0, what);
    /* (c) AMF's posts that waited for room in AMC's full mailbox are told, bounded: `event_waited`
     * records (one per streak of waits: at most one a second, and one at the unsubscription) that
     * count the waits and their time */
    char *amf = read_csv_log(&s, "AMF");
    long waits = 0, wait_ms = 0, records = 0;
    for (const char *at = amf ? strstr(amf, ",event_waited,AMC,") : NULL; at; at = strstr(at + 1, ",event_waited,AMC,")) {
        const char *w = strstr(at, " waits="), *t = strstr(at, " wait_ns=");
        records++;
        if (w) waits += strtol(w + 7, NULL, 10);
        if (t) wait_ms += (long)(strtoll(t + 9, NULL, 10) / 1000000);
    }
    int posted = amf ? count_of(amf, ",event_posted,AMC,") : 0;
    snprintf(what, sizeof what,
             "AMF's posts to the flooded AMC that waited for room are told: %ld event_waited record(s) (1 to 3: one per "
             "streak, at most one a second) counting %ld waits (at least 20, at most the %d posts) of %ld ms in all (at least 50)",
             records, waits, posted, wait_ms);
    check(records >= 1 && records <= 3 && waits >= 20 && waits <= posted && wait_ms >= 50, what);
    free(amf);
    if (scenario_failed(&s)) {
        char *txt = slurp(s.launch);
        say_output_tail("event-flood", txt, 3000);
        free(txt);
    }
    free(sks);
    free(amc);
}
