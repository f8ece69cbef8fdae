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
