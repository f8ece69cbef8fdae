#ifndef SHARED_WHEELTICKS_H
#define SHARED_WHEELTICKS_H
#include <stdio.h>
#include <string.h>
#include "tools.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_WheelTicks) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct WheelTicks{
    long count[2];
    double dt;
} WheelTicks;

static inline unsigned int serialize_WheelTicks(WheelTicks * arg, unsigned char * buffer);
static inline unsigned int deserialize_WheelTicks(WheelTicks * arg, unsigned char* buffer);
static inline int diff_WheelTicks(WheelTicks * arg1, WheelTicks * arg2);
static inline int eq_WheelTicks(WheelTicks * arg1, WheelTicks * arg2);
static inline int inf_WheelTicks(WheelTicks * arg1, WheelTicks * arg2);
static inline int sup_WheelTicks(WheelTicks * arg1, WheelTicks * arg2);
static inline int infeq_WheelTicks(WheelTicks * arg1, WheelTicks * arg2);
static inline int supeq_WheelTicks(WheelTicks * arg1, WheelTicks * arg2);
static inline void set_WheelTicks(WheelTicks * arg1, WheelTicks * arg2);
static inline int get_WheelTicks(WheelTicks * arg, char* description);
static inline void print_WheelTicks(WheelTicks * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_WheelTicks) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_WheelTicks(WheelTicks * arg, unsigned char * buffer){
    unsigned int size = 0;
    for (unsigned int i0 = 0; i0 < 2; i0++) { size += extract_int(buffer, size, arg->count[i0]); }
    size += extract_float(buffer, size, arg->dt);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_WheelTicks(WheelTicks * arg, unsigned char* buffer){
    unsigned int size = 0;
    for (unsigned int i0 = 0; i0 < 2; i0++) { size += fill_int(&arg->count[i0], size, buffer); }
    size += fill_float(&arg->dt, size, buffer);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_WheelTicks(WheelTicks * arg1, WheelTicks * arg2){
    if (arg1 == arg2) return;
    memmove(arg1->count, arg2->count, sizeof(arg1->count));
    arg1->dt=arg2->dt;
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_WheelTicks(WheelTicks * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    WheelTicks tmp;
    if (arg == NULL || description == NULL) return -1;
    set_WheelTicks(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    symbol = '{';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    for (unsigned int i0 = 0; i0 < 2; i0++) {
        if ((res = get_int(&tmp.count[i0], &description[sizeread])) == -1) return -1;
        sizeread += res;
        symbol = i0 + 1 < 2 ? ',' : '}';
        if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
        sizeread += res;
    }
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.dt, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_WheelTicks(arg, &tmp);
    return sizeread;
}

static inline void print_WheelTicks(WheelTicks * arg){
    printf("(object type %s : ", "WheelTicks");
    printf("%s : ", "count"); printf("["); for (unsigned int i0 = 0; i0 < 2; i0++) { if (i0 > 0) printf(","); printf("%ld", arg->count[i0]); } printf("]"); printf(" ; ");
    printf("%s : %lf ; ", "dt", arg->dt);
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_WheelTicks(WheelTicks * arg1, WheelTicks * arg2){
    /*PROTECTED REGION ID(protect_eq_WheelTicks) ENABLED START*/
    for (unsigned int i0 = 0; i0 < 2; i0++) if (!(arg1->count[i0] == arg2->count[i0])) return 0;
    if (!(arg1->dt == arg2->dt)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_WheelTicks(WheelTicks * arg1, WheelTicks * arg2){
    /*PROTECTED REGION ID(protect_diff_WheelTicks) ENABLED START*/
    if (eq_WheelTicks(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_WheelTicks(WheelTicks * arg1, WheelTicks * arg2){
    /*PROTECTED REGION ID(protect_inf_WheelTicks) ENABLED START*/
    for (unsigned int i0 = 0; i0 < 2; i0++) if (!(arg1->count[i0] < arg2->count[i0])) return 0;
    if (!(arg1->dt < arg2->dt)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_WheelTicks(WheelTicks * arg1, WheelTicks * arg2){
    /*PROTECTED REGION ID(protect_sup_WheelTicks) ENABLED START*/
    for (unsigned int i0 = 0; i0 < 2; i0++) if (!(arg1->count[i0] > arg2->count[i0])) return 0;
    if (!(arg1->dt > arg2->dt)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_WheelTicks(WheelTicks * arg1, WheelTicks * arg2){
    /*PROTECTED REGION ID(protect_infeq_WheelTicks) ENABLED START*/
    if (inf_WheelTicks(arg1,arg2) == 1 || eq_WheelTicks(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_WheelTicks(WheelTicks * arg1, WheelTicks * arg2){
    /*PROTECTED REGION ID(protect_supeq_WheelTicks) ENABLED START*/
    if (sup_WheelTicks(arg1,arg2) == 1 || eq_WheelTicks(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_WheelTicks) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
