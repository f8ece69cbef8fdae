/* The outbox: requests kept for a receiver whose mailbox is full, in a process that asked for
 * queued sends (ContractSetQueuedSends: the supervisors). Such a request is neither waited for
 * (the process would read nothing meanwhile: its timers late, its own mailbox filling, the
 * modules that post events to it waiting in turn) nor dropped (a supervisor's request is a
 * one-off transition nothing repeats). It is kept, in order, and sent again while the process
 * waits for requests (WaitForRequestUntil, an engine's wait: ContractRetryQueuedSends), every
 * OUTBOX_RETRY_NS (a call before that tries nothing), until its receiver has room or
 * SEND_TIMEOUT_MS (2 s, as the wait it replaces) has passed since it was sent: then it fails with the usual `error` record and stderr
 * line, and the process's handler hears of it (ContractSetKeptSendFailed: the supervisor ties it
 * back to its action). A later request to the same receiver is kept behind it (each receiver gets
 * its requests in order); requests to other receivers go at once.
 *
 * Room: OUTBOX_PER_RECEIVER requests per receiver, OUTBOX_MAX in all (one more fails at once): a
 * stuck module does not take the room that a request to another one needs (its undo). A new
 * value for a parameter port that has one kept replaces it (the older is dropped, the new one
 * goes behind the other kept requests, and is given the older's time: it fails 2 s after the
 * first value that could not be sent): a receiver that reads nothing would have found only the
 * last value anyway, and a supervisor parameterizing at 100 Hz keeps one request, not 200. Its
 * setparam_sent record, or its error, says how many it replaced (`in place of 74 earlier values
 * for its port`): every value is accounted for in the log.
 *
 * What the log says of it: besides each request's own record when it goes (setparam_sent, ...)
 * or fails (error), a receiver's streak of kept requests is bracketed: `requests_kept` (peer = the
 * receiver, detail `request=STOP`: the first one kept) when its first request is kept, and
 * `requests_kept_end` (`sent=N failed=M replaced=R kept_ns=T`) when none is kept for it any more,
 * so that a reader (the Monitor, `contract trace`) sees the requests waiting while they wait, not
 * only when one fails 2 s later.
 *
 * At exit the process tries its kept requests for OUTBOX_EXIT_NS more, then fails those left: a
 * supervisor ends at the run's stop, when a module that has not read its mailbox is about to be
 * stopped anyway, and waiting 2 s for it would delay the stop of every other module (the
 * launcher stops the modules after the supervisors). */
#define _GNU_SOURCE
#include <errno.h>
#include <stdalign.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "internal.h"

#define OUTBOX_MAX 256             /* requests kept at once ...                              */
#define OUTBOX_PER_RECEIVER 64     /* ... and for one receiver                               */
#define OUTBOX_RETRY_NS 5000000LL  /* a kept request is tried again this often while the process waits */
#define OUTBOX_EXIT_NS 500000000LL /* at exit, kept requests are tried this long more */

typedef struct {
    char module[CONTRACT_NAME_MAX];
    RTIME since;                   /* when it was sent: it fails SEND_TIMEOUT_MS later */
    unsigned replaced;             /* earlier values for its parameter port it replaced */
    size_t len;
    alignas(RequestMessage) unsigned char request[]; /* header and payload, as on the wire */
} Kept;

static Kept *kept[OUTBOX_MAX];
static int n_kept;

/* A receiver's streak of kept requests, from its first kept request to the moment none is kept
 * for it any more (at most one a receiver; a receiver has a streak only while it has kept requests). */
typedef struct {
    char module[CONTRACT_NAME_MAX];
    RTIME since;
    unsigned sent, failed, replaced;
} Streak;
static Streak streaks[OUTBOX_MAX];
static int n_streaks;
static RTIME retry_at; /* the next pass: a call before it tries nothing (the engine's wait and its
                          WaitForRequestUntil both call; each request received calls again) */
static ContractKeptSendFailed on_failed;

static const RequestMessage *header(const Kept *k) { return (const RequestMessage *)(const void *)k->request; }

int ContractSetQueuedSends(int on)
{
    int before = g_rt.send_queued;
    g_rt.send_queued = on != 0;
    return before;
}

void ContractSetKeptSendFailed(ContractKeptSendFailed handler) { on_failed = handler; }

int ContractQueuedSends(void) { return n_kept; }

