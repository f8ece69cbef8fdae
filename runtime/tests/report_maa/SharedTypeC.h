#ifndef SHARED_TYPEC_H
#define SHARED_TYPEC_H
#include <stdio.h>
#include <string.h>
#include "tools.h"
#include "SharedTypeA.h"

/* Written by hand in the style of the report's SharedTypeA.h: TypeC {string message, int messagetype, TypeA value}. */
typedef struct TypeC{
	char message[256];
	long messagetype;
	TypeA value;
} TypeC;

void set_TypeC(TypeC * arg1, TypeC * arg2);
void set_TypeC(TypeC * arg1, TypeC * arg2){
	strcpy(arg1->message, arg2->message);
	arg1->messagetype=arg2->messagetype;
	set_TypeA(&arg1->value, &arg2->value);
}

#endif
