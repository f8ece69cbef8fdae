/*
 * itest_flood.c — scenario 13: ORD's lines on stdout do not flood the run's output (field test:
 * a 55 s run of a 1 ms schema on a loaded machine went past the 1 MiB output limit, ORD writing
 * 99 % of the lines: one `deadline miss: S cycle k (ORD:0)` and one or two `overrun: ...` a cycle).
 * SKS.flood activates FLD (1 ms, critical delay 1 ms) whose FLM takes 3 ms a release: every cycle
 * misses its deadline and overruns. ORD prints each kind of line (numbers aside) at most once a
 * second, then how many it did not print; its CSV log still has every line, and the printed lines
 * plus the counts add up to them.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "itest_scenarios.h"
#include "itest_support.h"

#define MISS_KIND "deadline miss: FLD cycle N (ORD:0)"

/* The lines of `txt` that begin with `prefix`: how many */
static int lines_starting(const char *txt, const char *prefix) {
    int n = 0;
    size_t l = strlen(prefix);
    for (const char *line = txt; line && *line;) {
        if (strncmp(line, prefix, l) == 0) n++;
        const char *end = strchr(line, '\n');
        line = end ? end + 1 : NULL;
    }
    return n;
}

/* The sum of the counts of ORD's summary lines of kind `kind`, and how many there are in *lines */
static long summarised(const char *txt, const char *kind, int *lines) {
    long sum = 0;
    *lines = 0;
    const char *lead = "[ORD] (the same line ";
    for (const char *p = txt ? strstr(txt, lead) : NULL; p; p = strstr(p + 1, lead)) {
        const char *end = strchr(p, '\n');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        char line[512];
        snprintf(line, sizeof line, "%.*s", (int)len, p);
        char tail[256];
        int tl = snprintf(tail, sizeof tail, "in the CSV log only: %s)", kind);
        if (len < (size_t)tl || strcmp(line + len - (size_t)tl, tail) != 0) continue;
        sum += atol(line + strlen(lead));
        (*lines)++;
    }
    return sum;
}

void scenario_output_flood(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "output-flood")) return;
    const char *const names[] = {"stk/ORD", "SKS", "FLM", NULL};
    s.stop_first = "SKS";
    check(scenario_launch(&s, bin, launcher, "SKS.flood()", "2", names), "output flood: architecture ran and stopped");
    char *txt = slurp(s.launch), *ord = read_csv_log(&s, "ORD"), *js = slurp(s.stats);

    int csv_misses = count_of(ord, ",scheduler,,,0,deadline miss: FLD cycle ");
    long stat_misses = json_number(js, "deadline_misses");
    char what[600];
    snprintf(what, sizeof what, "FLD missed its deadline at nearly every cycle: %d in ORD's CSV log (its stats: %ld, at least 100)",
             csv_misses, stat_misses);
    check(csv_misses >= 100 && csv_misses == stat_misses, what);

    /* stdout: each kind at most once a second (2 s of run: 3 prints, with the stop's), then its count */
    int printed = lines_starting(txt, "[ORD] deadline miss: FLD cycle "), summaries = 0;
    long counted = summarised(txt, MISS_KIND, &summaries);
    int ord_lines = lines_starting(txt, "[ORD] ");
    snprintf(what, sizeof what,
             "ORD printed %d deadline-miss lines (at most 4) and %d summaries of them (at least 1) counting %ld more: "
             "%ld in all, the CSV log's %d; %d [ORD] lines in all (at most 40)",
             printed, summaries, counted, printed + counted, csv_misses, ord_lines);
    check(printed >= 1 && printed <= 4 && summaries >= 1 && printed + counted == csv_misses && ord_lines <= 40, what);
    check(txt && strstr(txt, "[ORD] overrun: FLD cycle still running (FLM), release skipped\n") &&
              strstr(txt, "in the CSV log only: overrun: FLD cycle still running (FLM), release skipped)\n"),
          "ORD's overrun lines are summarised the same way");
    if (scenario_failed(&s)) say_output_tail("output-flood", txt, 4000);
    free(txt);
    free(ord);
    free(js);
}