int ContractQueuedFor(const char *module)
{
    int n = 0;
    for (int i = 0; i < n_kept; i++) n += strcmp(kept[i]->module, module) == 0;
    return n;
}

int rt_outbox_holds(const char *module) { return ContractQueuedFor(module) > 0; }

static void take_out(int i)
{
    free(kept[i]);
    memmove(&kept[i], &kept[i + 1], (size_t)(n_kept - i - 1) * sizeof kept[0]);
    n_kept--;
}

static Streak *streak_of(const char *module)
{
    for (int i = 0; i < n_streaks; i++)
        if (strcmp(streaks[i].module, module) == 0) return &streaks[i];
    return NULL;
}

/* The first request kept for module: its streak begins (`requests_kept`). */
static void streak_begin(const char *module, const RequestMessage *request)
{
    if (streak_of(module) || n_streaks >= OUTBOX_MAX) return;
    Streak *st = &streaks[n_streaks++];
    snprintf(st->module, sizeof st->module, "%s", module);
    st->since = GetTime();
    st->sent = st->failed = st->replaced = 0;
    char detail[48];
    snprintf(detail, sizeof detail, "request=%s", rt_request_name(request->Type));
    ContractLog("requests_kept", module, -1, 0, detail);
}

/* What came of a request of module's streak, counted for its `requests_kept_end`. */
typedef enum { KEPT_SENT, KEPT_FAILED, KEPT_REPLACED } KeptFate;

static void streak_count(const char *module, KeptFate fate)
{
    Streak *st = streak_of(module);
    if (!st) return;
    if (fate == KEPT_SENT) st->sent++;
    else if (fate == KEPT_FAILED) st->failed++;
    else st->replaced++;
}

/* After a kept request for module went, failed or was replaced: its streak ends when none is left
 * (`requests_kept_end`). */
static void streak_check_end(const char *module)
{
    Streak *st = streak_of(module);
    if (!st || ContractQueuedFor(module) > 0) return;
    char detail[128];
    snprintf(detail, sizeof detail, "sent=%u failed=%u replaced=%u kept_ns=%lld", st->sent, st->failed, st->replaced,
             (long long)(GetTime() - st->since));
    char who[CONTRACT_NAME_MAX];
    snprintf(who, sizeof who, "%s", st->module);
    *st = streaks[--n_streaks]; /* st is free now: ContractLog below cannot reach the outbox */
    ContractLog("requests_kept_end", who, -1, 0, detail);
}

/* The kept request that a new one replaces: a value for the same parameter port of the same receiver. */
static int superseded_by(const char *module, const RequestMessage *request)
{
    if (request->Type != REQ_SETPARAM) return -1;
    for (int i = 0; i < n_kept; i++) {
        const RequestMessage *h = header(kept[i]);
        if (h->Type == REQ_SETPARAM && h->Param.SetParam.Port == request->Param.SetParam.Port &&
            strcmp(kept[i]->module, module) == 0)
            return i;
    }
    return -1;
}

int rt_outbox_add(const char *module, const RequestMessage *request, size_t len)
{
    RTIME since = GetTime();
    unsigned replaced = 0;
    int old = superseded_by(module, request);
    if (old >= 0) {
        since = kept[old]->since;
        replaced = kept[old]->replaced + 1;
        take_out(old);
        streak_count(module, KEPT_REPLACED);
    }
    int for_it = ContractQueuedFor(module);
    char why[CONTRACT_NAME_MAX + 96] = "";
    if (for_it >= OUTBOX_PER_RECEIVER)
        snprintf(why, sizeof why, "%d requests to %s already wait for its full mailbox", for_it, module);
    else if (n_kept >= OUTBOX_MAX)
        snprintf(why, sizeof why, "%d requests already wait for full mailboxes", n_kept);
    Kept *k = why[0] ? NULL : malloc(sizeof *k + len);
    if (!k) {
        int code = rt_send_failed(module, request->Type, EAGAIN, why[0] ? why : "no memory to keep it");
        streak_count(module, KEPT_FAILED);
        streak_check_end(module); /* the value it replaced was its last kept request */
        return code;
    }
    snprintf(k->module, sizeof k->module, "%s", module);
    k->since = since;
    k->replaced = replaced;
    k->len = len;
    memcpy(k->request, request, len);
    if (n_kept == 0) retry_at = GetTime() + OUTBOX_RETRY_NS; /* it found the mailbox full just now */
    kept[n_kept++] = k;
    streak_begin(module, request);
    return CONTRACT_OK;
}

