/*
 * itest_reactivate.c — scenario 4: deactivation and immediate reactivation of a periodic schema
 * while one of its modules still runs a release of the old activation, with real processes
 * (ORD iord.c -DIORD_RSC, RSU ireactivate.c, RMA/RMB/RMC imod.c; RMB is slow in its 4th activation).
 * RMB announces its slow run (RMB:0), RSU deactivates RSC and activates it again at once.
 * Asserted from the modules' traces (each START's release id and times), ORD's CSV log and its
 * stats, never from tight timings: the new activation's first cycle is held until RMB's late
 * ack of the old release (matched by its id), nothing is released while RMB still runs it, no
 * module is released twice in a cycle, RMA -> RMB -> RMC holds in every cycle, and everything
 * shuts down cleanly.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "itest_scenarios.h"
#include "itest_support.h"

static int starts_between(const Trace *t, long long from, long long to) {
    int n = 0;
    for (int k = 0; k < t->nstart; k++)
        if (t->start[k] > from && t->start[k] < to) n++;
    return n;
}

/* index of the first start of t in [from, to), or -1; *count receives how many there are */
static int first_start_in(const Trace *t, long long from, long long to, int *count) {
    int first = -1;
    *count = 0;
    for (int k = 0; k < t->nstart; k++)
        if (t->start[k] >= from && t->start[k] < to) {
            if (first < 0) first = k;
            (*count)++;
        }
    return first;
}

static int ids_distinct_and_increasing(const Trace *const *t, int n) {
    for (int i = 0; i < n; i++)
        for (int k = 0; k < t[i]->nstart; k++) {
            if (t[i]->id[k] <= 0 || (k > 0 && t[i]->id[k] <= t[i]->id[k - 1])) return 0;
            for (int j = 0; j < i; j++)
                for (int l = 0; l < t[j]->nstart; l++)
                    if (t[j]->id[l] == t[i]->id[k]) return 0;
        }
    return 1;
}

/* cycles are the windows between RMA's starts: in each, RMB and RMC at most once, RMB after
   RMA ended, RMC after RMB ended; *full counts the windows after `after` (all but the last) in
   which both ran exactly once, *windows how many such windows there are */
static int cycles_respect_precedence(const Trace *a, const Trace *b, const Trace *c, long long after, int *full,
                                     int *windows) {
    int ok = a->nstart > 0;
    *full = *windows = 0;
    for (int k = 0; k < a->nstart; k++) {
        long long from = a->start[k], to = k + 1 < a->nstart ? a->start[k + 1] : (long long)1 << 62;
        int nb, nc;
        int ib = first_start_in(b, from, to, &nb), ic = first_start_in(c, from, to, &nc);
        if (nb > 1 || nc > 1) ok = 0;
        if (ib >= 0 && (k >= a->nend || b->start[ib] < a->end[k])) ok = 0;
        if (ic >= 0 && (ib < 0 || ib >= b->nend || c->start[ic] < b->end[ib])) ok = 0;
        if (from > after && k + 1 < a->nstart) {
            (*windows)++;
            if (nb == 1 && nc == 1) (*full)++;
        }
    }
    return ok;
}

