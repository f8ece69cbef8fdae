/* Process-wide runtime state: run directory, socket addresses, names, errors, clean-up. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "internal.h"

ContractRuntime g_rt = { .run_dir_fd = -1, .mbx_fd = -1, .ctl_fd = -1, .wait_fd = -1 };

RTIME GetTime(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (RTIME)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

#define SAID_AGAIN_NS 1000000000LL /* ContractSay: the same line again this soon is counted */

static const char *self_name(void) { return g_rt.name[0] ? g_rt.name : "libmodule"; }

void ContractSayRepeats(ContractSaidLines *lines)
{
    if (!lines->repeats) return;
    fprintf(stderr, "%s: %s(the same %s %u more time%s in %.1f s)\n", self_name(), lines->countLead, lines->noun,
            lines->repeats, lines->repeats == 1 ? "" : "s", (double)(GetTime() - lines->said) / 1e9);
    lines->repeats = 0;
}

void ContractSay(ContractSaidLines *lines, const char *text)
{
    RTIME now = GetTime();
    if (strncmp(text, lines->last, sizeof lines->last) == 0 && now - lines->said < SAID_AGAIN_NS) {
        lines->repeats++;
        return;
    }
    ContractSayRepeats(lines);
    fprintf(stderr, "%s: %s%s\n", self_name(), lines->lead, text);
    snprintf(lines->last, sizeof lines->last, "%s", text);
    lines->said = now;
}

/* libmodule's error lines: a supervisor parameterizing a crashed module at 100 Hz printed 100
 * identical lines a second, and a run's output is bounded; every one is still a CSV record. */
static ContractSaidLines error_lines = { "error: ", "error: ", "error", "", 0, 0 };

void rt_error_repeats_say(void) { ContractSayRepeats(&error_lines); }

void rt_error(const char *fmt, ...)
{
    char text[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    ContractLog("error", "", -1, 0, text);
    ContractSay(&error_lines, text);
}

int rt_run_stopping(void)
{
    struct stat st;
    return g_rt.run_dir_fd >= 0 && fstatat(g_rt.run_dir_fd, CONTRACT_RUN_STOPPING_FILE, &st, 0) == 0;
}

int rt_valid_name(const char *name)
{
    if (name == NULL || name[0] == '\0' || strlen(name) >= CONTRACT_NAME_MAX) return 0;
    for (const char *p = name; *p; p++) {
        char c = *p;
        if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
              c == '_' || c == '-' || c == '.'))
            return 0;
    }
    return name[0] != '.';
}

static int mkdir_p(const char *path)
{
    char tmp[PATH_MAX];
    if (snprintf(tmp, sizeof tmp, "%s", path) >= (int)sizeof tmp) { errno = ENAMETOOLONG; return -1; }
    for (char *p = tmp + 1; *p; p++) {
        if (*p != '/') continue;
        *p = '\0';
        if (mkdir(tmp, 0755) != 0 && errno != EEXIST) return -1;
        *p = '/';
    }
    if (mkdir(tmp, 0755) != 0 && errno != EEXIST) return -1;
    return 0;
}

int rt_init_run_dir(void)
{
    if (g_rt.run_dir_fd >= 0) return 0;
    const char *env = getenv("CONTRACT_RUN_DIR");
    if (env != NULL && env[0] != '\0') {
        if (mkdir_p(env) != 0) {
            rt_error("cannot create run directory %s: %s", env, strerror(errno));
            return -1;
        }
        if (realpath(env, g_rt.run_dir) == NULL) {
            rt_error("run directory %s: %s", env, strerror(errno));
            return -1;
        }
    } else {
        const char *tmp = getenv("TMPDIR");
        snprintf(g_rt.run_dir, sizeof g_rt.run_dir, "%s/contract-run-XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (mkdtemp(g_rt.run_dir) == NULL) {
            rt_error("cannot create a run directory under %s: %s", tmp && *tmp ? tmp : "/tmp", strerror(errno));
            return -1;
        }
        g_rt.run_dir_created = 1;
        setenv("CONTRACT_RUN_DIR", g_rt.run_dir, 1);
        fprintf(stderr, "%s: CONTRACT_RUN_DIR not set, using %s\n", g_rt.name, g_rt.run_dir);
    }
    g_rt.run_dir_fd = open(g_rt.run_dir, O_PATH | O_DIRECTORY | O_CLOEXEC);
    if (g_rt.run_dir_fd < 0) {
        rt_error("cannot open run directory %s: %s", g_rt.run_dir, strerror(errno));
        return -1;
    }
    return 0;
}

