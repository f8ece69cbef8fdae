/* Whole-process behaviour: contract-launch, clean shutdown, side-by-side run directories,
 * the control tool, priorities. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <sched.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <linux/capability.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>
#include "harness.h"
#include "../launcher/run_bounds.h"

static pid_t start_launcher(char *const argv[], const char *out_file)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/contract-launch", h_bin_dir);
    pid_t pid = fork();
    if (pid == 0) {
        int fd = open(out_file, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); close(fd); }
        execv(path, argv);
        _exit(127);
    }
    return pid;
}

/* The launcher with its stdout and its stderr in two files. */
static pid_t start_launcher_split(char *const argv[], const char *out_file, const char *err_file)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/contract-launch", h_bin_dir);
    pid_t pid = fork();
    if (pid == 0) {
        int fd = open(out_file, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        int efd = open(err_file, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) { dup2(fd, 1); close(fd); }
        if (efd >= 0) { dup2(efd, 2); close(efd); }
        execv(path, argv);
        _exit(127);
    }
    return pid;
}

/* A file's bytes (NULs included) and their count; NULL when unreadable. */
static char *read_bytes(const char *file, size_t *len)
{
    FILE *f = fopen(file, "rb");
    if (!f) return NULL;
    char *buf = malloc(1 << 16);
    *len = buf ? fread(buf, 1, (1 << 16) - 1, f) : 0;
    fclose(f);
    if (buf) buf[*len] = '\0';
    return buf;
}

static int wait_for_text(const char *file, const char *text, int timeout_ms)
{
    for (int t = 0; t < timeout_ms; t += 20) {
        char *s = h_read_file(file);
        int found = s && strstr(s, text);
        free(s);
        if (found) return 1;
        usleep(20000);
    }
    return 0;
}

static long pid_of(const char *dir, const char *name)
{
    char p[1024];
    snprintf(p, sizeof p, "%s/%s.pid", dir, name);
    char *s = h_read_file(p);
    long pid = s ? atol(s) : -1;
    free(s);
    return pid;
}

static int process_exists(long pid) { return pid > 0 && (kill((pid_t)pid, 0) == 0 || errno == EPERM); }

void test_launcher_crash_cleanup(void)
{
    REQUIRE(h_setup("launch") == 0);
    ContractShutdown(); /* the tester needs no mailbox here: it must not sit in the launcher's run dir */
    char exe_p[600], exe_c1[600], exe_c2[600], out[600];
    snprintf(exe_p, sizeof exe_p, "%s/P", h_bin_dir);
    snprintf(exe_c1, sizeof exe_c1, "%s/C1", h_bin_dir);
    snprintf(exe_c2, sizeof exe_c2, "%s/C2", h_bin_dir);
    snprintf(out, sizeof out, "%s/launch.out", h_work_dir);
    /* a crash file of an earlier run in the log folder: not this run's, removed at the launch */
    char old_crash[1200];
    snprintf(old_crash, sizeof old_crash, "%s/P.crash", h_log_dir);
    mkdir(h_log_dir, 0755);
    FILE *oc = fopen(old_crash, "w");
    if (oc) { fputs("==contract-crash== module P signal 11 SIGSEGV addr 0x0\n", oc); fclose(oc); }
    setenv("TMOD_CRASH_NAME", "C2", 1);
    char *argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, exe_p, exe_c1, exe_c2, NULL };
    pid_t launcher = start_launcher(argv, out);
    unsetenv("TMOD_CRASH_NAME");
    REQUIRE(launcher > 0);
    CHECK(wait_for_text(out, "module C2 (pid", 5000));
    CHECK(wait_for_text(out, "[P] P ready", 2000));
    long pp = pid_of(h_run_dir, "P"), pc1 = pid_of(h_run_dir, "C1");
    CHECK(process_exists(pp) && process_exists(pc1));
    CHECK(ModuleState("P") == CONTRACT_OK && ModuleState("C1") == CONTRACT_OK);
    /* its files are removed when it is reaped, just after the line saying it died */
    int c2_state = ModuleState("C2");
    for (int i = 0; i < 200 && c2_state != CONTRACT_EUNKNOWN; i++) {
        usleep(10000);
        c2_state = ModuleState("C2");
    }
    CHECK(c2_state == CONTRACT_EUNKNOWN);
    char *kill_argv[] = { "contract-launch", "--kill", h_run_dir, NULL };
    char kout[600];
    snprintf(kout, sizeof kout, "%s/kill.out", h_work_dir);
    CHECK(h_run(kill_argv, kout, 10000) == 0);
    CHECK(h_wait_exit(launcher, 5000) == 1); /* non-zero: a module crashed */
    char *text = h_read_file(out);
    CHECK(text && strstr(text, "module C2 (pid") && strstr(text, "died by signal 6"));
    CHECK(text && strstr(text, "FAILED: module C2 died by signal 6 (Aborted)"));
    /* its crash report, saved in the run's logs as C2.crash (the block as it wrote it); none for the others */
    char crash_file[1200];
    snprintf(crash_file, sizeof crash_file, "%s/C2.crash", h_log_dir);
    char *crash = h_read_file(crash_file);
    CHECK_MSG(crash && strncmp(crash, "==contract-crash== module C2 signal 6 SIGABRT addr 0x0\n==contract-crash== build-id ", 81) == 0,
              "C2.crash: %s", crash ? crash : "(none)");
    size_t crash_len = crash ? strlen(crash) : 0;
    CHECK(crash_len > 8 && strcmp(crash + crash_len - 8, " frames\n") == 0 && strstr(crash, "\n==contract-crash== end "));
    CHECK(crash && !strstr(crash, "[C2]"));
    free(crash);
    CHECK_MSG(access(old_crash, F_OK) != 0, "the earlier run's P.crash is still there");
    snprintf(crash_file, sizeof crash_file, "%s/C1.crash", h_log_dir);
    CHECK(access(crash_file, F_OK) != 0);
    CHECK(text && strstr(text, "module P (pid") && strstr(text, "exited with status 0"));
    /* the stop line says what stopped the run: make kill (contract-launch --kill) */
    CHECK_MSG(text && strstr(text, "contract-launch: stopping: make kill (contract-launch --kill, pid "), "launcher output: %s", text ? text : "(none)");
    free(text);
    CHECK(!process_exists(pp) && !process_exists(pc1));
    CHECK(h_count_entries(h_run_dir) == -1); /* run directory removed: nothing left in it */
    CHECK(!h_unix_socket_listed(h_run_dir));
    char *logs = h_read_logs("P_");
    CHECK(logs && strstr(logs, ",P,module_exit,"));
    free(logs);
    /* the crashed module's log says so last (docs/runtime-api.md "CSV log") */
    logs = h_read_logs("C2_");
    CHECK(logs && strstr(logs, ",C2,module_started,") && strstr(logs, ",C2,module_crashed,,,0,signal 6 (SIGABRT) records="));
    free(logs);
    h_teardown();
}

/* One launcher run with $TMOD_END = `end` (tmod.c): its exit status in *code (-1 when it did not
 * end within `timeout_ms`), its output (free it). */
static char *launch_ending(char **argv, const char *out, const char *end, int timeout_ms, int *code)
{
    setenv("TMOD_END", end, 1);
    pid_t launcher = start_launcher(argv, out);
    *code = launcher > 0 ? h_wait_exit(launcher, timeout_ms) : -1;
    return h_read_file(out);
}

/* How modules end is told as it is: one whose own code ends it mid-run (exit(0)) is said to end
 * before the run's end; one that crashes or exits non-zero while the run stops (its exit code) is a
 * crash like any other (exit 1, FAILED); one that does not end on its KILL is terminated, said,
 * and not counted as a crash. */
