/* Test runner: runs every registered test (or those named on the command line after the
 * binary directory), prints one line per test and "N passed, N failed". */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <signal.h>
#include <unistd.h>
#include "harness.h"
#include "tests.h"

static const char *current = "";

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
    if (argc < 2) { fprintf(stderr, "usage: %s BIN_DIR [TEST...]\n", argv[0]); return 2; }
    static char bin[4096];
    if (!realpath(argv[1], bin)) { perror(argv[1]); return 2; }
    h_bin_dir = bin;
    int passed = 0, failed = 0;
    for (const TestCase *t = ALL_TESTS; t->name; t++) {
        if (argc > 2) {
            int wanted = 0;
            for (int i = 2; i < argc; i++) wanted |= strcmp(argv[i], t->name) == 0;
            if (!wanted) continue;
        }
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