const char *ContractRunDir(void) { return g_rt.run_dir; }
int ContractRunStopping(void) { return rt_run_stopping(); }
int ContractPeerGoneAtStop(int rc) { return (rc == CONTRACT_EUNKNOWN || rc == CONTRACT_ENOTRUNNING) && rt_run_stopping(); }
const char *ContractSelfName(void) { return g_rt.name; }
long ContractActivations(void) { return g_rt.activations; }

int rt_addr(const char *file, struct sockaddr_un *sa, socklen_t *len)
{
    memset(sa, 0, sizeof *sa);
    sa->sun_family = AF_UNIX;
    int n = snprintf(sa->sun_path, sizeof sa->sun_path, "%s/%s", g_rt.run_dir, file);
    if (n < 0 || (size_t)n >= sizeof sa->sun_path) {
        /* Long run directory: go through the directory fd (Linux /proc magic link). */
        n = snprintf(sa->sun_path, sizeof sa->sun_path, "/proc/self/fd/%d/%s", g_rt.run_dir_fd, file);
        if (n < 0 || (size_t)n >= sizeof sa->sun_path) { errno = ENAMETOOLONG; return -1; }
    }
    *len = (socklen_t)(offsetof(struct sockaddr_un, sun_path) + (size_t)n + 1);
    return 0;
}

int rt_module_addr(const char *module, const char *suffix, struct sockaddr_un *sa, socklen_t *len)
{
    char file[CONTRACT_NAME_MAX + 32];
    if (!rt_valid_name(module)) { errno = EINVAL; return -1; }
    snprintf(file, sizeof file, "%s%s", module, suffix);
    return rt_addr(file, sa, len);
}

/* `fd` moved above the standard streams: module code that closed its stdout or stderr (close(1))
 * must not have its next printf written into a peer's mailbox through a socket that took fd 1. */
static int above_stdio(int fd)
{
    if (fd < 0 || fd > 2) return fd;
    int high = fcntl(fd, F_DUPFD_CLOEXEC, 3);
    int e = errno;
    close(fd);
    errno = e;
    return high;
}

void rt_register_file(const char *file)
{
    if (g_rt.n_created < (int)(sizeof g_rt.created / sizeof g_rt.created[0])) {
        snprintf(g_rt.created[g_rt.n_created], PATH_MAX, "%s", file);
        g_rt.n_created++; /* counted once its name is whole: a handler reads the list */
    }
}

/* A run file is created and then registered for removal; a stop signal (SIGTERM at the launcher's
 * stop, a test's teardown) between the two would end the process through on_fatal_signal with the
 * file on disk but not in the list, left behind in the run directory. The stop signals wait while
 * a file is created and registered, and are delivered as they are released. */
static void hold_stop_signals(sigset_t *before)
{
    sigset_t stop;
    sigemptyset(&stop);
    sigaddset(&stop, SIGTERM);
    sigaddset(&stop, SIGINT);
    sigaddset(&stop, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &stop, before);
}

static void release_stop_signals(const sigset_t *before)
{
    pthread_sigmask(SIG_SETMASK, before, NULL);
}

