/*
 * itest_undo.c — scenario 6 (iundo.c, iord.c -DIORD_UNDO, imod.c as UMA, amod.c as AMX and
 * AMY): every undo undoes only what its own action did, with real processes. UPA activates
 * USM.aux twice (the second is refused), USM activates the periodic schema PSC that UPA runs
 * (refused by ORD; both activations carry the number 1), both supervisors use the event flow
 * AMX:0 =* AMY:0, and UPA (twice) and USM (once, in between) change AMX's priority. From the
 * launcher's output, the CSV logs and the modules' traces: nobody's undo ends what someone else
 * still uses.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "itest_scenarios.h"
#include "itest_support.h"

#define MS 1000000LL

/* mono_ns of the last CSV record whose line contains text, or -1 */
static long long csv_last_time(const char *csv, const char *text) {
    long long last = -1, t;
    const char *at = csv;
    while ((t = csv_time_of(csv, at, text, &at)) >= 0) last = t;
    return last;
}

void scenario_undo_own(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "undo")) return;
    const char *const names[] = {"undo/ORD", "UPA", "USM", "UMA", "AMX", "AMY", NULL};
    check(scenario_launch(&s, bin, launcher, "UPA.top()", "1.0", names),
          "undo: architecture ran and stopped cleanly");
    char *txt = slurp(s.launch);
    char *upa = read_csv_log(&s, "UPA"), *usm = read_csv_log(&s, "USM"), *amy = read_csv_log(&s, "AMY");

    /* activate supervisor: K2's activation refused, and its undo leaves K1's run */
    check(txt && strstr(txt, "[USM] refused: function aux already running") &&
              strstr(txt, "of USM.aux refused: its undo stops nothing"),
          "activate supervisor: USM refused K2's activation of aux and UPA learned it");
    /* its stderr line gives the reason its CSV record gives, not "unknown or already running" */
    check(txt && strstr(txt, "[USM] USM: start refused: activation #") &&
              strstr(txt, " of USM.aux from UPA: function aux already running\n") &&
              !strstr(txt, "(unknown or already running)"),
          "activate supervisor: USM's stderr says why it refused (function aux already running)");
    long long k1_end = csv_time_of(upa, NULL, "rule top.K1 inactive", NULL);
    long long k2_end = csv_time_of(upa, NULL, "rule top.K2 inactive", NULL);
    long long aux_end = csv_time_of(usm, NULL, "function aux stopped", NULL);
    check(k1_end > 0 && k2_end > 0 && aux_end >= k1_end && count_of(usm, "function aux stopped") == 1,
          "activate supervisor: aux ran until K1's undo (the caller whose activation it runs), not K2's");

    /* periodic schema: USM's refused PSC (its #1) undone on ORD:1 leaves UPA's PSC (#1 too) */
    Trace uma;
    int have_uma = read_trace(s.out, "UMA", &uma) == 0;
    check(txt && strstr(txt, "[ORD] ignored: deactivate PSC (not this activation)") && have_uma &&
              uma.nstart >= 10,
          "periodic schema: ORD ignored USM's undo of its refused PSC; UPA's PSC kept running (>= 10 releases)");

    /* event flow: USM's EVG undone while UPA's EVF uses AMX:0 =* AMY:0 */
    long long a3_end = csv_time_of(usm, NULL, "rule aux.A3 inactive", NULL);
    long long amy_last = csv_last_time(amy, ",event_received,AMX,");
    check(usm && strstr(usm, "hold dropped (kept connected: used by 1 other supervisor(s))") && a3_end > 0 &&
              amy_last >= a3_end + 40 * MS,
          "event flow: USM's undo left AMX:0 =* AMY:0 connected for UPA's EVF (AMY kept receiving)");
    check(upa && strstr(upa, "last hold dropped (disconnected)"), "event flow: UPA, its last user, disconnected it");
    /* the flow's connect and its undo, logged by each supervisor before its hold (peer = the source) */
    check(upa && usm && count_of(upa, ",supervisor,AMX,,0,connect AMX:0 =* AMY:0\n") == 1 &&
              count_of(upa, ",supervisor,AMX,,0,undo: disconnect AMX:0 =* AMY:0\n") == 1 &&
              count_of(usm, ",supervisor,AMX,,0,connect AMX:0 =* AMY:0\n") == 1 &&
              count_of(usm, ",supervisor,AMX,,0,undo: disconnect AMX:0 =* AMY:0\n") == 1,
          "event flow: each supervisor logged its connect and its undo (connect AMX:0 =* AMY:0, undo: disconnect ...)");

    /* priority: P1 (UPA), A4 (USM), P2 (UPA) on AMX; P1 and A4 undone while a later change
       stands: no request; P2's undo restores the priority from before P1 */
    check(upa && strstr(upa, ",priority_kept,AMX,") && count_of(upa, ",module_priority,AMX,") == 3,
          "priority: UPA changed AMX 3 times (critical, resttime, back to the one before P1), none at P1's undo");
    check(usm && strstr(usm, ",priority_kept,AMX,") && count_of(usm, ",module_priority,AMX,") == 2,
          "priority: USM's undo of A4 changed nothing (UPA's later change stood): start + A4 only");
    /* each claim and its undo logged as an action, by its activation number (the claim's, shown) */
    check(upa && lines_with(upa, ",supervisor,AMX,,0,set priority of AMX to ", " (claim #") == 2 &&
              count_of(upa, ",supervisor,AMX,,0,undo: release priority claim #") == 2 && usm &&
              lines_with(usm, ",supervisor,AMX,,0,set priority of AMX to ", " (claim #") == 1 &&
              count_of(usm, ",supervisor,AMX,,0,undo: release priority claim #") == 1,
          "priority: UPA logged P1's and P2's claims and their releases, USM A4's (set priority of AMX to P (claim #N))");

    /* subscription: B1's one-shot, spent, undone after B2 subscribed AMX:0 to :0 again */
    long long b1_end = csv_time_of(usm, NULL, "rule aux.B1 inactive", NULL);
    long long usm_last = csv_last_time(usm, "EVENT from_port=0");
    check(usm && strstr(usm, "kept: subscription AMX:0 to :0 (made again since by another rule)") && b1_end > 0 &&
              usm_last >= b1_end + 40 * MS,
          "subscription: B1's undo left B2's subscription of AMX:0 (USM kept receiving AMX's events)");
    /* each action a supervisor sends and each undo: a `supervisor` record, peer = where it goes
       (a detail with a comma is quoted in the CSV) */
    check(count_of(upa, ",supervisor,USM,,0,activate supervisor USM.aux() (activation #") == 2 &&
              count_of(upa, ",supervisor,USM,,0,undo: stop USM.aux (activation #") == 1 &&
              strstr(upa, ",supervisor,ORD,,0,\"activate schema PSC() (activation #") &&
              strstr(upa, ",supervisor,ORD,,0,\"undo: deactivate schema PSC (activation #"),
          "actions: UPA recorded K1's and K2's activate supervisor, K1's undo only (K2 was refused), PSC and its undo");
    check(strstr(usm, ",supervisor,ORD,,0,\"activate schema PSC() (activation #1, to ORD)\"") &&
              strstr(usm, ",supervisor,ORD,,0,\"undo: deactivate schema PSC (activation #1, to ORD)\"") &&
              count_of(usm, ",supervisor,AMX,,0,subscribe AMX:0 => :0 (activation #") == 1 &&
              count_of(usm, ",supervisor,AMX,,0,subscribe AMX:0 =* :0 (activation #") == 1 &&
              count_of(usm, ",supervisor,AMX,,0,undo: unsubscribe AMX:0 :0 (activation #") == 1,
          "actions: USM recorded A2's PSC and its undo on ORD:1, B1's and B2's subscriptions, one unsubscribe (B1's undo kept B2's)");

    /* a supervisor records each module event it takes as event_received, as a module does */
    int usm_events = lines_with(usm, ",request_received,AMX,", "EVENT from_port="), usm_received = count_of(usm, ",event_received,AMX,");
    check(usm_events > 0 && usm_received == usm_events && strstr(usm, ",event_received,AMX,0,") &&
              strstr(usm, "from_port=0 latency_ns="),
          "event received: USM recorded each of AMX's events it took (event_received, its port and latency)");

    if (scenario_failed(&s)) fprintf(stderr, "launcher output (undo scenario):\n%s\n", txt ? txt : "(none)");
    free(txt);
    free(upa);
    free(usm);
    free(amy);
}
