/* Fixed priorities: SCHED_FIFO when permitted, otherwise a nice level. At start-up
 * (ContractSetPriority) a refused SCHED_FIFO is said once on stderr; later changes asked by a
 * supervisor (REQ_PRIORITY, ContractSetModulePriority) are applied by the module to itself and
 * answered, the requester decides what to say. */
#define _GNU_SOURCE
#include <errno.h>
#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>
#include "internal.h"

#if defined(__SANITIZE_ADDRESS__)
#define RT_SANITIZED 1 /* ASan reserves terabytes of shadow memory: never lock it */
#else
#define RT_SANITIZED 0
#endif

static int clamp(int priority) { return priority < 1 ? 1 : priority > 99 ? 99 : priority; }

/* higher priority = lower nice value; 99 -> 0, 1 -> 19 */
static int nice_of(int priority) { return (99 - priority) * 19 / 98; }

static int fifo_wanted(void)
{
    const char *mode = getenv("CONTRACT_SCHED");
    return !(mode && strcmp(mode, "other") == 0);
}

static int try_fifo(int priority)
{
    struct sched_param sp;
    memset(&sp, 0, sizeof sp);
    sp.sched_priority = priority;
    return sched_setscheduler(0, SCHED_FIFO | SCHED_RESET_ON_FORK, &sp) == 0;
}


int ContractPriority(void) { return g_rt.priority; }

/* $CONTRACT_REQUIRE_REALTIME=1 (`make run REQUIRE_REALTIME=1`): a module refused SCHED_FIFO at its
 * priority does not run at a nice level instead: it says how to grant it and ends (status 2),
 * before it is ready, and contract-launch stops the run without its start (docs/deploying.md). */
int rt_realtime_required(void)
{
    const char *v = getenv(CONTRACT_REQUIRE_REALTIME_ENV);
    return v && strcmp(v, "1") == 0;
}

int ContractSetPriority(int priority)
{
    priority = clamp(priority);
    int want_fifo = fifo_wanted();
    char detail[96];
    if (want_fifo && try_fifo(priority)) {
        g_rt.priority = priority;
        snprintf(detail, sizeof detail, "SCHED_FIFO %d", priority);
        ContractLog("priority", "", -1, 0, detail);
        return 1;
    }
    int err = errno;
    if (want_fifo && rt_realtime_required()) {
        struct rlimit rl;
        char limit[48] = "";
        if (getrlimit(RLIMIT_RTPRIO, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
            snprintf(limit, sizeof limit, " (RLIMIT_RTPRIO is %llu)", (unsigned long long)rl.rlim_cur);
        fprintf(stderr, "%s: error: SCHED_FIFO priority %d not permitted (%s)%s and real-time is required (%s=1): "
                "not starting. %s\n", g_rt.name[0] ? g_rt.name : "libmodule", priority, strerror(err), limit,
                CONTRACT_REQUIRE_REALTIME_ENV, CONTRACT_REALTIME_HOWTO);
        ContractLog("priority", "", -1, 0, "SCHED_FIFO refused: real-time required, not starting");
        exit(2);
    }
    int nice_level = nice_of(priority);
    int ok = setpriority(PRIO_PROCESS, 0, nice_level) == 0;
    g_rt.priority = priority;
    if (want_fifo)
        fprintf(stderr, "%s: warning: SCHED_FIFO not permitted (%s): priority %d runs as nice %d%s\n",
                g_rt.name[0] ? g_rt.name : "libmodule", strerror(err), priority, nice_level,
                ok ? "" : " (could not set it either)");
    snprintf(detail, sizeof detail, "nice %d (priority %d)", nice_level, priority);
    ContractLog("priority", "", -1, 0, detail);
    return 0;
}

int rt_apply_priority(int priority, const char *requester)
{
    priority = clamp(priority);
    char detail[128];
    int before = g_rt.priority;
    if (fifo_wanted() && try_fifo(priority)) {
        g_rt.priority = priority;
        snprintf(detail, sizeof detail, "SCHED_FIFO %d (was %d)", priority, before);
        ContractLog("priority_changed", requester, -1, 0, detail);
        return 1;
    }
    /* A process under SCHED_FIFO that may not use it any more is not expected; under
     * SCHED_OTHER the nice level carries the priority. Raising it (a lower nice) needs
     * CAP_SYS_NICE or RLIMIT_NICE: refused, the process keeps its priority. */
    int nice_level = nice_of(priority);
    if (sched_getscheduler(0) == SCHED_OTHER && setpriority(PRIO_PROCESS, 0, nice_level) != 0) {
        int err = errno;
        snprintf(detail, sizeof detail, "priority %d (nice %d) refused: %s; stays %d", priority, nice_level,
                 strerror(err), before);
        ContractLog("priority_changed", requester, -1, 0, detail);
        errno = err;
        return CONTRACT_EPERM;
    }
    if (sched_getscheduler(0) != SCHED_OTHER) {
        errno = EPERM;
        snprintf(detail, sizeof detail, "priority %d refused: SCHED_FIFO not permitted any more; stays %d",
                 priority, before);
        ContractLog("priority_changed", requester, -1, 0, detail);
        return CONTRACT_EPERM;
    }
    g_rt.priority = priority;
    snprintf(detail, sizeof detail, "nice %d (priority %d, was %d)", nice_level, priority, before);
    ContractLog("priority_changed", requester, -1, 0, detail);
    return 0;
}

/* Prefault this much stack: the first touch of a stack page is a page fault (µs to ms on a VM). */
#define PREFAULT_STACK_BYTES (256 * 1024)

static void __attribute__((noinline)) prefault_stack(void)
{
    volatile unsigned char stack[PREFAULT_STACK_BYTES];
    for (size_t i = 0; i < sizeof stack; i += 4096) stack[i] = 0;
}

int rt_lock_memory(void)
{
    const char *env = getenv("CONTRACT_MLOCK");
    if (RT_SANITIZED || (env && strcmp(env, "0") == 0)) return 0;
    /* An unprivileged module (SCHED_FIFO through RLIMIT_RTPRIO or an inherited start: the build
     * service's real-time mode, docs/sandbox.md) has a finite RLIMIT_MEMLOCK: with MCL_FUTURE every
     * later allocation past it would fail, so it locks what it has only. */
    struct rlimit memlock;
    int future = geteuid() == 0 || (getrlimit(RLIMIT_MEMLOCK, &memlock) == 0 && memlock.rlim_cur == RLIM_INFINITY);
    if (mlockall(MCL_CURRENT | (future ? MCL_FUTURE : 0)) != 0) {
        char detail[96];
        snprintf(detail, sizeof detail, "mlockall not permitted (%s): memory may page-fault", strerror(errno));
        ContractLog("memory_lock", "", -1, 0, detail);
        return 0;
    }
    prefault_stack();
    ContractLog("memory_lock", "", -1, 0,
                future ? "mlockall(MCL_CURRENT|MCL_FUTURE), 256 KiB of stack prefaulted"
                       : "mlockall(MCL_CURRENT) (RLIMIT_MEMLOCK finite: later allocations not locked), 256 KiB of stack prefaulted");
    return 1;
}
