/*
 * itest.c — integration test of the engines with real processes through libmodule and
 * contract-launch. Runs every scenario of itest_scenarios.h in a fresh temporary directory,
 * kept for inspection when a check fails.
 * Usage: itest <dir with the test executables> <contract-launch>. Prints "N passed, N failed".
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>

#include "itest_scenarios.h"
#include "itest_support.h"

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: itest <bin dir> <contract-launch>\n");
        return 2;
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    char tmpl[] = "/tmp/contract-engines-itest-XXXXXX";
    char *root = mkdtemp(tmpl);
    if (!root) {
        perror("mkdtemp");
        return 2;
    }
    scenario_scheduler(root, argv[1], argv[2]);
    scenario_nested(root, argv[1], argv[2]);
    scenario_shared_module(root, argv[1], argv[2]);
    scenario_reactivation(root, argv[1], argv[2]);
    scenario_hold_toggles(root, argv[1], argv[2]);
    scenario_undo_own(root, argv[1], argv[2]);
    if (itest_failed()) {
        fprintf(stderr, "kept %s for inspection\n", root);
    } else {
        char cmd[300];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
        if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", root);
    }
    printf("%d passed, %d failed\n", itest_passed(), itest_failed());
    return itest_failed() ? 1 : 0;
}
