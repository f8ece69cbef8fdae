/*
 * module_holds.h — which supervisors use which asynchronous modules, shared through the run
 * directory so that SPEC §4.3 holds across supervisors: an event schema starts a module only
 * if it is not already running, and a module used by several active schemas (of one or more
 * supervisors) runs until the last one is deactivated.
 *
 * Files (empty, in the run directory):
 *   <SUP>.<M>.hold     supervisor SUP holds module M (one file per supervisor and module)
 *   <M>.started.hold   M was started by a supervisor's event schema (so the last holder stops it)
 * The launcher removes a crashed supervisor's <SUP>.*.hold (and a crashed module's
 * <M>.started.hold) with its other files, and every *.hold at the end of a run.
 */
#ifndef CONTRACT_MODULE_HOLDS_H
#define CONTRACT_MODULE_HOLDS_H

/** This supervisor holds `module`; `started`: it has just started it. 0, or -1 (logged). */
int holds_take(const char *module, int started);
/** This supervisor stops holding `module`. Returns the number of other supervisors that
 *  still hold it (0: this was the last holder). */
int holds_drop(const char *module);
/** 1 if `module` was started by a supervisor and is not stopped yet; `clear` removes the mark. */
int holds_started(const char *module, int clear);

#endif
