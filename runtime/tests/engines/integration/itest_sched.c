/*
 * itest_sched.c — scenario 1: ORD (iord.c), the supervisor ISU (isup.c) and three synchronous
 * modules IMA/IMB/IMC (imod.c); ISU.go activates ISC(gain = g) for 300 ms. Checks what the
 * modules recorded: parameterisation from the supervisor's local, precedence in every cycle,
 * absolute-time releases (a release the machine stalled, seen by stall_watch.h, is left out), `* 1` / `* 2` deliveries, deactivation, ORD:1 reaching ISU.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "itest_scenarios.h"
#include "itest_support.h"
#include "stall_watch.h"

static int cmp_ll(const void *x, const void *y) {
    long long a = *(const long long *)x, b = *(const long long *)y;
    return (a > b) - (a < b);
}

/* The ticks the releases follow: start + k * slope, fitted on the releases `use` marks by the
   median of their pairwise slopes (Theil-Sen: a release delayed by the machine does not move it),
   then fitted again on the releases at or before the median of that first line: a release can
   come late, never early, so the ticks are where the earliest releases are. Without that second
   fit, a loaded host that delays the second half's releases by 0.5 ms tilts the line by 40 us a
   period, which is no drift of the scheduler. */
typedef struct Fit {
    long long slope, origin;
} Fit;

static int fit_line(const Trace *t, const char *use, Fit *f);

static int fit_ticks(const Trace *t, const char *use, Fit *f) {
    if (!fit_line(t, use, f)) return 0;
    int n = t->nstart, m = 0;
    long long *res = malloc(sizeof *res * (size_t)n), *sorted = malloc(sizeof *sorted * (size_t)n);
    char *early = malloc((size_t)n);
    if (res && sorted && early) {
        /* each release's lateness against the first line, once */
        for (int k = 0; k < n; k++)
            if (use[k]) sorted[m++] = res[k] = t->start[k] - (f->origin + k * f->slope);
        qsort(sorted, (size_t)m, sizeof *sorted, cmp_ll);
        long long median = sorted[m / 2];
        for (int k = 0; k < n; k++) early[k] = use[k] && res[k] <= median;
        Fit lower;
        if (fit_line(t, early, &lower)) *f = lower;
    }
    free(res);
    free(sorted);
    free(early);
    return 1;
}

static int fit_line(const Trace *t, const char *use, Fit *f) {
    int n = t->nstart, m = 0;
    for (int k = 0; k < n; k++) m += use[k] != 0;
    if (m < 3) return 0;
    long long *v = malloc(sizeof *v * (size_t)(m * (m - 1) / 2 > n ? m * (m - 1) / 2 : n));
    if (!v) return 0;
    int nv = 0;
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            if (use[i] && use[j]) v[nv++] = (t->start[j] - t->start[i]) / (j - i);
    qsort(v, (size_t)nv, sizeof *v, cmp_ll);
    f->slope = v[nv / 2];
    nv = 0;
    for (int k = 0; k < n; k++)
        if (use[k]) v[nv++] = t->start[k] - k * f->slope;
    qsort(v, (size_t)nv, sizeof *v, cmp_ll);
    f->origin = v[nv / 2];
    free(v);
    return 1;
}

/* releases of a that `use` marks and that are more than 2 ms off the fitted ticks */
static int releases_off(const Trace *a, const char *use, const Fit *f) {
    int off = 0;
    for (int k = 0; k < a->nstart; k++)
        if (use[k] && llabs(a->start[k] - (f->origin + k * f->slope)) > 2000000) off++;
    return off;
}

/* The ticks ORD's ord_release records of `module` name, in order (docs/runtime-api.md "Trace
   records"); returns how many (at most max). */
static int ord_ticks(const char *csv, const char *module, long long *ticks, int max) {
    char key[64];
    snprintf(key, sizeof key, ",ord_release,%s,", module);
    int n = 0;
    for (const char *p = csv ? strstr(csv, key) : NULL; p && n < max; p = strstr(p + 1, key)) {
        const char *d = strstr(p, "tick_ns=");
        if (!d || sscanf(d, "tick_ns=%lld", &ticks[n]) != 1) break;
        n++;
    }
    return n;
}

/* cycles the machine delayed: the last module ended more than 5 ms after the tick (each runs
   0.3 ms; an undisturbed cycle ends within about 1 ms) */
