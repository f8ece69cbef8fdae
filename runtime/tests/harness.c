#define _GNU_SOURCE
#include "harness.h"
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

int h_failures;
int h_active;
const char *h_bin_dir = ".";
char h_run_dir[600], h_log_dir[600], h_work_dir[512];
static pid_t spawned[32];
static int n_spawned;
static RequestMessage *msgs[16];
static int n_msgs;

void h_fail(const char *file, int line, const char *what)
{
    h_failures++;
    fprintf(stderr, "    FAILED %s:%d: %s\n", file, line, what);
}

void h_failf(const char *file, int line, const char *fmt, ...)
{
    h_failures++;
    fprintf(stderr, "    FAILED %s:%d: ", file, line);
    va_list ap;
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

RequestMessage *h_msg(void)
{
    RequestMessage *m = calloc(1, sizeof *m);
    if (m && n_msgs < 16) msgs[n_msgs++] = m;
    return m;
}

int h_setup(const char *test)
{
    snprintf(h_work_dir, sizeof h_work_dir, "/tmp/contract-test-%s-XXXXXX", test);
    if (!mkdtemp(h_work_dir)) { perror("mkdtemp"); return -1; }
    snprintf(h_run_dir, sizeof h_run_dir, "%s/run", h_work_dir);
    snprintf(h_log_dir, sizeof h_log_dir, "%s/logs", h_work_dir);
    mkdir(h_run_dir, 0777);
    mkdir(h_log_dir, 0777);
    setenv("CONTRACT_RUN_DIR", h_run_dir, 1);
    setenv("CONTRACT_LOG_DIR", h_log_dir, 1);
    setenv("CONTRACT_SCHED", "other", 1);
    unsetenv("TMOD_CRASH_NAME");
    unsetenv("TMOD_END");
    n_spawned = 0;
    h_active = 1;
    return ContractClientInit("tester");
}

static void rm_rf(const char *path)
{
    DIR *d = opendir(path);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..")) continue;
            char sub[1024];
            snprintf(sub, sizeof sub, "%s/%s", path, e->d_name);
            rm_rf(sub);
        }
        closedir(d);
        rmdir(path);
    } else {
        unlink(path);
    }
}

int h_wait_exit(pid_t pid, int timeout_ms)
{
    for (int t = 0; t <= timeout_ms; t += 10) {
        int st;
        pid_t r = waitpid(pid, &st, WNOHANG);
        if (r == pid) return WIFSIGNALED(st) ? 128 + WTERMSIG(st) : WEXITSTATUS(st);
        if (r < 0) return -2;
        usleep(10000);
    }
    return -1;
}

int h_asan_reports(int sig)
{
#if defined(__SANITIZE_ADDRESS__)
    return sig == SIGSEGV || sig == SIGBUS || sig == SIGFPE;
#else
    (void)sig;
    return 0;
#endif
}

int h_crash_status(int sig)
{
    return h_asan_reports(sig) ? 1 : 128 + sig;
}

void h_teardown(void)
{
    h_active = 0;
    for (int i = 0; i < n_spawned; i++) {
        if (kill(spawned[i], 0) != 0) { waitpid(spawned[i], NULL, WNOHANG); continue; }
        kill(spawned[i], SIGTERM);
        if (h_wait_exit(spawned[i], 2000) == -1) { kill(spawned[i], SIGKILL); waitpid(spawned[i], NULL, 0); }
    }
    n_spawned = 0;
    ContractShutdown();
    /* every runtime file must be gone once its process has ended */
    DIR *d = opendir(h_run_dir);
    if (d) {
        struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (e->d_name[0] == '.') continue;
            h_failf(__FILE__, __LINE__, "left behind in the run directory: %s", e->d_name);
        }
        closedir(d);
    }
    if (h_failures == 0 || !getenv("KEEP_FAILED")) rm_rf(h_work_dir);
    else fprintf(stderr, "    kept %s\n", h_work_dir);
    for (int i = 0; i < n_msgs; i++) free(msgs[i]);
    n_msgs = 0;
}

