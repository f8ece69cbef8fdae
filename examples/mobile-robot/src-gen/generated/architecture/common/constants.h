//          named constants of the architecture (generated; do not edit)
#ifndef CONTRACT_GENERATED_CONSTANTS_H
#define CONTRACT_GENERATED_CONSTANTS_H

#define NBEAMS (180)
#define AHEAD (90)

#endif
