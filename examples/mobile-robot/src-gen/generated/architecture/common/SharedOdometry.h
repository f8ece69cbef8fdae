#ifndef SHARED_ODOMETRY_H
#define SHARED_ODOMETRY_H
#include <stdio.h>
#include <string.h>
#include "tools.h"
#include "SharedPose.h"
#include "SharedTwist.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_Odometry) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct Odometry{
    Pose pose;
    Twist twist;
} Odometry;

static inline unsigned int serialize_Odometry(Odometry * arg, unsigned char * buffer);
static inline unsigned int deserialize_Odometry(Odometry * arg, unsigned char* buffer);
static inline int diff_Odometry(Odometry * arg1, Odometry * arg2);
static inline int eq_Odometry(Odometry * arg1, Odometry * arg2);
static inline int inf_Odometry(Odometry * arg1, Odometry * arg2);
static inline int sup_Odometry(Odometry * arg1, Odometry * arg2);
static inline int infeq_Odometry(Odometry * arg1, Odometry * arg2);
static inline int supeq_Odometry(Odometry * arg1, Odometry * arg2);
static inline void set_Odometry(Odometry * arg1, Odometry * arg2);
static inline int get_Odometry(Odometry * arg, char* description);
static inline void print_Odometry(Odometry * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_Odometry) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_Odometry(Odometry * arg, unsigned char * buffer){
    unsigned int size = 0;
    size += serialize_Pose(&arg->pose, &buffer[size]);
    size += serialize_Twist(&arg->twist, &buffer[size]);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_Odometry(Odometry * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += deserialize_Pose(&arg->pose, &buffer[size]);
    size += deserialize_Twist(&arg->twist, &buffer[size]);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_Odometry(Odometry * arg1, Odometry * arg2){
    if (arg1 == arg2) return;
    set_Pose(&arg1->pose, &arg2->pose);
    set_Twist(&arg1->twist, &arg2->twist);
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_Odometry(Odometry * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    Odometry tmp;
    if (arg == NULL || description == NULL) return -1;
    set_Odometry(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_Pose(&tmp.pose, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_Twist(&tmp.twist, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_Odometry(arg, &tmp);
    return sizeread;
}

static inline void print_Odometry(Odometry * arg){
    printf("(object type %s : ", "Odometry");
    printf("%s : ", "pose"); print_Pose(&arg->pose); printf(" ; ");
    printf("%s : ", "twist"); print_Twist(&arg->twist); printf(" ; ");
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_Odometry(Odometry * arg1, Odometry * arg2){
    /*PROTECTED REGION ID(protect_eq_Odometry) ENABLED START*/
    if (!(eq_Pose(&arg1->pose, &arg2->pose))) return 0;
    if (!(eq_Twist(&arg1->twist, &arg2->twist))) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_Odometry(Odometry * arg1, Odometry * arg2){
    /*PROTECTED REGION ID(protect_diff_Odometry) ENABLED START*/
    if (eq_Odometry(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_Odometry(Odometry * arg1, Odometry * arg2){
    /*PROTECTED REGION ID(protect_inf_Odometry) ENABLED START*/
    if (!(inf_Pose(&arg1->pose, &arg2->pose))) return 0;
    if (!(inf_Twist(&arg1->twist, &arg2->twist))) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_Odometry(Odometry * arg1, Odometry * arg2){
    /*PROTECTED REGION ID(protect_sup_Odometry) ENABLED START*/
    if (!(sup_Pose(&arg1->pose, &arg2->pose))) return 0;
    if (!(sup_Twist(&arg1->twist, &arg2->twist))) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_Odometry(Odometry * arg1, Odometry * arg2){
    /*PROTECTED REGION ID(protect_infeq_Odometry) ENABLED START*/
    if (inf_Odometry(arg1,arg2) == 1 || eq_Odometry(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_Odometry(Odometry * arg1, Odometry * arg2){
    /*PROTECTED REGION ID(protect_supeq_Odometry) ENABLED START*/
    if (sup_Odometry(arg1,arg2) == 1 || eq_Odometry(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_Odometry) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
