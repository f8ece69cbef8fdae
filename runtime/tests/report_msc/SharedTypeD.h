#ifndef SHARED_TYPED_H
#define SHARED_TYPED_H
#include <stdio.h>
#include <string.h>
#include "tools.h"

/* Written by hand in the style of the report's SharedTypeA.h (section 8.2). */
typedef struct TypeD{
	char dataname[256];
	long datavalue;
} TypeD;

unsigned int serialize_TypeD(TypeD * arg, unsigned char * buffer);
unsigned int deserialize_TypeD(TypeD * arg, unsigned char* buffer);
int get_TypeD(TypeD * arg, char* description);
void print_TypeD(TypeD * arg);

unsigned int serialize_TypeD(TypeD * arg, unsigned char * buffer){
	unsigned int size = 0;
	size += extract_string(buffer, size, arg->dataname);
	size += extract_int(buffer, size, arg->datavalue);
	return size;
}

unsigned int deserialize_TypeD(TypeD * arg, unsigned char* buffer){
	unsigned int size = 0;
	size += fill_string(arg->dataname, size, buffer);
	size += fill_int(&arg->datavalue, size, buffer);
	return size;
}

int get_TypeD(TypeD * arg, char* description){
	int sizeread=0, res=0;
	char symbol = '{';
	if (arg == NULL) return -1;
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
	sizeread+=res;
	if((res=get_string(arg->dataname, &description[sizeread])) == -1) return -1;
	sizeread += res;
	symbol = ',';
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
	sizeread+=res;
	if((res=get_int(&arg->datavalue, &description[sizeread])) == -1) return -1;
	sizeread += res;
	symbol = '}';
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
	sizeread+=res;
	return sizeread;
}

void print_TypeD(TypeD * arg){
	printf("(object type %s : %s : %s ; %s : %ld ; )", "TypeD", "dataname", arg->dataname, "datavalue", arg->datavalue);
}

#endif
