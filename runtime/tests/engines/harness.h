/*
 * harness.h — a minimal test harness for the engine tests: CHECK macros that report the
 * file/line and let the test continue, and an event log (one line per observable effect)
 * compared line by line against the expected sequence.
 */
#ifndef ENGINES_TEST_HARNESS_H
#define ENGINES_TEST_HARNESS_H

#include <stdio.h>

extern int th_current_failed;

#define CHECK(cond)                                                                      \
    do {                                                                                 \
        if (!(cond)) {                                                                   \
            fprintf(stderr, "  %s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);   \
            th_current_failed = 1;                                                       \
        }                                                                                \
    } while (0)

#define LOG_MAX_LINES 1024
#define LOG_LINE 200

/** The observable effects of a run, in order. */
typedef struct TestLog {
    int n;
    char lines[LOG_MAX_LINES][LOG_LINE];
} TestLog;

void log_clear(TestLog *l);
void log_add(TestLog *l, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/** Lines of the log that contain one of the `prefixes` strings (NULL-terminated list; NULL:
 *  every line), in order,
 *  must be exactly `expected` (NULL-terminated). Prints a diff and fails the test otherwise. */
void check_log_filtered(const TestLog *l, const char *const *prefixes, const char *const *expected,
                        const char *file, int line);
#define CHECK_LOG(log, ...)                                                              \
    check_log_filtered((log), NULL, (const char *const[]){__VA_ARGS__, NULL}, __FILE__, __LINE__)
/** Index of the first line equal to s at or after from, or -1. */
int log_find(const TestLog *l, const char *s, int from);
void log_dump(const TestLog *l);

typedef struct TestCase {
    const char *name;
    void (*fn)(void);
} TestCase;

#endif