static int cycles_delayed(const Trace *const *t, int nt, const Fit *f) {
    int delayed = 0;
    for (int k = 0; k < t[0]->nstart; k++) {
        long long last = 0;
        for (int i = 0; i < nt; i++)
            if (k < t[i]->nend && t[i]->end[k] > last) last = t[i]->end[k];
        if (last - (f->origin + k * f->slope) > 5000000) delayed++;
    }
    return delayed;
}

/* ORD's ord_release records of `module` (docs/runtime-api.md "Trace records"): cycles 0, 1, 2...
   in order (none skipped unless ORD skipped the tick), each tick exactly tick_0 + cycle * period,
   released at or after its tick. Returns the number of records, -1 when one breaks that. */
static int check_releases(const char *csv, const char *module, long long period, long skipped) {
    char key[64];
    snprintf(key, sizeof key, ",ord_release,%s,", module);
    long prev = -1;
    long long tick0 = -1;
    int n = 0;
    for (const char *p = csv ? strstr(csv, key) : NULL; p; p = strstr(p + 1, key)) {
        long cycle = -1;
        long long tick = -1, rel = -1;
        const char *d = strstr(p, "cycle=");
        if (!d || sscanf(d, "cycle=%ld tick_ns=%lld release_ns=%lld", &cycle, &tick, &rel) != 3) return -1;
        if (tick0 < 0) tick0 = tick - cycle * period;
        if (cycle <= prev || cycle - prev - 1 > skipped || tick != tick0 + cycle * period || rel < tick) return -1;
        prev = cycle;
        n++;
    }
    return n;
}