pid_t h_spawn_module(const char *exe, const char *name)
{
    char path[1024], out[1024];
    snprintf(path, sizeof path, "%s/%s", h_bin_dir, exe);
    snprintf(out, sizeof out, "%s/%s.out", h_work_dir, name);
    pid_t pid = fork();
    if (pid == 0) {
        int fd = open(out, O_WRONLY | O_CREAT | O_APPEND, 0644);
        if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); close(fd); }
        if (chdir(h_work_dir) != 0) _exit(126);
        execl(path, path, (char *)NULL);
        _exit(127);
    }
    if (pid < 0) return -1;
    if (n_spawned < 32) spawned[n_spawned++] = pid;
    for (int t = 0; t < 500; t++) { /* 5 s */
        char pidfile[1024];
        snprintf(pidfile, sizeof pidfile, "%s/%s.pid", h_run_dir, name);
        if (access(pidfile, F_OK) == 0 && ModuleState(name) == CONTRACT_OK) return pid;
        if (h_wait_exit(pid, 0) != -1) { fprintf(stderr, "    module %s exited at start-up\n", name); return -1; }
        usleep(10000);
    }
    fprintf(stderr, "    module %s not ready after 5 s\n", name);
    return -1;
}

int h_run(char *const argv[], const char *out_file, int timeout_ms)
{
    char path[1024];
    if (strchr(argv[0], '/')) snprintf(path, sizeof path, "%s", argv[0]);
    else snprintf(path, sizeof path, "%s/%s", h_bin_dir, argv[0]);
    pid_t pid = fork();
    if (pid == 0) {
        if (out_file) {
            int fd = open(out_file, O_WRONLY | O_CREAT | O_TRUNC, 0644);
            if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); close(fd); }
        }
        execv(path, argv);
        _exit(127);
    }
    if (pid < 0) return -1;
    int st = h_wait_exit(pid, timeout_ms);
    if (st == -1) { kill(pid, SIGKILL); waitpid(pid, NULL, 0); fprintf(stderr, "    %s timed out\n", argv[0]); }
    return st;
}

int h_wait_event(const char *from, int port, int timeout_ms, RequestMessage *msg)
{
    RTIME deadline = GetTime() + (RTIME)timeout_ms * 1000000;
    for (;;) {
        int r = WaitForRequestUntil(msg, deadline);
        if (r != 1) return 0;
        if (msg->Type == REQ_EVENT && strcmp(msg->Sender, from) == 0 && msg->Param.Event.targetPort == port) return 1;
    }
}

int h_wait_ack(const char *from, int ackId, int mask, int timeout_ms, RequestMessage *msg)
{
    return WaitForAck(from, ackId, mask, GetTime() + (RTIME)timeout_ms * 1000000, msg) == 1;
}

char *h_read_file(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return NULL;
    size_t cap = 4096, len = 0;
    char *s = malloc(cap);
    size_t n;
    while (s && (n = fread(s + len, 1, cap - len - 1, f)) > 0) {
        len += n;
        if (cap - len < 2) { char *t = realloc(s, cap *= 2); if (!t) { free(s); s = NULL; break; } s = t; }
    }
    fclose(f);
    if (s) s[len] = '\0';
    return s;
}

int h_find_log_file(const char *prefix, const char *suffix, char *out, size_t cap)
{
    DIR *d = opendir(h_log_dir);
    if (!d) return 0;
    struct dirent *e;
    int found = 0;
    while (!found && (e = readdir(d)) != NULL) {
        size_t n = strlen(e->d_name), s = strlen(suffix);
        if (strncmp(e->d_name, prefix, strlen(prefix)) == 0 && n > s && strcmp(e->d_name + n - s, suffix) == 0) {
            snprintf(out, cap, "%s/%s", h_log_dir, e->d_name);
            found = 1;
        }
    }
    closedir(d);
    return found;
}

char *h_read_logs(const char *prefix)
{
    DIR *d = opendir(h_log_dir);
    char *all = calloc(1, 1);
    size_t len = 0;
    if (!d) return all;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, prefix, strlen(prefix)) != 0) continue;
        char p[1024];
        snprintf(p, sizeof p, "%s/%s", h_log_dir, e->d_name);
        char *s = h_read_file(p);
        if (!s) continue;
        size_t l = strlen(s);
        char *t = realloc(all, len + l + 1);
        if (t) { all = t; memcpy(all + len, s, l + 1); len += l; }
        free(s);
    }
    closedir(d);
    return all;
}

int h_count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) if (e->d_name[0] != '.') n++;
    closedir(d);
    return n;
}

int h_unix_socket_listed(const char *text)
{
    char *s = h_read_file("/proc/net/unix");
    int found = s && strstr(s, text) != NULL;
    free(s);
    return found;
}

/* This process's stderr into <work dir>/stderr.txt (its path in path): the fd to give back to
 * h_stderr_back, -1 when it could not. */
int h_stderr_to_file(char *path, size_t cap)
{
    snprintf(path, cap, "%s/stderr.txt", h_work_dir);
    fflush(stderr);
    int saved = dup(2), out = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (saved < 0 || out < 0) return -1;
    dup2(out, 2);
    close(out);
    return saved;
}

void h_stderr_back(int saved)
{
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
}
