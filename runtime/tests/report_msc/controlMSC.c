/* A control tool as the generator writes it for module MSC (parameter port 0: TypeA). */
#include <libmodule/control.h>
#include <stdio.h>
#include "SharedTypeA.h"

CONTROL_DEFINE_PARSER(get_TypeA, TypeA)
static const ControlParam PARAMS[] = { { 0, sizeof(TypeA), control_get_TypeA, "TypeA" }, CONTROL_PARAM_TERM };
int main(int argc, char *argv[]) { return ControlMain("MSC", PARAMS, argc, argv); }