void test_launcher_module_ends(void)
{
    REQUIRE(h_setup("ends") == 0);
    ContractShutdown();
    char exe_p[600], exe_c1[600], exe_c2[600], out[600];
    snprintf(exe_p, sizeof exe_p, "%s/P", h_bin_dir);
    snprintf(exe_c1, sizeof exe_c1, "%s/C1", h_bin_dir);
    snprintf(exe_c2, sizeof exe_c2, "%s/C2", h_bin_dir);
    snprintf(out, sizeof out, "%s/launch.out", h_work_dir);
    char *argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "1", exe_p, exe_c1, exe_c2, NULL };
    int code = -1;
    char *text = launch_ending(argv, out, "P:exit0", 8000, &code);
    CHECK(code == 0);
    CHECK(text && strstr(text, "module P (pid") && strstr(text, "exited with status 0 before the run's end"));
    CHECK(text && strstr(text, "all modules stopped cleanly"));
    free(text);

    text = launch_ending(argv, out, "C1:crash", 8000, &code);
    CHECK(code == 1);
    CHECK(text && strstr(text, "died by signal 6 (Aborted) while the run stopped"));
    CHECK(text && strstr(text, "FAILED: module C1 died by signal 6 (Aborted)"));
    CHECK(text && !strstr(text, "FAILED: module C2") && !strstr(text, "FAILED: module P"));
    free(text);

    /* a module's stdout and stderr stay apart: its stderr lines on the launcher's stderr, a line
     * its stdout left unfinished not glued to them, a NUL among a line's bytes kept */
    {
        char err[600];
        snprintf(err, sizeof err, "%s/launch.err", h_work_dir);
        setenv("TMOD_END", "C1:outputs", 1);
        pid_t launcher = start_launcher_split(argv, out, err);
        unsetenv("TMOD_END");
        CHECK(launcher > 0 && h_wait_exit(launcher, 8000) == 0);
        size_t olen = 0, elen = 0;
        char *o = read_bytes(out, &olen), *e = read_bytes(err, &elen);
        CHECK(o && memmem(o, olen, "[C1] C1 out-part C1 out-end\n", 28));
        CHECK(o && memmem(o, olen, "[C1] C1 nul:before\0after\n", 25));
        CHECK(o && !memmem(o, olen, "err line", 8));
        CHECK(e && memmem(e, elen, "[C1] C1 err line\n", 17));
        CHECK(e && strstr(e, "contract-launch: all modules stopped cleanly"));
        free(o);
        free(e);
    }

    /* a SIGKILL the launcher did not send (the kernel's OOM killer sends one) is no crash of its code: said apart */
    text = launch_ending(argv, out, "C1:sigkill", 8000, &code);
    CHECK(code == 1);
    CHECK(text && strstr(text, "module C1 (pid") && strstr(text, "died by signal 9 (Killed)"));
    CHECK(text && strstr(text, "FAILED: module C1 was killed (a SIGKILL the launcher did not send: "));
    CHECK(text && !strstr(text, "FAILED: module C1 died by"));
    free(text);

    text = launch_ending(argv, out, "C1:exit3", 8000, &code);
    CHECK(code == 1);
    CHECK(text && strstr(text, "module C1 (pid") && strstr(text, "exited with status 3 while the run stopped"));
    /* an exit with a status is no crash: the FAILED line says what its end line says */
    CHECK(text && strstr(text, "FAILED: module C1 exited with status 3") && !strstr(text, "FAILED: module C1 crashed"));
    free(text);

    /* a process left behind in a session of its own holds the output: the launcher does not wait for it */
    RTIME t0 = GetTime();
    text = launch_ending(argv, out, "C1:daemon", 7000, &code);
    CHECK(code == 0);
    CHECK(GetTime() - t0 < 6000000000LL);
    CHECK(text && strstr(text, "module C1: a process it started still holds its output after it ended"));
    free(text);

    text = launch_ending(argv, out, "C2:hang", 10000, &code);
    CHECK(code == 0);
    CHECK(text && strstr(text, "module C2 did not end on its KILL request within 2 s: terminating it (SIGTERM)"));
    CHECK(text && !strstr(text, "FAILED: module C2") && !strstr(text, "while the run stopped"));
    CHECK(text && strstr(text, "all modules stopped (terminated at the stop: C2)") && !strstr(text, "stopped cleanly"));
    free(text);

    /* a module whose init never returns (it never looks for a request) is not ready: the run stops
     * at the ready timeout without its start request, and the module is terminated */
    char *ready_argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "30",
                           "--ready-timeout", "1", "--start", "P.mission()", exe_p, exe_c1, exe_c2, NULL };
    t0 = GetTime();
    text = launch_ending(ready_argv, out, "C2:inithang", 10000, &code);
    CHECK(code == 0);
    CHECK(GetTime() - t0 < 6000000000LL); /* not the 30 s asked: nothing would ever start */
    CHECK(text && strstr(text, "module C2 is not ready after 1 s: its init has not returned (does its init region loop or block?); the run stops without its start request"));
    CHECK(text && !strstr(text, "module P is not ready") && !strstr(text, "module C1 is not ready"));
    CHECK(text && !strstr(text, "started P.mission") && !strstr(text, "module(s) running"));
    CHECK(text && strstr(text, "module C2 did not end on its KILL request within 2 s: terminating it (SIGTERM)"));
    free(text);
    /* stopped (SIGTERM: a cancelled job) while it waits for that init: no module is said late */
    char *wait_argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "30",
                          "--ready-timeout", "5", exe_p, exe_c1, exe_c2, NULL };
    setenv("TMOD_END", "C2:inithang", 1);
    pid_t waiting = start_launcher(wait_argv, out);
    REQUIRE(waiting > 0);
    usleep(700000);
    kill(waiting, SIGTERM);
    CHECK(h_wait_exit(waiting, 8000) >= 0);
    text = h_read_file(out);
    CHECK(text && strstr(text, "stopping") && !strstr(text, "is not ready"));
    free(text);
    /* nor is the start request sent before a slow init has returned: P's START is read after C2's 300 ms */
    char *slow_argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "1",
                          "--start", "P.mission()", exe_p, exe_c1, exe_c2, NULL };
    text = launch_ending(slow_argv, out, "C2:slowinit", 10000, &code);
    CHECK(code == 0);
    CHECK(text && !strstr(text, "is not ready"));
    CHECK(text && strstr(text, "C2 init done\n") && strstr(text, "started P.mission"));
    CHECK(text && strstr(text, "C2 init done\n") < strstr(text, "started P.mission"));
    free(text);
    unsetenv("TMOD_END");
    CHECK(h_count_entries(h_run_dir) == -1);
    h_teardown();
}

