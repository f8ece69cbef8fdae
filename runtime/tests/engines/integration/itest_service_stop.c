/*
 * itest_service_stop.c — a service manager's stop (systemd's default KillMode=control-group):
 * SIGTERM to the launcher (twice: make passes its own on) and to every module at once, while the
 * reactivation architecture runs (rsc/ORD, RSU --stop-first, RMA/RMB/RMC). The stop still goes
 * supervisors first: each module passes the SIGTERM it got to the launcher instead of ending
 * (core.c), the launcher's stop is not cut short by the repeated signal, so RSU's undo of its last
 * activation of RSC reaches ORD, which logs the deactivation; the launcher says no false wait.
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "itest_scenarios.h"
#include "itest_support.h"

static void sleep_ms(long ms) {
    struct timespec ts = {ms / 1000, (ms % 1000) * 1000000L};
    nanosleep(&ts, NULL);
}

/* the pids of the run directory's *.pid files (the launcher's and every module's), up to max */
static int run_pids(const char *run, pid_t *pids, int max) {
    DIR *d = opendir(run);
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL && n < max) {
        size_t l = strlen(e->d_name);
        if (l <= 4 || strcmp(e->d_name + l - 4, ".pid") != 0) continue;
        char path[800];
        snprintf(path, sizeof path, "%s/%s", run, e->d_name);
        char *text = slurp(path);
        long pid = text ? strtol(text, NULL, 10) : 0;
        free(text);
        if (pid > 1) pids[n++] = (pid_t)pid;
    }
    if (d) closedir(d);
    return n;
}

/* waits for the launcher `pid` up to `ms`; its wait status, or -1 (then it is killed) */
static int wait_launcher(pid_t pid, long ms) {
    int st = 0;
    for (long t = 0; t < ms; t += 20) {
        if (waitpid(pid, &st, WNOHANG) == pid) return st;
        sleep_ms(20);
    }
    kill(pid, SIGKILL);
    waitpid(pid, &st, 0);
    return -1;
}

void scenario_service_stop(const char *root, const char *bin, const char *launcher) {
    Scenario s;
    if (!scenario_begin(&s, root, "service-stop")) return;
    const char *const names[] = {"rsc/ORD", "RSU", "RMA", "RMB", "RMC", NULL};
    s.stop_first = "RSU";
    pid_t lp = scenario_spawn(&s, bin, launcher, "RSU.go()", NULL, names);
    if (!check(lp > 0, "service stop: the launcher started")) return;
    char *txt = NULL, *ord = NULL;
    for (int t = 0; t < 500; t++) { /* 10 s at most: the start sent, RSC activated */
        free(txt);
        free(ord);
        txt = slurp(s.launch);
        ord = read_csv_log(&s, "ORD");
        if (txt && strstr(txt, "started RSU.go(") && ord && strstr(ord, ",activate RSC")) break;
        sleep_ms(20);
    }
    check(txt && strstr(txt, "started RSU.go("), "service stop: the architecture started");
    sleep_ms(400);
    pid_t pids[16];
    int n = run_pids(s.run, pids, 16);
    check(n == 6, "service stop: the launcher and its 5 modules found by their .pid files");
    /* the service manager's: every process of the service, the modules first, then the launcher
     * (what make passes on). In the other order the launcher, woken by its own signal, could run
     * the whole stop (8 ms here) before this loop's signals reached the modules: they would end on
     * the launcher's KILL requests with no SIGTERM of their own to pass on */
    for (int i = 0; i < n; i++)
        if (pids[i] != lp) kill(pids[i], SIGTERM);
    kill(lp, SIGTERM);
    int st = wait_launcher(lp, 15000);
    free(txt);
    free(ord);
    txt = slurp(s.launch);
    ord = read_csv_log(&s, "ORD");
    check(st >= 0 && WIFEXITED(st) && WEXITSTATUS(st) == 0 && txt && strstr(txt, "all modules stopped cleanly"),
          "service stop: every module stopped cleanly, the launcher exited 0");
    check(txt && !strstr(txt, "did not end within"), "service stop: no 'did not end within' line (the supervisor's wait was not cut short)");
    /* the signals read before the stop began are one stop; one read while it runs is said, once */
    check(txt && count_of(txt, "while the run stops: the stop goes on in order") <= 1, "service stop: a repeated SIGTERM is said once at most");
    check(txt && strstr(txt, "[ORD] ORD: SIGTERM from pid ") && strstr(txt, "passed to contract-launch (pid "),
          "service stop: ORD passed its SIGTERM on to the launcher instead of ending");
    /* the launcher's end lines (not "SIGTERM from module ORD (pid N) while the run stops", which
     * names ORD when its passed-on signal is the repeated one the launcher tells) */
    const char *rsu_end = txt ? strstr(txt, "contract-launch: module RSU (pid ") : NULL, *ord_end = txt ? strstr(txt, "contract-launch: module ORD (pid ") : NULL;
    check(rsu_end && ord_end && rsu_end < ord_end, "service stop: RSU ended before ORD (supervisors first)");

    /* RSU's last undo of RSC reached ORD: ORD logged that very deactivation */
    char *rsu = read_csv_log(&s, "RSU");
    const char *undo = NULL;
    for (const char *p = rsu ? strstr(rsu, "\"undo: deactivate schema RSC (activation #") : NULL; p;
         p = strstr(p + 1, "\"undo: deactivate schema RSC (activation #"))
        undo = p;
    long activation = undo ? strtol(undo + strlen("\"undo: deactivate schema RSC (activation #"), NULL, 10) : -1;
    char served[96];
    snprintf(served, sizeof served, ",deactivate RSC (activation #%ld from RSU)", activation);
    check(activation > 0 && ord && strstr(ord, served), "service stop: RSU's undo of its last activation of RSC reached ORD");
    struct stat sb;
    check(stat(s.run, &sb) != 0, "service stop: no runtime file left in the run directory");
    if (scenario_failed(&s)) say_output_tail("service-stop", txt, 4000);
    free(rsu);
    free(txt);
    free(ord);
}
