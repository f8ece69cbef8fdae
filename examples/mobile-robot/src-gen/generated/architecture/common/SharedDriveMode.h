#ifndef SHARED_DRIVEMODE_H
#define SHARED_DRIVEMODE_H
#include <stdio.h>
#include <string.h>
#include "tools.h"

/* enum DriveMode { TELEOP, AUTO, SAFESTOP } */
typedef enum DriveMode { DriveMode_TELEOP = 0, DriveMode_AUTO = 1, DriveMode_SAFESTOP = 2 } DriveMode;

static inline unsigned int serialize_DriveMode(DriveMode * arg, unsigned char * buffer){ return extract_int(buffer, 0, (long)*arg); }
static inline unsigned int deserialize_DriveMode(DriveMode * arg, unsigned char* buffer){
    long value = 0;
    unsigned int size = fill_int(&value, 0, buffer);
    if (value >= 0 && value < 3) *arg = (DriveMode)value;
    return size;
}
static inline int eq_DriveMode(DriveMode * arg1, DriveMode * arg2){ return *arg1 == *arg2; }
static inline int diff_DriveMode(DriveMode * arg1, DriveMode * arg2){ return *arg1 != *arg2; }
static inline int inf_DriveMode(DriveMode * arg1, DriveMode * arg2){ return *arg1 < *arg2; }
static inline int sup_DriveMode(DriveMode * arg1, DriveMode * arg2){ return *arg1 > *arg2; }
static inline int infeq_DriveMode(DriveMode * arg1, DriveMode * arg2){ return *arg1 <= *arg2; }
static inline int supeq_DriveMode(DriveMode * arg1, DriveMode * arg2){ return *arg1 >= *arg2; }
static inline void set_DriveMode(DriveMode * arg1, DriveMode * arg2){ *arg1 = *arg2; }

/* parses a member name (AUTO or DriveMode.AUTO) or its number; returns the number of characters
   read, or -1 (then *arg is unchanged) */
static inline int get_DriveMode(DriveMode * arg, char* description){
    static const char *const names[3] = { "TELEOP", "AUTO", "SAFESTOP" };
    int i = 0;
    if (arg == NULL || description == NULL) return -1;
    while (description[i] == ' ' || description[i] == '\t' || description[i] == '\n' || description[i] == '\r') i++;
    if (strncmp(&description[i], "DriveMode.", 10) == 0) i += 10;
    for (unsigned int m = 0; m < 3; m++) {
        size_t n = strlen(names[m]);
        char next = description[i + (int)n];
        if (strncmp(&description[i], names[m], n) == 0 && !(next == '_' || (next >= '0' && next <= '9') || (next >= 'a' && next <= 'z') || (next >= 'A' && next <= 'Z'))) {
            *arg = (DriveMode)m;
            return i + (int)n;
        }
    }
    long value = 0;
    int res = get_int(&value, &description[i]);
    if (res == -1 || value < 0 || value >= 3) return -1;
    *arg = (DriveMode)value;
    return i + res;
}

static inline void print_DriveMode(DriveMode * arg){
    static const char *const names[3] = { "TELEOP", "AUTO", "SAFESTOP" };
    if ((int)*arg >= 0 && (int)*arg < 3) printf("%s", names[*arg]);
    else printf("%d", (int)*arg);
}

#endif