static int bind_dgram_held(const char *file, int *fd_out)
{
    struct sockaddr_un sa;
    socklen_t len;
    if (rt_addr(file, &sa, &len) != 0) { rt_error("socket path for %s: %s", file, strerror(errno)); return -1; }
    int fd = above_stdio(socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0));
    if (fd < 0) { rt_error("socket: %s", strerror(errno)); return -1; }
    int rc = bind(fd, (struct sockaddr *)&sa, len);
    if (rc != 0 && errno == EADDRINUSE) {
        /* A socket file is there: alive (someone bound) or stale (its process died). */
        int probe = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
        int alive = probe >= 0 && connect(probe, (struct sockaddr *)&sa, len) == 0;
        if (probe >= 0) close(probe);
        if (alive) {
            rt_error("%s already exists and is in use in %s: is this module already running?", file, g_rt.run_dir);
            close(fd);
            return -1;
        }
        unlinkat(g_rt.run_dir_fd, file, 0);
        rc = bind(fd, (struct sockaddr *)&sa, len);
    }
    if (rc != 0) {
        rt_error("bind %s/%s: %s", g_rt.run_dir, file, strerror(errno));
        close(fd);
        return -1;
    }
    rt_register_file(file);
    *fd_out = fd;
    return 0;
}

int rt_bind_dgram(const char *file, int *fd_out)
{
    sigset_t before;
    hold_stop_signals(&before);
    int rc = bind_dgram_held(file, fd_out);
    release_stop_signals(&before);
    return rc;
}

int rt_bind_mailbox(void)
{
    char file[CONTRACT_NAME_MAX + 8];
    snprintf(file, sizeof file, "%s.mbx", g_rt.name);
    if (rt_bind_dgram(file, &g_rt.mbx_fd) != 0) return -1;
    snprintf(file, sizeof file, "%s.ctl", g_rt.name);
    if (rt_bind_dgram(file, &g_rt.ctl_fd) != 0) {
        close(g_rt.mbx_fd);
        g_rt.mbx_fd = -1;
        return -1;
    }
    return 0;
}

int rt_connect_peer(const struct sockaddr_un *sa, socklen_t len, int nonblock)
{
    int fd = above_stdio(socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | (nonblock ? SOCK_NONBLOCK : 0), 0));
    if (fd < 0) return -1;
    if (!nonblock) {
        struct timeval tv = { SEND_TIMEOUT_MS / 1000, (SEND_TIMEOUT_MS % 1000) * 1000 };
        setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &tv, sizeof tv);
    }
    int buf = 4 * 1024 * 1024;
    setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &buf, sizeof buf);
    if (connect(fd, (const struct sockaddr *)sa, len) != 0) {
        int e = errno;
        close(fd);
        errno = e;
        return -1;
    }
    return fd;
}

int rt_errno_to_code(int err)
{
    switch (err) {
    case ENOENT: return CONTRACT_EUNKNOWN;
    case ECONNREFUSED: return CONTRACT_ENOTRUNNING;
    case EMSGSIZE: case ENOBUFS: return CONTRACT_ETOOBIG;
    case EAGAIN: case ETIMEDOUT: return CONTRACT_EBUSY;
    case EINVAL: return CONTRACT_EINVAL;
    default: return CONTRACT_ESYS;
    }
}

const char *ContractStrError(int code)
{
    switch (code) {
    case CONTRACT_OK: return "ok";
    case CONTRACT_EUNKNOWN: return "unknown module (no mailbox in the run directory)";
    case CONTRACT_ENOTRUNNING: return "module not running (its mailbox is stale)";
    case CONTRACT_ETOOBIG: return "message too large";
    case CONTRACT_EBUSY: return "mailbox full: the module did not read its requests in time";
    case CONTRACT_EINVAL: return "invalid argument";
    case CONTRACT_EPERM: return "not permitted";
    default: return "system error";
    }
}

const char *rt_request_name(int type)
{
    static const char *names[] = { "UNKNOWN", "START", "STOP", "KILL", "EVENT", "SETPARAM", "SUBSCRIBE",
                                   "UNSUBSCRIBE", "SUB_EVENT", "UNSUB_EVENT", "PURGE_MBX", "ACK",
                                   "STATUS", "STATUS_REPLY", "PRIORITY", "PRIORITY_REPLY" };
    if (type < 0 || type >= (int)(sizeof names / sizeof names[0])) return "INVALID";
    return names[type];
}

const char *ContractRequestName(int type) { return rt_request_name(type); }

const char *rt_ack_name(int ack)
{
    switch (ack) {
    case ACK_START: return "ACK_START";
    case ACK_FINISHED: return "ACK_FINISHED";
    case ACK_STOPPED: return "ACK_STOPPED";
    case ACK_KILLED: return "ACK_KILLED";
    case ACK_NOTDONE: return "ACK_NOTDONE";
    case ACK_NOTHING: return "ACK_NOTHING";
    default: return "ACK_?";
    }
}

