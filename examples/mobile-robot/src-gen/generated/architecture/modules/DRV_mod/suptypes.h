// suptypes.h of supervisor DRV (generated): the supervision engine's types are in contract/vocabulary.h,
// the data types of its variables in the common/Shared<Type>.h headers that vocabulary.c includes.
#ifndef SUPTYPES_DRV_H
#define SUPTYPES_DRV_H
#include <contract/vocabulary.h>
#include "tools.h"
#endif
