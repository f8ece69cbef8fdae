// schedtypes.h: types and constants of the scheduler (generated; the engine's are in contract/vocabulary.h)
#ifndef SCHEDTYPES_H
#define SCHEDTYPES_H
#include <contract/vocabulary.h>
#include "schedmessages.h"
#endif