static int write_run_file_held(const char *file, const char *text)
{
    int fd = openat(g_rt.run_dir_fd, file, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) {
        /* O_PATH dirfds cannot be used to create files on every kernel: fall back to the path. */
        char path[PATH_MAX + CONTRACT_NAME_MAX + 8];
        snprintf(path, sizeof path, "%s/%s", g_rt.run_dir, file);
        fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    }
    if (fd < 0) { rt_error("cannot write %s/%s: %s", g_rt.run_dir, file, strerror(errno)); return -1; }
    rt_register_file(file); /* removed at the end even when it could not be written whole */
    size_t n = strlen(text);
    if (write(fd, text, n) != (ssize_t)n) { close(fd); return -1; }
    close(fd);
    return 0;
}

/* Writes <NAME><suffix> in the run directory with `text` (removed when the process ends). */
static int write_run_file(const char *suffix, const char *text)
{
    char file[CONTRACT_NAME_MAX + 8];
    snprintf(file, sizeof file, "%s%s", g_rt.name, suffix);
    sigset_t before;
    hold_stop_signals(&before);
    int rc = write_run_file_held(file, text);
    release_stop_signals(&before);
    return rc;
}

int rt_write_pid_file(void)
{
    char text[32];
    snprintf(text, sizeof text, "%ld\n", (long)getpid());
    return write_run_file(".pid", text);
}

/* A module is ready when it first looks for a request (WaitForRequestUntil, under every way of
 * waiting for one): its init region has returned. It then writes <NAME>.ready, which the launcher
 * waits for before it sends the start request (contract-launch: `module M is not ready after 10 s`
 * names a module whose init loops or blocks). A module that cannot write it ends (status 2), as
 * one that cannot write its <NAME>.pid. */
void rt_mark_ready(void)
{
    if (g_rt.ready || !g_rt.is_module) return;
    g_rt.ready = 1;
    if (write_run_file(".ready", "") != 0) exit(2);
}

static void remove_created_files(void)
{
    for (int i = 0; i < g_rt.n_created; i++) unlinkat(g_rt.run_dir_fd, g_rt.created[i], 0);
    g_rt.n_created = 0;
    if (g_rt.run_dir_created) rmdir(g_rt.run_dir); /* only if empty */
}

static int log_dying; /* a handler writes the log's last records (only one: the first) */

/* SIGTERM, SIGINT, SIGHUP: the records the CSV log has not written yet are written (a module blocked
 * in its own code, which the launcher terminates at the stop, would lose what it did before: its
 * buffer is written only when it calls the library), then its files are removed and it dies by the
 * signal. Async-signal-safe (rt_log_at_signal). */
static pid_t launcher_pid; /* $CONTRACT_LAUNCHER_PID: the launcher that started this module, 0 when none */

/* Decimal digits of v at the end of buf (of `size`); returns where they begin. Async-signal-safe. */
static char *digits_of(long v, char *buf, size_t size)
{
    char *p = buf + size;
    *--p = '\0';
    do { *--p = (char)('0' + v % 10); v /= 10; } while (v > 0 && p > buf);
    return p;
}

/* A stop signal from another process than the launcher that started this module (and still is its
 * parent): passed to the launcher, which stops the architecture in order, and said on stderr
 * (rt_install_signal_cleanup). 1 when it was passed on. Async-signal-safe. */
