/*
 * platform_probe.h — the machine's own timer floor, measured while the scheduler benchmark runs.
 *
 * A child process pinned to one CPU, at SCHED_FIFO above every process of the architecture
 * (locked memory, PM QoS 0 us when root), sleeps to absolute ticks every PROBE_TICK_NS with
 * clock_nanosleep and records when it woke and how late. It does nothing else (~2 us of CPU a
 * tick), so a late wake-up means the CPU itself was not available: the hypervisor ran something
 * else, or the kernel did. The benchmark uses the trace to tell missed periods that fall in such a
 * stall from the others.
 */
#ifndef CONTRACT_PLATFORM_PROBE_H
#define CONTRACT_PLATFORM_PROBE_H

#include <sys/types.h>

#define PROBE_TICK_NS 250000LL

typedef struct {
    long long *wake; /* CLOCK_MONOTONIC ns of each wake-up */
    long long *late; /* ns after its tick */
    int n;
} ProbeTrace;

/** Starts the probe for `ticks` ticks on `cpu` at SCHED_FIFO `prio` (best effort); it writes its
 *  trace to `path` when done. Returns its pid, or -1. */
pid_t probe_start(int cpu, int prio, int ticks, const char *path);
/** Waits for the probe and reads its trace. 0, or -1. */
int probe_finish(pid_t pid, const char *path, ProbeTrace *t);
void probe_free(ProbeTrace *t);
/** p50, p99, max lateness (us) and the number of wake-ups more than 100 us late. */
void probe_summary(const ProbeTrace *t, double out[4]);
/** 1 if the probe woke at least `min_late_ns` late at some time in [when - before_ns, when + after_ns]. */
int probe_stalled_near(const ProbeTrace *t, long long when, long long before_ns, long long after_ns,
                       long long min_late_ns);

#endif