void scenario_reactivation(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "reactivation")) return;
    const char *const names[] = {"rsc/ORD", "RSU", "RMA", "RMB", "RMC", NULL};
    s.stop_first = "RSU"; /* as the generated Makefile names its supervisors */
    check(scenario_launch(&s, bin, launcher, "RSU.go()", "0.9", names),
          "reactivation: architecture ran and stopped cleanly");

    Trace a, b, c;
    int rt = read_trace(s.out, "RMA", &a) | read_trace(s.out, "RMB", &b) | read_trace(s.out, "RMC", &c);
    int slow = b.slow;
    check(rt == 0 && slow >= 0 && slow < b.nend, "RMB ran its slow activation (traces of RMA, RMB, RMC)");
    long long slow_start = slow >= 0 ? b.start[slow] : -1, slow_end = slow >= 0 && slow < b.nend ? b.end[slow] : -1;
    long slow_id = slow >= 0 ? b.id[slow] : -1;

    char *ord = read_csv_log(&s, "ORD");
    const char *at = NULL;
    long long t_act1 = csv_time_of(ord, NULL, ",activate RSC", &at);
    long long t_deact = t_act1 < 0 ? -1 : csv_time_of(ord, at, ",deactivate RSC", &at);
    long long t_act2 = t_deact < 0 ? -1 : csv_time_of(ord, at, ",activate RSC", &at);
    check(t_act2 > 0 && slow_start < t_deact && t_act2 < slow_end,
          "RSC deactivated and activated again while RMB still ran its slow release");

    char late[160], acked[80];
    snprintf(late, sizeof late, "late ack: RMB finished release #%ld of an earlier cycle of RSC", slow_id);
    snprintf(acked, sizeof acked, "ack_received,RMB,,0,ACK_FINISHED id=%ld\n", slow_id);
    const char *after_act2 = at;
    long long t_held = t_act2 < 0 ? -1 : csv_time_of(ord, after_act2, "cycle of RSC held: RMB still runs", &at);
    long long t_late = t_held < 0 ? -1 : csv_time_of(ord, at, late, &at);
    long long t_resumed = t_late < 0 ? -1 : csv_time_of(ord, at, "cycle of RSC resumed", NULL);
    check(t_held >= 0 && t_late >= 0 && t_resumed >= 0,
          "the new activation's first cycle is held, then resumed after RMB's late ack");
    check(csv_time_of(ord, NULL, acked, NULL) >= 0 && t_late >= slow_end,
          "RMB's late ack carries the id of its slow release and is taken as late (frees RMB, completes nothing)");
    check(slow_end > 0 && starts_between(&a, slow_start, slow_end) == 0 && starts_between(&c, slow_start, slow_end) == 0,
          "nothing released while RMB still ran the old release (RMA is free but waits)");
    check(slow + 1 < b.nstart && b.id[slow + 1] > slow_id && b.start[slow + 1] > t_resumed,
          "RMB released again only after the held cycle resumed");

    int full = 0, windows = 0;
    check(cycles_respect_precedence(&a, &b, &c, slow_end, &full, &windows),
          "no module released twice in a cycle; RMA -> RMB -> RMC in every cycle, before and after");
    check(windows >= 3 && full == windows, "every cycle after the reactivation releases each module once");
    const Trace *all[3] = {&a, &b, &c};
    check(ids_distinct_and_increasing(all, 3), "every START carries its own release id (AckID), increasing");

    /* the end of the run: RSC is still active; RSU stops first, so its undo reaches ORD */
    char *rsu = read_csv_log(&s, "RSU"), *txt = slurp(s.launch);
    check(rsu && strstr(rsu, ",supervisor,ORD,,0,\"undo: deactivate schema RSC (activation #"),
          "at the end of the run RSU undoes its last activation of RSC (a supervisor record)");
    check(t_act2 > 0 && csv_time_of(ord, after_act2, ",deactivate RSC", NULL) > 0,
          "ORD deactivates RSC at the end of the run (RSU stopped before ORD: --stop-first)");
    const char *rsu_end = txt ? strstr(txt, "contract-launch: module RSU (pid ") : NULL, *ord_end = txt ? strstr(txt, "contract-launch: module ORD (pid ") : NULL;
    check(rsu_end && ord_end && rsu_end < ord_end && strstr(txt, "all modules stopped cleanly"),
          "the launcher saw RSU end before ORD, and every module stop cleanly");
    free(rsu);

    char *js = slurp(s.stats);
    check(json_number(js, "held_cycles") >= 1 && json_number(js, "late_acks") >= 1,
          "ORD stats count the held cycle and the late ack");
    struct stat st;
    check(stat(s.run, &st) != 0, "clean shutdown: no runtime file left in the run directory");
    if (scenario_failed(&s))
        fprintf(stderr, "launcher output (reactivation scenario):\n%s\nORD stats: %s\n", txt ? txt : "(none)",
                js ? js : "(none)");
    free(txt);
    free(js);
    free(ord);
}
