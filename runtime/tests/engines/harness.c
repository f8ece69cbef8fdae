/* harness.c — see harness.h; also main(): runs every test of tests.def, prints the counts. */
#include "harness.h"
#include "../test_select.h"

#include <stdarg.h>
#include <string.h>

int th_current_failed;

void log_clear(TestLog *l) { l->n = 0; }

void log_add(TestLog *l, const char *fmt, ...) {
    if (l->n >= LOG_MAX_LINES) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(l->lines[l->n], LOG_LINE, fmt, ap);
    va_end(ap);
    l->n++;
}

static int wanted(const char *line, const char *const *prefixes) {
    if (!prefixes) return 1;
    for (int i = 0; prefixes[i]; i++)
        if (strstr(line, prefixes[i])) return 1;
    return 0;
}

void log_dump(const TestLog *l) {
    for (int i = 0; i < l->n; i++) fprintf(stderr, "      | %s\n", l->lines[i]);
}

void check_log_filtered(const TestLog *l, const char *const *prefixes, const char *const *expected,
                        const char *file, int line) {
    int j = 0, ok = 1;
    for (int i = 0; i < l->n; i++) {
        if (!wanted(l->lines[i], prefixes)) continue;
        if (!expected[j] || strcmp(expected[j], l->lines[i]) != 0) {
            fprintf(stderr, "  %s:%d: log line %d is \"%s\", expected \"%s\"\n", file, line, j,
                    l->lines[i], expected[j] ? expected[j] : "(end)");
            ok = 0;
            break;
        }
        j++;
    }
    if (ok && expected[j]) {
        fprintf(stderr, "  %s:%d: log ended, expected \"%s\"\n", file, line, expected[j]);
        ok = 0;
    }
    if (!ok) {
        fprintf(stderr, "    actual log:\n");
        log_dump(l);
        th_current_failed = 1;
    }
}

int log_find(const TestLog *l, const char *s, int from) {
    for (int i = from < 0 ? 0 : from; i < l->n; i++)
        if (strcmp(l->lines[i], s) == 0) return i;
    return -1;
}

#define TEST(name) void name(void);
#include "tests.def"
#undef TEST

static const TestCase TESTS[] = {
#define TEST(name) {#name, name},
#include "tests.def"
#undef TEST
};

/* is the test `name` chosen by one of the words given (none given: every test) */
static int chosen(const char *name, int argc, char **argv) {
    if (argc <= 1) return 1;
    for (int i = 1; i < argc; i++)
        if (ts_chooses(argv[i], name, 0)) return 1;
    return 0;
}

#define NTESTS (sizeof TESTS / sizeof TESTS[0])
#define LIST_HOW "make -C runtime test-engines T=--list (tests/engines/tests.def)"

/* Runs the tests whose names contain one of the words given (every test without any; `test_`
 * prefix optional); a word that chooses no test fails the run before any test runs (exit 2, with
 * the names near it); `--list` prints every name. */
int main(int argc, char **argv) {
    const char *names[NTESTS];
    for (size_t i = 0; i < NTESTS; i++) names[i] = TESTS[i].name;
    int known = 1;
    for (int a = 1; a < argc; a++) {
        if (strcmp(argv[a], "--list") == 0) {
            for (size_t i = 0; i < NTESTS; i++) printf("%s\n", names[i]);
            return 0;
        }
        int found = 0;
        for (size_t i = 0; i < NTESTS; i++) found |= ts_chooses(argv[a], names[i], 0);
        if (!found) { ts_say_unknown(argv[a], names, NTESTS, LIST_HOW); known = 0; }
    }
    if (!known) return 2;
    int passed = 0, failed = 0;
    for (size_t i = 0; i < NTESTS; i++) {
        if (!chosen(TESTS[i].name, argc, argv)) continue;
        th_current_failed = 0;
        TESTS[i].fn();
        if (th_current_failed) {
            failed++;
            printf("FAIL %s\n", TESTS[i].name);
        } else {
            passed++;
            printf("ok   %s\n", TESTS[i].name);
        }
    }
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
