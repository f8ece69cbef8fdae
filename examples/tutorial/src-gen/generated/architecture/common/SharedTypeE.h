#ifndef SHARED_TYPEE_H
#define SHARED_TYPEE_H
#include <stdio.h>
#include <string.h>
#include "tools.h"
#include "SharedTypeC.h"
#include "SharedTypeD.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_TypeE) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct TypeE{
    TypeC message;
    TypeD data_;
} TypeE;

static inline unsigned int serialize_TypeE(TypeE * arg, unsigned char * buffer);
static inline unsigned int deserialize_TypeE(TypeE * arg, unsigned char* buffer);
static inline int diff_TypeE(TypeE * arg1, TypeE * arg2);
static inline int eq_TypeE(TypeE * arg1, TypeE * arg2);
static inline int inf_TypeE(TypeE * arg1, TypeE * arg2);
static inline int sup_TypeE(TypeE * arg1, TypeE * arg2);
static inline int infeq_TypeE(TypeE * arg1, TypeE * arg2);
static inline int supeq_TypeE(TypeE * arg1, TypeE * arg2);
static inline void set_TypeE(TypeE * arg1, TypeE * arg2);
static inline int get_TypeE(TypeE * arg, char* description);
static inline void print_TypeE(TypeE * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_TypeE) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_TypeE(TypeE * arg, unsigned char * buffer){
    unsigned int size = 0;
    size += serialize_TypeC(&arg->message, &buffer[size]);
    size += serialize_TypeD(&arg->data_, &buffer[size]);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_TypeE(TypeE * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += deserialize_TypeC(&arg->message, &buffer[size]);
    size += deserialize_TypeD(&arg->data_, &buffer[size]);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_TypeE(TypeE * arg1, TypeE * arg2){
    if (arg1 == arg2) return;
    set_TypeC(&arg1->message, &arg2->message);
    set_TypeD(&arg1->data_, &arg2->data_);
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_TypeE(TypeE * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    TypeE tmp;
    if (arg == NULL || description == NULL) return -1;
    set_TypeE(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_TypeC(&tmp.message, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_TypeD(&tmp.data_, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_TypeE(arg, &tmp);
    return sizeread;
}

static inline void print_TypeE(TypeE * arg){
    printf("(object type %s : ", "TypeE");
    printf("%s : ", "message"); print_TypeC(&arg->message); printf(" ; ");
    printf("%s : ", "data_"); print_TypeD(&arg->data_); printf(" ; ");
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_TypeE(TypeE * arg1, TypeE * arg2){
    /*PROTECTED REGION ID(protect_eq_TypeE) ENABLED START*/
    if (!(eq_TypeC(&arg1->message, &arg2->message))) return 0;
    if (!(eq_TypeD(&arg1->data_, &arg2->data_))) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_TypeE(TypeE * arg1, TypeE * arg2){
    /*PROTECTED REGION ID(protect_diff_TypeE) ENABLED START*/
    if (eq_TypeE(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_TypeE(TypeE * arg1, TypeE * arg2){
    /*PROTECTED REGION ID(protect_inf_TypeE) ENABLED START*/
    if (!(inf_TypeC(&arg1->message, &arg2->message))) return 0;
    if (!(inf_TypeD(&arg1->data_, &arg2->data_))) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_TypeE(TypeE * arg1, TypeE * arg2){
    /*PROTECTED REGION ID(protect_sup_TypeE) ENABLED START*/
    if (!(sup_TypeC(&arg1->message, &arg2->message))) return 0;
    if (!(sup_TypeD(&arg1->data_, &arg2->data_))) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_TypeE(TypeE * arg1, TypeE * arg2){
    /*PROTECTED REGION ID(protect_infeq_TypeE) ENABLED START*/
    if (inf_TypeE(arg1,arg2) == 1 || eq_TypeE(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_TypeE(TypeE * arg1, TypeE * arg2){
    /*PROTECTED REGION ID(protect_supeq_TypeE) ENABLED START*/
    if (sup_TypeE(arg1,arg2) == 1 || eq_TypeE(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_TypeE) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
