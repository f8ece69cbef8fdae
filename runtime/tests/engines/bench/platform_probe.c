/* platform_probe.c — see platform_probe.h. */
#define _GNU_SOURCE
#include "platform_probe.h"
#include "rt_placement.h"

#include <sched.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static long long mono_ns(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (long long)t.tv_sec * 1000000000LL + t.tv_nsec;
}

static void probe_run(int cpu, int prio, int ticks, const char *path) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    sched_setaffinity(0, sizeof set, &set);
    char err[256];
    int qos = rt_hold_pm_qos(0, err, sizeof err); /* as contract-launch --pm-qos-us 0; -1 if not root */
    struct sched_param sp = {.sched_priority = prio};
    sched_setscheduler(0, SCHED_FIFO, &sp);
    long long *rec = calloc((size_t)ticks * 2, sizeof *rec);
    if (!rec) _exit(1);
    mlockall(MCL_CURRENT | MCL_FUTURE);
    long long t = mono_ns() + PROBE_TICK_NS;
    for (int i = 0; i < ticks; i++, t += PROBE_TICK_NS) {
        struct timespec ts = {(time_t)(t / 1000000000LL), (long)(t % 1000000000LL)};
        clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL);
        long long now = mono_ns();
        rec[2 * i] = now;
        rec[2 * i + 1] = now - t;
        if (now - t > PROBE_TICK_NS) t += (now - t) / PROBE_TICK_NS * PROBE_TICK_NS; /* no burst after a stall */
    }
    if (qos >= 0) close(qos);
    FILE *f = fopen(path, "wb");
    int ok = f && fwrite(rec, sizeof *rec, (size_t)ticks * 2, f) == (size_t)ticks * 2;
    if (f && fclose(f) != 0) ok = 0;
    _exit(ok ? 0 : 1);
}

pid_t probe_start(int cpu, int prio, int ticks, const char *path) {
    pid_t pid = fork();
    if (pid == 0) probe_run(cpu, prio, ticks, path);
    return pid;
}

int probe_finish(pid_t pid, const char *path, ProbeTrace *t) {
    memset(t, 0, sizeof *t);
    int st = 0;
    if (pid <= 0 || waitpid(pid, &st, 0) != pid || !WIFEXITED(st) || WEXITSTATUS(st) != 0) return -1;
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    int n = (int)(size / (long)(2 * sizeof(long long)));
    long long *rec = n > 0 ? malloc((size_t)n * 2 * sizeof *rec) : NULL;
    int ok = rec && fread(rec, 2 * sizeof *rec, (size_t)n, f) == (size_t)n;
    fclose(f);
    if (!ok) {
        free(rec);
        return -1;
    }
    t->wake = malloc((size_t)n * sizeof *t->wake);
    t->late = malloc((size_t)n * sizeof *t->late);
    if (!t->wake || !t->late) {
        free(rec);
        probe_free(t);
        return -1;
    }
    for (int i = 0; i < n; i++) {
        t->wake[i] = rec[2 * i];
        t->late[i] = rec[2 * i + 1];
    }
    t->n = n;
    free(rec);
    return 0;
}

void probe_free(ProbeTrace *t) {
    free(t->wake);
    free(t->late);
    memset(t, 0, sizeof *t);
}

static int cmp_ll(const void *a, const void *b) {
    long long x = *(const long long *)a, y = *(const long long *)b;
    return (x > y) - (x < y);
}

void probe_summary(const ProbeTrace *t, double out[4]) {
    out[0] = out[1] = out[2] = -1;
    out[3] = 0;
    if (t->n <= 0) return;
    long long *s = malloc((size_t)t->n * sizeof *s);
    if (!s) return;
    memcpy(s, t->late, (size_t)t->n * sizeof *s);
    qsort(s, (size_t)t->n, sizeof *s, cmp_ll);
    for (int i = 0; i < t->n; i++)
        if (s[i] > 100000) out[3]++;
    out[0] = (double)s[t->n / 2] / 1e3;
    out[1] = (double)s[(t->n - 1) * 99 / 100] / 1e3;
    out[2] = (double)s[t->n - 1] / 1e3;
    free(s);
}

int probe_stalled_near(const ProbeTrace *t, long long when, long long before_ns, long long after_ns,
                       long long min_late_ns) {
    for (int i = 0; i < t->n; i++)
        if (t->wake[i] >= when - before_ns && t->wake[i] <= when + after_ns && t->late[i] >= min_late_ns) return 1;
    return 0;
}
