/*
 * itest_cross.c — scenario 9 (icross.c, amod.c as AMD and AME, busy 250 ms after each post):
 * DLA and DLB each claim the priority of the module it started, then of the other's, while the
 * modules answer late. Each holds one module's lock for a claim in flight when it wants the
 * other's; it first settles its own answers (prio_requests_settle, before holds_lock waits), so
 * both go on: every claim is recorded, both take rule T on time, and the run stops cleanly.
 * Without the settling, both wait for each other until the launcher kills them.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "itest_scenarios.h"
#include "itest_support.h"

#define MS 1000000LL

void scenario_crossed_claims(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "crossed-claims")) return;
    const char *const names[] = {"DLA", "DLB", "AMD", "AME", NULL};
    s.stop_first = "DLA DLB"; /* their undos reach the modules (no "not applied" at the end) */
    check(scenario_launch(&s, bin, launcher, "DLA.go()", "1.3", names),
          "crossed claims: architecture ran and stopped cleanly");
    char *dla = read_csv_log(&s, "DLA"), *dlb = read_csv_log(&s, "DLB");
    /* start priority, A1/B1 on its own module, A2/B2 on the other's, and the undos at the end */
    check(dla && dlb && lines_with(dla, ",module_priority,AMD,", "(was ") >= 2 &&
              lines_with(dla, ",module_priority,AME,", "(was ") >= 1 && lines_with(dlb, ",module_priority,AME,", "(was ") >= 2 &&
              lines_with(dlb, ",module_priority,AMD,", "(was ") >= 1 && !strstr(dla, "not applied") && !strstr(dlb, "not applied"),
          "both supervisors' claims on AMD and AME were answered and recorded");
    long long a_go = csv_time_of(dla, NULL, "function go() started", NULL), a_t = csv_time_of(dla, NULL, "rule go.T active", NULL);
    long long b_go = csv_time_of(dlb, NULL, "function go() started", NULL), b_t = csv_time_of(dlb, NULL, "rule go.T active", NULL);
    check(a_go > 0 && a_t > 0 && b_go > 0 && b_t > 0 && a_t - a_go < 1100 * MS && b_t - b_go < 1100 * MS,
          "neither supervisor waited for the other: both took rule T (900 ms) on time");
    if (scenario_failed(&s)) {
        char *txt = slurp(s.launch);
        fprintf(stderr, "DLA's log:\n%s\nDLB's log:\n%s\nlauncher output (crossed claims):\n%s\n", dla ? dla : "(none)",
                dlb ? dlb : "(none)", txt ? txt : "(none)");
        free(txt);
    }
    free(dla);
    free(dlb);
}