void scenario_scheduler(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "scheduler")) return;
    const char *const names[] = {"ORD", "ISU", "IMA", "IMB", "IMC", NULL};
    int watched = stall_watch_start();
    int launched = scenario_launch(&s, bin, launcher, "ISU.go()", "0.6", names);
    stall_watch_stop();
    check(launched, "contract-launch ran the architecture and stopped it cleanly");
    check(watched > 0, "the stall watch ran on the machine's CPUs");

    Trace a, b, c;
    int ra = read_trace(s.out, "IMA", &a), rb = read_trace(s.out, "IMB", &b), rc = read_trace(s.out, "IMC", &c);
    check(ra == 0 && rb == 0 && rc == 0, "the three modules wrote their traces");
    check(a.param == 7, "IMA parameterised with gain = 7 (the supervisor's local through ORD)");
    char *js = slurp(s.stats);
    long misses = json_number(js, "deadline_misses"), overruns = json_number(js, "overruns"),
         missed = json_number(js, "missed_ticks");
    /* R1 active from 10 ms to 310 ms, period 20 ms: 15 ticks (14..16 with start-up slack), each
       a release unless ORD skipped it (overrun, or a tick ORD itself woke up too late for) */
    long ticks = a.nstart + overruns + missed;
    check(js && ticks >= 14 && ticks <= 16, "IMA released once per period while ISC was active, none after");
    check(b.nstart == a.nstart && c.nstart == a.nstart, "IMB and IMC released in every cycle");
    int prec = a.nstart > 0 && a.nend == a.nstart;
    for (int k = 0; k < a.nstart && k < b.nstart && k < c.nstart; k++)
        if (b.start[k] < a.end[k] || c.start[k] < a.end[k]) prec = 0;
    check(prec, "precedence IMA -> IMB, IMA -> IMC respected in every cycle");
    /* Absolute ticks, seen from IMA: its starts follow start + k * 20 ms. A release the machine
       delayed for every process at once (the stall watch saw a CPU wake up late between the
       release's tick, as ORD logged it, and IMA's start) is left out of the fit and the count:
       on a loaded host that is the host's doing, not the runtime's. */
    char *ord = read_csv_log(&s, "ORD"), *isu = read_csv_log(&s, "ISU");
    long long ord_tick[TRACE_MAX];
    int nticks = ord_ticks(ord, "IMA", ord_tick, TRACE_MAX), stalled = 0;
    char use[TRACE_MAX];
    for (int k = 0; k < a.nstart; k++) {
        use[k] = !(k < nticks && stall_watch_between(ord_tick[k] - STALL_WATCH_LATE_NS, a.start[k]));
        stalled += !use[k];
    }
    Fit fit = {0, 0};
    int fitted = a.nstart - stalled >= 5 && fit_ticks(&a, use, &fit), off = fitted ? releases_off(&a, use, &fit) : 0;
    char ticked[400];
    snprintf(ticked, sizeof ticked,
             "releases at absolute ticks start + k * 20 ms (fitted on the %d of %d the machine did not stall, "
             "at least 5: period %lld ns, within 25 us: no drift; %d of them more than 2 ms off, at most a quarter)",
             a.nstart - stalled, a.nstart, fit.slope, off);
    check(fitted && llabs(fit.slope - 20000000LL) <= 25000 && off * 4 <= a.nstart - stalled, ticked);
    if (!fitted) {
        for (int k = 0; k < a.nstart; k++) use[k] = 1; /* the delayed-cycles count below needs ticks */
        fitted = fit_ticks(&a, use, &fit);
    }
    const Trace *abc[3] = {&a, &b, &c};
    int late = fitted ? cycles_delayed(abc, 3, &fit) : a.nstart;
    int ones = b.ngot == a.nstart;
    for (int k = 0; k < b.ngot; k++)
        if (b.got[k] != k + 1) ones = 0;
    check(ones, "IMA:0 -> IMB:0 * 1 delivers every activation's value");
    int twos = c.ngot == a.nstart / 2;
    for (int k = 0; k < c.ngot; k++)
        if (c.got[k] != 2 * (k + 1)) twos = 0;
    check(twos, "IMA:0 -> IMC:0 * 2 delivers every second activation's value");
    /* the run-time trace (docs/runtime-api.md "Trace records"): one ord_release per release the
       module ran, cycle numbers in order; one ord_finished per completion; one ord_complete per
       completed cycle (ORD's own count); the causes of ISU's rule changes */
    check(ord && check_releases(ord, "IMA", 20000000LL, overruns + missed) == a.nstart &&
              check_releases(ord, "IMB", 20000000LL, overruns + missed) == b.nstart,
          "ORD's log has an ord_release record per release IMA and IMB ran, cycles in order, ticks at "
          "tick_0 + cycle * 20 ms, released at or after the tick");
    check(ord && count_of(ord, ",ord_finished,IMA,") == a.nend && count_of(ord, ",ord_finished,IMC,") == c.nend,
          "ORD's log has an ord_finished record per run IMA and IMC finished");
    check(ord && count_of(ord, ",ord_complete,") == json_number(js, "completed") &&
              count_of(ord, ",ord_deadline_miss,") == misses,
          "ORD's log has an ord_complete record per completed cycle and an ord_deadline_miss per miss");
    check(isu && strstr(isu, ",sup_rule,,,0,go.R1 active cause=elapsed=10000000ns\n") &&
              strstr(isu, ",sup_rule,,,0,\"go.R3 active cause=ORD:1 value=\"\"ICF\"\"\"\n") &&
              strstr(isu, ",sup_rule,,,0,go.R1 inactive cause=elapsed=300000000ns\n"),
          "ISU's log has its rule changes with their causes (elapsed=10ms, ORD:1 \"ICF\", elapsed=300ms)");
    if (scenario_failed(&s)) fprintf(stderr, "ORD's log:\n%s\nISU's log:\n%s\n", ord ? ord : "(none)", isu ? isu : "(none)");
    free(ord);
    free(isu);
    char *txt = slurp(s.launch);
    check(txt && strstr(txt, "[ORD] conflict: ICF shares a module with active ISC (ORD:1)"),
          "ORD refuses ICF (shares IMB with ISC)");
    check(txt && strstr(txt, "[ISU] rule go.R3 active"), "ORD:1 with ord_schema == \"ICF\" reached the supervisor");
    check(txt && strstr(txt, "[ORD] deactivate ISC"), "R1's postcondition deactivates ISC");
    char what[200];
    snprintf(what, sizeof what, "deadline misses (%ld) and skipped ticks (%ld) only after cycles the machine delayed by > 5 ms (%d)",
             misses, overruns + missed, late);
    check(misses >= 0 && overruns >= 0 && missed >= 0 && misses <= late && overruns + missed <= late, what);
    if (scenario_failed(&s)) fprintf(stderr, "launcher output (scheduler scenario):\n%s\n", txt ? txt : "(none)");
    free(txt);
    free(js);
}
