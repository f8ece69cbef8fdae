/*
 * itest_share.c — scenario 3 (ishare.c, amod.c): two supervisors SHA and SHB use AMX through
 * event schemas: AMX is started once, survives the end of SHA's schema and is stopped at the
 * end of SHB's; no hold file is left.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "itest_scenarios.h"
#include "itest_support.h"

void scenario_shared_module(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "shared")) return;
    const char *const names[] = {"SHA", "SHB", "AMX", NULL};
    check(scenario_launch(&s, bin, launcher, "SHA.top()", "0.5", names),
          "shared module: architecture ran and stopped cleanly");
    char path[600];
    snprintf(path, sizeof path, "%s/AMX.trace", s.out);
    char *amx = slurp(path);
    int starts = 0, stops = 0, posts = 0;
    for (const char *p = amx; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : "") {
        if (strncmp(p, "start\n", 6) == 0) starts++;
        else if (strncmp(p, "stop\n", 5) == 0) stops++;
        else if (strncmp(p, "post ", 5) == 0) posts++;
    }
    check(starts == 1, "AMX started once: SHB found it running (started by SHA) and did not start it again");
    /* SHA's schema ends at 150 ms (~14 posts), SHB's at ~320 ms (~31 posts) */
    check(stops == 1 && posts >= 22 && posts <= 45,
          "AMX kept running after SHA's schema ended, stopped once when SHB's (its last user) ended");
    char *txt = slurp(s.launch);
    check(txt && strstr(txt, "[SHA] rule top.A1 inactive") && strstr(txt, "[SHB] rule use.B1 inactive"),
          "both schemas were activated and deactivated");
    struct stat st;
    check(stat(s.run, &st) != 0, "no hold file (or other runtime file) left in the run directory");
    if (scenario_failed(&s))
        fprintf(stderr, "launcher output (shared module scenario):\n%s\nAMX trace:\n%s\n", txt ? txt : "(none)",
                amx ? amx : "(none)");
    free(amx);
    free(txt);
}
