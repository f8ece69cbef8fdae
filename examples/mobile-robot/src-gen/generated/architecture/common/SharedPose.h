#ifndef SHARED_POSE_H
#define SHARED_POSE_H
#include <stdio.h>
#include <string.h>
#include "tools.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_Pose) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct Pose{
    double x;
    double y;
    double theta;
} Pose;

static inline unsigned int serialize_Pose(Pose * arg, unsigned char * buffer);
static inline unsigned int deserialize_Pose(Pose * arg, unsigned char* buffer);
static inline int diff_Pose(Pose * arg1, Pose * arg2);
static inline int eq_Pose(Pose * arg1, Pose * arg2);
static inline int inf_Pose(Pose * arg1, Pose * arg2);
static inline int sup_Pose(Pose * arg1, Pose * arg2);
static inline int infeq_Pose(Pose * arg1, Pose * arg2);
static inline int supeq_Pose(Pose * arg1, Pose * arg2);
static inline void set_Pose(Pose * arg1, Pose * arg2);
static inline int get_Pose(Pose * arg, char* description);
static inline void print_Pose(Pose * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_Pose) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_Pose(Pose * arg, unsigned char * buffer){
    unsigned int size = 0;
    size += extract_float(buffer, size, arg->x);
    size += extract_float(buffer, size, arg->y);
    size += extract_float(buffer, size, arg->theta);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_Pose(Pose * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += fill_float(&arg->x, size, buffer);
    size += fill_float(&arg->y, size, buffer);
    size += fill_float(&arg->theta, size, buffer);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_Pose(Pose * arg1, Pose * arg2){
    if (arg1 == arg2) return;
    arg1->x=arg2->x;
    arg1->y=arg2->y;
    arg1->theta=arg2->theta;
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_Pose(Pose * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    Pose tmp;
    if (arg == NULL || description == NULL) return -1;
    set_Pose(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.x, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.y, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.theta, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_Pose(arg, &tmp);
    return sizeread;
}

static inline void print_Pose(Pose * arg){
    printf("(object type %s : ", "Pose");
    printf("%s : %lf ; ", "x", arg->x);
    printf("%s : %lf ; ", "y", arg->y);
    printf("%s : %lf ; ", "theta", arg->theta);
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_Pose(Pose * arg1, Pose * arg2){
    /*PROTECTED REGION ID(protect_eq_Pose) ENABLED START*/
    if (!(arg1->x == arg2->x)) return 0;
    if (!(arg1->y == arg2->y)) return 0;
    if (!(arg1->theta == arg2->theta)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_Pose(Pose * arg1, Pose * arg2){
    /*PROTECTED REGION ID(protect_diff_Pose) ENABLED START*/
    if (eq_Pose(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_Pose(Pose * arg1, Pose * arg2){
    /*PROTECTED REGION ID(protect_inf_Pose) ENABLED START*/
    if (!(arg1->x < arg2->x)) return 0;
    if (!(arg1->y < arg2->y)) return 0;
    if (!(arg1->theta < arg2->theta)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_Pose(Pose * arg1, Pose * arg2){
    /*PROTECTED REGION ID(protect_sup_Pose) ENABLED START*/
    if (!(arg1->x > arg2->x)) return 0;
    if (!(arg1->y > arg2->y)) return 0;
    if (!(arg1->theta > arg2->theta)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_Pose(Pose * arg1, Pose * arg2){
    /*PROTECTED REGION ID(protect_infeq_Pose) ENABLED START*/
    if (inf_Pose(arg1,arg2) == 1 || eq_Pose(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_Pose(Pose * arg1, Pose * arg2){
    /*PROTECTED REGION ID(protect_supeq_Pose) ENABLED START*/
    if (sup_Pose(arg1,arg2) == 1 || eq_Pose(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_Pose) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
