/*
 * itest_stuck.c — scenarios 10 and 11. 10: a module stuck in a fast schema does not freeze ORD (the field
 * test's D4: the mobile robot's VEL looping in its exec region). ORD (iord.c -DIORD_STK), the
 * supervisor SKS (istuck.c), STK (imod.c, never returns from its 5th release) in FST (10 ms) and
 * OKM (imod.c) in SLW (20 ms). SKS deactivates and activates FST again at each of its deadline
 * misses: every activation makes ORD send STK a parameter request, and STK's mailbox, which it no
 * longer reads, is full within half a second. A request ORD cannot deliver at once must fail at
 * once (it used to block ORD up to 2 s each: SLW then missed nearly every tick, and ORD, still
 * blocked at the stop, did not answer its KILL and was terminated, losing its last records).
 * Asserted on ORD's CSV log, its stats and the launcher's output, with bounds that a loaded host
 * keeps: SLW released on nearly every tick from its activation to SKS's undo, ORD's failed sends
 * to STK reported within 100 ms of the request, FST toggled many times, and ORD ending on KILL.
 * 11 (D4b): CRS, killed in its 5th release of CRH, is reported stuck as a module that is no
 * longer running, in ORD's CSV record (what contract trace and the IDE's Monitor show) in the
 * same words as on ORD's stderr, not with the advice to set *stateindex = -1. STK, asleep in its
 * release, is reported as waiting (ORD looks at its thread: ord_stuck_cause.h).
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "itest_scenarios.h"
#include "itest_support.h"

#define MS 1000000LL
#define SLW_PERIOD (20 * MS)

/* ORD's ord_release records of OKM up to `until` (ORD's clock): how many, the first one's tick 0
   (its tick minus cycle * period) and the largest gap between two released cycles (1: none
   skipped). Returns the count. */
static int okm_releases(const char *csv, long long until, long long *tick0, long *max_gap) {
    int n = 0;
    long prev = -1;
    *tick0 = -1;
    *max_gap = 0;
    for (const char *p = csv ? strstr(csv, ",ord_release,OKM,") : NULL; p; p = strstr(p + 1, ",ord_release,OKM,")) {
        long cycle = -1;
        long long tick = -1;
        const char *d = strstr(p, "cycle=");
        if (!d || sscanf(d, "cycle=%ld tick_ns=%lld", &cycle, &tick) != 2) break;
        if (until >= 0 && tick > until) break;
        if (*tick0 < 0) *tick0 = tick - cycle * SLW_PERIOD;
        if (prev >= 0 && cycle - prev > *max_gap) *max_gap = cycle - prev;
        prev = cycle;
        n++;
    }
    return n;
}

/* mono_ns of the last record of a CSV log, -1 if none */
static long long last_record_time(const char *csv) {
    long long t = -1, v;
    for (const char *line = csv; line && *line;) {
        if (sscanf(line, "%lld,", &v) == 1) t = v;
        const char *end = strchr(line, '\n');
        line = end ? end + 1 : NULL;
    }
    return t;
}

/* Each `error` record of a request to STK that its full mailbox refused, against ORD's
   `parameterize STK:0` record just before it (logged before the request is sent): how many,
   and the longest time from the one to the other in *slowest. */
static int refused_sends(const char *csv, long long *slowest) {
    int n = 0;
    long long asked = -1;
    *slowest = 0;
    for (const char *line = csv; line && *line;) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        long long t = -1;
        const char *param = strstr(line, ",parameterize STK:0 gain ");
        const char *refused = strstr(line, ",error,,,0,SETPARAM request to STK: mailbox full");
        if (sscanf(line, "%lld,", &t) == 1) {
            if (param && param < line + len) asked = t;
            if (refused && refused < line + len && asked >= 0) {
                if (t - asked > *slowest) *slowest = t - asked;
                n++;
            }
        }
        line = end ? end + 1 : NULL;
    }
    return n;
}

