/*
 * sup_claims.h — the bookkeeping that lets one supervisor's undos undo only what their own
 * action did when several active rules act on the same module or event flow (docs/engines.md
 * §4, "Undo and refusals"). Pure data structures, no I/O, no clock: part of the core.
 *
 * Priority claims: each `activate resttime|critical module M` on a running M is a claim
 * (the priority it set, the one M had before it), kept in order per module, whichever
 * supervisor made it. Undoing the latest claim restores the priority before it; undoing an
 * earlier one changes nothing on M (a later change still stands) and hands its "before" to the
 * next claim, so the last undo restores the priority M had before the first change, whatever
 * the order of the undos. The binding keeps the claims of every supervisor of the run in the
 * run directory (prio_claims.c) and decides with these functions.
 *
 * Flow users: how many active event schemas of this supervisor use each event flow
 * (`A:o =* B:i`), so that only the last one disconnects it.
 */
#ifndef CONTRACT_SUP_CLAIMS_H
#define CONTRACT_SUP_CLAIMS_H

#include <stdint.h>

#include "contract/vocabulary.h"

typedef struct SupPrioClaim {
    char owner[64];  /* the supervisor that made it */
    char module[64];
    uint32_t id;     /* the activation that made it (unique in its supervisor) */
    int prio;        /* the priority it set          */
    int before;      /* the priority to restore when it is the latest claim undone */
} SupPrioClaim;

typedef struct SupFlowUse {
    const ContractEventFlow *flow;
    int users;
} SupFlowUse;

typedef struct SupClaims {
    SupPrioClaim *prio;
    int nprio, capprio;
    SupFlowUse *flows;
    int nflows, capflows;
} SupClaims;

/** Records claim `id` of `owner` on `module`, the latest one. 0, or -1 when out of memory
 *  (then its undo restores nothing). */
int sup_claims_push_priority(SupClaims *s, const char *owner, const char *module, uint32_t id,
                             int prio, int before);
/** Drops claim `id` of `owner` on `module`. 1 when it was the module's latest claim:
 *  *restore = the priority to apply now. 0 when a later claim stands (nothing to apply):
 *  *later = the index, after the drop, of that claim, whose `before` is now this one's.
 *  -1 when unknown. */
int sup_claims_drop_priority(SupClaims *s, const char *owner, const char *module, uint32_t id,
                             int *restore, int *later);
/** Adds `delta` (+1 / -1) users to `flow` (same source and destination ports = same flow).
 *  Returns the number of users after it (never below 0). */
int sup_claims_flow_use(SupClaims *s, const ContractEventFlow *flow, int delta);
void sup_claims_free(SupClaims *s);

#endif
