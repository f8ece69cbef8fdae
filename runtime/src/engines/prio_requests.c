/* prio_requests.c — see prio_requests.h. */
#define _GNU_SOURCE
#include "prio_requests.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine_array.h"
#include "module_holds.h"
#include "prio_claims.h"

/* as long as ContractSetModulePriority waits */
#define ANSWER_WITHIN_NS 1000000000LL

typedef enum { ASK_CLAIM, ASK_RESTORE, ASK_START } AskKind;

typedef struct {
    AskKind kind;
    char module[CONTRACT_NAME_MAX];
    uint32_t id;      /* the claim's activation (ASK_CLAIM) */
    int prio;
    unsigned seq;
    int undone;       /* the claim's undo came before its answer */
    int64_t deadline;
} PrioRequest;

static PrioRequest *reqs;
static int nreqs, capreqs;

static int find_claim(const char *m, uint32_t id) {
    for (int i = 0; i < nreqs; i++)
        if (reqs[i].kind == ASK_CLAIM && reqs[i].id == id && strcmp(reqs[i].module, m) == 0) return i;
    return -1;
}

static PrioRequest take(int i) {
    PrioRequest q = reqs[i];
    memmove(&reqs[i], &reqs[i + 1], (size_t)(nreqs - i - 1) * sizeof *reqs);
    nreqs--;
    return q;
}

/* One module_priority record per outcome (`rc` as ContractSetModulePriority's, `before` the
   priority the module had). Returns `before` when the module applied it, else -1. */
static int log_outcome(const char *m, int prio, int rc, int before) {
    char detail[160];
    if (rc == 1 || rc == 0) {
        snprintf(detail, sizeof detail, "%s %d (was %d)", rc == 1 ? "SCHED_FIFO" : "nice level for priority", prio,
                 before);
        ContractLog("module_priority", m, -1, 0, detail);
        return before;
    }
    if (rc == CONTRACT_EPERM) {
        fprintf(stderr, "%s: cannot raise %s to priority %d: not permitted for an unprivileged process "
                        "(needs CAP_SYS_NICE or RLIMIT_RTPRIO/RLIMIT_NICE); it keeps priority %d\n",
                ContractSelfName(), m, prio, before);
        snprintf(detail, sizeof detail, "priority %d not permitted; keeps %d", prio, before);
    } else {
        snprintf(detail, sizeof detail, "priority %d not applied: %s", prio, ContractStrError(rc));
    }
    ContractLog("module_priority", m, -1, 0, detail);
    return -1;
}

/* Sends a request; a claim and a restore take the module's lock until their answer. */
static int ask(AskKind kind, const char *m, uint32_t id, int prio) {
    if (kind != ASK_START) holds_lock(m);
    unsigned seq = 0;
    int rc = ContractAskModulePriority(m, prio, &seq);
    void *grown = reqs;
    if (rc == CONTRACT_OK && engine_grow(&grown, &capreqs, nreqs + 1, sizeof *reqs, 8) != 0)
        rc = CONTRACT_ESYS; /* sent, but its answer cannot be waited for: taken as not applied */
    reqs = grown;
    if (rc != CONTRACT_OK) {
        log_outcome(m, prio, rc, -1);
        if (kind != ASK_START) holds_unlock(m);
        return -1;
    }
    PrioRequest *q = &reqs[nreqs++];
    memset(q, 0, sizeof *q);
    q->kind = kind;
    snprintf(q->module, sizeof q->module, "%s", m);
    q->id = id;
    q->prio = prio;
    q->seq = seq;
    q->deadline = (int64_t)GetTime() + ANSWER_WITHIN_NS;
    return 0;
}

/* The undo of a recorded claim: restore the priority before it when it is the latest claim of
   any supervisor, else leave the later change standing (prio_claims.h). */
static void release_recorded(const char *m, uint32_t id) {
    holds_lock(m);
    int restore = -1;
    char later[CONTRACT_NAME_MAX] = "";
    int r = prio_claims_release(m, id, &restore, later, sizeof later);
    if (r == 1) {
        ask(ASK_RESTORE, m, 0, restore);
    } else if (r == 0) {
        char detail[160];
        snprintf(detail, sizeof detail, "kept: a later change by %s stands", later);
        ContractLog("priority_kept", m, -1, 0, detail);
    }
    holds_unlock(m);
}

static void finish(PrioRequest *q, int rc, int before) {
    int old = log_outcome(q->module, q->prio, rc, before);
    if (q->kind == ASK_START) return;
    if (q->kind == ASK_CLAIM && old >= 0 && prio_claims_record(q->module, q->id, q->prio, old) == 0 && q->undone)
        release_recorded(q->module, q->id);
    holds_unlock(q->module);
}

int prio_request_claim(const char *module, uint32_t id, int prio) { return ask(ASK_CLAIM, module, id, prio); }

void prio_request_release(const char *module, uint32_t id) {
    int i = find_claim(module, id);
    if (i >= 0) {
        reqs[i].undone = 1;
        return;
    }
    release_recorded(module, id);
}

void prio_request_start(const char *module, int prio) { ask(ASK_START, module, 0, prio); }

void prio_request_answered(const RequestMessage *reply) {
    for (int i = 0; i < nreqs; i++) {
        if (reqs[i].seq != reply->Param.Priority.Seq || strcmp(reqs[i].module, reply->Sender) != 0) continue;
        PrioRequest q = take(i);
        finish(&q, reply->Param.Priority.Result, reply->Param.Priority.Priority);
        return;
    }
    /* the answer to a request whose deadline passed: it was logged as not applied */
}

int64_t prio_requests_next_deadline(void) {
    int64_t d = INT64_MAX;
    for (int i = 0; i < nreqs; i++)
        if (reqs[i].deadline < d) d = reqs[i].deadline;
    return d;
}

void prio_requests_expire(int64_t t) {
    for (int i = 0; i < nreqs;) {
        if (reqs[i].deadline > t) {
            i++;
            continue;
        }
        PrioRequest q = take(i);
        finish(&q, CONTRACT_EBUSY, -1); /* may add a request (a restore): the loop sees it, not yet due */
    }
}

void prio_requests_settle(void) {
    RequestMessage *reply = malloc(sizeof *reply);
    while (nreqs > 0) {
        int got = reply ? ContractWaitModulePriority(prio_requests_next_deadline(), reply) : -1;
        if (got == 1) prio_request_answered(reply);
        else prio_requests_expire(got == 0 ? (int64_t)GetTime() : INT64_MAX);
    }
    free(reply);
}

int prio_requests_in_flight(void) { return nreqs; }
