#ifndef SHARED_TYPEF_H
#define SHARED_TYPEF_H
#include <stdio.h>
#include <string.h>
#include "tools.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_TypeF) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct TypeF{
    long fufu;
    long juju;
} TypeF;

static inline unsigned int serialize_TypeF(TypeF * arg, unsigned char * buffer);
static inline unsigned int deserialize_TypeF(TypeF * arg, unsigned char* buffer);
static inline int diff_TypeF(TypeF * arg1, TypeF * arg2);
static inline int eq_TypeF(TypeF * arg1, TypeF * arg2);
static inline int inf_TypeF(TypeF * arg1, TypeF * arg2);
static inline int sup_TypeF(TypeF * arg1, TypeF * arg2);
static inline int infeq_TypeF(TypeF * arg1, TypeF * arg2);
static inline int supeq_TypeF(TypeF * arg1, TypeF * arg2);
static inline void set_TypeF(TypeF * arg1, TypeF * arg2);
static inline int get_TypeF(TypeF * arg, char* description);
static inline void print_TypeF(TypeF * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_TypeF) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_TypeF(TypeF * arg, unsigned char * buffer){
    unsigned int size = 0;
    size += extract_int(buffer, size, arg->fufu);
    size += extract_int(buffer, size, arg->juju);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_TypeF(TypeF * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += fill_int(&arg->fufu, size, buffer);
    size += fill_int(&arg->juju, size, buffer);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_TypeF(TypeF * arg1, TypeF * arg2){
    if (arg1 == arg2) return;
    arg1->fufu=arg2->fufu;
    arg1->juju=arg2->juju;
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_TypeF(TypeF * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    TypeF tmp;
    if (arg == NULL || description == NULL) return -1;
    set_TypeF(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_int(&tmp.fufu, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_int(&tmp.juju, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_TypeF(arg, &tmp);
    return sizeread;
}

static inline void print_TypeF(TypeF * arg){
    printf("(object type %s : ", "TypeF");
    printf("%s : %ld ; ", "fufu", arg->fufu);
    printf("%s : %ld ; ", "juju", arg->juju);
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_TypeF(TypeF * arg1, TypeF * arg2){
    /*PROTECTED REGION ID(protect_eq_TypeF) ENABLED START*/
    if (!(arg1->fufu == arg2->fufu)) return 0;
    if (!(arg1->juju == arg2->juju)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_TypeF(TypeF * arg1, TypeF * arg2){
    /*PROTECTED REGION ID(protect_diff_TypeF) ENABLED START*/
    if (eq_TypeF(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_TypeF(TypeF * arg1, TypeF * arg2){
    /*PROTECTED REGION ID(protect_inf_TypeF) ENABLED START*/
    if (!(arg1->fufu < arg2->fufu)) return 0;
    if (!(arg1->juju < arg2->juju)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_TypeF(TypeF * arg1, TypeF * arg2){
    /*PROTECTED REGION ID(protect_sup_TypeF) ENABLED START*/
    if (!(arg1->fufu > arg2->fufu)) return 0;
    if (!(arg1->juju > arg2->juju)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_TypeF(TypeF * arg1, TypeF * arg2){
    /*PROTECTED REGION ID(protect_infeq_TypeF) ENABLED START*/
    if (inf_TypeF(arg1,arg2) == 1 || eq_TypeF(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_TypeF(TypeF * arg1, TypeF * arg2){
    /*PROTECTED REGION ID(protect_supeq_TypeF) ENABLED START*/
    if (sup_TypeF(arg1,arg2) == 1 || eq_TypeF(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_TypeF) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
