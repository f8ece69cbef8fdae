import { expandToNode, toString } from 'langium/generate';

/** `modules/<S>_mod/suptypes.h`: the supervisor's types (the engine's are in contract/vocabulary.h). */
export function supTypesHeader(name: string): string {
    return toString(expandToNode`
        // suptypes.h of supervisor ${name} (generated): the supervision engine's types are in contract/vocabulary.h,
        // the data types of its variables in the common/Shared<Type>.h headers that vocabulary.c includes.
        #ifndef SUPTYPES_${name}_H
        #define SUPTYPES_${name}_H
        #include <contract/vocabulary.h>
        #include "tools.h"
        #endif
    `) + '\n';
}
