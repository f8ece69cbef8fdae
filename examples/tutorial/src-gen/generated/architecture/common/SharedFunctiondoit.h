#ifndef SHARED_FUNCTION_DOIT_H
#define SHARED_FUNCTION_DOIT_H
#include <stdio.h>
#include <string.h>
#include "tools.h"

//from here you can make inclusions and definitions
/*PROTECTED REGION ID(protect_additional_import_function_doit) ENABLED START*/
//TODO
/*PROTECTED REGION END*/

static inline void doit(char * argfirst, double * argsecond);

static inline void doit(char * argfirst, double * argsecond){
    /*PROTECTED REGION ID(protect_function_impl_doit) ENABLED START*/
    //compute function: logs its arguments and halves the set point component it is given
    printf("doit(\"%s\", %f)\n", argfirst, *argsecond);
    *argsecond = *argsecond / 2.0;
    /*PROTECTED REGION END*/
}

#endif
