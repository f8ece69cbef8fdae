#ifndef SHARED_LASERSCAN_H
#define SHARED_LASERSCAN_H
#include <stdio.h>
#include <string.h>
#include <stdbool.h>
#include "tools.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_LaserScan) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct LaserScan{
    double ranges[180];
    bool blocked;
} LaserScan;

static inline unsigned int serialize_LaserScan(LaserScan * arg, unsigned char * buffer);
static inline unsigned int deserialize_LaserScan(LaserScan * arg, unsigned char* buffer);
static inline int diff_LaserScan(LaserScan * arg1, LaserScan * arg2);
static inline int eq_LaserScan(LaserScan * arg1, LaserScan * arg2);
static inline int inf_LaserScan(LaserScan * arg1, LaserScan * arg2);
static inline int sup_LaserScan(LaserScan * arg1, LaserScan * arg2);
static inline int infeq_LaserScan(LaserScan * arg1, LaserScan * arg2);
static inline int supeq_LaserScan(LaserScan * arg1, LaserScan * arg2);
static inline void set_LaserScan(LaserScan * arg1, LaserScan * arg2);
static inline int get_LaserScan(LaserScan * arg, char* description);
static inline void print_LaserScan(LaserScan * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_LaserScan) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_LaserScan(LaserScan * arg, unsigned char * buffer){
    unsigned int size = 0;
    for (unsigned int i0 = 0; i0 < 180; i0++) { size += extract_float(buffer, size, arg->ranges[i0]); }
    size += extract_bool(buffer, size, arg->blocked);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_LaserScan(LaserScan * arg, unsigned char* buffer){
    unsigned int size = 0;
    for (unsigned int i0 = 0; i0 < 180; i0++) { size += fill_float(&arg->ranges[i0], size, buffer); }
    size += fill_bool(&arg->blocked, size, buffer);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_LaserScan(LaserScan * arg1, LaserScan * arg2){
    if (arg1 == arg2) return;
    memmove(arg1->ranges, arg2->ranges, sizeof(arg1->ranges));
    arg1->blocked=arg2->blocked;
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_LaserScan(LaserScan * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    LaserScan tmp;
    if (arg == NULL || description == NULL) return -1;
    set_LaserScan(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    symbol = '{';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    for (unsigned int i0 = 0; i0 < 180; i0++) {
        if ((res = get_float(&tmp.ranges[i0], &description[sizeread])) == -1) return -1;
        sizeread += res;
        symbol = i0 + 1 < 180 ? ',' : '}';
        if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
        sizeread += res;
    }
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_bool(&tmp.blocked, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_LaserScan(arg, &tmp);
    return sizeread;
}

static inline void print_LaserScan(LaserScan * arg){
    printf("(object type %s : ", "LaserScan");
    printf("%s : ", "ranges"); printf("["); for (unsigned int i0 = 0; i0 < 180; i0++) { if (i0 > 0) printf(","); printf("%lf", arg->ranges[i0]); } printf("]"); printf(" ; ");
    printf("%s : %s ; ", "blocked", arg->blocked ? "true" : "false");
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_LaserScan(LaserScan * arg1, LaserScan * arg2){
    /*PROTECTED REGION ID(protect_eq_LaserScan) ENABLED START*/
    for (unsigned int i0 = 0; i0 < 180; i0++) if (!(arg1->ranges[i0] == arg2->ranges[i0])) return 0;
    if (!(arg1->blocked == arg2->blocked)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_LaserScan(LaserScan * arg1, LaserScan * arg2){
    /*PROTECTED REGION ID(protect_diff_LaserScan) ENABLED START*/
    if (eq_LaserScan(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_LaserScan(LaserScan * arg1, LaserScan * arg2){
    /*PROTECTED REGION ID(protect_inf_LaserScan) ENABLED START*/
    for (unsigned int i0 = 0; i0 < 180; i0++) if (!(arg1->ranges[i0] < arg2->ranges[i0])) return 0;
    if (!(arg1->blocked < arg2->blocked)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_LaserScan(LaserScan * arg1, LaserScan * arg2){
    /*PROTECTED REGION ID(protect_sup_LaserScan) ENABLED START*/
    for (unsigned int i0 = 0; i0 < 180; i0++) if (!(arg1->ranges[i0] > arg2->ranges[i0])) return 0;
    if (!(arg1->blocked > arg2->blocked)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_LaserScan(LaserScan * arg1, LaserScan * arg2){
    /*PROTECTED REGION ID(protect_infeq_LaserScan) ENABLED START*/
    if (inf_LaserScan(arg1,arg2) == 1 || eq_LaserScan(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_LaserScan(LaserScan * arg1, LaserScan * arg2){
    /*PROTECTED REGION ID(protect_supeq_LaserScan) ENABLED START*/
    if (sup_LaserScan(arg1,arg2) == 1 || eq_LaserScan(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_LaserScan) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
