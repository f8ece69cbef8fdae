#ifndef SHARED_TYPEB_H
#define SHARED_TYPEB_H
#include <stdio.h>
#include <string.h>
#include "tools.h"
#include "SharedTypeA.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_TypeB) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct TypeB{
    TypeA coord;
    long frfrrrf;
} TypeB;

static inline unsigned int serialize_TypeB(TypeB * arg, unsigned char * buffer);
static inline unsigned int deserialize_TypeB(TypeB * arg, unsigned char* buffer);
static inline int diff_TypeB(TypeB * arg1, TypeB * arg2);
static inline int eq_TypeB(TypeB * arg1, TypeB * arg2);
static inline int inf_TypeB(TypeB * arg1, TypeB * arg2);
static inline int sup_TypeB(TypeB * arg1, TypeB * arg2);
static inline int infeq_TypeB(TypeB * arg1, TypeB * arg2);
static inline int supeq_TypeB(TypeB * arg1, TypeB * arg2);
static inline void set_TypeB(TypeB * arg1, TypeB * arg2);
static inline int get_TypeB(TypeB * arg, char* description);
static inline void print_TypeB(TypeB * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_TypeB) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_TypeB(TypeB * arg, unsigned char * buffer){
    unsigned int size = 0;
    size += serialize_TypeA(&arg->coord, &buffer[size]);
    size += extract_int(buffer, size, arg->frfrrrf);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_TypeB(TypeB * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += deserialize_TypeA(&arg->coord, &buffer[size]);
    size += fill_int(&arg->frfrrrf, size, buffer);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_TypeB(TypeB * arg1, TypeB * arg2){
    if (arg1 == arg2) return;
    set_TypeA(&arg1->coord, &arg2->coord);
    arg1->frfrrrf=arg2->frfrrrf;
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_TypeB(TypeB * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    TypeB tmp;
    if (arg == NULL || description == NULL) return -1;
    set_TypeB(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_TypeA(&tmp.coord, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_int(&tmp.frfrrrf, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_TypeB(arg, &tmp);
    return sizeread;
}

static inline void print_TypeB(TypeB * arg){
    printf("(object type %s : ", "TypeB");
    printf("%s : ", "coord"); print_TypeA(&arg->coord); printf(" ; ");
    printf("%s : %ld ; ", "frfrrrf", arg->frfrrrf);
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_TypeB(TypeB * arg1, TypeB * arg2){
    /*PROTECTED REGION ID(protect_eq_TypeB) ENABLED START*/
    if (!(eq_TypeA(&arg1->coord, &arg2->coord))) return 0;
    if (!(arg1->frfrrrf == arg2->frfrrrf)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_TypeB(TypeB * arg1, TypeB * arg2){
    /*PROTECTED REGION ID(protect_diff_TypeB) ENABLED START*/
    if (eq_TypeB(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_TypeB(TypeB * arg1, TypeB * arg2){
    /*PROTECTED REGION ID(protect_inf_TypeB) ENABLED START*/
    if (!(inf_TypeA(&arg1->coord, &arg2->coord))) return 0;
    if (!(arg1->frfrrrf < arg2->frfrrrf)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_TypeB(TypeB * arg1, TypeB * arg2){
    /*PROTECTED REGION ID(protect_sup_TypeB) ENABLED START*/
    if (!(sup_TypeA(&arg1->coord, &arg2->coord))) return 0;
    if (!(arg1->frfrrrf > arg2->frfrrrf)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_TypeB(TypeB * arg1, TypeB * arg2){
    /*PROTECTED REGION ID(protect_infeq_TypeB) ENABLED START*/
    if (inf_TypeB(arg1,arg2) == 1 || eq_TypeB(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_TypeB(TypeB * arg1, TypeB * arg2){
    /*PROTECTED REGION ID(protect_supeq_TypeB) ENABLED START*/
    if (sup_TypeB(arg1,arg2) == 1 || eq_TypeB(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_TypeB) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
