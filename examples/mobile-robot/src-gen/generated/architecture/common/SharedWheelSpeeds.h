#ifndef SHARED_WHEELSPEEDS_H
#define SHARED_WHEELSPEEDS_H
#include <stdio.h>
#include <string.h>
#include "tools.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_WheelSpeeds) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct WheelSpeeds{
    double speed[2];
} WheelSpeeds;

static inline unsigned int serialize_WheelSpeeds(WheelSpeeds * arg, unsigned char * buffer);
static inline unsigned int deserialize_WheelSpeeds(WheelSpeeds * arg, unsigned char* buffer);
static inline int diff_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2);
static inline int eq_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2);
static inline int inf_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2);
static inline int sup_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2);
static inline int infeq_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2);
static inline int supeq_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2);
static inline void set_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2);
static inline int get_WheelSpeeds(WheelSpeeds * arg, char* description);
static inline void print_WheelSpeeds(WheelSpeeds * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_WheelSpeeds) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_WheelSpeeds(WheelSpeeds * arg, unsigned char * buffer){
    unsigned int size = 0;
    for (unsigned int i0 = 0; i0 < 2; i0++) { size += extract_float(buffer, size, arg->speed[i0]); }
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_WheelSpeeds(WheelSpeeds * arg, unsigned char* buffer){
    unsigned int size = 0;
    for (unsigned int i0 = 0; i0 < 2; i0++) { size += fill_float(&arg->speed[i0], size, buffer); }
    (void)arg; (void)buffer;
    return size;
}

static inline void set_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    if (arg1 == arg2) return;
    memmove(arg1->speed, arg2->speed, sizeof(arg1->speed));
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_WheelSpeeds(WheelSpeeds * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    WheelSpeeds tmp;
    if (arg == NULL || description == NULL) return -1;
    set_WheelSpeeds(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    symbol = '{';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    for (unsigned int i0 = 0; i0 < 2; i0++) {
        if ((res = get_float(&tmp.speed[i0], &description[sizeread])) == -1) return -1;
        sizeread += res;
        symbol = i0 + 1 < 2 ? ',' : '}';
        if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
        sizeread += res;
    }
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_WheelSpeeds(arg, &tmp);
    return sizeread;
}

static inline void print_WheelSpeeds(WheelSpeeds * arg){
    printf("(object type %s : ", "WheelSpeeds");
    printf("%s : ", "speed"); printf("["); for (unsigned int i0 = 0; i0 < 2; i0++) { if (i0 > 0) printf(","); printf("%lf", arg->speed[i0]); } printf("]"); printf(" ; ");
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    /*PROTECTED REGION ID(protect_eq_WheelSpeeds) ENABLED START*/
    for (unsigned int i0 = 0; i0 < 2; i0++) if (!(arg1->speed[i0] == arg2->speed[i0])) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    /*PROTECTED REGION ID(protect_diff_WheelSpeeds) ENABLED START*/
    if (eq_WheelSpeeds(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    /*PROTECTED REGION ID(protect_inf_WheelSpeeds) ENABLED START*/
    for (unsigned int i0 = 0; i0 < 2; i0++) if (!(arg1->speed[i0] < arg2->speed[i0])) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    /*PROTECTED REGION ID(protect_sup_WheelSpeeds) ENABLED START*/
    for (unsigned int i0 = 0; i0 < 2; i0++) if (!(arg1->speed[i0] > arg2->speed[i0])) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    /*PROTECTED REGION ID(protect_infeq_WheelSpeeds) ENABLED START*/
    if (inf_WheelSpeeds(arg1,arg2) == 1 || eq_WheelSpeeds(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    /*PROTECTED REGION ID(protect_supeq_WheelSpeeds) ENABLED START*/
    if (sup_WheelSpeeds(arg1,arg2) == 1 || eq_WheelSpeeds(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_WheelSpeeds) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