void scenario_stuck_module(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "stuck")) return;
    const char *const names[] = {"stk/ORD", "SKS", "STK", "OKM", NULL};
    s.stop_first = "SKS"; /* as the generated Makefile names its supervisors: its undo reaches ORD */
    check(scenario_launch(&s, bin, launcher, "SKS.go()", "2.5", names),
          "stuck module: architecture ran and stopped (the stuck STK terminated by the launcher)");

    char *stk = NULL;
    char path[700];
    snprintf(path, sizeof path, "%s/STK.trace", s.out);
    stk = slurp(path);
    check(stk && count_of(stk, "start ") == 5 && strstr(stk, "stuck\n"),
          "STK ran 4 releases and never returned from its 5th");

    char *ord = read_csv_log(&s, "ORD"), *txt = slurp(s.launch), *js = slurp(s.stats);
    check(txt && strstr(txt, "[ORD] STUCK: STK has not finished release #"), "ORD reported STK stuck");
    /* STK sleeps in its 5th release: ORD looked at its thread (/proc) and says it waits, not that
       its exec region may never set *stateindex = -1 */
    const char *stk_line = txt ? strstr(txt, "[ORD] STUCK: STK has not finished release #") : NULL;
    size_t stk_len = stk_line ? strcspn(stk_line, "\n") : 0;
    char said[400] = "";
    if (stk_len && stk_len < sizeof said) memcpy(said, stk_line, stk_len);
    char what_stk[500];
    snprintf(what_stk, sizeof what_stk, "ORD's STUCK line says the sleeping STK is waiting (`%s`)", said);
    check(strstr(said, ": it is waiting, not running (a sleep, a read, a lock or a send to a full mailbox in its "
                       "exec region?)") != NULL,
          what_stk);

    /* ORD went on serving SKS: each ORD:0 of FST became a deactivation and an activation */
    int toggles = count_of(ord, ",activate FST (activation #");
    char what[400];
    snprintf(what, sizeof what, "ORD served SKS's activations of FST all along (%d, at least 25: one per ~30 ms)", toggles);
    check(toggles >= 25, what);

    /* the requests STK's full mailbox refused failed at once, told as any failed request */
    long long slowest = 0;
    int refused = refused_sends(ord, &slowest);
    snprintf(what, sizeof what,
             "a request to STK's full mailbox fails at once (%d refused, at least 5; the slowest told %lld ms after "
             "ORD logged it, at most 100 ms: no 2 s wait)",
             refused, slowest / MS);
    check(refused >= 5 && slowest <= 100 * MS, what);
    check(txt && strstr(txt, "[ORD] ORD: cannot set parameter 0 of STK: mailbox full") &&
              strstr(txt, "ORD does not wait for a full mailbox"),
          "ORD says on stderr that it could not parameterize STK, whose mailbox is full");

    /* SKS's own parameter requests to STK are kept for its full mailbox, not waited for: SKS went
       on toggling FST (the check above; waiting 2 s at each, it toggled once per 2 s). A new value
       replaces the one kept (STK would read only the last), and the one kept fails after 2 s, told
       on SKS's stderr and in its log with the values it replaced: every value is accounted for */
    char *sks = read_csv_log(&s, "SKS");
    int asked = count_of(sks, ",parameterize STK:0 gain "), sent = count_of(sks, ",setparam_sent,STK,0,");
    int failed = count_of(sks, "SETPARAM request to STK: mailbox full"), replaced = 0;
    for (const char *p = sks ? strstr(sks, "in place of ") : NULL; p; p = strstr(p + 1, "in place of ")) replaced += atoi(p + 12);
    int told = count_of(sks, "error: not sent: SETPARAM request to STK (kept 2 s for its full mailbox)");
    int stayed = count_of(sks, "its mailbox stayed full for 2 s; SKS kept the request meanwhile");
    snprintf(what, sizeof what,
             "SKS's %d values for STK: %d sent, %d replaced by a later one, %d failed (%d after 2 s kept, each tied to "
             "its action: %d; the rest at its end), none lost, none waited for",
             asked, sent, replaced, failed, stayed, told);
    check(asked >= 25 && sent + replaced + failed == asked && stayed >= 1 && told == stayed &&
              txt && strstr(txt, "[SKS] SKS: error: SETPARAM request to STK: mailbox full") && !strstr(txt, "SKS did not end"),
          what);
    /* each streak of kept requests for STK is bracketed, and its end accounts for them as the
       requests' own records do: the values replaced, the requests failed; the last ends before SKS's exit */
    int streaks = count_of(sks, ",requests_kept,STK,,0,request=SETPARAM"), ends = count_of(sks, ",requests_kept_end,STK,,0,");
    long long end_replaced = sum_of_key(sks, ",requests_kept_end,STK,,0,", "replaced"),
              end_failed = sum_of_key(sks, ",requests_kept_end,STK,,0,", "failed");
    const char *last_end = NULL;
    for (const char *p = sks ? strstr(sks, ",requests_kept_end,STK,") : NULL; p; p = strstr(p + 1, ",requests_kept_end,STK,")) last_end = p;
    snprintf(what, sizeof what,
             "SKS's streaks of kept requests for STK: %d begun, %d ended, the ends count %lld values replaced (the records "
             "say %d) and %lld failed (%d), the last before its exit (%s)",
             streaks, ends, end_replaced, replaced, end_failed, failed, last_end && strstr(last_end, ",SKS,module_exit,") ? "yes" : "no");
    check(streaks >= 1 && ends == streaks && end_replaced == replaced && end_failed == failed && last_end &&
              strstr(last_end, ",SKS,module_exit,"),
          what);
    /* at the stop SKS still kept requests for STK: it tried them 0.5 s more, then ended */
    long long killed = csv_time_of(sks, NULL, ",request_received,contract-launch,,0,KILL", NULL),
              ended = csv_time_of(sks, NULL, ",SKS,module_exit,", NULL);
    snprintf(what, sizeof what, "SKS ended %lld ms after its KILL (at most 1 s: its kept requests tried 0.5 s more)",
             killed > 0 && ended > 0 ? (ended - killed) / MS : -1);
    check(killed > 0 && ended > killed && ended - killed <= 1000 * MS &&
              count_of(sks, "SKS ended before its mailbox had room") >= 1,
          what);

    /* SLW on time: from its first release to SKS's undo at the stop (or, when ORD's log has none,
       its last record), every tick released but a few */
    long long t_deact = csv_time_of(ord, NULL, ",deactivate SLW (activation #", NULL), tick0 = -1;
    long long t_end = t_deact > 0 ? t_deact : last_record_time(ord);
    long max_gap = 0;
    int released = okm_releases(ord, t_end, &tick0, &max_gap);
    long window = t_end > 0 && tick0 > 0 && t_end >= tick0 ? (long)((t_end - tick0) / SLW_PERIOD) + 1 : -1;
    long missed = window - released;
    snprintf(what, sizeof what,
             "SLW released on its ticks while STK was stuck (%d of %ld ticks from its activation to %s, at least "
             "100; %ld skipped, at most 3 + 5 %%; largest gap %ld periods, at most 5)",
             released, window, t_deact > 0 ? "its deactivation" : "ORD's last record (no deactivation)", missed, max_gap);
    check(t_deact > 0 && window >= 100 && missed <= 3 + window / 20 && max_gap <= 5, what);
    int misses = count_of(ord, ",deadline miss: SLW cycle ");
    snprintf(what, sizeof what, "SLW missed few deadlines (%d, at most 2 + 5 %% of %ld)", misses, window);
    check(window > 0 && misses <= 2 + window / 20, what);

    /* the stop: SKS's undo reached ORD, which then ended on its KILL with its records whole */
    check(txt && strstr(txt, "module STK did not end on its KILL request"), "the stuck STK did not read its KILL (expected)");
    check(txt && !strstr(txt, "module ORD did not end on its KILL request") && ord && strstr(ord, ",ORD,module_exit,,,0,status=0 "),
          "ORD ended on its KILL (its module_exit record written, not terminated by the launcher)");
    check(json_number(js, "stuck_releases") >= 1 && json_number(js, "cycles") > 0,
          "ORD wrote its stats at its end, counting STK's stuck release");
    struct stat st;
    check(stat(s.run, &st) != 0, "clean shutdown: no runtime file left in the run directory");
    if (scenario_failed(&s))
        fprintf(stderr, "launcher output (stuck scenario):\n%s\nORD stats: %s\n", txt ? txt : "(none)", js ? js : "(none)");
    free(stk);
    free(ord);
    free(sks);
    free(txt);
    free(js);
}

