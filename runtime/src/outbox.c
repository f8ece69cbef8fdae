/* The outbox: requests kept for a receiver whose mailbox is full, in a process that asked for
 * queued sends (ContractSetQueuedSends: the supervisors). Such a request is neither waited for
 * (the process would read nothing meanwhile: its timers late, its own mailbox filling, the
 * modules that post events to it waiting in turn) nor dropped (a supervisor's request is a
 * one-off transition nothing repeats). It is kept, in order, and sent again each time the
 * process waits for requests (WaitForRequestUntil, an engine's wait: ContractRetryQueuedSends),
 * every OUTBOX_RETRY_NS, until its receiver has room or SEND_TIMEOUT_MS (2 s, as the wait it
 * replaces) has passed since it was sent: then it fails with the usual `error` record and stderr
 * line. A later request to the same receiver is kept behind it (each receiver gets its requests
 * in the order they were sent); requests to other receivers go at once. At exit the process
 * tries its kept requests for OUTBOX_EXIT_NS more, then fails those left: a supervisor ends at
 * the run's stop, when a module that has not read its mailbox is about to be killed anyway, and
 * waiting 2 s for it would delay the stop of every other module (the launcher stops the modules
 * after the supervisors). */
#define _GNU_SOURCE
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "internal.h"

#define OUTBOX_MAX 256             /* requests kept at once; one more fails (CONTRACT_EBUSY) */
#define OUTBOX_RETRY_NS 5000000LL  /* a kept request is tried again this often while the process waits */
#define OUTBOX_EXIT_NS 500000000LL /* at exit, kept requests are tried this long more */

typedef struct {
    char module[CONTRACT_NAME_MAX];
    int type;
    RTIME since;                   /* when it was sent: it fails SEND_TIMEOUT_MS later */
    size_t len;
    unsigned char request[];       /* header and payload, as on the wire */
} Kept;

static Kept *kept[OUTBOX_MAX];
static int n_kept;

int ContractSetQueuedSends(int on)
{
    int before = g_rt.send_queued;
    g_rt.send_queued = on != 0;
    return before;
}

int ContractQueuedSends(void) { return n_kept; }

int rt_outbox_holds(const char *module)
{
    for (int i = 0; i < n_kept; i++)
        if (strcmp(kept[i]->module, module) == 0) return 1;
    return 0;
}

int rt_outbox_add(const char *module, int type, const void *request, size_t len)
{
    Kept *k = n_kept < OUTBOX_MAX ? malloc(sizeof *k + len) : NULL;
    if (!k) {
        char why[96];
        snprintf(why, sizeof why, "%d requests already wait for full mailboxes", n_kept);
        return rt_send_failed(module, type, EAGAIN, why);
    }
    snprintf(k->module, sizeof k->module, "%s", module);
    k->type = type;
    k->since = GetTime();
    k->len = len;
    memcpy(k->request, request, len);
    kept[n_kept++] = k;
    return CONTRACT_OK;
}

static void take_out(int i)
{
    free(kept[i]);
    memmove(&kept[i], &kept[i + 1], (size_t)(n_kept - i - 1) * sizeof kept[0]);
    n_kept--;
}

RTIME ContractRetryQueuedSends(void)
{
    if (n_kept == 0) return 0;
    RTIME now = GetTime(), next = now + OUTBOX_RETRY_NS;
    /* receivers still full in this pass: their later requests stay behind */
    const char *full[OUTBOX_MAX];
    int n_full = 0;
    for (int i = 0; i < n_kept;) {
        Kept *k = kept[i];
        int behind = 0;
        for (int f = 0; f < n_full && !behind; f++) behind = strcmp(full[f], k->module) == 0;
        if (behind) { i++; continue; }
        int err = rt_send_datagram(k->module, k->request, k->len, 1);
        int still_full = err == EAGAIN || err == EWOULDBLOCK;
        RTIME fails_at = k->since + (RTIME)SEND_TIMEOUT_MS * 1000000LL;
        if (still_full && now < fails_at) {
            full[n_full++] = k->module;
            if (fails_at < next) next = fails_at;
            i++;
            continue;
        }
        if (err) {
            char why[160];
            snprintf(why, sizeof why, still_full ? "its mailbox stayed full for %d s; %s kept the request meanwhile"
                                                 : "kept while its mailbox was full (%d s at most); %s sent it later",
                     SEND_TIMEOUT_MS / 1000, g_rt.name);
            rt_send_failed(k->module, k->type, err, why);
        }
        take_out(i);
    }
    return n_kept ? next : 0;
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
    while (n_kept > 0) {
        rt_send_failed(kept[0]->module, kept[0]->type, EAGAIN, why);
        take_out(0);
    }
}