void test_launcher_start_duration(void)
{
    REQUIRE(h_setup("duration") == 0);
    ContractShutdown();
    char exe_p[600], out[600];
    snprintf(exe_p, sizeof exe_p, "%s/P", h_bin_dir);
    snprintf(out, sizeof out, "%s/launch.out", h_work_dir);
    char *argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "1",
                     "--start", "P.mission(consigne={1.0,2.0,3.0})", exe_p, NULL };
    pid_t launcher = start_launcher(argv, out);
    REQUIRE(launcher > 0);
    CHECK(h_wait_exit(launcher, 8000) == 0);
    char *text = h_read_file(out);
    CHECK(text && strstr(text, "[P] P ready\n"));
    CHECK(text && strstr(text, "started P.mission(consigne={1.0,2.0,3.0})"));
    CHECK(text && strstr(text, "contract-launch: stopping: the run's duration (1 s) is over\n"));
    CHECK(text && strstr(text, "all modules stopped cleanly"));
    free(text);
    char *logs = h_read_logs("P_");
    CHECK(logs && strstr(logs, ",P,request_received,contract-launch,,23,START mission"));
    free(logs);
    CHECK(h_count_entries(h_run_dir) == -1);
    /* a start the supervisor refuses: the run goes on to its end, then exits 3 (not 0: a service
     * manager's Restart=on-failure must see that the robot did nothing) */
    char *refused[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "1",
                        "--start", "P.nosuch()", exe_p, NULL };
    CHECK(h_run(refused, out, 8000) == 3);
    text = h_read_file(out);
    CHECK(text && strstr(text, "P refused to start nosuch()"));
    CHECK(text && strstr(text, "all modules stopped cleanly"));
    free(text);
    /* bad usage is reported, not a crash */
    char *bad[] = { "contract-launch", "--duration", "soon", exe_p, NULL };
    CHECK(h_run(bad, out, 3000) == 2);
    char *missing[] = { "contract-launch", "/nonexistent/module", NULL };
    CHECK(h_run(missing, out, 3000) == 2);
    h_teardown();
}

void test_two_run_dirs(void)
{
    REQUIRE(h_setup("twodirs") == 0);
    ContractShutdown();
    char dir_a[600], dir_b[600], exe_p[600], out_a[600], out_b[600];
    snprintf(dir_a, sizeof dir_a, "%s/a", h_work_dir);
    snprintf(dir_b, sizeof dir_b, "%s/b", h_work_dir);
    snprintf(exe_p, sizeof exe_p, "%s/P", h_bin_dir);
    snprintf(out_a, sizeof out_a, "%s/a.out", h_work_dir);
    snprintf(out_b, sizeof out_b, "%s/b.out", h_work_dir);
    char *argv_a[] = { "contract-launch", "--run-dir", dir_a, "--log-dir", h_log_dir, "--duration", "3", exe_p, NULL };
    char *argv_b[] = { "contract-launch", "--run-dir", dir_b, "--log-dir", h_log_dir, "--duration", "3", exe_p, NULL };
    pid_t la = start_launcher(argv_a, out_a), lb = start_launcher(argv_b, out_b);
    REQUIRE(la > 0 && lb > 0);
    CHECK(wait_for_text(out_a, "1 module(s) running", 5000) && wait_for_text(out_b, "1 module(s) running", 5000));
    const char *dirs[2] = { dir_a, dir_b };
    long pids[2];
    for (int i = 0; i < 2; i++) {
        setenv("CONTRACT_RUN_DIR", dirs[i], 1);
        ContractShutdown();
        CHECK(ContractClientInit("tester") == 0);
        char status[512] = "";
        CHECK(QueryStatus("P", status, sizeof status, GetTime() + 2000000000LL) == 0);
        char want[700];
        snprintf(want, sizeof want, "run_dir=%s ", dirs[i]);
        CHECK_MSG(strstr(status, want) != NULL, "status '%s'", status);
        pids[i] = pid_of(dirs[i], "P");
        ContractShutdown();
    }
    CHECK(pids[0] > 0 && pids[1] > 0 && pids[0] != pids[1]);
    CHECK(h_wait_exit(la, 8000) == 0 && h_wait_exit(lb, 8000) == 0);
    CHECK(h_count_entries(dir_a) == -1 && h_count_entries(dir_b) == -1);
    setenv("CONTRACT_RUN_DIR", h_run_dir, 1);
    h_teardown();
}

static int control(const char *out, char *a1, char *a2, char *a3)
{
    char *argv[] = { "controlMSC", a1, a2, a3, NULL };
    return h_run(argv, out, 5000);
}

void test_control_tool(void)
{
    REQUIRE(h_setup("control") == 0);
    char out[600];
    snprintf(out, sizeof out, "%s/control.out", h_work_dir);
    CHECK(control(out, "status", NULL, NULL) == 2); /* not started yet */
    pid_t pid = h_spawn_module("MSC", "MSC");
    REQUIRE(pid > 0);
    CHECK(control(out, "status", NULL, NULL) == 0);
    char *text = h_read_file(out);
    CHECK(text && strstr(text, "module=MSC") && strstr(text, "test synchronous module C"));
    free(text);
    CHECK(control(out, "setparam", "0", "{20,20,20}") == 0);
    CHECK(control(out, "setparam", "0", "{1.0,2.0}") == 4);
    text = h_read_file(out);
    CHECK(text && strstr(text, "bad value '{1.0,2.0}' for parameter port 0 of type TypeA"));
    free(text);
    CHECK(control(out, "setparam", "0", "{1,2,3} trailing") == 4);
    CHECK(control(out, "setparam", "3", "{1,2,3}") == 4);
    CHECK(control(out, "setparam", "x", "1") == 4);
    CHECK(control(out, "frobnicate", NULL, NULL) == 1);
    CHECK(control(out, "stop", "now", NULL) == 1);
    CHECK(control(out, "start", NULL, NULL) == 0);
    /* MSC's run is over once its status says so (a loaded host may not have run it yet) */
    int over = 0;
    for (int i = 0; i < 200 && !over; i++) {
        if (control(out, "status", NULL, NULL) == 0 && (text = h_read_file(out)) != NULL) {
            over = strstr(text, " running=no ") != NULL;
            free(text);
        }
        if (!over) usleep(10000);
    }
    CHECK(over);
    CHECK(control(out, "stop", NULL, NULL) == 5); /* MSC's run is over: nothing to stop */
    CHECK(control(out, "kill", NULL, NULL) == 0);
    CHECK(h_wait_exit(pid, 2000) == 0);
    CHECK(control(out, "status", NULL, NULL) == 2);
    char *log = h_read_logs("MSC_");
    CHECK(log && strstr(log, ",MSC,setparam,controlMSC-"));
    free(log);
    /* a crashed module: its mailbox is stale */
    pid = h_spawn_module("MSC", "MSC");
    REQUIRE(pid > 0);
    kill(pid, SIGKILL);
    h_wait_exit(pid, 2000);
    CHECK(control(out, "start", NULL, NULL) == 3);
    text = h_read_file(out);
    CHECK(text && strstr(text, "not running"));
    free(text);
    char f[700];
    const char *left[] = { "MSC.mbx", "MSC.ctl", "MSC.0.in", "MSC.pid", "MSC.ready" };
    for (int i = 0; i < 5; i++) { snprintf(f, sizeof f, "%s/%s", h_run_dir, left[i]); unlink(f); }
    unsetenv("CONTRACT_RUN_DIR");
    CHECK(control(out, "status", NULL, NULL) == 2);
    setenv("CONTRACT_RUN_DIR", h_run_dir, 1);
    h_teardown();
}

