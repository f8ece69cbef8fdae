#ifndef SHARED_TYPEA_H
#define SHARED_TYPEA_H
#include <stdio.h>
#include <string.h>
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

static inline unsigned int serialize_TypeA(TypeA * arg, unsigned char * buffer);
static inline unsigned int deserialize_TypeA(TypeA * arg, unsigned char* buffer);
static inline int diff_TypeA(TypeA * arg1, TypeA * arg2);
static inline int eq_TypeA(TypeA * arg1, TypeA * arg2);
static inline int inf_TypeA(TypeA * arg1, TypeA * arg2);
static inline int sup_TypeA(TypeA * arg1, TypeA * arg2);
static inline int infeq_TypeA(TypeA * arg1, TypeA * arg2);
static inline int supeq_TypeA(TypeA * arg1, TypeA * arg2);
static inline void set_TypeA(TypeA * arg1, TypeA * arg2);
static inline int get_TypeA(TypeA * arg, char* description);
static inline void print_TypeA(TypeA * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_TypeA) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_TypeA(TypeA * arg, unsigned char * buffer){
    unsigned int size = 0;
    size += extract_float(buffer, size, arg->i);
    size += extract_float(buffer, size, arg->j);
    size += extract_float(buffer, size, arg->k);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_TypeA(TypeA * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += fill_float(&arg->i, size, buffer);
    size += fill_float(&arg->j, size, buffer);
    size += fill_float(&arg->k, size, buffer);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_TypeA(TypeA * arg1, TypeA * arg2){
    if (arg1 == arg2) return;
    arg1->i=arg2->i;
    arg1->j=arg2->j;
    arg1->k=arg2->k;
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_TypeA(TypeA * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    TypeA tmp;
    if (arg == NULL || description == NULL) return -1;
    set_TypeA(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.i, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.j, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.k, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_TypeA(arg, &tmp);
    return sizeread;
}

static inline void print_TypeA(TypeA * arg){
    printf("(object type %s : ", "TypeA");
    printf("%s : %lf ; ", "i", arg->i);
    printf("%s : %lf ; ", "j", arg->j);
    printf("%s : %lf ; ", "k", arg->k);
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_TypeA(TypeA * arg1, TypeA * arg2){
    /*PROTECTED REGION ID(protect_eq_TypeA) ENABLED START*/
    if (!(arg1->i == arg2->i)) return 0;
    if (!(arg1->j == arg2->j)) return 0;
    if (!(arg1->k == arg2->k)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_TypeA(TypeA * arg1, TypeA * arg2){
    /*PROTECTED REGION ID(protect_diff_TypeA) ENABLED START*/
    if (eq_TypeA(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_TypeA(TypeA * arg1, TypeA * arg2){
    /*PROTECTED REGION ID(protect_inf_TypeA) ENABLED START*/
    //TypeA is a position: compare the distances to the origin
    if ((arg1->i*arg1->i + arg1->j*arg1->j + arg1->k*arg1->k) < (arg2->i*arg2->i + arg2->j*arg2->j + arg2->k*arg2->k))
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int sup_TypeA(TypeA * arg1, TypeA * arg2){
    /*PROTECTED REGION ID(protect_sup_TypeA) ENABLED START*/
    //TypeA is a position: compare the distances to the origin
    if ((arg1->i*arg1->i + arg1->j*arg1->j + arg1->k*arg1->k) > (arg2->i*arg2->i + arg2->j*arg2->j + arg2->k*arg2->k))
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int infeq_TypeA(TypeA * arg1, TypeA * arg2){
    /*PROTECTED REGION ID(protect_infeq_TypeA) ENABLED START*/
    if (inf_TypeA(arg1,arg2) == 1 || eq_TypeA(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_TypeA(TypeA * arg1, TypeA * arg2){
    /*PROTECTED REGION ID(protect_supeq_TypeA) ENABLED START*/
    if (sup_TypeA(arg1,arg2) == 1 || eq_TypeA(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_TypeA) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
