/* harness.c — see harness.h; also main(): runs every test of tests.def, prints the counts. */
#include "harness.h"

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

int main(int argc, char **argv) {
    int passed = 0, failed = 0;
    for (size_t i = 0; i < sizeof TESTS / sizeof TESTS[0]; i++) {
        if (argc > 1 && !strstr(TESTS[i].name, argv[1])) continue;
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
