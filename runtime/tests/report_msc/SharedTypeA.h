#ifndef SHARED_TYPEA_H
#define SHARED_TYPEA_H
#include "tools.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_TypeA) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct TypeA{
	double i;
	double j;
	double k;
} TypeA;

unsigned int serialize_TypeA(TypeA * arg, unsigned char * buffer);
unsigned int deserialize_TypeA(TypeA * arg, unsigned char* buffer);
int diff_TypeA(TypeA * arg1, TypeA * arg2);
int eq_TypeA(TypeA * arg1, TypeA * arg2);
int inf_TypeA(TypeA * arg1, TypeA * arg2);
int sup_TypeA(TypeA * arg1, TypeA * arg2);
int infeq_TypeA(TypeA * arg1, TypeA * arg2);
int supeq_TypeA(TypeA * arg1, TypeA * arg2);
void set_TypeA(TypeA * arg1, TypeA * arg2);
int get_TypeA(TypeA * arg, char* description);
void print_TypeA(TypeA * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_TypeA) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

unsigned int serialize_TypeA(TypeA * arg, unsigned char * buffer){
	unsigned int size = 0;
	size += extract_float(buffer, size, arg->i);
	size += extract_float(buffer, size, arg->j);
	size += extract_float(buffer, size, arg->k);
	return size;
}

unsigned int deserialize_TypeA(TypeA * arg, unsigned char* buffer){
	unsigned int size = 0;
	size += fill_float(&arg->i, size, buffer);
	size += fill_float(&arg->j, size, buffer);
	size += fill_float(&arg->k, size, buffer);
	return size;
}

void set_TypeA(TypeA * arg1, TypeA * arg2){
	arg1->i=arg2->i;
	arg1->j=arg2->j;
	arg1->k=arg2->k;
}

int get_TypeA(TypeA * arg, char* description){
	int sizeread=0, res=0, nbfields=3;
	char symbol = '{';
	if (arg == NULL) return -1;
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
	sizeread+=res;
	if((res=get_float(&arg->i, &description[sizeread])) == -1) return -1;
	nbfields--;
	sizeread += res;
	if (nbfields != 0) symbol = ',';
	else symbol = '}';
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1){
		return -1;
	}
	sizeread+=res;
	if((res=get_float(&arg->j, &description[sizeread])) == -1) return -1;
	nbfields--;
	sizeread += res;
	if (nbfields != 0) symbol = ',';
	else symbol = '}';
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1){
		return -1;
	}
	sizeread+=res;
	if((res=get_float(&arg->k, &description[sizeread])) == -1) return -1;
	nbfields--;
	sizeread += res;
	if (nbfields != 0) symbol = ',';
	else symbol = '}';
	if ((res=increment_until_markerfound(&description[sizeread], &symbol)) == -1){
		return -1;
	}
	sizeread+=res;
	return sizeread;
}

void print_TypeA(TypeA * arg){
	printf("(object type %s : ", "TypeA");
	printf("%s : %lf ; ", "i", arg->i);
	printf("%s : %lf ; ", "j", arg->j);
	printf("%s : %lf ; ", "k", arg->k);
	printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

int eq_TypeA(TypeA * arg1, TypeA * arg2){
	/*PROTECTED REGION ID(protect_eq_TypeA) ENABLED START*/
	if ((arg1->i==arg2->i?1:0) == 0) return 0;
	if ((arg1->j==arg2->j?1:0) == 0) return 0;
	if ((arg1->k==arg2->k?1:0) == 0) return 0;
	return 1;
	/*PROTECTED REGION END*/
}

int diff_TypeA(TypeA * arg1, TypeA * arg2){
	/*PROTECTED REGION ID(protect_diff_TypeA) ENABLED START*/
	if (eq_TypeA(arg1,arg2) == 0) return 1;
	return 0;
	/*PROTECTED REGION END*/
}

int inf_TypeA(TypeA * arg1, TypeA * arg2){
	/*PROTECTED REGION ID(protect_inf_TypeA) ENABLED START*/
	if ((arg1->i<arg2->i?1:0) == 0) return 0;
	if ((arg1->j<arg2->j?1:0) == 0) return 0;
	if ((arg1->k<arg2->k?1:0) == 0) return 0;
	return 1;
	/*PROTECTED REGION END*/
}

int sup_TypeA(TypeA * arg1, TypeA * arg2){
	/*PROTECTED REGION ID(protect_sup_TypeA) ENABLED START*/
	if (inf_TypeA(arg1,arg2) == 0 && eq_TypeA(arg1,arg2) == 0)
		return 1;
	return 0;
	/*PROTECTED REGION END*/
}

int infeq_TypeA(TypeA * arg1, TypeA * arg2){
	/*PROTECTED REGION ID(protect_infeq_TypeA) ENABLED START*/
	if (inf_TypeA(arg1,arg2) == 1 || eq_TypeA(arg1,arg2) == 1)
		return 1;
	return 0;
	/*PROTECTED REGION END*/
}

int supeq_TypeA(TypeA * arg1, TypeA * arg2){
	/*PROTECTED REGION ID(protect_supeq_TypeA) ENABLED START*/
	if (sup_TypeA(arg1,arg2) == 1 || eq_TypeA(arg1,arg2) == 1)
		return 1;
	return 0;
	/*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type

/*PROTECTED REGION ID(protect_additionnal_impl_TypeA) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
