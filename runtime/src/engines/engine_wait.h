/*
 * engine_wait.h — the engines' only blocking point: wait for a request in the mailbox or for
 * an absolute CLOCK_MONOTONIC deadline, whichever comes first (timerfd armed with
 * TFD_TIMER_ABSTIME + poll on the mailbox fd; no sleep loop, no busy wait).
 */
#ifndef CONTRACT_ENGINE_WAIT_H
#define CONTRACT_ENGINE_WAIT_H

#include <stdint.h>

#include "libmodule/libmodule.h"

/** Returns 1 (a request is in *m), 0 (the deadline passed; INT64_MAX = none), -1 (a fatal
 *  error, reported on stderr: the engine should end). Interruptions by signals are retried. */
int engine_wait(RequestMessage *m, int64_t deadline);

/** The deadlines of an engine's core (ord_core / sup_core): when the next one is due (0 and
 *  INT64_MAX when none) and how to fire the ones due at t. */
typedef struct EngineClock {
    void *core;
    int (*next_deadline)(const void *core, int64_t *deadline);
    void (*advance)(void *core, int64_t t);
} EngineClock;

/** The engines' main-loop step: waits, firing the core's deadlines as they come due, until a
 *  request arrives. Returns 1 (the request in *m, its name fields NUL-terminated, *now = the
 *  time it was read) or -1 (a fatal error of engine_wait: the engine should end). */
int engine_next_request(RequestMessage *m, const EngineClock *clock, int64_t *now);

#endif
