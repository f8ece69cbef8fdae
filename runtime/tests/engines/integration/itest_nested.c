/*
 * itest_nested.c — scenario 2 (inest.c, amod.c): GLT activates SLV.work, which runs an event
 * schema with the asynchronous AMX, ends on its third event, notifies GLT, which stops SLV.work.
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "itest_scenarios.h"
#include "itest_support.h"

/* `trace` is `head`, then only further posts of the same step (AMX posts every 10 ms until the
   STOP reaches it: a supervisor the machine stalled past 10 ms lets it post once more), then
   "stop". */
static int posts_then_stop(const char *trace, const char *head, long step) {
    size_t n = strlen(head);
    if (strncmp(trace, head, n) != 0) return 0;
    long last = 0;
    for (const char *p = head; (p = strstr(p, "post ")) != NULL; p += 5) last = strtol(p + 5, NULL, 10);
    const char *p = trace + n;
    long v;
    int used;
    while (sscanf(p, "post %ld\n%n", &v, &used) == 1 && used > 0) {
        if (v != last + step) return 0;
        last = v;
        p += used;
    }
    return strcmp(p, "stop\n") == 0;
}

void scenario_nested(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "nested")) return;
    const char *const names[] = {"GLT", "SLV", "AMX", NULL};
    check(scenario_launch(&s, bin, launcher, "GLT.top()", "0.5", names),
          "nested supervisors: architecture ran and stopped cleanly");
    char path[600];
    snprintf(path, sizeof path, "%s/AMX.trace", s.out);
    char *amx = slurp(path);
    char *slv = read_csv_log(&s, "SLV");
    check(amx && posts_then_stop(amx, "param 2\nstart\npost 2\npost 4\npost 6\n", 2) && slv &&
              strstr(slv, ",work.W1 inactive cause=AMX:0 value=6\n"),
          "event schema: AMX parameterised (GLT's value through SLV's local), started, stopped after W1, "
          "which ended on AMX's 6");
    char *txt = slurp(s.launch);
    const char *order[] = {"[GLT] rule top.T1 active", "[SLV] function work(n = 2) started", "[SLV] rule work.W1 active",
                           "[SLV] rule work.W1 inactive", "[SLV] rule work.W2 active",
                           "[SLV] function work stopped", NULL};
    int in_order = txt != NULL;
    const char *at = txt;
    for (int i = 0; order[i] && in_order; i++) {
        const char *p = strstr(at, order[i]);
        if (!p) in_order = 0;
        else at = p;
    }
    check(in_order, "SLV.work started by GLT, W1 -> W2 on endof, stopped by GLT");
    check(txt && strstr(txt, "[GLT] rule top.T1 inactive"), "SLV's notify reached GLT (T1 ended)");
    /* each event a supervisor took is recorded with its value and the rule changes it made:
       AMX's 2 and 4 changed no rule (W1 waits for ev > 5), its 6 ended W1 (and started W2) */
    char *glt = read_csv_log(&s, "GLT");
    check(slv && strstr(slv, ",SLV,event_received,AMX,0,") && strstr(slv, " rules=0 value=2\n") &&
              strstr(slv, " rules=0 value=4\n") && strstr(slv, " value=6\n") && !strstr(slv, " rules=0 value=6\n") &&
              glt && strstr(glt, ",GLT,event_received,SLV,0,") && strstr(glt, " value=\"\"finished\"\"\"\n") &&
              !strstr(glt, " rules=0 value=\"\"finished"),
          "event received: SLV's records of AMX's events say their values and what they changed (rules=0 for 2 "
          "and 4, not for 6), GLT's of SLV's \"finished\" (a string, CSV-quoted)");
    free(glt);
    if (scenario_failed(&s)) fprintf(stderr, "launcher output (nested scenario):\n%s\n", txt ? txt : "(none)");
    free(amx);
    free(slv);
    free(txt);
}