void test_priority(void)
{
    REQUIRE(h_setup("prio") == 0);
    chmod(h_work_dir, 0777);
    chmod(h_run_dir, 0777);
    chmod(h_log_dir, 0777);
    unsetenv("CONTRACT_SCHED");
    char err[600], path[600];
    snprintf(err, sizeof err, "%s/prio.err", h_work_dir);
    snprintf(path, sizeof path, "%s/MSC", h_bin_dir);
    int am_root = geteuid() == 0;
    pid_t pid = fork();
    if (pid == 0) {
        int fd = open(err, O_WRONLY | O_CREAT | O_TRUNC, 0666);
        if (fd >= 0) { dup2(fd, 2); close(fd); }
        if (am_root && (setgid(65534) != 0 || setuid(65534) != 0)) _exit(125);
        if (chdir(h_work_dir) != 0) _exit(126);
        execl(path, path, (char *)NULL);
        _exit(127);
    }
    REQUIRE(pid > 0);
    for (int t = 0; t < 300 && ModuleState("MSC") != CONTRACT_OK; t++) usleep(10000);
    CHECK(ModuleState("MSC") == CONTRACT_OK);
    char mbx[700];
    snprintf(mbx, sizeof mbx, "%s/tester.mbx", h_run_dir);
    chmod(mbx, 0666); /* connecting to a socket needs write permission: let "nobody" answer us */
    int policy = sched_getscheduler(pid) & ~SCHED_RESET_ON_FORK;
    CHECK(SendKill("MSC", ACK_KILLED, 1) == 0 && h_wait_ack("MSC", 1, ACK_KILLED, 2000, NULL));
    CHECK(h_wait_exit(pid, 2000) == 0);
    char *text = h_read_file(err);
    int warnings = 0;
    for (char *s = text; s && (s = strstr(s, "SCHED_FIFO not permitted")) != NULL; s++) warnings++;
    if (policy == SCHED_FIFO) {
        CHECK(warnings == 0);
    } else {
        CHECK_MSG(warnings == 1, "%d SCHED_FIFO warnings in: %s", warnings, text ? text : "");
        CHECK(text && strstr(text, "priority 40 runs as nice 11"));
    }
    free(text);
    if (am_root) {
        /* as root SCHED_FIFO is normally permitted: check that it is used */
        pid = h_spawn_module("MSC", "MSC");
        REQUIRE(pid > 0);
        struct sched_param sp;
        int pol = sched_getscheduler(pid) & ~SCHED_RESET_ON_FORK;
        sched_getparam(pid, &sp);
        if (pol == SCHED_FIFO) CHECK(sp.sched_priority == 40);
        else fprintf(stderr, "    note: SCHED_FIFO refused even to root here (policy %d)\n", pol);
        CHECK(SendKill("MSC", ACK_NOTHING, 0) == 0);
        CHECK(h_wait_exit(pid, 2000) == 0);
    }
    setenv("CONTRACT_SCHED", "other", 1);
    h_teardown();
}

/* Test `name`: `modules` (test executables, NULL-terminated, at most 4) under a launcher, its
 * output in `out`; the launcher's pid once they all run (-1: it did not start). */
static pid_t launch_modules(const char *name, const char *const modules[], char *out, size_t size)
{
    if (h_setup(name) != 0) return -1;
    ContractShutdown(); /* the tester needs no mailbox here: it must not sit in the launcher's run dir */
    char exes[4][600];
    char *argv[10] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir };
    int n = 0;
    for (; modules[n] && n < 4; n++) {
        snprintf(exes[n], sizeof exes[n], "%s/%s", h_bin_dir, modules[n]);
        argv[5 + n] = exes[n];
    }
    argv[5 + n] = NULL;
    snprintf(out, size, "%s/launch.out", h_work_dir);
    pid_t launcher = start_launcher(argv, out);
    char running[32];
    snprintf(running, sizeof running, "%d module(s) running", n);
    if (launcher > 0) CHECK(wait_for_text(out, running, 5000));
    return launcher;
}

static const char *const P_ONLY[] = { "P", NULL };
static const char *const P_AND_C1[] = { "P", "C1", NULL };

void test_launcher_sigint(void)
{
    char out[600];
    pid_t launcher = launch_modules("sigint", P_AND_C1, out, sizeof out);
    REQUIRE(launcher > 0);
    long pp = pid_of(h_run_dir, "P"), pc1 = pid_of(h_run_dir, "C1");
    kill(launcher, SIGINT); /* what Ctrl-C in a terminal does */
    CHECK(h_wait_exit(launcher, 6000) == 0);
    CHECK(!process_exists(pp) && !process_exists(pc1));
    CHECK(h_count_entries(h_run_dir) == -1);
    CHECK(!h_unix_socket_listed(h_run_dir));
    char *text = h_read_file(out);
    CHECK(text && strstr(text, "all modules stopped cleanly"));
    char from_me[80];
    snprintf(from_me, sizeof from_me, "contract-launch: stopping: SIGINT from pid %ld\n", (long)getpid());
    CHECK_MSG(text && strstr(text, from_me), "launcher output: %s", text ? text : "(none)");
    free(text);
    h_teardown();

    /* a Ctrl-C in the terminal comes from pid 0 (the terminal's driver): said so, not "from pid 0"
     * (a SIGINT with si_pid 0 queued here stands for it) */
    launcher = launch_modules("sigint0", P_AND_C1, out, sizeof out);
    REQUIRE(launcher > 0);
    siginfo_t si;
    memset(&si, 0, sizeof si);
    si.si_signo = SIGINT;
    si.si_code = SI_QUEUE;
    si.si_pid = 0;
    CHECK(syscall(SYS_rt_sigqueueinfo, launcher, SIGINT, &si) == 0);
    CHECK(h_wait_exit(launcher, 6000) == 0);
    text = h_read_file(out);
    CHECK_MSG(text && strstr(text, "contract-launch: stopping: SIGINT from the terminal\n") && !strstr(text, "pid 0"),
              "launcher output: %s", text ? text : "(none)");
    free(text);
    h_teardown();
}

/* The launcher stopped: it exited 0 and said `said`, and P's log holds the KILL record `kill`. */
static void stopped_saying(pid_t launcher, const char *out, const char *said, const char *kill)
{
    CHECK(h_wait_exit(launcher, 6000) == 0);
    char *text = h_read_file(out);
    CHECK_MSG(text && strstr(text, said), "launcher output: %s", text ? text : "(none)");
    free(text);
    char *p_log = h_read_logs("P_");
    CHECK_MSG(p_log && strstr(p_log, kill), "P's log: %s", p_log ? p_log : "(none)");
    free(p_log);
}

/* The build service's stop with a reason (a limit hit: SIGTERM with a value queued, `kill -q 1`):
 * the launcher says it, and every module's KILL record reads it, so that the run's CSV logs say why
 * it stopped. An unknown value is a plain stop. */
void test_launcher_stop_why(void)
{
    char out[600];
    pid_t launcher = launch_modules("stopwhy", P_AND_C1, out, sizeof out);
    REQUIRE(launcher > 0);
    CHECK(sigqueue(launcher, SIGTERM, (union sigval){ .sival_int = 1 }) == 0);
    CHECK(h_wait_exit(launcher, 6000) == 0);
    char *text = h_read_file(out);
    CHECK_MSG(text && strstr(text, "contract-launch: stopping: the build service's memory limit was reached") && strstr(text, "all modules stopped cleanly"),
              "launcher output: %s", text ? text : "(none)");
    free(text);
    const char *kill_why = ",request_received,contract-launch,,45,KILL (the build service's memory limit was reached)";
    char *p_log = h_read_logs("P_"), *c1_log = h_read_logs("C1_");
    CHECK_MSG(p_log && strstr(p_log, kill_why) && strstr(p_log, ",module_exit,"), "P's log: %s", p_log ? p_log : "(none)");
    CHECK_MSG(c1_log && strstr(c1_log, kill_why), "C1's log: %s", c1_log ? c1_log : "(none)");
    free(p_log);
    free(c1_log);
    h_teardown();

    /* a value the launcher does not know: a plain stop, a plain KILL */
    launcher = launch_modules("stopwhy2", P_ONLY, out, sizeof out);
    REQUIRE(launcher > 0);
    CHECK(sigqueue(launcher, SIGTERM, (union sigval){ .sival_int = 99 }) == 0);
    char from_me[80];
    snprintf(from_me, sizeof from_me, "contract-launch: stopping: SIGTERM from pid %ld\n", (long)getpid());
    stopped_saying(launcher, out, from_me, ",request_received,contract-launch,,0,KILL\n");
    h_teardown();

    /* `contract-launch --term-why CODE PID` (the build service's way in a container without a `kill`
     * that queues): the same stop, the same words; a code it does not know sends nothing */
    launcher = launch_modules("stopwhy3", P_ONLY, out, sizeof out);
    REQUIRE(launcher > 0);
    char pid_text[24], why_out[600];
    snprintf(pid_text, sizeof pid_text, "%ld", (long)launcher);
    snprintf(why_out, sizeof why_out, "%s/why.out", h_work_dir);
    char *unknown[] = { "contract-launch", "--term-why", "99", pid_text, NULL };
    CHECK(h_run(unknown, why_out, 5000) == 2);
    CHECK_MSG(h_wait_exit(launcher, 300) == -1, "the launcher stopped on a code --term-why does not know");
    char *term[] = { "contract-launch", "--term-why", "5", pid_text, NULL };
    CHECK(h_run(term, why_out, 5000) == 0);
    stopped_saying(launcher, out, "contract-launch: stopping: the job was cancelled\n", ",request_received,contract-launch,,22,KILL (the job was cancelled)\n");
    h_teardown();
}