/* `, in place of N earlier values for its port` (none: '') */
static void replaced_text(char *out, size_t cap, const Kept *k)
{
    out[0] = '\0';
    if (k->replaced) snprintf(out, cap, "in place of %u earlier value%s for its port", k->replaced, k->replaced == 1 ? "" : "s");
}

/* Kept request i failed (err): said, then its record, then the handler (the supervisor's). */
static void fail(int i, int err, const char *why)
{
    Kept *k = kept[i];
    const RequestMessage *h = header(k);
    char replaced[64], text[CONTRACT_NAME_MAX + 192];
    replaced_text(replaced, sizeof replaced, k);
    snprintf(text, sizeof text, "%s%s%s", why, replaced[0] ? ", " : "", replaced);
    int code = rt_send_failed(k->module, h->Type, err, text);
    rt_log_sent(k->module, h, 0, NULL);
    streak_count(k->module, KEPT_FAILED);
    char module[CONTRACT_NAME_MAX];
    snprintf(module, sizeof module, "%s", k->module);
    if (on_failed) on_failed(k->module, h, code);
    /* the handler may send: the list may have changed (what it sent to this receiver was kept
       behind k, in the same streak); k is still ours */
    for (int j = 0; j < n_kept; j++)
        if (kept[j] == k) { take_out(j); break; }
    streak_check_end(module);
}

RTIME ContractRetryQueuedSends(void)
{
    if (n_kept == 0) return 0;
    RTIME now = GetTime(), next = now + OUTBOX_RETRY_NS;
    if (now < retry_at) return retry_at;
    /* receivers still full in this pass: their later requests stay behind */
    char full[OUTBOX_MAX][CONTRACT_NAME_MAX];
    int n_full = 0;
    for (int i = 0; i < n_kept;) {
        Kept *k = kept[i];
        int behind = 0;
        for (int f = 0; f < n_full && !behind; f++) behind = strcmp(full[f], k->module) == 0;
        if (behind) { i++; continue; }
        int err = rt_send_datagram(k->module, k->request, k->len, 1);
        if (err == 0) {
            char replaced[64];
            replaced_text(replaced, sizeof replaced, k);
            rt_log_sent(k->module, header(k), 1, replaced);
            streak_count(k->module, KEPT_SENT);
            char module[CONTRACT_NAME_MAX];
            snprintf(module, sizeof module, "%s", k->module);
            take_out(i);
            streak_check_end(module);
            continue;
        }
        RTIME fails_at = k->since + (RTIME)SEND_TIMEOUT_MS * 1000000LL;
        int still_full = err == EAGAIN || err == EWOULDBLOCK;
        if (still_full && now < fails_at) {
            snprintf(full[n_full++], CONTRACT_NAME_MAX, "%s", k->module);
            if (fails_at < next) next = fails_at;
            i++;
            continue;
        }
        char why[CONTRACT_NAME_MAX + 96];
        if (still_full)
            snprintf(why, sizeof why, "its mailbox stayed full for %d s; %s kept the request meanwhile", SEND_TIMEOUT_MS / 1000, g_rt.name);
        else
            snprintf(why, sizeof why, "%s had kept the request while its mailbox was full", g_rt.name);
        fail(i, err, why); /* the next one is at i now (a handler's own kept requests go at the end) */
    }
    retry_at = n_kept ? next : 0;
    return retry_at;
}

void rt_outbox_drain(void)
{
    RTIME give_up = GetTime() + OUTBOX_EXIT_NS;
    for (RTIME next; (next = ContractRetryQueuedSends()) != 0;) {
        if (next > give_up) next = give_up;
        RTIME wait = next - GetTime();
        if (wait > 0) {
            struct timespec ts = { (time_t)(wait / 1000000000LL), (long)(wait % 1000000000LL) };
            nanosleep(&ts, NULL);
        } else if (GetTime() >= give_up) {
            break;
        }
    }
    char why[CONTRACT_NAME_MAX + 64];
    snprintf(why, sizeof why, "%s ended before its mailbox had room", g_rt.name);
    ContractSetKeptSendFailed(NULL); /* the process ends: nothing to tie back */
    while (n_kept > 0) fail(0, EAGAIN, why);
}
