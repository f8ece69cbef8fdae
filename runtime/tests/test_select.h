/* Choosing tests by name on a runner's command line (runtime/tests/runner.c and the engines'
 * tests/engines/harness.c, `make -C runtime test-c T=...` / `test-engines T=...`): a name may be
 * given with or without the `test_` prefix of its C function; a name that chooses no test is an
 * error, said with the names near it and how to list them all (a run of nothing that "passes"
 * hid a misspelt name). Header-only: each runner is one program of its own. */
#ifndef TEST_SELECT_H
#define TEST_SELECT_H
#include <stdio.h>
#include <string.h>

/* `name` without a leading "test_" */
static inline const char *ts_bare(const char *name)
{
    return strncmp(name, "test_", 5) == 0 ? name + 5 : name;
}

/* does the word `given` choose the test `name`: equal (`exact`) or contained in it, either
 * without its "test_" prefix */
static inline int ts_chooses(const char *given, const char *name, int exact)
{
    const char *g = ts_bare(given), *n = ts_bare(name);
    return exact ? strcmp(g, n) == 0 : *g && strstr(n, g) != NULL;
}

/* do `a` and `b` (bare names) share a `_`-separated word of 3 letters or more */
static inline int ts_share_word(const char *a, const char *b)
{
    for (const char *p = a; *p;) {
        size_t l = strcspn(p, "_");
        if (l >= 3) {
            for (const char *q = b; *q;) {
                size_t m = strcspn(q, "_");
                if (m == l && strncmp(p, q, l) == 0) return 1;
                q += m + (q[m] == '_');
            }
        }
        p += l + (p[l] == '_');
    }
    return 0;
}

/* says on stderr that `given` chooses none of the `n` tests `names`, with up to 8 near names
 * (containing it, or sharing a word with it) and how to list every name (`list_how`) */
static inline void ts_say_unknown(const char *given, const char *const *names, size_t n, const char *list_how)
{
    fprintf(stderr, "no test is named '%s'", given);
    int shown = 0;
    for (size_t i = 0; i < n && shown < 8; i++) {
        const char *g = ts_bare(given), *b = ts_bare(names[i]);
        if ((*g && strstr(b, g)) || (*b && strstr(g, b)) || ts_share_word(g, b))
            fprintf(stderr, "%s%s", shown++ ? ", " : "; near names: ", names[i]);
    }
    fprintf(stderr, "\nevery name: %s\n", list_how);
}
#endif
