/* Fixed priorities: SCHED_FIFO when permitted, otherwise one warning and a nice level. */
#define _GNU_SOURCE
#include <errno.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include "internal.h"

int ContractSetPriority(int priority)
{
    if (priority < 1) priority = 1;
    if (priority > 99) priority = 99;
    const char *mode = getenv("CONTRACT_SCHED");
    int want_fifo = !(mode && strcmp(mode, "other") == 0);
    char detail[96];
    if (want_fifo) {
        struct sched_param sp;
        memset(&sp, 0, sizeof sp);
        sp.sched_priority = priority;
        if (sched_setscheduler(0, SCHED_FIFO | SCHED_RESET_ON_FORK, &sp) == 0) {
            snprintf(detail, sizeof detail, "SCHED_FIFO %d", priority);
            ContractLog("priority", "", -1, 0, detail);
            return 1;
        }
    }
    int err = errno;
    /* higher priority = lower nice value; 99 -> 0, 1 -> 19 (unprivileged processes may only raise nice) */
    int nice_level = (99 - priority) * 19 / 98;
    int ok = setpriority(PRIO_PROCESS, 0, nice_level) == 0;
    if (want_fifo)
        fprintf(stderr, "%s: warning: SCHED_FIFO not permitted (%s): priority %d runs as nice %d%s\n",
                g_rt.name[0] ? g_rt.name : "libmodule", strerror(err), priority, nice_level,
                ok ? "" : " (could not set it either)");
    snprintf(detail, sizeof detail, "nice %d (priority %d)", nice_level, priority);
    ContractLog("priority", "", -1, 0, detail);
    return 0;
}
