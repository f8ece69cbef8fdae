/* Test runner: runs every registered test (or those named on the command line after the
 * binary directory, with or without the `test_` prefix of their C function), prints one line per
 * test and "N passed, N failed". A name that is no test's fails the run before any test runs
 * (exit 2, with the names near it); `--list` prints every name. */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <signal.h>
#include <unistd.h>
#include "harness.h"
#include "tests.h"
#include "test_select.h"

static const char *current = "";

#define LIST_HOW "make -C runtime test-c T=--list (tests/tests.h, ALL_TESTS)"

/* is the test `name` among the names given (none given: every test) */
static int wanted(const char *name, int argc, char *argv[])
{
    if (argc <= 2) return 1;
    for (int i = 2; i < argc; i++)
        if (ts_chooses(argv[i], name, 1)) return 1;
    return 0;
}

/* every given name chooses a test, else says which does not (0) */
static int names_known(int argc, char *argv[])
{
    static const char *names[sizeof ALL_TESTS / sizeof ALL_TESTS[0]];
    size_t n = 0;
    for (const TestCase *t = ALL_TESTS; t->name; t++) names[n++] = t->name;
    int ok = 1;
    for (int i = 2; i < argc; i++) {
        int found = 0;
        for (size_t k = 0; k < n; k++) found |= ts_chooses(argv[i], names[k], 1);
        if (!found) { ts_say_unknown(argv[i], names, n, LIST_HOW); ok = 0; }
    }
    return ok;
}

static void on_timeout(int sig)
{
    (void)sig;
    /* a test must never hang the suite: report it and stop */
    static const char msg[] = "FAIL timeout (60 s) in test ";
    ssize_t w = write(2, msg, sizeof msg - 1);
    w = write(2, current, strlen(current));
    w = write(2, "\n", 1);
    (void)w;
    _exit(3);
}

int main(int argc, char *argv[])
{
    signal(SIGALRM, on_timeout);
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--list") == 0) {
            for (const TestCase *t = ALL_TESTS; t->name; t++) printf("%s\n", t->name);
            return 0;
        }
    if (argc < 2) { fprintf(stderr, "usage: %s BIN_DIR [TEST...] | --list\n", argv[0]); return 2; }
    if (!names_known(argc, argv)) return 2;
    static char bin[4096];
    if (!realpath(argv[1], bin)) { perror(argv[1]); return 2; }
    h_bin_dir = bin;
    int passed = 0, failed = 0;
    for (const TestCase *t = ALL_TESTS; t->name; t++) {
        if (!wanted(t->name, argc, argv)) continue;
        h_failures = 0;
        struct timespec a, b;
        clock_gettime(CLOCK_MONOTONIC, &a);
        current = t->name;
        alarm(60);
        t->fn();
        alarm(0);
        if (h_active) h_teardown();
        clock_gettime(CLOCK_MONOTONIC, &b);
        double ms = (double)(b.tv_sec - a.tv_sec) * 1e3 + (double)(b.tv_nsec - a.tv_nsec) / 1e6;
        if (h_failures) failed++; else passed++;
        printf("%s %s (%.0f ms)\n", h_failures ? "FAIL" : "ok  ", t->name, ms);
        fflush(stdout);
    }
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
