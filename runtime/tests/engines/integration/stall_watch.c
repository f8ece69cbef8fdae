/* stall_watch.c — see stall_watch.h. */
#define _GNU_SOURCE
#include "stall_watch.h"

#include <pthread.h>
#include <sched.h>
#include <stdatomic.h>
#include <time.h>
#include <unistd.h>

enum { MAX_CPUS = 16, MAX_STALLS = 4096 };

typedef struct Watcher {
    pthread_t thread;
    int cpu;
    int n; /* stalls recorded (owned by the thread until joined) */
    long long due[MAX_STALLS], woke[MAX_STALLS];
} Watcher;

static Watcher watchers[MAX_CPUS];
static int nwatchers;
static atomic_int stopping;

static long long now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (long long)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

static void *watch(void *arg) {
    Watcher *w = arg;
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(w->cpu, &set);
    (void)pthread_setaffinity_np(pthread_self(), sizeof set, &set);
    struct sched_param sp = {.sched_priority = 99};
    (void)pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp); /* refused without privilege */
    long long due = now_ns();
    while (!atomic_load(&stopping)) {
        due += 1000000LL;
        struct timespec ts = {.tv_sec = due / 1000000000LL, .tv_nsec = due % 1000000000LL};
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL) != 0) {
        }
        long long woke = now_ns();
        if (woke - due >= STALL_WATCH_LATE_NS && w->n < MAX_STALLS) {
            w->due[w->n] = due;
            w->woke[w->n] = woke;
            w->n++;
        }
        if (woke - due > 1000000LL) due = woke; /* no burst of catch-up wake-ups after a stall */
    }
    return NULL;
}

int stall_watch_start(void) {
    long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    if (cpus < 1) cpus = 1;
    if (cpus > MAX_CPUS) cpus = MAX_CPUS;
    atomic_store(&stopping, 0);
    nwatchers = 0;
    for (int c = 0; c < cpus; c++) {
        Watcher *w = &watchers[nwatchers];
        w->cpu = c;
        w->n = 0;
        if (pthread_create(&w->thread, NULL, watch, w) == 0) nwatchers++;
    }
    return nwatchers;
}

void stall_watch_stop(void) {
    atomic_store(&stopping, 1);
    for (int i = 0; i < nwatchers; i++) pthread_join(watchers[i].thread, NULL);
}

int stall_watch_between(long long from, long long to) {
    for (int i = 0; i < nwatchers; i++)
        for (int k = 0; k < watchers[i].n; k++)
            if (watchers[i].due[k] <= to && watchers[i].woke[k] >= from) return 1;
    return 0;
}

int stall_watch_count(void) {
    int n = 0;
    for (int i = 0; i < nwatchers; i++) n += watchers[i].n;
    return n;
}
