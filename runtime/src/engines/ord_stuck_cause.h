/*
 * ord_stuck_cause.h — why a module has not finished its release, as ORD's stuck report says it.
 *
 * ORD looks at the module's main thread twice (OrdIo.module_activity): half way to the stuck
 * report and at it. From its state then and the CPU time it got in between, the report tells
 * apart three cases that a bare "does its exec region set *stateindex = -1?" mixed up:
 *  - running: it got more CPU time between the looks than one period of its schema (a release
 *    that needs less, as a release of a schema that meets its deadlines does, would have finished
 *    with it), or at least half of a CPU: its exec region loops, or returns without ever setting
 *    *stateindex = -1 (the module calls it again at once);
 *  - waiting (sleeping, blocked): its exec region sleeps, reads, waits on a lock or on a full
 *    mailbox;
 *  - ready to run most of the time but given less CPU than that: starved by processes at
 *    real-time priority or a machine loaded past its CPUs;
 *  - asleep in a write to a full pipe at the last look (its wchan): blocked on its own output,
 *    printed faster than the run's output is read (a printf flood), not looping; or, between the
 *    looks, it wrote ORD_FLOOD_BYTES or more (its io's wchar): a flood whatever the pipe's state;
 * and says a module that has ended (a zombie: "no longer running", as OrdIo.module_gone) or is
 * stopped (SIGSTOP, a debugger).
 * Without both looks (no module_activity, the module's /proc entry unreadable, a release
 * reported before the half-way look) the report keeps the question.
 */
#ifndef CONTRACT_ORD_STUCK_CAUSE_H
#define CONTRACT_ORD_STUCK_CAUSE_H

#include <stddef.h>
#include <stdint.h>

/** One look at a module's main thread: its scheduler state ('R' running or ready, 'S' sleeping,
 *  'D' uninterruptible wait, ...: /proc's letter), the CPU time it has used and the time it has
 *  spent ready to run but waiting for a CPU (-1: unknown), in ns, and the kernel function it
 *  sleeps in (/proc's `wchan`: `anon_pipe_write`, `pipe_write` or `pipe_wait_writable` for a write
 *  to a full pipe; "" when not known or not sleeping). */
typedef struct OrdModuleActivity {
    char state;
    int64_t cpu_ns;
    int64_t wait_ns;
    char waiting_in[32];
    /* the bytes its thread has written (/proc's `io`, wchar: its output, its CSV log, any file),
       -1 when not known */
    int64_t written_bytes;
} OrdModuleActivity;

/** Bytes written between the two looks from which a module is said to print without end (1 MiB:
 *  a period's printf writes far less; a flood, whatever the pipe's state at the look). */
#define ORD_FLOOD_BYTES (1024 * 1024)

/** Whether a look shows the thread asleep in a write to a full pipe (its stdout or stderr, read
 *  by contract-launch: the module prints faster than the run's output is read). Only the kernel's
 *  functions that wait for room in a pipe count (an older kernel's `pipe_wait`, shared by reads
 *  and writes, does not). */
int ord_activity_writing_to_full_pipe(const OrdModuleActivity *a);

/** The advice ORD gives when it cannot tell (no look at the module). */
#define ORD_STUCK_ADVICE "does its exec region set *stateindex = -1?"

/** The cause part of a stuck report (after "after N periods: "), written into buf: from the
 *  look `then` at time then_t and the look `now` at now_t (ns, one clock), for a release of a
 *  schema of period period_ns. then may be NULL (no earlier look) and now NULL (unreadable): the
 *  question ORD_STUCK_ADVICE. Returns buf. */
const char *ord_stuck_cause(const OrdModuleActivity *then, int64_t then_t, const OrdModuleActivity *now,
                            int64_t now_t, int64_t period_ns, char *buf, size_t n);

#endif
