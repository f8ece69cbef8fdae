#ifndef SHARED_TYPEE_H
#define SHARED_TYPEE_H
#include "tools.h"
#include "SharedTypeC.h"
#include "SharedTypeD.h"

/* Written by hand in the style of the report's SharedTypeA.h: TypeE {TypeC message, TypeD data_}. */
typedef struct TypeE{
	TypeC message;
	TypeD data_;
} TypeE;

#endif