static int pass_stop_to_launcher(int sig, const siginfo_t *si)
{
    if (launcher_pid <= 0 || getppid() != launcher_pid) return 0;
    if (si && si->si_code <= 0 && si->si_pid == launcher_pid) return 0; /* the launcher's own: end */
    if (kill(launcher_pid, sig) != 0) return 0;
    char from[24], to[24], line[CONTRACT_NAME_MAX + 320];
    const char *name = sig == SIGINT ? "SIGINT" : sig == SIGHUP ? "SIGHUP" : "SIGTERM";
    const char *parts[] = { self_name(), ": ", name, si && si->si_code <= 0 ? " from pid " : " from the kernel",
                            si && si->si_code <= 0 ? digits_of((long)si->si_pid, from, sizeof from) : "",
                            " passed to contract-launch (pid ", digits_of((long)launcher_pid, to, sizeof to),
                            "): it stops the architecture in order, the supervisors first\n" };
    size_t len = 0;
    for (size_t i = 0; i < sizeof parts / sizeof parts[0]; i++)
        for (const char *c = parts[i]; *c && len < sizeof line; c++) line[len++] = *c;
    ssize_t w = write(STDERR_FILENO, line, len);
    (void)w;
    return 1;
}

static void on_fatal_signal(int sig, siginfo_t *si, void *context)
{
    (void)context;
    int saved = errno;
    if (pass_stop_to_launcher(sig, si)) { errno = saved; return; }
    if (!__atomic_exchange_n(&log_dying, 1, __ATOMIC_SEQ_CST)) rt_log_at_signal(sig, 0);
    remove_created_files(); /* unlinkat / rmdir are async-signal-safe */
    signal(sig, SIG_DFL);
    raise(sig);
}

/* A crash of the module's code: the crash report (crash_report.c: where it crashed, on stderr)
 * is written, and its CSV log's records not written yet, then the
 * process dies by the same signal (the launcher's `died by signal 11`, core dump and exit status as
 * without the handler). Async-signal-safe (rt_log_at_signal). The signal is reset to SIG_DFL on entry
 * (SA_RESETHAND) and every crash signal is blocked while the handler runs: a fault in the handler
 * kills the process at once (the kernel forces the default action of a blocked fault), nothing
 * loops. The writer thread blocks every signal: a fault there kills at once too. A crash in a
 * second thread while the first is handled ends the process at once when it is the same signal
 * (reset by then), else waits for the first to end the process (1 s at most). */
static const int crash_signals[] = { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT };
#define N_CRASH_SIGNALS (sizeof crash_signals / sizeof crash_signals[0])
static char crash_stack[64 * 1024]; /* the handler's stack: a stack overflow leaves none */

/* Under AddressSanitizer (the runtime's ASan test builds) a crash signal whose handler the
 * sanitizer installed before main (SIGSEGV, SIGBUS and SIGFPE by default) is the sanitizer's to
 * report: its report (the faulting access, its stack with files and lines) is better than the
 * crash report there. The runtime's handler then writes the log's records only and hands the
 * signal back to the sanitizer's handler, which reports it and ends the process (exit status 1,
 * ASan's exitcode). */
#if defined(__SANITIZE_ADDRESS__)
#define RT_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RT_UNDER_ASAN 1
#endif
#endif
static struct sigaction sanitizer_action[N_CRASH_SIGNALS];
static int sanitizer_has[N_CRASH_SIGNALS];

static int crash_signal_index(int sig)
{
    for (size_t i = 0; i < N_CRASH_SIGNALS; i++)
        if (crash_signals[i] == sig) return (int)i;
    return -1;
}

/* Keeps the sanitizer's handler of crash signal i, if it has one (never without ASan). */
static void keep_sanitizer_handler(size_t i)
{
    sanitizer_has[i] = 0;
#ifdef RT_UNDER_ASAN
    /* sa_handler and sa_sigaction share their storage: SIG_DFL and SIG_IGN are neither's handler */
    if (sigaction(crash_signals[i], NULL, &sanitizer_action[i]) == 0 && sanitizer_action[i].sa_handler != SIG_DFL &&
        sanitizer_action[i].sa_handler != SIG_IGN)
        sanitizer_has[i] = 1;
#endif
}

static void on_crash_signal(int sig, siginfo_t *info, void *context)
{
    int saved = errno;
    int k = crash_signal_index(sig);
    int to_sanitizer = k >= 0 && sanitizer_has[k];
    if (!__atomic_exchange_n(&log_dying, 1, __ATOMIC_SEQ_CST)) {
        if (!to_sanitizer) rt_crash_report_write(sig, info, context); /* where: first, the log may take up to 100 ms */
        rt_log_at_signal(sig, 1);
    } else {
        struct timespec ts = { 1, 0 };
        nanosleep(&ts, NULL);
    }
    errno = saved;
    if (to_sanitizer) {
        sigaction(sig, &sanitizer_action[k], NULL);
        /* a fault happens again as the handler returns, at the same instruction: the sanitizer's
         * handler reports it with its own context; a signal sent is sent again */
        if (!info || info->si_code <= 0) raise(sig);
        return;
    }
    signal(sig, SIG_DFL);
    raise(sig); /* delivered as the handler returns: the process ends by it */
}