/* A stop by a signal under CONTRACT_STOP_BUDGET_MS (the build service's cancel grace, 900 ms)
 * fits its waits in it: a module that does not answer its KILL is terminated by the launcher
 * (said, and its records written by its SIGTERM handler) before the budget ends, not killed
 * from outside after it. */
void test_launcher_stop_budget(void)
{
    REQUIRE(h_setup("budget") == 0);
    ContractShutdown();
    char exe_p[600], exe_c2[600], out[600];
    snprintf(exe_p, sizeof exe_p, "%s/P", h_bin_dir);
    snprintf(exe_c2, sizeof exe_c2, "%s/C2", h_bin_dir);
    snprintf(out, sizeof out, "%s/launch.out", h_work_dir);
    char *argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, exe_p, exe_c2, NULL };
    setenv("TMOD_END", "C2:hang", 1);
    setenv("CONTRACT_STOP_BUDGET_MS", "900", 1);
    pid_t launcher = start_launcher(argv, out);
    unsetenv("CONTRACT_STOP_BUDGET_MS");
    unsetenv("TMOD_END");
    REQUIRE(launcher > 0);
    CHECK(wait_for_text(out, "2 module(s) running", 5000));
    RTIME t0 = GetTime();
    kill(launcher, SIGTERM); /* the build service's cancel */
    int rc = h_wait_exit(launcher, 5000);
    RTIME took = GetTime() - t0;
    char *text = h_read_file(out);
    CHECK_MSG(rc == 0 && took < 1300000000LL, "the launcher ended %lld ms after its SIGTERM with %d (expected within the 900 ms budget)",
              (long long)(took / 1000000), rc);
    CHECK_MSG(text && strstr(text, "module C2 did not end on its KILL request within 0.36 s: terminating it (SIGTERM)") &&
                  strstr(text, "module C2 (pid ") && strstr(text, "terminated by signal 15") &&
                  strstr(text, "all modules stopped (terminated at the stop: C2)"),
              "launcher output: %s", text ? text : "(none)");
    free(text);
    CHECK(h_count_entries(h_run_dir) == -1);
    h_teardown();
}

/* CONTRACT_END_BY_S (the build service: its run time limit less the room to stop): a run whose
 * start came late (a slow init) stops that long after the launch at the latest, said, rather than
 * its whole duration after the start. */
void test_launcher_end_by(void)
{
    REQUIRE(h_setup("endby") == 0);
    ContractShutdown();
    char exe_p[600], exe_c2[600], out[600];
    snprintf(exe_p, sizeof exe_p, "%s/P", h_bin_dir);
    snprintf(exe_c2, sizeof exe_c2, "%s/C2", h_bin_dir);
    snprintf(out, sizeof out, "%s/launch.out", h_work_dir);
    char *argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "3", exe_p, exe_c2, NULL };
    setenv("CONTRACT_END_BY_S", "1", 1);
    int code;
    RTIME t0 = GetTime();
    char *text = launch_ending(argv, out, "C2:slowinit", 10000, &code);
    RTIME took = GetTime() - t0;
    unsetenv("CONTRACT_END_BY_S");
    unsetenv("TMOD_END");
    CHECK_MSG(code == 0 && took < 2500000000LL, "the launcher ended %lld ms after its launch with %d (expected ~1 s: 3 s asked)",
              (long long)(took / 1000000), code);
    const char *said = text ? strstr(text, "the run stops ") : NULL;
    double before = 0, start = 0;
    CHECK_MSG(said && sscanf(said, "the run stops %lf s before the end of its 3 s: its start came %lf s after the launch", &before, &start) == 2 &&
                  start >= 0.25 && start < 1.0 && before > 2.0 && before < 2.8 &&
                  strstr(said, "and it must end 1 s after the launch (the run time limit)"),
              "launcher output: %s", text ? text : "(none)");
    free(text);
    CHECK(h_count_entries(h_run_dir) == -1);
    h_teardown();
}

/* CONTRACT_OUTPUT_LIMIT_BYTES (the build service's output limit): past it the launcher reads a
 * module's lines and drops them, whatever its reader does, so that a module printing past the
 * limit is never blocked on its full pipe. Here the launcher's stdout is a pipe nobody reads (a
 * reader that has cut the stream and is slow to drain it): the module's 200,000 lines (5 MB) go
 * through, the run ends on time and cleanly. Before, the launcher blocked writing to that pipe,
 * and the module with it. */
void test_launcher_output_limit(void)
{
    REQUIRE(h_setup("outlimit") == 0);
    ContractShutdown();
    char exe_p[600], exe_c2[600], err[600], path[1024];
    snprintf(exe_p, sizeof exe_p, "%s/P", h_bin_dir);
    snprintf(exe_c2, sizeof exe_c2, "%s/C2", h_bin_dir);
    snprintf(err, sizeof err, "%s/launch.err", h_work_dir);
    snprintf(path, sizeof path, "%s/contract-launch", h_bin_dir);
    char *argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "1", exe_p, exe_c2, NULL };
    int unread[2];
    REQUIRE(pipe(unread) == 0);
    setenv("TMOD_END", "C2:flood", 1);
    setenv("CONTRACT_OUTPUT_LIMIT_BYTES", "4096", 1);
    pid_t launcher = fork();
    if (launcher == 0) {
        int efd = open(err, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(unread[1], 1);
        if (efd >= 0) { dup2(efd, 2); close(efd); }
        close(unread[0]);
        close(unread[1]);
        execv(path, argv);
        _exit(127);
    }
    unsetenv("CONTRACT_OUTPUT_LIMIT_BYTES");
    unsetenv("TMOD_END");
    close(unread[1]);
    REQUIRE(launcher > 0);
    int code = h_wait_exit(launcher, 15000);
    if (code == -1) { /* blocked on the unread pipe: end it and its modules for the next tests */
        kill(launcher, SIGKILL);
        waitpid(launcher, NULL, 0);
        const char *names[] = { "P", "C2" };
        for (int i = 0; i < 2; i++) {
            char pid_file[700];
            snprintf(pid_file, sizeof pid_file, "%s/%s.pid", h_run_dir, names[i]);
            char *pid = h_read_file(pid_file);
            if (pid && atol(pid) > 1) kill((pid_t)atol(pid), SIGKILL);
            free(pid);
        }
    }
    char *text = h_read_file(err);
    CHECK_MSG(code == 0 && text && strstr(text, "[C2] C2 flood done") && strstr(text, "all modules stopped cleanly"),
              "launcher exit %d, stderr: %s", code, text ? text : "(none)");
    free(text);
    /* what it wrote on stdout: the limit and the line it falls inside, no more */
    char buf[65536];
    ssize_t n = read(unread[0], buf, sizeof buf);
    CHECK_MSG(n > 4096 && n < 4096 + 64, "%zd bytes on the launcher's stdout (the limit 4096 and the line it falls inside expected)", n);
    close(unread[0]);
    h_teardown();
}

