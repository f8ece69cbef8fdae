// tools.h of ORD_mod: the runtime's helpers (serialisation, parsing), kept here for the report's layout
#ifndef ORD_MOD_TOOLS_H
#define ORD_MOD_TOOLS_H
#include <tools.h>
#endif
