/*
 * module_holds.h — which supervisors use which asynchronous modules, shared through the run
 * directory so that docs/semantics.md "Event schemas: undo and shared modules" holds across
 * supervisors: an event schema starts a module only if it is not already running, and a module used by several active schemas (of one or more
 * supervisors) runs until the last one is deactivated.
 *
 * Files (empty, in the run directory):
 *   <SUP>.<M>.hold     supervisor SUP holds module M (one file per supervisor and module)
 *   <M>.started.hold   M was started by a supervisor's event schema (so the last holder stops it)
 *   <M>.engine-stopped.hold   the last decision of an engine on M was to stop it (removed
 *                      when an engine starts it again, or M answers that it runs): "no answer
 *                      within 0.5 s" then means a module paused with that STOP waiting in its
 *                      mailbox, not one busy in its run
 *   holds-<M>.hold     the lock of M's holds (hold_lock.h)
 *   <SUP>.<F>.hold     supervisor SUP's active event schemas use event flow F, named
 *                      flow-<SRC>-<o>-<DST>-<i> (engine_flow_hold_name): the last user disconnects it
 * The launcher removes a crashed supervisor's <SUP>.*.hold (and a crashed module's
 * <M>.started.hold) with its other files, and every *.hold at the end of a run.
 *
 * Atomicity across supervisors: the decide-and-act sequences on a module run under
 * holds_lock(M) — "is M running? then take a hold (share it), else start it and take a hold"
 * and "drop my hold, count the others, stop M if none" — so that a supervisor dropping its
 * last hold cannot stop M between another one's "it runs" decision and its hold (the module
 * would then be stopped under that supervisor's active schema). The lock is a flock(2), freed
 * by the kernel if its holder dies.
 */
#ifndef CONTRACT_MODULE_HOLDS_H
#define CONTRACT_MODULE_HOLDS_H

#include <stddef.h>

/** Takes the lock of `module`'s holds, waiting for other supervisors to release it. Nested
 *  calls in one process only count (the lock is released by the outermost holds_unlock).
 *  0, or -1 (logged: the caller goes on unlocked, as before the lock existed). */
int holds_lock(const char *module);
/** `fn` runs before this process waits for a lock another process holds (holds_lock), so that it
 *  first ends what others may be waiting for (prio_requests_settle). */
void holds_before_block(void (*fn)(void));
/** Releases one holds_lock of `module`. */
void holds_unlock(const char *module);
/** This supervisor holds `module`; `started`: it has just started it. 0, or -1 (logged). */
int holds_take(const char *module, int started);
/** This supervisor stops holding `module`. Returns the number of other supervisors that
 *  still hold it (0: this was the last holder). */
int holds_drop(const char *module);
/** 1 if `module` was started by a supervisor and is not stopped yet; `clear` removes the mark. */
int holds_started(const char *module, int clear);
/** The last holder of `module` has just sent it a STOP (holds_take(module, 1) clears the mark). */
void holds_mark_stopped(const char *module);
/** 1 if an engine stopped `module` last and none started it since; `clear` removes the mark
 *  (the module answered that it runs: someone else started it since). */
int holds_stopped(const char *module, int clear);

/** Event flows are held like modules (same files and lock, under the flow's own name): an
 *  event flow `SRC:o =* DST:i` is one subscription at SRC whichever schemas ask for it, so a
 *  supervisor's undo must not disconnect it while another supervisor's active schema uses it.
 *  The name: engine_flow_hold_name (engine_values.h), `flow-SRC-o-DST-i` (`flow-<hash>` when
 *  longer than a module name). */
/** This supervisor uses flow `name`. 0, or -1 (logged). Drop it with holds_drop(name). */
int holds_take_flow(const char *name);

#endif