void scenario_crashed_module(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "crashed")) return;
    const char *const names[] = {"stk/ORD", "SKS", "CRS", NULL};
    s.stop_first = "SKS";
    int launched = scenario_launch(&s, bin, launcher, "SKS.crash()", "1.6", names);
    char *txt = slurp(s.launch), *ord = read_csv_log(&s, "ORD"), *crs = NULL;
    check(!launched && txt && strstr(txt, "module CRS (pid ") && strstr(txt, "died by signal 9"),
          "crashed module: the launcher reports CRS killed (and fails the run)");
    char path[700];
    snprintf(path, sizeof path, "%s/CRS.trace", s.out);
    crs = slurp(path);
    check(crs && count_of(crs, "start ") == 5 && strstr(crs, "killed\n"), "CRS was killed in its 5th release");

    /* ORD's CSV record: `stuck: <sentence> (CRH)`; its stderr line: `STUCK: <sentence>` */
    const char *rec = ord ? strstr(ord, ",scheduler,,,0,stuck: CRS has not finished release #") : NULL;
    char sentence[400] = "", line[450] = "";
    if (rec) {
        rec += strlen(",scheduler,,,0,stuck: ");
        size_t n = strcspn(rec, "\n");
        if (n > 6 && n < sizeof sentence && strncmp(rec + n - 6, " (CRH)", 6) == 0) {
            memcpy(sentence, rec, n - 6);
            sentence[n - 6] = '\0';
        }
    }
    char what[600];
    snprintf(what, sizeof what, "ORD's CSV record says CRS is no longer running (`%s`), without the exec region advice",
             sentence);
    check(strstr(sentence, " periods: it is no longer running (it crashed or was killed)") &&
              !strstr(ord, "does its exec region set"),
          what);
    snprintf(line, sizeof line, "[ORD] STUCK: %s\n", sentence);
    check(sentence[0] && txt && strstr(txt, line), "ORD's stderr line says the same sentence as its CSV record");
    check(txt && !strstr(txt, "module ORD did not end on its KILL request") && ord && strstr(ord, ",ORD,module_exit,,,0,status=0 "),
          "ORD ended on its KILL");
    if (scenario_failed(&s))
        fprintf(stderr, "launcher output (crashed scenario):\n%s\nORD's log:\n%s\n", txt ? txt : "(none)", ord ? ord : "(none)");
    free(crs);
    free(ord);
    free(txt);
}

