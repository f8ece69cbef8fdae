/* engine_wait.c — see engine_wait.h. */
#define _GNU_SOURCE
#include "engine_wait.h"
#include "engine_wire.h"

#include <errno.h>
#include <poll.h>
#include <stdio.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/timerfd.h>
#include <time.h>
#include <unistd.h>

static int timer_fd = -1;

#define IDLE_FLUSH_SLACK_NS 200000LL  /* flush the CSV log only with this much time to spare */
#define IDLE_FLUSH_AGE_NS 25000000LL  /* ... at 25 ms boundaries (library: 50 ms), or the library's when watched (25 ms) */

static int ensure_timer(void) {
    if (timer_fd >= 0) return 0;
    timer_fd = timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC | TFD_NONBLOCK);
    if (timer_fd < 0) {
        fprintf(stderr, "%s: timerfd_create: %s\n", ContractSelfName(), strerror(errno));
        return -1;
    }
    prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0); /* wake at the deadline, not up to 50 us later */
    return 0;
}

int engine_wait(RequestMessage *m, int64_t deadline) {
    if (ensure_timer() != 0) return -1;
    for (;;) {
        if (WaitForRequestUntil(m, 0) == 1) return 1; /* (no read-ahead: an engine is never busy long) */
        if (deadline != INT64_MAX && GetTime() >= deadline) return 0;
        /* Write the CSV log while idle with time to spare (>= 200 us before the deadline), so
           that it is never written between a wake-up and the releases it is for. */
        RTIME delay = ContractLogFlushDelay();
        if (delay > IDLE_FLUSH_AGE_NS) delay = IDLE_FLUSH_AGE_NS;
        if (deadline == INT64_MAX || deadline - GetTime() >= IDLE_FLUSH_SLACK_NS) {
            ContractLogFlushIfDue(GetTime(), delay);
        }
        /* Records still buffered (their flush boundary not reached) must not wait for the next
           request, which may come seconds later: wake at the boundary (unless that is too close
           to the deadline), so that the log on disk — the live trace — lags at most about `delay`. */
        int64_t wake = deadline;
        /* requests kept for a full mailbox (a supervisor's: ContractSetQueuedSends) are tried
           again every 5 ms (the call above, WaitForRequestUntil, may have just tried them: then
           this only says when next), and wake it while they wait */
        RTIME retry = ContractRetryQueuedSends();
        if (retry && (int64_t)retry < wake) wake = (int64_t)retry;
        RTIME due = ContractLogFlushDue(delay);
        if (due && (int64_t)due < wake && (deadline == INT64_MAX || deadline - (int64_t)due >= IDLE_FLUSH_SLACK_NS)) wake = (int64_t)due;
        struct itimerspec its;
        memset(&its, 0, sizeof its);
        if (wake != INT64_MAX) {
            its.it_value.tv_sec = (time_t)(wake / 1000000000LL);
            its.it_value.tv_nsec = (long)(wake % 1000000000LL);
        }
        if (timerfd_settime(timer_fd, TFD_TIMER_ABSTIME, &its, NULL) != 0) {
            fprintf(stderr, "%s: timerfd_settime: %s\n", ContractSelfName(), strerror(errno));
            return -1;
        }
        struct pollfd p[2] = {{MailboxFd(), POLLIN, 0}, {timer_fd, POLLIN, 0}};
        int r = poll(p, 2, -1);
        if (r < 0) {
            if (errno == EINTR) continue;
            return -1;
        }
        if (p[0].revents & (POLLERR | POLLNVAL)) {
            fprintf(stderr, "%s: the mailbox is no longer readable\n", ContractSelfName());
            return -1;
        }
        if (p[1].revents & POLLIN) {
            uint64_t expirations;
            if (read(timer_fd, &expirations, sizeof expirations) < 0 && errno != EAGAIN) return -1;
        }
    }
}

int engine_next_request(RequestMessage *m, const EngineClock *clock, int64_t *now) {
    for (;;) {
        int64_t deadline = INT64_MAX;
        clock->next_deadline(clock->core, &deadline);
        int got = engine_wait(m, deadline);
        *now = GetTime();
        if (got < 0) return -1;
        if (got == 0) {
            clock->advance(clock->core, *now);
            continue;
        }
        engine_terminate_names(m);
        return 1;
    }
}
