/* controlECHO: the control tool of ECHO (emod.c) with a typed parameter port (ControlMainTyped):
 * port 0 is an XScan, parsed and shown through its vocabulary descriptor. */
#include <libmodule/control.h>
#include "ext_types_vocabulary.h"

static const ControlTypedParam PARAMS[] = { { 0, &t_scan }, CONTROL_TYPED_PARAM_TERM };

int main(int argc, char *argv[]) { return ControlMainTyped("ECHO", PARAMS, argc, argv); }
