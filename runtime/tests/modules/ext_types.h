/* Types of the extension (bool, enumeration, arrays, 2-D, arrays of structs) as the generator
 * maps them to C, for the mailbox round trip of emod.c / test_ext_types.c. */
#ifndef EXT_TYPES_H
#define EXT_TYPES_H
#include <stdbool.h>
typedef enum XMode { XMode_IDLE = 0, XMode_TELEOP = 1, XMode_AUTO = 2 } XMode;
typedef struct XCell { long id; double w; char tag[256]; } XCell;
typedef struct XScan {
    double ranges[180];
    XMode mode;
    bool ok;
    XCell cells[2];
    double m[3][3];
} XScan;
/* event port k of ECHO (in and out): 0 bool, 1 XMode, 2 float[3][3], 3 XCell[4], 4 XScan */
#define EXT_NPORTS 5
#endif
