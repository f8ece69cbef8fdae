/*
 * control.h -- the generic control tool, so that each generated tools/control<M>.c is tiny.
 * Audience: [GEN] generated control<M>.c files. Implemented in libmodule.a (src/control.c).
 *
 * A generated control tool looks like this (module MSC, parameter port 0 of type TypeA):
 *
 *     #include <libmodule/control.h>
 *     #include "SharedTypeA.h"
 *     CONTROL_DEFINE_PARSER(get_TypeA, TypeA)
 *     static const ControlParam PARAMS[] = {
 *         { 0, sizeof(TypeA), control_get_TypeA, "TypeA" },
 *         CONTROL_PARAM_TERM };
 *     int main(int argc, char *argv[]) { return ControlMain("MSC", PARAMS, argc, argv); }
 *
 * Command line (run directory: --run-dir DIR, else $CONTRACT_RUN_DIR):
 *     control<M> [--run-dir DIR] start [FUNCTION ['p=v,...']]   (FUNCTION for supervisors)
 *     control<M> [--run-dir DIR] stop | kill | status
 *     control<M> [--run-dir DIR] setparam PORT VALUE              (VALUE textual: '{1.0,2.0,3.0}')
 * Exit codes: see CONTROL_EXIT_*. Every error prints one explicit line on stderr.
 */
#ifndef LIBMODULE_CONTROL_H
#define LIBMODULE_CONTROL_H

#include <stddef.h>
#include "libmodule.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Parses the textual value at `text` into `dst`; returns characters consumed or -1. */
typedef int (*ControlParser)(void *dst, char *text);

/** One parameter port of the controlled module. */
typedef struct {
    int Port;
    size_t Size;
    ControlParser Parse;
    const char *TypeName;   /* for messages */
} ControlParam;

#define CONTROL_PARAM_TERM { -1, 0, NULL, NULL }

/** Defines `static int control_<getter>(void *dst, char *text)` calling `getter((ctype *)dst, text)`:
 *  CONTROL_DEFINE_PARSER(get_TypeA, TypeA), CONTROL_DEFINE_PARSER(get_float, double),
 *  CONTROL_DEFINE_PARSER(get_int, long), CONTROL_DEFINE_PARSER(get_string, char). */
#define CONTROL_DEFINE_PARSER(getter, ctype)                                   \
    static int control_##getter(void *dst, char *text) { return getter((ctype *)dst, text); }

/** Extension (bool, enumerations, arrays; docs/runtime-api.md "Control tools"): a parameter port
 *  described by its vocabulary descriptor (contract/vocabulary.h). ControlMainTyped parses the
 *  VALUE of `setparam` with contract_value_get and prints the value read in its readable form
 *  (`ARM: parameter 0 set to {q=[0.1,0.2,0.3],mode=AUTO}`):
 *      static const ControlTypedParam PARAMS[] = { { 0, &contract_type_ArmGoal }, CONTROL_TYPED_PARAM_TERM };
 *      int main(int argc, char *argv[]) { return ControlMainTyped("ARM", PARAMS, argc, argv); } */
struct ContractType;
typedef struct {
    int Port;
    const struct ContractType *Type;
} ControlTypedParam;

#define CONTROL_TYPED_PARAM_TERM { -1, NULL }

#define CONTROL_EXIT_OK          0
#define CONTROL_EXIT_USAGE       1   /* bad command line */
#define CONTROL_EXIT_UNKNOWN     2   /* no such module in the run directory / no run directory */
#define CONTROL_EXIT_NOTRUNNING  3   /* the module's mailbox exists but the module is dead */
#define CONTROL_EXIT_BADVALUE    4   /* setparam: unknown port or value that does not parse */
#define CONTROL_EXIT_NOACK       5   /* request sent, refused (ACK_NOTDONE) or not acknowledged in time */
#define CONTROL_EXIT_ERROR       6   /* other error */

/** Runs the control command line for `module`. `params` ends with CONTROL_PARAM_TERM (may be NULL). */
int ControlMain(const char *module, const ControlParam params[], int argc, char *argv[]);
/** Same, with typed parameter ports; `params` ends with CONTROL_TYPED_PARAM_TERM (may be NULL). */
int ControlMainTyped(const char *module, const ControlTypedParam params[], int argc, char *argv[]);

#ifdef __cplusplus
}
#endif
#endif /* LIBMODULE_CONTROL_H */
