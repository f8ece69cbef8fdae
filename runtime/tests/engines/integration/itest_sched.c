/*
 * itest_sched.c — scenario 1: ORD (iord.c), the supervisor ISU (isup.c) and three synchronous
 * modules IMA/IMB/IMC (imod.c); ISU.go activates ISC(gain = g) for 300 ms. Checks what the
 * modules recorded: parameterisation from the supervisor's local, precedence in every cycle,
 * absolute-time releases, `* 1` / `* 2` deliveries, deactivation, ORD:1 reaching ISU.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "itest_scenarios.h"
#include "itest_support.h"

static int cmp_ll(const void *x, const void *y) {
    long long a = *(const long long *)x, b = *(const long long *)y;
    return (a > b) - (a < b);
}

/* The releases follow start + k * period: the period fitted by the median of the pairwise
   slopes (Theil-Sen: one release delayed by the machine does not move it) is within 25 us of
   `period` (a release scheduled from the previous one would drift by its lateness every cycle),
   and all but at most 2 releases are within 2 ms of the fitted line. */
static int absolute_ticks(const Trace *t, long long period) {
    int n = t->nstart;
    if (n < 3) return 0;
    long long *v = malloc(sizeof *v * (size_t)(n * (n - 1) / 2 > n ? n * (n - 1) / 2 : n));
    if (!v) return 0;
    int nv = 0;
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) v[nv++] = (t->start[j] - t->start[i]) / (j - i);
    qsort(v, (size_t)nv, sizeof *v, cmp_ll);
    long long slope = v[nv / 2];
    for (int k = 0; k < n; k++) v[k] = t->start[k] - k * slope;
    qsort(v, (size_t)n, sizeof *v, cmp_ll);
    long long origin = v[n / 2];
    int off = 0;
    for (int k = 0; k < n; k++) {
        long long dev = t->start[k] - (origin + k * slope);
        if (dev < -2000000 || dev > 2000000) off++;
    }
    free(v);
    return llabs(slope - period) <= 25000 && off <= 2;
}

void scenario_scheduler(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "scheduler")) return;
    const char *const names[] = {"ORD", "ISU", "IMA", "IMB", "IMC", NULL};
    check(scenario_launch(&s, bin, launcher, "ISU.go()", "0.6", names),
          "contract-launch ran the architecture and stopped it cleanly");

    Trace a, b, c;
    int ra = read_trace(s.out, "IMA", &a), rb = read_trace(s.out, "IMB", &b), rc = read_trace(s.out, "IMC", &c);
    check(ra == 0 && rb == 0 && rc == 0, "the three modules wrote their traces");
    check(a.param == 7, "IMA parameterised with gain = 7 (the supervisor's local through ORD)");
    /* R1 active from 10 ms to 310 ms, period 20 ms: 15 cycles (14..16 with start-up slack) */
    check(a.nstart >= 14 && a.nstart <= 16, "IMA released once per period while ISC was active, none after");
    check(b.nstart == a.nstart && c.nstart == a.nstart, "IMB and IMC released in every cycle");
    int prec = a.nstart > 0 && a.nend == a.nstart;
    for (int k = 0; k < a.nstart && k < b.nstart && k < c.nstart; k++)
        if (b.start[k] < a.end[k] || c.start[k] < a.end[k]) prec = 0;
    check(prec, "precedence IMA -> IMB, IMA -> IMC respected in every cycle");
    check(absolute_ticks(&a, 20000000LL),
          "releases at absolute ticks start + k * 20 ms (fitted period within 25 us: no drift; "
          "at most 2 releases more than 2 ms off it, for a loaded machine)");
    int ones = b.ngot == a.nstart;
    for (int k = 0; k < b.ngot; k++)
        if (b.got[k] != k + 1) ones = 0;
    check(ones, "IMA:0 -> IMB:0 * 1 delivers every activation's value");
    int twos = c.ngot == a.nstart / 2;
    for (int k = 0; k < c.ngot; k++)
        if (c.got[k] != 2 * (k + 1)) twos = 0;
    check(twos, "IMA:0 -> IMC:0 * 2 delivers every second activation's value");
    char *txt = slurp(s.launch);
    check(txt && strstr(txt, "[ORD] conflict: ICF shares a module with active ISC (ORD:1)"),
          "ORD refuses ICF (shares IMB with ISC)");
    check(txt && strstr(txt, "[ISU] rule go.R3 active"), "ORD:1 with ord_schema == \"ICF\" reached the supervisor");
    check(txt && strstr(txt, "[ORD] deactivate ISC"), "R1's postcondition deactivates ISC");
    char *js = slurp(s.stats);
    check(js && strstr(js, "\"deadline_misses\": 0") && strstr(js, "\"overruns\": 0"), "no deadline miss, no overrun");
    if (scenario_failed(&s)) fprintf(stderr, "launcher output (scheduler scenario):\n%s\n", txt ? txt : "(none)");
    free(txt);
    free(js);
}
