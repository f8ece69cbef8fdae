/*
 * itest_late.c — scenario 8 (ilate.c, amod.c as AMB with AMOD_BUSY_MS=300): a module that
 * answers a priority change only after 300 ms of its own code does not hold up its supervisor.
 * PQS takes its next rule on time while two claims wait for AMB's answer, records both claims
 * when the answer comes, does the undo that came meanwhile then, and the last undo restores the
 * priority AMB had before them (docs/engines.md §4).
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "itest_scenarios.h"
#include "itest_support.h"

#define MS 1000000LL

/* the "(was N)" of a module_priority record line found at or after `from` */
static int was_of(const char *from) {
    const char *w = from ? strstr(from, "(was ") : NULL;
    int v = -1;
    return w && sscanf(w, "(was %d)", &v) == 1 ? v : -1;
}

void scenario_late_priority_answer(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "late-priority")) return;
    const char *const names[] = {"PQS", "AMB", NULL};
    check(scenario_launch(&s, bin, launcher, "PQS.go()", "0.8", names),
          "late priority answer: architecture ran and stopped cleanly");
    char *pqs = read_csv_log(&s, "PQS");
    long long go = csv_time_of(pqs, NULL, "function go() started", NULL);
    long long t_active = csv_time_of(pqs, NULL, "rule go.T active", NULL);
    /* the records of AMB's priority, in order: S's start, C1's and C2's claims (answered after
       AMB's 300 ms), C2's undo (restore), C1's undo (restore) */
    const char *at = NULL;
    long long p[5];
    const char *line[5];
    int n = 0;
    for (const char *from = pqs; n < 5 && (p[n] = csv_time_of(pqs, from, ",module_priority,AMB,", &at)) >= 0; n++) {
        line[n] = from ? strstr(from, ",module_priority,AMB,") : NULL;
        from = at;
    }
    check(pqs && n == 5 && count_of(pqs, ",module_priority,AMB,") == 5 && !strstr(pqs, "not applied"),
          "AMB's priority changed five times (start, C1, C2, C2's undo, C1's undo), each answered");
    check(go > 0 && t_active > 0 && t_active - go < 280 * MS && n == 5 && p[1] - go >= 290 * MS && t_active < p[1],
          "PQS took rule T on time (~120 ms) while C1's and C2's claims waited for AMB's answer (~305 ms)");
    check(n == 5 && p[3] - p[2] < 100 * MS && p[3] < p[4] && p[4] - go >= 490 * MS,
          "C2's undo, which came before its answer, was done when the answer came; C1's at 500 ms");
    /* each record says the priority before it: C1 found S's (critical 70) and set resttime 5, C2
       set 70 again, C2's undo restored C1's 5, C1's undo the 70 from before C1 */
    check(n == 5 && was_of(line[1]) == 70 && was_of(line[2]) == 5 && was_of(line[3]) == 70 && was_of(line[4]) == 5,
          "the claims were recorded in AMB's order: C2's undo restored C1's priority, C1's undo the one before C1");
    if (scenario_failed(&s)) {
        char *txt = slurp(s.launch);
        fprintf(stderr, "PQS's log:\n%s\nlauncher output (late priority scenario):\n%s\n", pqs ? pqs : "(none)",
                txt ? txt : "(none)");
        free(txt);
    }
    free(pqs);
}
