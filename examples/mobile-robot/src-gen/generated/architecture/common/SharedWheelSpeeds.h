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
    double left;
    double right;
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
    size += extract_float(buffer, size, arg->left);
    size += extract_float(buffer, size, arg->right);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_WheelSpeeds(WheelSpeeds * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += fill_float(&arg->left, size, buffer);
    size += fill_float(&arg->right, size, buffer);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    if (arg1 == arg2) return;
    arg1->left=arg2->left;
    arg1->right=arg2->right;
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
    if ((res = get_float(&tmp.left, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.right, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_WheelSpeeds(arg, &tmp);
    return sizeread;
}

static inline void print_WheelSpeeds(WheelSpeeds * arg){
    printf("(object type %s : ", "WheelSpeeds");
    printf("%s : %lf ; ", "left", arg->left);
    printf("%s : %lf ; ", "right", arg->right);
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    /*PROTECTED REGION ID(protect_eq_WheelSpeeds) ENABLED START*/
    if (!(arg1->left == arg2->left)) return 0;
    if (!(arg1->right == arg2->right)) return 0;
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
    if (!(arg1->left < arg2->left)) return 0;
    if (!(arg1->right < arg2->right)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_WheelSpeeds(WheelSpeeds * arg1, WheelSpeeds * arg2){
    /*PROTECTED REGION ID(protect_sup_WheelSpeeds) ENABLED START*/
    if (!(arg1->left > arg2->left)) return 0;
    if (!(arg1->right > arg2->right)) return 0;
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
