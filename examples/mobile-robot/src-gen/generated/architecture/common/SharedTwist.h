#ifndef SHARED_TWIST_H
#define SHARED_TWIST_H
#include <stdio.h>
#include <string.h>
#include "tools.h"

//from here you can make new inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_Twist) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

typedef struct Twist{
    double v;
    double w;
} Twist;

static inline unsigned int serialize_Twist(Twist * arg, unsigned char * buffer);
static inline unsigned int deserialize_Twist(Twist * arg, unsigned char* buffer);
static inline int diff_Twist(Twist * arg1, Twist * arg2);
static inline int eq_Twist(Twist * arg1, Twist * arg2);
static inline int inf_Twist(Twist * arg1, Twist * arg2);
static inline int sup_Twist(Twist * arg1, Twist * arg2);
static inline int infeq_Twist(Twist * arg1, Twist * arg2);
static inline int supeq_Twist(Twist * arg1, Twist * arg2);
static inline void set_Twist(Twist * arg1, Twist * arg2);
static inline int get_Twist(Twist * arg, char* description);
static inline void print_Twist(Twist * arg);

//from here you can declare new functions
/*PROTECTED REGION ID(protect_additional_decl_Twist) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline unsigned int serialize_Twist(Twist * arg, unsigned char * buffer){
    unsigned int size = 0;
    size += extract_float(buffer, size, arg->v);
    size += extract_float(buffer, size, arg->w);
    (void)arg; (void)buffer;
    return size;
}

static inline unsigned int deserialize_Twist(Twist * arg, unsigned char* buffer){
    unsigned int size = 0;
    size += fill_float(&arg->v, size, buffer);
    size += fill_float(&arg->w, size, buffer);
    (void)arg; (void)buffer;
    return size;
}

static inline void set_Twist(Twist * arg1, Twist * arg2){
    if (arg1 == arg2) return;
    arg1->v=arg2->v;
    arg1->w=arg2->w;
}

/* parses the textual form {v1, v2, ...} (nested structures, "strings"); returns the number of
   characters read, or -1 (then *arg is unchanged) */
static inline int get_Twist(Twist * arg, char* description){
    int sizeread = 0, res = 0;
    char symbol = '{';
    Twist tmp;
    if (arg == NULL || description == NULL) return -1;
    set_Twist(&tmp, arg);
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.v, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = ',';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    if ((res = get_float(&tmp.w, &description[sizeread])) == -1) return -1;
    sizeread += res;
    symbol = '}';
    if ((res = increment_until_markerfound(&description[sizeread], &symbol)) == -1) return -1;
    sizeread += res;
    set_Twist(arg, &tmp);
    return sizeread;
}

static inline void print_Twist(Twist * arg){
    printf("(object type %s : ", "Twist");
    printf("%s : %lf ; ", "v", arg->v);
    printf("%s : %lf ; ", "w", arg->w);
    printf(")");
}

//functions that can be redefined by the user (let the comment markers unchanged by default, simply remove the ENABLED flag if you want to regenerate code)

static inline int eq_Twist(Twist * arg1, Twist * arg2){
    /*PROTECTED REGION ID(protect_eq_Twist) ENABLED START*/
    if (!(arg1->v == arg2->v)) return 0;
    if (!(arg1->w == arg2->w)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int diff_Twist(Twist * arg1, Twist * arg2){
    /*PROTECTED REGION ID(protect_diff_Twist) ENABLED START*/
    if (eq_Twist(arg1,arg2) == 0) return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int inf_Twist(Twist * arg1, Twist * arg2){
    /*PROTECTED REGION ID(protect_inf_Twist) ENABLED START*/
    if (!(arg1->v < arg2->v)) return 0;
    if (!(arg1->w < arg2->w)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int sup_Twist(Twist * arg1, Twist * arg2){
    /*PROTECTED REGION ID(protect_sup_Twist) ENABLED START*/
    if (!(arg1->v > arg2->v)) return 0;
    if (!(arg1->w > arg2->w)) return 0;
    return 1;
    /*PROTECTED REGION END*/
}

static inline int infeq_Twist(Twist * arg1, Twist * arg2){
    /*PROTECTED REGION ID(protect_infeq_Twist) ENABLED START*/
    if (inf_Twist(arg1,arg2) == 1 || eq_Twist(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

static inline int supeq_Twist(Twist * arg1, Twist * arg2){
    /*PROTECTED REGION ID(protect_supeq_Twist) ENABLED START*/
    if (sup_Twist(arg1,arg2) == 1 || eq_Twist(arg1,arg2) == 1)
        return 1;
    return 0;
    /*PROTECTED REGION END*/
}

//from here you can define new functions for your newly defined type
/*PROTECTED REGION ID(protect_additional_impl_Twist) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

#endif