/* The mono_ns (first column) of the first CSV line of `logs` that holds `needle`; -1 when none does. */
static long long mono_of(const char *logs, const char *needle)
{
    const char *hit = logs ? strstr(logs, needle) : NULL;
    if (!hit) return -1;
    while (hit > logs && hit[-1] != '\n') hit--;
    return strtoll(hit, NULL, 10);
}

void test_kill_without_launcher(void)
{
    REQUIRE(h_setup("killnl") == 0);
    pid_t p = h_spawn_module("P", "P"), c = h_spawn_module("MSC", "MSC");
    REQUIRE(p > 0 && c > 0);
    ContractShutdown(); /* leave only the modules in the run directory */
    char *argv[] = { "contract-launch", "--kill", h_run_dir, NULL };
    char out[600];
    snprintf(out, sizeof out, "%s/kill.out", h_work_dir);
    CHECK(h_run(argv, out, 10000) == 0);
    CHECK(h_wait_exit(p, 2000) == 0 && h_wait_exit(c, 2000) == 0); /* ended on the KILL request */
    CHECK(h_count_entries(h_run_dir) == -1);
    char *text = h_read_file(out);
    CHECK(text && strstr(text, "stopped 2 module(s)"));
    free(text);
    char *missing[] = { "contract-launch", "--kill", "/nonexistent/run", NULL };
    CHECK(h_run(missing, out, 3000) == 2);
    h_teardown();

    /* with --stop-first (make kill gives the supervisors), those end before the others are asked:
     * MSC (standing for a supervisor here) has ended when P receives its KILL */
    REQUIRE(h_setup("killfirst") == 0);
    p = h_spawn_module("P", "P");
    c = h_spawn_module("MSC", "MSC");
    REQUIRE(p > 0 && c > 0);
    ContractShutdown();
    char *first[] = { "contract-launch", "--stop-first", "MSC", "--kill", h_run_dir, NULL };
    snprintf(out, sizeof out, "%s/kill.out", h_work_dir);
    CHECK(h_run(first, out, 10000) == 0);
    CHECK(h_wait_exit(p, 2000) == 0 && h_wait_exit(c, 2000) == 0);
    char *msc_log = h_read_logs("MSC_"), *p_log = h_read_logs("P_");
    long long msc_end = mono_of(msc_log, ",MSC,module_exit,"), p_kill = mono_of(p_log, ",KILL");
    CHECK_MSG(msc_end > 0 && p_kill > 0 && msc_end <= p_kill, "MSC ended at %lld, P got its KILL at %lld\nP's log: %s", msc_end, p_kill, p_log ? p_log : "(none)");
    free(msc_log);
    free(p_log);
    h_teardown();
}

/* A stop signal that reaches a module as it starts up removes every runtime file it has created:
 * each file is registered for removal before a stop signal can end the process (a SIGTERM between
 * the creation of P.pid and its registration left P.pid behind; the harness, which waits for that
 * file, sent its SIGTERM right then). Signals sent at once on the file's appearance, many times. */
void test_stop_signal_at_startup(void)
{
    REQUIRE(h_setup("stopstart") == 0);
    char exe[1024], pidfile[700], out[700];
    snprintf(exe, sizeof exe, "%s/P", h_bin_dir);
    snprintf(pidfile, sizeof pidfile, "%s/P.pid", h_run_dir);
    snprintf(out, sizeof out, "%s/P.out", h_work_dir);
    int left = 0, seen = 0;
    for (int round = 0; round < 150 && !left; round++) {
        pid_t pid = fork();
        if (pid == 0) {
            int fd = open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644);
            if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); close(fd); }
            execl(exe, exe, (char *)NULL);
            _exit(127);
        }
        REQUIRE(pid > 0);
        /* the moment P.pid appears (or P has gone: 2 s at most), not a poll later */
        for (int spin = 0; spin < 2000000 && access(pidfile, F_OK) != 0; spin++)
            if (waitpid(pid, NULL, WNOHANG) == pid) { pid = -1; break; }
        if (pid < 0) continue;
        seen++;
        kill(pid, SIGTERM);
        if (h_wait_exit(pid, 3000) == -1) { kill(pid, SIGKILL); waitpid(pid, NULL, 0); }
        DIR *d = opendir(h_run_dir);
        struct dirent *e;
        while (d && (e = readdir(d)) != NULL)
            if (!strncmp(e->d_name, "P.", 2)) {
                h_failf(__FILE__, __LINE__, "round %d: left behind: %s", round, e->d_name);
                left = 1;
            }
        if (d) closedir(d);
        if (left) { /* the next round would fail on the stale files */
            char path[1400];
            const char *ends[] = { "pid", "mbx", "ready" };
            for (int i = 0; i < 3; i++) { snprintf(path, sizeof path, "%s/P.%s", h_run_dir, ends[i]); unlink(path); }
        }
    }
    CHECK_MSG(left || seen >= 100, "P.pid seen in only %d of 150 start-ups", seen);
    h_teardown();
}

/* ContractSetModulePriority: the target module applies the priority to itself. An unprivileged
 * module (nice levels) may lower its priority but not raise it: CONTRACT_EPERM, unchanged, and
 * the previous priority is reported for the undo. With SCHED_FIFO permitted (root here) it
 * switches to SCHED_FIFO at that priority. */