void rt_install_signal_cleanup(void)
{
    const char *launcher = getenv(CONTRACT_LAUNCHER_PID_ENV);
    char *end;
    long lp = launcher && *launcher ? strtol(launcher, &end, 10) : 0;
    launcher_pid = lp > 1 && *end == '\0' ? (pid_t)lp : 0;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_sigaction = on_fatal_signal;
    sigemptyset(&sa.sa_mask);
    /* the stop signals wait for each other's handler; each is set back to SIG_DFL as it ends the process */
    sigaddset(&sa.sa_mask, SIGTERM);
    sigaddset(&sa.sa_mask, SIGINT);
    sigaddset(&sa.sa_mask, SIGHUP);
    sa.sa_flags = SA_SIGINFO;
    sigaction(SIGTERM, &sa, NULL);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGHUP, &sa, NULL);
    signal(SIGPIPE, SIG_IGN);
    /* the crash handler runs on a stack of its own (the module's thread: the one that calls this) */
    stack_t alt = { .ss_sp = crash_stack, .ss_size = sizeof crash_stack, .ss_flags = 0 };
    int on_alt = sigaltstack(&alt, NULL) == 0;
    struct sigaction ca;
    memset(&ca, 0, sizeof ca);
    ca.sa_sigaction = on_crash_signal;
    sigemptyset(&ca.sa_mask);
    for (size_t i = 0; i < N_CRASH_SIGNALS; i++) sigaddset(&ca.sa_mask, crash_signals[i]);
    ca.sa_flags = SA_SIGINFO | SA_RESETHAND | (on_alt ? SA_ONSTACK : 0);
    rt_crash_report_prepare();
    for (size_t i = 0; i < N_CRASH_SIGNALS; i++) {
        keep_sanitizer_handler(i);
        sigaction(crash_signals[i], &ca, NULL);
    }
}

void ContractShutdown(void)
{
    rt_outbox_drain(); /* its failures are logged: before the log closes */
    rt_eventflow_say_waits();
    rt_error_repeats_say();
    rt_log_close();
    rt_dataflow_teardown();
    rt_eventflow_teardown();
    if (g_rt.mbx_fd >= 0) { close(g_rt.mbx_fd); g_rt.mbx_fd = -1; }
    if (g_rt.ctl_fd >= 0) { close(g_rt.ctl_fd); g_rt.ctl_fd = -1; }
    if (g_rt.wait_fd >= 0) { close(g_rt.wait_fd); g_rt.wait_fd = -1; }
    rt_close_peers();
    remove_created_files();
    while (g_rt.pending_head) {
        Pending *p = g_rt.pending_head;
        g_rt.pending_head = p->next;
        free(p);
    }
    g_rt.pending_tail = NULL;
    g_rt.pending_count = 0;
    free(g_rt.last_event);
    g_rt.last_event = NULL;
    if (g_rt.run_dir_fd >= 0) { close(g_rt.run_dir_fd); g_rt.run_dir_fd = -1; }
}

static void shutdown_at_exit(void) { ContractShutdown(); }

int ContractClientInit(const char *name)
{
    if (!rt_valid_name(name)) {
        fprintf(stderr, "libmodule: error: invalid name '%s' (letters, digits, _ - . ; < %d chars)\n",
                name ? name : "(null)", CONTRACT_NAME_MAX);
        return -1;
    }
    snprintf(g_rt.name, sizeof g_rt.name, "%s", name);
    if (rt_init_run_dir() != 0) return -1;
    if (rt_bind_mailbox() != 0) return -1;
    static int registered = 0;
    if (!registered) { atexit(shutdown_at_exit); registered = 1; }
    return 0;
}