void scenario_kept_stop(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "kept-stop")) return;
    const char *const names[] = {"stk/ORD", "SKS", "AMS", NULL};
    s.stop_first = "SKS";
    scenario_launch(&s, bin, launcher, "SKS.busy()", "3", names); /* fails: AMS is terminated at the stop */
    char *sks = read_csv_log(&s, "SKS"), *txt = slurp(s.launch);
    long long kept = csv_time_of(sks, NULL, ",module_hold,AMS,,0,last hold dropped (stop kept: its mailbox is full)", NULL);
    long long failed = csv_time_of(sks, NULL, ",supervisor,AMS,,0,error: not sent: STOP request to AMS (kept 2 s for its full mailbox): mailbox full", NULL);
    long long mark = csv_time_of(sks, NULL, ",module_hold,AMS,,0,stop failed: it had been kept for its full mailbox (it still runs)", NULL);
    char what[400];
    snprintf(what, sizeof what,
             "A's undo, the STOP of the busy AMS, was kept (%s), failed %lld ms later tied to its action (%s), and its hold "
             "said it still runs (%s)",
             kept > 0 ? "yes" : "no", kept > 0 && failed > 0 ? (failed - kept) / MS : -1, failed > 0 ? "yes" : "no",
             mark > 0 ? "yes" : "no");
    check(kept > 0 && failed > kept && failed - kept >= 1900 * MS && failed - kept < 2500 * MS && mark >= failed, what);
    check(sks && count_of(sks, "in place of ") >= 1 && count_of(sks, ",setparam_sent,AMS,0,") >= 5,
          "P's values filled AMS's mailbox, the later ones replaced the one kept");
    /* the log said the requests were waiting while they waited: the streak holding the STOP began
       before it was kept, and did not end before its failure */
    const char *at = NULL;
    long long began = -1, ended = -1;
    for (long long t; (t = csv_time_of(sks, at, ",requests_kept,AMS,,0,request=", &at)) > 0 && t <= kept;) began = t;
    at = NULL;
    for (long long t; began > 0 && (t = csv_time_of(sks, at, ",requests_kept_end,AMS,,0,", &at)) > 0;)
        if (t >= began) { ended = t; break; }
    snprintf(what, sizeof what, "SKS's records of its requests kept for AMS: the streak with the STOP began %lld ms before it was kept, "
             "ended %lld ms after it failed", began > 0 ? (kept - began) / MS : -1, ended > 0 ? (ended - failed) / MS : -1);
    check(began > 0 && ended >= failed, what);
    if (scenario_failed(&s))
        fprintf(stderr, "launcher output (kept-stop scenario):\n%s\nSKS's log:\n%s\n", txt ? txt : "(none)", sks ? sks : "(none)");
    free(sks);
    free(txt);
}
