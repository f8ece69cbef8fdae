/*
 * prio_claims.h — the priority claims of every supervisor of a run on one module, kept in the
 * run directory so that an undo restores a module's priority only when no later change of any
 * supervisor stands (docs/engines.md §4, "Undo and refusals"; decisions: sup_claims.h).
 *
 * Files (one per claim, in the run directory): <SUP>.prio-<M>-<id>.hold = "<t> <prio> <before>"
 * (t: CLOCK_MONOTONIC ns when it was made, which orders the claims of all supervisors). The
 * launcher removes a crashed supervisor's claims with its other <SUP>.*.hold files.
 * Callers hold the module's lock (holds_lock) around a change and its record, and around a
 * release and the change it decides, so that claims are made and dropped one at a time.
 */
#ifndef CONTRACT_PRIO_CLAIMS_H
#define CONTRACT_PRIO_CLAIMS_H

#include <stddef.h>
#include <stdint.h>

/** Records this supervisor's claim `id` on `module` (it set `prio`; it was `before`). 0 or -1
 *  (logged: then its release restores nothing). */
int prio_claims_record(const char *module, uint32_t id, int prio, int before);
/** Drops this supervisor's claim `id` on `module`. 1: it was the latest, apply *restore. 0: a
 *  later claim of `later_owner` stands (its record now restores this one's "before"). -1:
 *  unknown (nothing to do). */
int prio_claims_release(const char *module, uint32_t id, int *restore, char *later_owner,
                        size_t later_size);

#endif