void test_set_module_priority(void)
{
    REQUIRE(h_setup("setprio") == 0);
    chmod(h_work_dir, 0777);
    chmod(h_run_dir, 0777);
    chmod(h_log_dir, 0777);
    char mbx[700], path[600], out[600];
    snprintf(mbx, sizeof mbx, "%s/tester.mbx", h_run_dir);
    chmod(mbx, 0666);
    snprintf(path, sizeof path, "%s/P", h_bin_dir);
    snprintf(out, sizeof out, "%s/P.out", h_work_dir);
    int am_root = geteuid() == 0;
    pid_t pid = fork();
    if (pid == 0) { /* P (priority 30) as an unprivileged process, under nice levels */
        int fd = open(out, O_WRONLY | O_CREAT | O_TRUNC, 0666);
        if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); close(fd); }
        if (am_root && (setgid(65534) != 0 || setuid(65534) != 0)) _exit(125);
        execl(path, path, (char *)NULL);
        _exit(127);
    }
    REQUIRE(pid > 0);
    /* Ready is the pid file, written after the priority is set (as the launcher waits for it);
     * the mailbox (ModuleState) exists earlier, so under load the priority may still be unset then. */
    char pidfile[700];
    snprintf(pidfile, sizeof pidfile, "%s/P.pid", h_run_dir);
    for (int t = 0; t < 500 && access(pidfile, F_OK) != 0; t++) usleep(10000);
    REQUIRE(access(pidfile, F_OK) == 0);
    REQUIRE(ModuleState("P") == CONTRACT_OK);
    errno = 0;
    CHECK(getpriority(PRIO_PROCESS, (id_t)pid) == (99 - 30) * 19 / 98);
    int prev = -1;
    CHECK(ContractSetModulePriority("P", 10, &prev) == 0); /* lower: permitted */
    CHECK(prev == 30);
    CHECK(getpriority(PRIO_PROCESS, (id_t)pid) == (99 - 10) * 19 / 98);
    struct rlimit rl;
    if (getrlimit(RLIMIT_NICE, &rl) == 0 && rl.rlim_cur == 0) {
        prev = -1;
        CHECK(ContractSetModulePriority("P", 60, &prev) == CONTRACT_EPERM); /* raise: refused */
        CHECK(prev == 10);
        CHECK(getpriority(PRIO_PROCESS, (id_t)pid) == (99 - 10) * 19 / 98);
    }
    CHECK(ContractSetModulePriority("P", 0, &prev) == CONTRACT_EINVAL);
    CHECK(ContractSetModulePriority("NOPE", 10, &prev) == CONTRACT_EUNKNOWN);
    CHECK(SendKill("P", ACK_KILLED, 1) == 0 && h_wait_ack("P", 1, ACK_KILLED, 2000, NULL));
    CHECK(h_wait_exit(pid, 2000) == 0);
    char *text = h_read_file(out);
    CHECK_MSG(text && !strstr(text, "warning") && !strstr(text, "error"), "P said: %s", text ? text : "");
    free(text);
    char *log = h_read_logs("P_");
    CHECK(log && strstr(log, "priority_changed") && strstr(log, "nice 17 (priority 10, was 30)"));
    free(log);
    if (am_root) { /* SCHED_FIFO permitted: the module switches to it */
        unsetenv("CONTRACT_SCHED");
        pid = h_spawn_module("C1", "C1");
        setenv("CONTRACT_SCHED", "other", 1);
        REQUIRE(pid > 0);
        if ((sched_getscheduler(pid) & ~SCHED_RESET_ON_FORK) == SCHED_FIFO) {
            CHECK(ContractSetModulePriority("C1", 12, &prev) == 1);
            CHECK(prev == 30);
            struct sched_param sp;
            CHECK(sched_getparam(pid, &sp) == 0 && sp.sched_priority == 12);
        } else {
            fprintf(stderr, "    note: SCHED_FIFO refused even to root here\n");
        }
    }
    h_teardown();
}

/* Reads the system's PM QoS CPU latency target (us), or -1 when /dev/cpu_dma_latency is not readable. */
static long pm_qos_now(void)
{
    int fd = open("/dev/cpu_dma_latency", O_RDONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    int32_t v = -1;
    ssize_t n = read(fd, &v, sizeof v);
    close(fd);
    return n == (ssize_t)sizeof v ? v : -1;
}

void test_launcher_placement(void)
{
    REQUIRE(h_setup("placement") == 0);
    ContractShutdown();
    char exe_p[600], out[600], status_path[64];
    snprintf(exe_p, sizeof exe_p, "%s/P", h_bin_dir);
    snprintf(out, sizeof out, "%s/launch.out", h_work_dir);
    long before = pm_qos_now();
    /* the CPU list comes from the environment, the latency from the option */
    setenv("CONTRACT_CPUS", "0", 1);
    char *argv[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "30",
                     "--pm-qos-us", "0", exe_p, NULL };
    pid_t launcher = start_launcher(argv, out);
    unsetenv("CONTRACT_CPUS");
    REQUIRE(launcher > 0);
    CHECK(wait_for_text(out, "[P] P ready", 5000));
    long pp = pid_of(h_run_dir, "P");
    snprintf(status_path, sizeof status_path, "/proc/%ld/status", pp);
    char *st = h_read_file(status_path);
    CHECK_MSG(st && strstr(st, "Cpus_allowed_list:\t0\n"), "module P is not pinned to CPU 0");
    free(st);
    char *text = h_read_file(out);
    CHECK(text && strstr(text, "modules pinned to CPUs 0"));
    if (before >= 0 && text && strstr(text, "CPU wake-up latency held at 0 us")) {
        CHECK(pm_qos_now() == 0); /* held while the architecture runs */
    } else {
        /* not root, or no such device in this sandbox: one clear line, and the run goes on */
        CHECK(text && strstr(text, "/dev/cpu_dma_latency") && strstr(text, "not lowered"));
    }
    free(text);
    kill(launcher, SIGTERM);
    CHECK(h_wait_exit(launcher, 6000) == 0);
    if (before > 0) CHECK(pm_qos_now() == before); /* released with the launcher */
    CHECK(h_count_entries(h_run_dir) == -1);
    /* a CPU outside the mask the launcher inherits (a service started under `taskset -c 0`) is
     * still one it may pin the modules to */
    long online = sysconf(_SC_NPROCESSORS_ONLN);
    cpu_set_t mine, only0;
    if (online >= 2 && sched_getaffinity(0, sizeof mine, &mine) == 0 && CPU_ISSET(0, &mine) && CPU_ISSET((int)online - 1, &mine)) {
        CPU_ZERO(&only0);
        CPU_SET(0, &only0);
        REQUIRE(sched_setaffinity(0, sizeof only0, &only0) == 0);
        char last[24], want[48];
        snprintf(last, sizeof last, "%ld", online - 1);
        char *outside[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "30",
                            "--cpus", last, exe_p, NULL };
        unlink(out); /* the first launcher's "[P] P ready" must not be read as this one's */
        pid_t l2 = start_launcher(outside, out);
        sched_setaffinity(0, sizeof mine, &mine);
        REQUIRE(l2 > 0);
        CHECK(wait_for_text(out, "[P] P ready", 5000));
        snprintf(status_path, sizeof status_path, "/proc/%ld/status", pid_of(h_run_dir, "P"));
        char *st2 = h_read_file(status_path);
        snprintf(want, sizeof want, "Cpus_allowed_list:\t%s\n", last);
        CHECK_MSG(st2 && strstr(st2, want), "module P is not pinned to the CPU outside the launcher's inherited mask");
        free(st2);
        kill(l2, SIGTERM);
        CHECK(h_wait_exit(l2, 6000) == 0);
    }
    /* bad lists are refused before anything starts */
    char *bad_cpu[] = { "contract-launch", "--cpus", "4096", exe_p, NULL };
    CHECK(h_run(bad_cpu, out, 3000) == 2);
    char *bad_list[] = { "contract-launch", "--cpus", "0-", exe_p, NULL };
    CHECK(h_run(bad_list, out, 3000) == 2);
    char *text2 = h_read_file(out);
    CHECK(text2 && strstr(text2, "expected a CPU list"));
    free(text2);
    char *bad_qos[] = { "contract-launch", "--pm-qos-us", "-1", exe_p, NULL };
    CHECK(h_run(bad_qos, out, 3000) == 2);
    h_teardown();
}

/* The launcher takes CONTRACT_LAUNCHER_MAX_MODULES module executables (run_bounds.h, written from
 * packages/conventions/src/run-bounds.ts: the number `contract check` and the docs give), and
 * refuses one more before starting anything, naming both counts. Paths that do not exist: the
 * count is checked first, so a count it takes goes on to say the path is missing. */
void test_launcher_module_bound(void)
{
    REQUIRE(h_setup("modbound") == 0);
    enum { MAX = CONTRACT_LAUNCHER_MAX_MODULES };
    CHECK(MAX > 128); /* 128 modules + 7 supervisors + ORD were refused */
    static char *argv[MAX + 8];
    char missing[600];
    snprintf(missing, sizeof missing, "%s/no-such-module", h_work_dir);
    int n = 0;
    argv[n++] = "contract-launch";
    argv[n++] = "--run-dir";
    argv[n++] = h_run_dir;
    for (int k = 0; k < MAX; k++) argv[n++] = missing;
    argv[n] = NULL;
    char out[600], want[200];
    snprintf(out, sizeof out, "%s/bound.out", h_work_dir);
    CHECK(h_run(argv, out, 5000) == 2);
    char *text = h_read_file(out);
    CHECK_MSG(text && strstr(text, "no-such-module: No such file or directory") && !strstr(text, "too many modules"), "%d modules: %s", MAX, text ? text : "(no output)");
    free(text);
    argv[n++] = missing;
    argv[n] = NULL;
    CHECK(h_run(argv, out, 5000) == 2);
    text = h_read_file(out);
    snprintf(want, sizeof want, "contract-launch: too many modules: %d module executables given, at most %d", MAX + 1, MAX);
    CHECK_MSG(text && strstr(text, want), "%d modules: %s", MAX + 1, text ? text : "(no output)");
    free(text);
    h_teardown();
}

/* This process without the right to SCHED_FIFO above priority `rtprio` (0: none): RLIMIT_RTPRIO,
 * and no CAP_SYS_NICE, dropped from the bounding set too, so that a test run as root is refused
 * as an unprivileged user is (the executables it starts then get none either). */
static void without_realtime_rights(rlim_t rtprio)
{
    struct rlimit rl = { rtprio, rtprio };
    setrlimit(RLIMIT_RTPRIO, &rl);
    prctl(PR_CAPBSET_DROP, CAP_SYS_NICE, 0, 0, 0);
    struct __user_cap_header_struct hdr = { _LINUX_CAPABILITY_VERSION_3, 0 };
    struct __user_cap_data_struct caps[2];
    if (syscall(SYS_capget, &hdr, caps) != 0) return;
    uint32_t bit = 1u << (CAP_SYS_NICE % 32);
    caps[CAP_SYS_NICE / 32].effective &= ~bit;
    caps[CAP_SYS_NICE / 32].permitted &= ~bit;
    caps[CAP_SYS_NICE / 32].inheritable &= ~bit;
    syscall(SYS_capset, &hdr, caps);
}

/* contract-launch without real-time rights above `rtprio`, `require` as $CONTRACT_REQUIRE_REALTIME
 * (NULL: unset), the modules asking SCHED_FIFO (no CONTRACT_SCHED=other); its exit status. */
static int launch_without_realtime(char *const argv[], const char *out, rlim_t rtprio, const char *require)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/contract-launch", h_bin_dir);
    pid_t pid = fork();
    if (pid == 0) {
        without_realtime_rights(rtprio);
        unsetenv("CONTRACT_SCHED");
        if (require) setenv("CONTRACT_REQUIRE_REALTIME", require, 1);
        else unsetenv("CONTRACT_REQUIRE_REALTIME");
        int fd = open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); close(fd); }
        execv(path, argv);
        _exit(127);
    }
    return h_wait_exit(pid, 15000);
}

