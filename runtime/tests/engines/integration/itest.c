/*
 * itest.c — integration test of the engines with real processes through libmodule and
 * contract-launch. Runs every scenario of itest_scenarios.h in a fresh temporary directory,
 * kept for inspection when a check fails.
 * Usage: itest <dir with the test executables> <contract-launch>. Prints "N passed, N failed".
 * ITEST_ONLY=name[,name…] runs only those scenarios (scheduler, nested, shared, reactivation,
 * toggles, toggles-paused, undo, late-priority, crossed-claims, stuck, crashed, kept-stop, service-stop, output-flood, event-flood): to repeat one that failed, e.g. ITEST_ONLY=toggles in a loop.
 * ITEST_KEEP=1 keeps the directory when every check passed too.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "itest_scenarios.h"
#include "itest_support.h"

typedef void (*ScenarioFn)(const char *root, const char *bin, const char *launcher);

static const struct {
    const char *name;
    ScenarioFn run;
} SCENARIOS[] = {{"scheduler", scenario_scheduler},  {"nested", scenario_nested},
                 {"shared", scenario_shared_module}, {"reactivation", scenario_reactivation},
                 {"toggles", scenario_hold_toggles}, {"toggles-paused", scenario_hold_toggles_paused},
                 {"undo", scenario_undo_own},
                 {"late-priority", scenario_late_priority_answer},
                 {"crossed-claims", scenario_crossed_claims},
                 {"stuck", scenario_stuck_module},
                 {"crashed", scenario_crashed_module},
                 {"kept-stop", scenario_kept_stop},
                 {"service-stop", scenario_service_stop},
                 {"output-flood", scenario_output_flood},
                 {"event-flood", scenario_event_flood}};
#define NSCENARIOS (sizeof SCENARIOS / sizeof SCENARIOS[0])

/* is `name` in the comma-separated list `only` (NULL or empty: every scenario)? */
static int selected(const char *only, const char *name) {
    if (!only || !*only) return 1;
    size_t n = strlen(name);
    for (const char *p = only; *p;) {
        const char *comma = strchr(p, ',');
        size_t l = comma ? (size_t)(comma - p) : strlen(p);
        if (l == n && strncmp(p, name, n) == 0) return 1;
        if (!comma) break;
        p = comma + 1;
    }
    return 0;
}

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: itest <bin dir> <contract-launch>\n");
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    char tmpl[] = "/tmp/contract-engines-itest-XXXXXX";
    char *root = mkdtemp(tmpl);
    if (!root) {
        perror("mkdtemp");
        return 2;
    }
    const char *only = getenv("ITEST_ONLY");
    int ran = 0;
    for (size_t i = 0; i < NSCENARIOS; i++)
        if (selected(only, SCENARIOS[i].name)) {
            SCENARIOS[i].run(root, argv[1], argv[2]);
            ran++;
        }
    if (ran == 0) {
        fprintf(stderr, "ITEST_ONLY=%s names no scenario\n", only);
        return 2;
    }
    if (itest_failed() || getenv("ITEST_KEEP")) {
        fprintf(stderr, "kept %s for inspection\n", root);
    } else {
        char cmd[300];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
        if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", root);
    }
    printf("%d passed, %d failed\n", itest_passed(), itest_failed());
    return itest_failed() ? 1 : 0;
}
