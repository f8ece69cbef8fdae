/*
 * ord_stuck_cause.c — the cause part of ORD's stuck report (ord_stuck_cause.h).
 */
#include "ord_stuck_cause.h"

#include <stdio.h>
#include <string.h>

/* a thread that runs at least this share of the wall time is running its code, not starved; one
   ready to run (running or waiting for a CPU) that long wants the CPU */
#define RUNNING_SHARE_PERCENT 50

#define WAITING "it is waiting, not running (a sleep, a read, a lock or a send to a full mailbox in its exec region?)"

#define WRITING_OUTPUT                                                                                         \
    "it is blocked writing its output: the pipe is full (it prints faster than the run's output is read): does " \
    "its exec region print too much?"

int ord_activity_writing_to_full_pipe(const OrdModuleActivity *a) {
    if (!a || (a->state != 'S' && a->state != 'D')) return 0;
    /* the kernel's names for a writer waiting for room in a pipe: pipe_write (up to 6.x),
       anon_pipe_write (6.15 on), pipe_wait_writable (5.6 on, when not inlined) */
    return strcmp(a->waiting_in, "pipe_write") == 0 || strcmp(a->waiting_in, "anon_pipe_write") == 0 ||
           strcmp(a->waiting_in, "pipe_wait_writable") == 0;
}

static long percent_of(int64_t part, int64_t whole) {
    return part >= whole ? 100 : (long)(part * 100 / whole);
}

const char *ord_stuck_cause(const OrdModuleActivity *then, int64_t then_t, const OrdModuleActivity *now,
                            int64_t now_t, int64_t period_ns, char *buf, size_t n) {
    if (!now) {
        snprintf(buf, n, "%s", ORD_STUCK_ADVICE);
        return buf;
    }
    if (now->state == 'Z' || now->state == 'X') {
        snprintf(buf, n, "it is no longer running (it crashed or was killed)");
        return buf;
    }
    if (now->state == 'T' || now->state == 't') {
        snprintf(buf, n, "it is stopped (by SIGSTOP, or a debugger holds it)");
        return buf;
    }
    if (ord_activity_writing_to_full_pipe(now)) {
        snprintf(buf, n, "%s", WRITING_OUTPUT);
        return buf;
    }
    int64_t wall = now_t - then_t;
    if (then && wall > 0 && then->written_bytes >= 0 && now->written_bytes - then->written_bytes >= ORD_FLOOD_BYTES) {
        snprintf(buf, n,
                 "it prints without end (%.1f MiB written in the last %.1f s): does its exec region print too much, "
                 "or loop printing?",
                 (double)(now->written_bytes - then->written_bytes) / (1024.0 * 1024.0), (double)wall / 1e9);
        return buf;
    }
    int compared = then && wall > 0 && now->cpu_ns >= then->cpu_ns;
    if (!compared) {
        if (now->state == 'S' || now->state == 'D')
            snprintf(buf, n, "%s", WAITING);
        else
            snprintf(buf, n, "%s", ORD_STUCK_ADVICE);
        return buf;
    }
    int64_t cpu = now->cpu_ns - then->cpu_ns;
    long ran = percent_of(cpu, wall);
    double seconds = (double)wall / 1e9;
    /* ready to run while not running: known when both looks read it */
    int wait_known = then->wait_ns >= 0 && now->wait_ns >= then->wait_ns;
    long wanted = wait_known ? ran + percent_of(now->wait_ns - then->wait_ns, wall) : -1;
    /* more CPU than a period of its schema and not done: no starvation explains it (a loaded
       machine or the real-time budget may hold a loop under half a CPU) */
    if (ran >= RUNNING_SHARE_PERCENT || (period_ns > 0 && cpu > period_ns))
        snprintf(buf, n,
                 "does its exec region loop, or never set *stateindex = -1? (its thread got %ld%% of a CPU in the "
                 "last %.1f s, more than a period needs; a loaded machine gives it less)",
                 ran, seconds);
    else if (wanted >= RUNNING_SHARE_PERCENT || (!wait_known && now->state != 'S' && now->state != 'D'))
        snprintf(buf, n, "it wanted the CPU but got only %ld%% of it in the last %.1f s: do processes at real-time "
                         "priority or an overloaded machine starve it, or does its exec region loop?", ran, seconds);
    else
        snprintf(buf, n, "%s", WAITING);
    return buf;
}