/* Required real time (field test 68: a run as a user without rights went on at nice levels, exit 0):
 * --require-realtime or CONTRACT_REQUIRE_REALTIME=1 refuses to start anything when SCHED_FIFO is not
 * permitted, saying how to grant it; a module refused its own priority (the limit below it) ends
 * before the start and the run stops without it; without the requirement the run goes on as before. */
void test_launcher_require_realtime(void)
{
    REQUIRE(h_setup("realtime") == 0);
    char exe_p[1024], out[600];
    snprintf(exe_p, sizeof exe_p, "%s/P", h_bin_dir);
    snprintf(out, sizeof out, "%s/realtime.out", h_work_dir);
    char *flag[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "0.3", "--require-realtime", exe_p, NULL };
    char *plain[] = { "contract-launch", "--run-dir", h_run_dir, "--log-dir", h_log_dir, "--duration", "0.3", exe_p, NULL };
    const char *refused = "contract-launch: real-time is required (--require-realtime, CONTRACT_REQUIRE_REALTIME=1) but SCHED_FIFO is not "
                          "permitted here (Operation not permitted; RLIMIT_RTPRIO is 0): nothing started. Grant real-time priorities: run as root";
    for (int env = 0; env < 2; env++) {
        CHECK(launch_without_realtime(env ? plain : flag, out, 0, env ? "1" : NULL) == 2);
        char *text = h_read_file(out);
        CHECK_MSG(text && strstr(text, refused) && strstr(text, "LimitRTPRIO=99") && strstr(text, "/etc/security/limits.d/") &&
                  strstr(text, "CAP_SYS_NICE") && !strstr(text, "[P]") && !strstr(text, "run directory"),
                  "%s: %s", env ? "CONTRACT_REQUIRE_REALTIME=1" : "--require-realtime", text ? text : "(no output)");
        free(text);
    }
    /* SCHED_FIFO 1 permitted, P's priority 30 not: P says so and ends, the run stops without its start
     * (raising RLIMIT_RTPRIO's hard limit to 1 needs CAP_SYS_RESOURCE: where this test has none, P is
     * run alone instead, the module's half of it) */
    struct rlimit rl;
    int raisable = getrlimit(RLIMIT_RTPRIO, &rl) == 0 && (rl.rlim_max == RLIM_INFINITY || rl.rlim_max >= 1);
    pid_t probe = raisable ? -1 : fork();
    if (probe == 0) { struct rlimit one = { 1, 1 }; _exit(setrlimit(RLIMIT_RTPRIO, &one) == 0 ? 0 : 1); }
    if (probe > 0) raisable = h_wait_exit(probe, 3000) == 0;
    const char *p_refused = "P: error: SCHED_FIFO priority 30 not permitted (Operation not permitted) (RLIMIT_RTPRIO is %d) and real-time is "
                            "required (CONTRACT_REQUIRE_REALTIME=1): not starting. Grant real-time priorities";
    char want[400];
    char *text;
    if (raisable) {
        CHECK(launch_without_realtime(flag, out, 1, NULL) == 1);
        text = h_read_file(out);
        snprintf(want, sizeof want, p_refused, 1);
        CHECK_MSG(text && strstr(text, want) &&
                  strstr(text, "module P ended before the start, and real-time is required: the architecture does not run without it; the run stops without its start request"),
                  "%s", text ? text : "(no output)");
        free(text);
    }
    char *alone[] = { exe_p, NULL };
    pid_t p = fork();
    if (p == 0) {
        without_realtime_rights(0);
        unsetenv("CONTRACT_SCHED");
        setenv("CONTRACT_REQUIRE_REALTIME", "1", 1);
        int fd = open(out, O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); close(fd); }
        execv(exe_p, alone);
        _exit(127);
    }
    int p_status = h_wait_exit(p, 5000);
    if (p_status == -1) { kill(p, SIGKILL); waitpid(p, NULL, 0); }
    CHECK(p_status == 2);
    text = h_read_file(out);
    snprintf(want, sizeof want, p_refused, 0);
    CHECK_MSG(text && strstr(text, want), "%s", text ? text : "(no output)");
    free(text);
    CHECK(access(h_run_dir, F_OK) != 0 || pid_of(h_run_dir, "P") < 0); /* it left nothing behind */
    /* not required: the run goes on at a nice level, as before */
    CHECK(launch_without_realtime(plain, out, 0, NULL) == 0);
    text = h_read_file(out);
    CHECK_MSG(text && strstr(text, "[P] P: warning: SCHED_FIFO not permitted (Operation not permitted): priority 30 runs as nice") &&
              strstr(text, "all modules stopped cleanly"), "%s", text ? text : "(no output)");
    free(text);
    h_teardown();
}
