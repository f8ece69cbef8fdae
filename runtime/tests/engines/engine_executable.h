/*
 * engine_executable.h — the module.c part of a test or benchmark engine executable (ORD or a
 * supervisor), as the generator writes it: name, priority, description and empty port tables
 * (the engines take their ports from the vocabulary). Used by integration/ and bench/:
 *
 *   #include "../engine_executable.h"
 *   ENGINE_EXECUTABLE("ORD", 80, "engines integration test scheduler")
 *   ... vocabulary tables ...
 *   int ModuleMain(int argc, const char *argv[]) { return contract_ord_main(&V, argc, argv); }
 */
#ifndef ENGINES_TEST_EXECUTABLE_H
#define ENGINES_TEST_EXECUTABLE_H

#include <contract/vocabulary.h>
#include <libmodule/libmodule.h>

/* Built with AddressSanitizer (the integration test's it-san executables, and imod.c/amod.c
   through integration/imodule.h): leave SCHED_FIFO before LeakSanitizer's check at exit. That
   check stops the process's threads from a helper it clones, which starts under SCHED_OTHER
   (libmodule sets SCHED_RESET_ON_FORK), and waits for it spinning on sched_yield(): under
   SCHED_FIFO the spinner keeps its CPU, so when two modules end at once (the launcher stops
   them together) both CPUs of a 2-CPU host spin until RT throttling lets the helpers run, 5 %
   of each second: every scenario's end took ~1 s more under ASan, and beside CPU hogs a module
   took over 2 s to end (the reactivation scenario's `--stop-first` checks failed, 3 runs in 36).
   This handler runs after libmodule's own (atexit order), before the leak check (registered
   before main). The run is over by then: no check of the test depends on that priority. */
#if defined(__SANITIZE_ADDRESS__)
#define ENGINE_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define ENGINE_TEST_ASAN 1
#endif
#endif
#ifdef ENGINE_TEST_ASAN
#include <sched.h>
#include <stdlib.h>
static void engine_test_leave_fifo(void) {
    struct sched_param sp = {.sched_priority = 0};
    (void)sched_setscheduler(0, SCHED_OTHER, &sp);
}
__attribute__((constructor)) static void engine_test_leave_fifo_at_exit(void) { atexit(engine_test_leave_fifo); }
#endif

#define ENGINE_EXECUTABLE(name, priority, description)                                     \
    MODULE_DESCRIPTION(description);                                                       \
    MODULE_AUTHOR("engines tests");                                                        \
    char MODULE_NAME[] = name;                                                             \
    int MODULE_PRIORITY = priority;                                                        \
    ModuleUse IUSE[] = {IUSE_TERM};                                                        \
    ModuleProduce IPRODUCE[] = {IPRODUCE_TERM};                                            \
    ModuleReact IREACT[] = {IREACT_TERM};                                                  \
    ModuleDetect IDETECT[] = {IDETECT_TERM};                                               \
    size_t PARAM_SIZE_IN[] = {PARAM_SIZE_TERM};                                            \
    size_t PARAM_SIZE_OUT[] = {PARAM_SIZE_TERM};

#endif
