/* engine_array.h — the growable arrays of the engines and the simulator (timers, holds, claims,
 * virtual modules): capacity doubled from `first`, so that appending stays amortised O(1). */
#ifndef CONTRACT_ENGINE_ARRAY_H
#define CONTRACT_ENGINE_ARRAY_H

#include <stdlib.h>

/* Makes room for `need` elements of `elem` bytes in *p (capacity *cap); 0, or -1 when out of
 * memory (then *p and *cap are unchanged). */
static inline int engine_grow(void **p, int *cap, int need, size_t elem, int first) {
    if (need <= *cap) return 0;
    int n = *cap ? *cap * 2 : first;
    while (n < need) n *= 2;
    void *q = realloc(*p, (size_t)n * elem);
    if (!q) return -1;
    *p = q;
    *cap = n;
    return 0;
}

#endif
