#ifndef SHARED_TYPEC_H
#define SHARED_TYPEC_H
#include <stdio.h>
#include <string.h>
#include "tools.h"
#include "SharedTypeA.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_TypeC) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct TypeC{
    char message[256];
    long messagetype;
    TypeA value;
} TypeC;

static inline unsigned int serialize_TypeC(TypeC * arg, unsigned char * buffer);
static inline unsigned int deserialize_TypeC(TypeC * arg, unsigned char* buffer);
static inline int diff_TypeC(TypeC * arg1, TypeC * arg2);
static inline int eq_TypeC(TypeC * arg1, TypeC * arg2);
static inline int inf_TypeC(TypeC * arg1, TypeC * arg2);
static inline int sup_TypeC(TypeC * arg1, TypeC * arg2);
static inline int infeq_TypeC(TypeC * arg1, TypeC * arg2);
static inline int supeq_TypeC(TypeC * arg1, TypeC * arg2);
static inline void set_TypeC(TypeC * arg1, TypeC * arg2);
static inline int get_TypeC(TypeC * arg, char* description);
static inline void print_TypeC(TypeC * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_TypeC) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_TypeC(TypeC * arg, unsigned char * buffer){
    unsigned int size = 0;
    size += extract_string(buffer, size, arg->message);
    size += extract_int(buffer, size, arg->messagetype);
    size += serialize_TypeA(&arg->value, &buffer[size]);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_TypeC(TypeC * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += fill_string(arg->message, size, buffer);
    size += fill_int(&arg->messagetype, size, buffer);
    size += deserialize_TypeA(&arg->value, &buffer[size]);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_TypeC(TypeC * arg1, TypeC * arg2){
    if (arg1 == arg2) return;
    memmove(arg1->message, arg2->message, sizeof(arg1->message));
    arg1->messagetype=arg2->messagetype;
    set_TypeA(&arg1->value, &arg2->value);
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_TypeC(TypeC * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    TypeC tmp;
    if (arg == NULL || description == NULL) return -1;
    set_TypeC(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_string(tmp.message, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_int(&tmp.messagetype, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_TypeA(&tmp.value, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_TypeC(arg, &tmp);
    return sizeread;
}

static inline void print_TypeC(TypeC * arg){
    printf("(object type %s : ", "TypeC");
    printf("%s : %s ; ", "message", arg->message);
    printf("%s : %ld ; ", "messagetype", arg->messagetype);
    printf("%s : ", "value"); print_TypeA(&arg->value); printf(" ; ");
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_TypeC(TypeC * arg1, TypeC * arg2){
    /*PROTECTED REGION ID(protect_eq_TypeC) ENABLED START*/
    if (!(strcmp(arg1->message, arg2->message) == 0)) return 0;
    if (!(arg1->messagetype == arg2->messagetype)) return 0;
    if (!(eq_TypeA(&arg1->value, &arg2->value))) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_TypeC(TypeC * arg1, TypeC * arg2){
    /*PROTECTED REGION ID(protect_diff_TypeC) ENABLED START*/
    if (eq_TypeC(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_TypeC(TypeC * arg1, TypeC * arg2){
    /*PROTECTED REGION ID(protect_inf_TypeC) ENABLED START*/
    if (!(strcmp(arg1->message, arg2->message) < 0)) return 0;
    if (!(arg1->messagetype < arg2->messagetype)) return 0;
    if (!(inf_TypeA(&arg1->value, &arg2->value))) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_TypeC(TypeC * arg1, TypeC * arg2){
    /*PROTECTED REGION ID(protect_sup_TypeC) ENABLED START*/
    if (!(strcmp(arg1->message, arg2->message) > 0)) return 0;
    if (!(arg1->messagetype > arg2->messagetype)) return 0;
    if (!(sup_TypeA(&arg1->value, &arg2->value))) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_TypeC(TypeC * arg1, TypeC * arg2){
    /*PROTECTED REGION ID(protect_infeq_TypeC) ENABLED START*/
    if (inf_TypeC(arg1,arg2) == 1 || eq_TypeC(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_TypeC(TypeC * arg1, TypeC * arg2){
    /*PROTECTED REGION ID(protect_supeq_TypeC) ENABLED START*/
    if (sup_TypeC(arg1,arg2) == 1 || eq_TypeC(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_TypeC) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
