#ifndef SHARED_TYPED_H
#define SHARED_TYPED_H
#include <stdio.h>
#include <string.h>
#include "tools.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_TypeD) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct TypeD{
    char dataname[256];
    long datavalue;
} TypeD;

static inline unsigned int serialize_TypeD(TypeD * arg, unsigned char * buffer);
static inline unsigned int deserialize_TypeD(TypeD * arg, unsigned char* buffer);
static inline int diff_TypeD(TypeD * arg1, TypeD * arg2);
static inline int eq_TypeD(TypeD * arg1, TypeD * arg2);
static inline int inf_TypeD(TypeD * arg1, TypeD * arg2);
static inline int sup_TypeD(TypeD * arg1, TypeD * arg2);
static inline int infeq_TypeD(TypeD * arg1, TypeD * arg2);
static inline int supeq_TypeD(TypeD * arg1, TypeD * arg2);
static inline void set_TypeD(TypeD * arg1, TypeD * arg2);
static inline int get_TypeD(TypeD * arg, char* description);
static inline void print_TypeD(TypeD * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_TypeD) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_TypeD(TypeD * arg, unsigned char * buffer){
    unsigned int size = 0;
    size += extract_string(buffer, size, arg->dataname);
    size += extract_int(buffer, size, arg->datavalue);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_TypeD(TypeD * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += fill_string(arg->dataname, size, buffer);
    size += fill_int(&arg->datavalue, size, buffer);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_TypeD(TypeD * arg1, TypeD * arg2){
    if (arg1 == arg2) return;
    memmove(arg1->dataname, arg2->dataname, sizeof(arg1->dataname));
    arg1->datavalue=arg2->datavalue;
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_TypeD(TypeD * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    TypeD tmp;
    if (arg == NULL || description == NULL) return -1;
    set_TypeD(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_string(tmp.dataname, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_int(&tmp.datavalue, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_TypeD(arg, &tmp);
    return sizeread;
}

static inline void print_TypeD(TypeD * arg){
    printf("(object type %s : ", "TypeD");
    printf("%s : %s ; ", "dataname", arg->dataname);
    printf("%s : %ld ; ", "datavalue", arg->datavalue);
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_TypeD(TypeD * arg1, TypeD * arg2){
    /*PROTECTED REGION ID(protect_eq_TypeD) ENABLED START*/
    if (!(strcmp(arg1->dataname, arg2->dataname) == 0)) return 0;
    if (!(arg1->datavalue == arg2->datavalue)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_TypeD(TypeD * arg1, TypeD * arg2){
    /*PROTECTED REGION ID(protect_diff_TypeD) ENABLED START*/
    if (eq_TypeD(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_TypeD(TypeD * arg1, TypeD * arg2){
    /*PROTECTED REGION ID(protect_inf_TypeD) ENABLED START*/
    //failures are ordered by their value only
    return arg1->datavalue < arg2->datavalue ? 1 : 0;
    /*PROTECTED REGION END*/
}

static inline int sup_TypeD(TypeD * arg1, TypeD * arg2){
    /*PROTECTED REGION ID(protect_sup_TypeD) ENABLED START*/
    //failures are ordered by their value only
    return arg1->datavalue > arg2->datavalue ? 1 : 0;
    /*PROTECTED REGION END*/
}

static inline int infeq_TypeD(TypeD * arg1, TypeD * arg2){
    /*PROTECTED REGION ID(protect_infeq_TypeD) ENABLED START*/
    if (inf_TypeD(arg1,arg2) == 1 || eq_TypeD(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_TypeD(TypeD * arg1, TypeD * arg2){
    /*PROTECTED REGION ID(protect_supeq_TypeD) ENABLED START*/
    if (sup_TypeD(arg1,arg2) == 1 || eq_TypeD(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_TypeD) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
