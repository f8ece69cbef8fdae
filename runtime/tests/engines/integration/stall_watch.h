/*
 * stall_watch.h — a witness of the machine's stalls during a scenario, independent of the
 * architecture under test: one thread per CPU (pinned to it, SCHED_FIFO 99 when allowed) wakes at
 * absolute 1 ms ticks and records every wake-up later than STALL_WATCH_LATE_NS. A timing check
 * can then tell a release the runtime made late from one the machine (a loaded CI host, a stolen
 * virtual CPU) delayed for every process at once.
 */
#ifndef STALL_WATCH_H
#define STALL_WATCH_H

/** A wake-up at least this late counts as a stall of the machine. */
#define STALL_WATCH_LATE_NS 1000000LL

/** Starts the watch threads (CLOCK_MONOTONIC). Returns the number of CPUs watched (0: none). */
int stall_watch_start(void);
/** Stops and joins them; the stalls recorded stay readable until the next start. */
void stall_watch_stop(void);
/** 1 if a CPU was stalled (a late wake-up's interval [due, woke] meets [from, to]). */
int stall_watch_between(long long from, long long to);
/** Number of stalls recorded, over every CPU. */
int stall_watch_count(void);

#endif
