/*
 * hold_lock.h — the cross-process lock behind module_holds.c: an exclusive flock(2) on
 * <dir>/holds-<module>.hold, one lock file per module. The kernel releases it when its holder
 * dies, so a crashed supervisor never leaves it taken; the file has a single dot, so it never
 * reads as a <SUP>.<M>.hold, and the launcher removes it with the other *.hold files at the end
 * of the run. No libmodule dependency (tested on its own by tests/engines/test_hold_lock.c).
 */
#ifndef CONTRACT_HOLD_LOCK_H
#define CONTRACT_HOLD_LOCK_H

/** Waits for the lock of `module` in `dir` (signals are retried). Returns the descriptor that
 *  holds it (give it to hold_lock_release), or -1 with errno set. */
int hold_lock_acquire(const char *dir, const char *module);
/** As hold_lock_acquire, without waiting: -1 with errno EWOULDBLOCK when someone holds it. */
int hold_lock_try(const char *dir, const char *module);
/** Releases and closes a descriptor from hold_lock_acquire/hold_lock_try (-1: no-op). */
void hold_lock_release(int fd);

#endif
