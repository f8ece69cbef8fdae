#ifndef SHARED_FUNCTION_TESTIT_H
#define SHARED_FUNCTION_TESTIT_H
#include <stdio.h>
#include <string.h>
#include "tools.h"
#include "SharedTypeA.h"

//from here you can make inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_function_testit) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline int testit(char * arg1, TypeA * arg2);

static inline int testit(char * arg1, TypeA * arg2){
    /*PROTECTED REGION ID(protect_function_impl_testit) ENABLED START*/
    //true when a message is given and the set point is a real position (no NaN component)
    if (arg1 == NULL || arg2 == NULL || arg1[0] == '\0') return 0;
    if (arg2->i != arg2->i || arg2->j != arg2->j || arg2->k != arg2->k) return 0;
    printf("testit(\"%s\", ", arg1); print_TypeA(arg2); printf(") => 1\n");
    return 1;//return 0 when result is false otherwise must return 1
    /*PROTECTED REGION END*/
}

#endif
