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

#endif
