#ifndef SHARED_TYPEB_H
#define SHARED_TYPEB_H
#include "tools.h"
#include "SharedTypeA.h"

/* Written by hand in the style of the report's SharedTypeA.h (section 8.2). */
typedef struct TypeB{
	TypeA coord;
	long frfrrrf;
} TypeB;

unsigned int serialize_TypeB(TypeB * arg, unsigned char * buffer);
unsigned int deserialize_TypeB(TypeB * arg, unsigned char* buffer);
int get_TypeB(TypeB * arg, char* description);
void print_TypeB(TypeB * arg);

unsigned int serialize_TypeB(TypeB * arg, unsigned char * buffer){
	unsigned int size = 0;
	size += serialize_TypeA(&arg->coord, &buffer[size]);
	size += extract_int(buffer, size, arg->frfrrrf);
	return size;
}

unsigned int deserialize_TypeB(TypeB * arg, unsigned char* buffer){
	unsigned int size = 0;
	size += deserialize_TypeA(&arg->coord, &buffer[size]);
	size += fill_int(&arg->frfrrrf, size, buffer);
	return size;
}

int get_TypeB(TypeB * arg, char* description){
	int sizeread=0, res=0;
	char symbol = '{';
	if (arg == NULL) return -1;
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
	sizeread+=res;
	if((res=get_TypeA(&arg->coord, &description[sizeread])) == -1) return -1;
	sizeread += res;
	symbol = ',';
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
	sizeread+=res;
	if((res=get_int(&arg->frfrrrf, &description[sizeread])) == -1) return -1;
	sizeread += res;
	symbol = '}';
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
	sizeread+=res;
	return sizeread;
}

void print_TypeB(TypeB * arg){
	printf("(object type %s : ", "TypeB");
	printf("%s : ", "coord"); print_TypeA(&arg->coord); printf(" ; ");
	printf("%s : %ld ; ", "frfrrrf", arg->frfrrrf);
	printf(")");
}

#endif
