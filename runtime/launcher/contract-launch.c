/*
 * contract-launch -- starts the module executables of one architecture in one run directory,
 * tags their output lines with the module name, reports any module that dies, optionally sends
 * the supervisor start request, and stops everything cleanly (no process or socket left).
 *
 *   contract-launch [--run-dir DIR] [--log-dir DIR] [--start 'SUP.function(p=v,...)']
 *                   [--duration SECONDS] [--ready-timeout SECONDS] [--stop-first 'NAME ...']
 *                   [--cpus LIST] [--pm-qos-us N] [--require-realtime] [--stdin NAME=FILE]... EXECUTABLE...
 *
 * Stopping (end of --duration, SIGINT, SIGTERM, --kill): the modules named by --stop-first (the
 * generated Makefile names the supervisors) get their KILL request first and the launcher waits
 * for them (up to 2 s), so that their undo (deactivate schemas, stop modules) still reaches ORD
 * and the modules; then every other module gets its KILL request. A stop by a signal under
 * $CONTRACT_STOP_BUDGET_MS fits those waits in that budget (stop_waits). $CONTRACT_END_BY_S: a
 * run with a --duration stops that long after the launch at the latest (end_by_deadline).
 * $CONTRACT_OUTPUT_LIMIT_BYTES: past that many bytes written on its stdout (or stderr), the
 * modules' lines for it are read and dropped, not relayed (the reader cuts there: emit_line).
 *   contract-launch --kill RUN_DIR
 *
 * Exit status: 0 all modules ran and stopped cleanly; 1 a module crashed (named on stderr);
 * 2 usage / set-up error. See docs/runtime-api.md.
 */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/signalfd.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "libmodule/libmodule.h"
#include "rt_placement.h"
#include "run_bounds.h" /* CONTRACT_LAUNCHER_MAX_MODULES, from packages/conventions/src/run-bounds.ts */
#include "internal.h" /* rt_log_recover */

#define MAX_MODULES CONTRACT_LAUNCHER_MAX_MODULES
#define LINE_MAX_LEN 4096
/* the exit status of a run whose --start could not be sent or was refused (no module failed): a
 * service manager's Restart=on-failure sees it; 1 is a module that failed, 2 nothing started */
#define EXIT_START_REFUSED 3

/* One of a module's output streams: the read end of its pipe, and the line being gathered. */
typedef struct {
    int fd;               /* -1 at EOF */
    char line[LINE_MAX_LEN];
    size_t len;
} Output;

typedef struct {
    const char *exe;
    char name[CONTRACT_NAME_MAX];
    pid_t pid;
    /* its stdout and its stderr, each a pipe of its own: forwarded as `[NAME] line` to the
     * launcher's stdout and stderr, so that a reader (the build service, a terminal) tells them
     * apart, and a line one of them leaves unfinished is never glued to the other's next */
    Output out[2];
    int alive;
    int named;            /* its <NAME>.pid file was read: `name` is the module's own */
    int ready;            /* its <NAME>.ready file exists: its init returned */
    int failed;           /* died on its own with a signal or a non-zero status (also while the run stops) */
    int signalled;        /* the signal the launcher sent it at the stop (SIGTERM, then SIGKILL), 0 when none */
    int killed;           /* failed by a SIGKILL the launcher did not send (the kernel's OOM killer, RLIMIT_RTTIME, another process) */
    /* its crash report (runtime crash_report.c), read from its stderr: saved as its crash file in
     * the run's logs once it died by a signal the launcher did not send (save_crash) */
    char *crash;          /* the block's lines, allocated at its head; NULL when none */
    size_t crash_len;
    int crash_state;      /* 0 none, 1 a block naming it is open, 2 a whole block read (a later head starts anew), 3 saved */
    int crashed;          /* died by a signal the launcher did not send */
    int end_signal;       /* the signal it died by (0: it exited) and its exit status: the FAILED line says which */
    int end_status;
    int stdin_fd;         /* --stdin NAME=FILE: the file it reads on its stdin (opened O_CLOEXEC), -1: /dev/null */
} Child;

static Child children[MAX_MODULES];
static int n_children;
static char run_dir[PATH_MAX];
static int stopping;
static int stop_signalled;      /* the stop came from SIGINT, SIGTERM or SIGHUP */
static const char *stop_why;    /* why the build service asked the stop (stop_reason), NULL when it did not say */

/* Why the build service stops a run: the value it queues with its SIGTERM (sigqueue; `kill -q N`),
 * as @contract-studio/conventions STOP_REASON_CODES numbers them. Each module's KILL says it. */
static const char *stop_reason(int code)
{
    switch (code) {
    case 1: return "the build service's memory limit was reached";
    case 2: return "the build service's process limit was reached";
    case 3: return "the build service's work disk limit was reached";
    case 4: return "the build service's run time limit was reached";
    case 5: return "the job was cancelled";
    default: return NULL;
    }
}
/* The value `contract-launch --kill` (make kill) queues with its SIGTERM: no stop reason of the build
 * service (stop_reason), so that the launcher it stops can say the stop came from make kill. */
#define KILL_MODE_SIGNAL_VALUE 7007
static char stop_cause[200];    /* what stopped the run, for the `stopping: ...` line */
static RTIME stop_budget_ns;    /* CONTRACT_STOP_BUDGET_MS: a stop by a signal fits in it (stop_waits) */
static double end_by_s;         /* CONTRACT_END_BY_S: the run stops this long after the launch at the latest */
static const char *stop_first;  /* --stop-first: names, separated by spaces or commas */
static cpu_set_t module_cpus;  /* --cpus: every module's affinity */
static int pin_modules;

/* --stdin NAME=FILE: module NAME reads FILE on its stdin (the others read /dev/null) */
typedef struct { const char *name; size_t name_len; const char *file; int fd; } StdinFile;
static StdinFile stdin_files[MAX_MODULES];
static int n_stdin_files;

/* The launcher's own lines file in the logs folder (--log-dir): each line it says, also written
 * there as `<mono_ns> <line>` (CLOCK_MONOTONIC, the clock of the CSV records' mono_ns), through an
 * fd of its own that no module inherits (O_CLOEXEC). A run's recordings (contract trace LOGDIR, the
 * IDE's replay of a logs folder) read a module's end from it: the module's own output reaches the
 * launcher's stderr tagged `[NAME]`, never this file. The name is LAUNCHER_LINES_FILE of
 * packages/build-service/src/trace/launcher-lines-file.ts. */
#define LAUNCHER_LINES_FILE "contract-launch.log"
/* Bytes written to it at most (a run of 256 modules says far less): past them it is no longer written. */
#define LAUNCHER_LINES_MAX_BYTES (1024 * 1024)
static int lines_fd = -1;
static size_t lines_written;

static void write_own_line(const char *fmt, va_list ap) __attribute__((format(printf, 1, 0)));
static void write_own_line(const char *fmt, va_list ap)
{
    char text[1024];
    char line[1100];
    if (lines_fd < 0) return;
    vsnprintf(text, sizeof text, fmt, ap);
    for (char *p = text; *p; p++)
        if (*p == '\n' || *p == '\r') *p = ' '; /* one line a line, whatever a path or an error holds */
    int n = snprintf(line, sizeof line, "%lld %s\n", (long long)GetTime(), text);
    if (n <= 0) return;
    size_t len = (size_t)n < sizeof line ? (size_t)n : sizeof line - 1;
    if (len > sizeof line - 1 || lines_written + len > LAUNCHER_LINES_MAX_BYTES) return;
    line[len - 1] = '\n';
    ssize_t k;
    do k = write(lines_fd, line, len); while (k < 0 && errno == EINTR);
    if (k > 0) lines_written += (size_t)k;
}

static void say(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void relay_flush_all(void);
static long long written[2]; /* bytes the launcher wrote on its stdout and stderr (emit_line, say) */
static void say(const char *fmt, ...)
{
    relay_flush_all(); /* the modules' lines relayed before come out before this one */
    va_list ap, again;
    va_start(ap, fmt);
    va_copy(again, ap);
    int n = fprintf(stderr, "contract-launch: ");
    int m = vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    write_own_line(fmt, again);
    va_end(again);
    va_end(ap);
    written[1] += (n > 0 ? n : 0) + (m > 0 ? m : 0) + 1;
}

/* Opens the lines file in `log_dir`, emptied (the run before's was moved to previous/ by make run
 * and contract run); never through a link. Not opened: the lines are on stderr only, said once. */
static void open_own_lines(const char *log_dir)
{
    char path[PATH_MAX];
    int n = snprintf(path, sizeof path, "%s/%s", log_dir, LAUNCHER_LINES_FILE);
    if (n <= 0 || (size_t)n >= sizeof path) return;
    lines_fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_APPEND | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK, 0644);
    if (lines_fd < 0) { say("cannot write %s (%s): the modules' ends are in this output only, not in the logs folder", path, strerror(errno)); return; }
    struct stat st;
    if (fstat(lines_fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(lines_fd);
        lines_fd = -1;
        say("%s is not a regular file: the modules' ends are in this output only, not in the logs folder", path);
    }
}

static void usage(void)
{
    fprintf(stderr,
            "usage: contract-launch [--run-dir DIR] [--log-dir DIR] [--start 'SUP.function(p=v,...)']\n"
            "                       [--duration SECONDS] [--ready-timeout SECONDS] [--stop-first 'NAME ...']\n"
            "                       [--cpus LIST] [--pm-qos-us N] [--require-realtime] [--stdin NAME=FILE]... EXECUTABLE...\n"
            "       contract-launch --check-realtime [--require-realtime]\n"
            "       contract-launch [--stop-first 'NAME ...'] --kill RUN_DIR\n"
            "       contract-launch --term-why CODE PID\n");
}

static RTIME now_ns(void) { return GetTime(); }

static int mkdir_p(const char *path)
{
    char tmp[PATH_MAX];
    snprintf(tmp, sizeof tmp, "%s", path);
    for (char *p = tmp + 1; *p; p++) {
        if (*p != '/') continue;
        *p = '\0';
        if (mkdir(tmp, 0755) != 0 && errno != EEXIST) return -1;
        *p = '/';
    }
    return mkdir(tmp, 0755) != 0 && errno != EEXIST ? -1 : 0;
}

static long read_pid_file(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    long pid = -1;
    if (fscanf(f, "%ld", &pid) != 1) pid = -1;
    fclose(f);
    return pid;
}

/* The runtime's files in a run directory, by their ends: NAME.mbx, NAME.ctl, NAME.<port>.in, NAME.pid,
 * NAME.ready, and the module and flow holds of the supervisor engines (NAME.<module>.hold,
 * NAME.started.hold, NAME.engine-stopped.hold, NAME.flow-<...>.hold, NAME.prio-<module>-<id>.hold);
 * launcher.pid too. */
static int is_runtime_file(const char *file)
{
    static const char *const ends[] = { ".mbx", ".ctl", ".pid", ".ready", ".in", ".hold" };
    size_t l = strlen(file);
    for (size_t i = 0; i < sizeof ends / sizeof ends[0]; i++) {
        size_t n = strlen(ends[i]);
        if (l > n && strcmp(file + l - n, ends[i]) == 0) return 1;
    }
    return 0;
}

/* Remove the runtime files of module `name` from the run directory (is_runtime_file). */
static void remove_module_files(const char *dir, const char *name)
{
    DIR *d = opendir(dir);
    if (!d) return;
    size_t n = strlen(name);
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strncmp(e->d_name, name, n) == 0 && e->d_name[n] == '.' && is_runtime_file(e->d_name))
            unlinkat(dirfd(d), e->d_name, 0);
    closedir(d);
}

/* Remove every runtime file (is_runtime_file, launcher.stopping) and the directory if empty. */
static void clean_run_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (is_runtime_file(e->d_name) || strcmp(e->d_name, CONTRACT_RUN_STOPPING_FILE) == 0)
            unlinkat(dirfd(d), e->d_name, 0);
    closedir(d);
    rmdir(dir);
}

/* CONTRACT_RUN_STOPPING_FILE of the run directory $CONTRACT_RUN_DIR into path; 0 if there is none. */
static int stopping_file(char *path, size_t size)
{
    const char *dir = getenv("CONTRACT_RUN_DIR");
    return dir && snprintf(path, size, "%s/%s", dir, CONTRACT_RUN_STOPPING_FILE) < (int)size;
}

/* Tells the modules the run is stopping (CONTRACT_RUN_STOPPING_FILE): a module that posts to a
 * peer already gone then logs it without an error line. */
static void mark_stopping(void)
{
    char path[PATH_MAX + 32];
    if (!stopping_file(path, sizeof path)) return;
    int fd = open(path, O_WRONLY | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd >= 0) close(fd);
}

/* ------------------------------------------------------------------ --kill */

/* Alive and not a zombie (a launcher started by a test or a shell may wait to be reaped). */
static int process_running(long pid)
{
    char path[64], buf[256];
    snprintf(path, sizeof path, "/proc/%ld/stat", pid);
    FILE *f = fopen(path, "r");
    if (!f) return kill((pid_t)pid, 0) == 0;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = '\0';
    const char *close = strrchr(buf, ')');
    return !(close && close[1] == ' ' && (close[2] == 'Z' || close[2] == 'X'));
}

/* --term-why CODE PID: SIGTERM to PID with CODE queued (sigqueue), as the build service's `kill -q`
 * does from the host: where no `kill` with `-q` is at hand (a container of the image, which has only
 * the shell's), the launcher it stops then says why. 0 when sent; 2 for a code it does not know or
 * a pid that is no number (nothing sent); 1 when the signal could not be sent. */
static int term_why_mode(const char *code_text, const char *pid_text)
{
    char *end;
    long code = strtol(code_text, &end, 10);
    if (*end || !*code_text || code < 0 || code > 1000 || !stop_reason((int)code)) {
        say("--term-why '%s': not a stop reason's code", code_text);
        return 2;
    }
    long pid = strtol(pid_text, &end, 10);
    if (*end || !*pid_text || pid <= 1 || pid > 4194304) {
        say("--term-why: '%s' is not a process id", pid_text);
        return 2;
    }
    union sigval v = { .sival_int = (int)code };
    if (sigqueue((pid_t)pid, SIGTERM, v) != 0) {
        say("--term-why: pid %ld: %s", pid, strerror(errno));
        return 1;
    }
    return 0;
}

static int stops_first(const char *name);

static int kill_mode(const char *dir)
{
    struct stat st;
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        say("no run directory %s", dir);
        return 2;
    }
    char path[PATH_MAX + 32];
    snprintf(path, sizeof path, "%s/launcher.pid", dir);
    long lp = read_pid_file(path);
    if (lp > 0 && kill((pid_t)lp, 0) == 0) {
        if (sigqueue((pid_t)lp, SIGTERM, (union sigval){ .sival_int = KILL_MODE_SIGNAL_VALUE }) != 0) kill((pid_t)lp, SIGTERM);
        for (int i = 0; i < 300 && process_running(lp); i++) usleep(50000);
        if (process_running(lp)) { say("launcher %ld did not stop within 15 s", lp); return 1; }
        say("stopped the architecture of %s", dir);
        return 0;
    }
    /* No launcher (it died, or the modules were started by hand): ask each one to end, those
     * --stop-first names (the supervisors: make kill gives them) first, as the launcher's stop does,
     * so that their undo still reaches ORD and the modules; then terminate stragglers. */
    setenv("CONTRACT_RUN_DIR", dir, 1);
    mark_stopping();
    DIR *d = opendir(dir);
    static char names[MAX_MODULES][CONTRACT_NAME_MAX];
    long pids[MAX_MODULES];
    int n = 0;
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL && n < MAX_MODULES) {
        size_t l = strlen(e->d_name);
        if (l <= 4 || strcmp(e->d_name + l - 4, ".pid") != 0 || strcmp(e->d_name, "launcher.pid") == 0) continue;
        snprintf(names[n], sizeof names[n], "%.*s", (int)(l - 4), e->d_name);
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        pids[n++] = read_pid_file(path);
    }
    if (d) closedir(d);
    for (int first = 1; first >= 0; first--) {
        int sent = 0;
        for (int i = 0; i < n; i++)
            if (stops_first(names[i]) == first && ModuleState(names[i]) == CONTRACT_OK) { SendKill(names[i], ACK_NOTHING, -1); sent++; }
        for (int t = 0; sent && t < 40; t++) { /* 2 s at most, as the launcher's stop */
            int alive = 0;
            for (int i = 0; i < n; i++) if (stops_first(names[i]) == first && pids[i] > 0 && process_running(pids[i])) alive++;
            if (!alive) break;
            usleep(50000);
        }
    }
    for (int i = 0; i < n; i++) if (pids[i] > 0 && process_running(pids[i])) kill((pid_t)pids[i], SIGKILL);
    clean_run_dir(dir);
    say("stopped %d module(s) of %s", n, dir);
    return 0;
}

/* ------------------------------------------------------------------ output */

/* The modules' lines relayed to the launcher's stdout (0) and stderr (1), gathered and written in
 * blocks rather than one write each: the run's reader (the build service reads a socket whose
 * buffer is charged per write, a few hundred lines of a flood at a time when each is one write)
 * then takes a module's flood at the speed of its reads, and a module printing past the run's
 * output limit is not held by the relay. Written out at the end of each read of a module's output
 * (pump), before each of the launcher's own lines (say) and when full: lines keep their order. */
#define RELAY_BLOCK (64 * 1024)
static struct { char data[RELAY_BLOCK]; size_t len; } relay[2];

/* CONTRACT_OUTPUT_LIMIT_BYTES (the build service's outputBytesPerStream; 0: none): the reader keeps
 * that much of each stream and cuts the rest. Once the launcher itself has written that much on a
 * stream (its reader has then seen at least as much: make's lines come before), the modules' lines
 * for that stream are read and dropped here, not relayed to be dropped there: a module printing
 * past the limit is drained at the speed of the launcher's reads and keeps its period. The
 * launcher's own lines go on. */
static long long output_limit;

/* Writes what stream `k`'s block holds (what the reader refuses, EPIPE, is dropped). */
static void relay_flush(int k)
{
    size_t done = 0;
    while (done < relay[k].len) {
        ssize_t w = write(k ? STDERR_FILENO : STDOUT_FILENO, relay[k].data + done, relay[k].len - done);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) break;
        done += (size_t)w;
    }
    relay[k].len = 0;
}

static void relay_flush_all(void)
{
    relay_flush(0);
    relay_flush(1);
}

/* `[NAME] ` and line `text` (its bytes as they are: a NUL among them too) to stream `k` (0: the
 * launcher's stdout, 1: its stderr), whole in one block so that lines of different modules never interleave. */
static void emit_line(const Child *c, int k, const char *text, size_t len)
{
    char head[CONTRACT_NAME_MAX + 4];
    int hl = snprintf(head, sizeof head, "[%s] ", c->name);
    if (hl < 0) return;
    if (len > LINE_MAX_LEN) len = LINE_MAX_LEN;
    if (output_limit > 0 && written[k] >= output_limit) return;
    written[k] += hl + (long long)len + 1;
    if (relay[k].len + (size_t)hl + len + 1 > sizeof relay[k].data) relay_flush(k);
    char *at = relay[k].data + relay[k].len;
    memcpy(at, head, (size_t)hl);
    memcpy(at + hl, text, len);
    at[(size_t)hl + len] = '\n';
    relay[k].len += (size_t)hl + len + 1;
}

/* ------------------------------------------------------------------ crash file */

/* A crashed module's crash report, saved as <CONTRACT_LOG_DIR>/<NAME>.crash (docs/runtime-api.md
 * "Crash file"): the last whole block of its stderr that names it (the crash handler writes its
 * block just before the process dies: a block the module's code printed before is not kept), saved
 * once its stderr is read to its end, its lines as they are, each
 * CRASH_LINE_MAX characters at most, CRASH_LINES_MAX lines at most (head, build-id, 48 frames,
 * end). Readers (contract trace) read it in the exact format only. */
#define CRASH_MARK "==contract-crash== "
#define CRASH_LINE_MAX 160
#define CRASH_LINES_MAX 51
#define CRASH_BLOCK_MAX (CRASH_LINES_MAX * (CRASH_LINE_MAX + 1))

/* <CONTRACT_LOG_DIR>/<NAME>.crash into `path`; 0 when there is no log folder. */
static int crash_path(const Child *c, char *path, size_t size)
{
    const char *dir = getenv("CONTRACT_LOG_DIR");
    if (!dir || !*dir) return 0;
    int n = snprintf(path, size, "%s/%s.crash", dir, c->name);
    return n > 0 && (size_t)n < size;
}

/* The crash file of `c`, once it crashed and its stderr was read to its end (either may come first). */
static void save_crash(Child *c)
{
    char path[PATH_MAX];
    if (c->crash_state != 2 || !c->crashed || c->out[1].fd >= 0 || !crash_path(c, path, sizeof path)) return;
    c->crash_state = 3;
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) { say("module %s: its crash file %s: %s", c->name, path, strerror(errno)); return; }
    for (size_t w = 0; w < c->crash_len;) {
        ssize_t k = write(fd, c->crash + w, c->crash_len - w);
        if (k <= 0) { if (k < 0 && errno == EINTR) continue; say("module %s: its crash file %s: %s", c->name, path, strerror(errno)); break; }
        w += (size_t)k;
    }
    close(fd);
}

/* A line of `c`'s stderr: kept while it is a line of a crash report block that names `c`. */
static void note_crash_line(Child *c, int k, const char *text, size_t len)
{
    const size_t m = sizeof CRASH_MARK - 1;
    if (k != 1 || c->crash_state == 3) return;
    int marked = len >= m && len <= CRASH_LINE_MAX && memcmp(text, CRASH_MARK, m) == 0 && !memchr(text, '\0', len);
    char head[CONTRACT_NAME_MAX + 32];
    int hl = snprintf(head, sizeof head, CRASH_MARK "module %s ", c->name);
    if (marked && hl > 0 && len > (size_t)hl && memcmp(text, head, (size_t)hl) == 0) { /* a head: the block starts (anew) */
        if (!c->crash && !(c->crash = malloc(CRASH_BLOCK_MAX))) return;
        c->crash_len = 0;
        c->crash_state = 1;
    } else if (c->crash_state != 1) { /* outside a block, or after a whole one */
        return;
    } else if (!marked || c->crash_len + len + 1 > CRASH_BLOCK_MAX) { /* not the runtime's block */
        c->crash_state = 0;
        return;
    }
    memcpy(c->crash + c->crash_len, text, len);
    c->crash_len += len;
    c->crash[c->crash_len++] = '\n';
    if (len > m + 4 && memcmp(text + m, "end ", 4) == 0) c->crash_state = 2;
}

/* A crash file left in the log folder by an earlier run of a module of this one: not this run's. */
static void remove_old_crash_file(const Child *c)
{
    char path[PATH_MAX];
    if (crash_path(c, path, sizeof path)) unlink(path);
}

/* Output `k` of `c` at its end: its unfinished line forwarded, its pipe closed. */
static void close_output(Child *c, int k)
{
    Output *o = &c->out[k];
    if (o->fd < 0) return;
    if (o->len) { note_crash_line(c, k, o->line, o->len); emit_line(c, k, o->line, o->len); o->len = 0; }
    relay_flush_all();
    close(o->fd);
    o->fd = -1;
    if (k == 1) save_crash(c);
}

/* Reads what output `k` of `c` holds and forwards its whole lines (a line longer than
 * LINE_MAX_LEN goes in pieces of that length, each a line). */
static void pump(Child *c, int k)
{
    Output *o = &c->out[k];
    static char buf[16384];
    ssize_t n = read(o->fd, buf, sizeof buf);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) return;
    if (n <= 0) { close_output(c, k); return; }
    for (ssize_t i = 0; i < n; i++) {
        if (buf[i] == '\n' || o->len == LINE_MAX_LEN) {
            note_crash_line(c, k, o->line, o->len);
            emit_line(c, k, o->line, o->len);
            o->len = 0;
            if (buf[i] == '\n') continue;
        }
        o->line[o->len++] = buf[i];
    }
    relay_flush_all();
}

/* The open outputs of every module in `pfd` (`idx`: child * 2 + stream), up to `max`; how many. */
static int poll_outputs(struct pollfd *pfd, int *idx, int max)
{
    int n = 0;
    for (int i = 0; i < n_children; i++)
        for (int k = 0; k < 2; k++)
            if (children[i].out[k].fd >= 0 && n < max) { pfd[n].fd = children[i].out[k].fd; pfd[n].events = POLLIN; idx[n++] = i * 2 + k; }
    return n;
}

/* ------------------------------------------------------------------ children */

/* The module name of an executable path: its base name. */
static const char *exe_name(const char *exe)
{
    const char *base = strrchr(exe, '/');
    return base ? base + 1 : exe;
}

/*
 * Opens the file of each --stdin NAME=FILE (read-only, never inherited by the other modules),
 * NAME one of the executables given, once: anything else is said and nothing starts (exit 2).
 */
static int open_stdin_files(char **exes, int n_exes)
{
    for (int k = 0; k < n_stdin_files; k++) {
        StdinFile *f = &stdin_files[k];
        int found = 0;
        for (int e = 0; e < n_exes && !found; e++) {
            const char *name = exe_name(exes[e]);
            found = strlen(name) == f->name_len && strncmp(name, f->name, f->name_len) == 0;
        }
        if (!found) { say("--stdin %.*s=...: no module %.*s among the executables given", (int)f->name_len, f->name, (int)f->name_len, f->name); return -1; }
        for (int j = 0; j < k; j++)
            if (stdin_files[j].name_len == f->name_len && strncmp(stdin_files[j].name, f->name, f->name_len) == 0) {
                say("--stdin %.*s=...: given twice", (int)f->name_len, f->name);
                return -1;
            }
    }
    for (int k = 0; k < n_stdin_files; k++) {
        StdinFile *f = &stdin_files[k];
        f->fd = open(f->file, O_RDONLY | O_CLOEXEC);
        struct stat st;
        if (f->fd < 0 || fstat(f->fd, &st) != 0 || S_ISDIR(st.st_mode)) {
            say("--stdin %.*s=%s: cannot read it: %s", (int)f->name_len, f->name, f->file, f->fd < 0 ? strerror(errno) : "a folder");
            return -1;
        }
        say("module %.*s reads its stdin from %s", (int)f->name_len, f->name, f->file);
    }
    return 0;
}

/* The file module `name` reads on its stdin (--stdin), -1 for /dev/null. */
static int stdin_file_of(const char *name)
{
    for (int k = 0; k < n_stdin_files; k++)
        if (strlen(name) == stdin_files[k].name_len && strncmp(name, stdin_files[k].name, stdin_files[k].name_len) == 0) return stdin_files[k].fd;
    return -1;
}

static void derive_name(Child *c)
{
    snprintf(c->name, sizeof c->name, "%s", exe_name(c->exe));
}

static int spawn(Child *c, const sigset_t *oldmask)
{
    int fds[2], efds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) { say("pipe: %s", strerror(errno)); return -1; }
    if (pipe2(efds, O_CLOEXEC) != 0) { say("pipe: %s", strerror(errno)); close(fds[0]); close(fds[1]); return -1; }
    pid_t pid = fork();
    if (pid < 0) { say("fork: %s", strerror(errno)); close(fds[0]); close(fds[1]); close(efds[0]); close(efds[1]); return -1; }
    if (pid == 0) {
        setpgid(0, 0); /* terminal Ctrl-C reaches the launcher only; it stops the modules itself */
        sigprocmask(SIG_SETMASK, oldmask, NULL);
        signal(SIGPIPE, SIG_DFL);
        if (pin_modules && sched_setaffinity(0, sizeof module_cpus, &module_cpus) != 0) {
            fprintf(stderr, "cannot set the CPU affinity of %s: %s\n", c->exe, strerror(errno));
            _exit(127);
        }
        int in = c->stdin_fd >= 0 ? c->stdin_fd : open("/dev/null", O_RDONLY);
        if (in == STDIN_FILENO) fcntl(in, F_SETFD, 0);
        else if (in >= 0) { dup2(in, STDIN_FILENO); close(in); }
        dup2(fds[1], STDOUT_FILENO);
        dup2(efds[1], STDERR_FILENO);
        execl(c->exe, c->exe, (char *)NULL);
        fprintf(stderr, "cannot execute %s: %s\n", c->exe, strerror(errno));
        _exit(127);
    }
    close(fds[1]);
    close(efds[1]);
    fcntl(fds[0], F_SETFL, O_NONBLOCK);
    fcntl(efds[0], F_SETFL, O_NONBLOCK);
    c->pid = pid;
    c->out[0].fd = fds[0];
    c->out[1].fd = efds[0];
    c->alive = 1;
    return 0;
}

/* Learn module names from the <NAME>.pid files the library writes at start-up, and which modules
 * are ready from their <NAME>.ready files (written when the module first looks for a request: its
 * init has returned). */
static void scan_ready(void)
{
    DIR *d = opendir(run_dir);
    if (!d) return;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t l = strlen(e->d_name);
        if (l <= 4 || l - 4 >= CONTRACT_NAME_MAX || strcmp(e->d_name + l - 4, ".pid") != 0) continue;
        if (strcmp(e->d_name, "launcher.pid") == 0) continue;
        char path[PATH_MAX + 300];
        snprintf(path, sizeof path, "%s/%s", run_dir, e->d_name);
        long pid = read_pid_file(path);
        for (int i = 0; i < n_children; i++) {
            if (children[i].pid == pid && !children[i].named) {
                children[i].named = 1;
                snprintf(children[i].name, sizeof children[i].name, "%.*s", (int)(l - 4), e->d_name);
            }
        }
    }
    for (int i = 0; i < n_children; i++) {
        if (!children[i].named || children[i].ready) continue;
        char ready[CONTRACT_NAME_MAX + 8];
        snprintf(ready, sizeof ready, "%s.ready", children[i].name);
        if (faccessat(dirfd(d), ready, F_OK, 0) == 0) children[i].ready = 1;
    }
    closedir(d);
}

/* Real-time mode bounds a process that runs under SCHED_FIFO without blocking with RLIMIT_RTTIME
 * (SIGXCPU at the soft limit, SIGKILL at the hard one; docs/sandbox.md "Real-time mode"): a module
 * stopped that way is named as such, not as a crash. Empty when the bound is not the reason. */
static const char *rttime_note(int sig, const struct rusage *ru, char *buf, size_t size)
{
    struct rlimit rl;
    buf[0] = '\0';
    if (getrlimit(RLIMIT_RTTIME, &rl) != 0 || rl.rlim_cur == RLIM_INFINITY) return buf;
    double cpu_us = (double)(ru->ru_utime.tv_sec + ru->ru_stime.tv_sec) * 1e6 + (double)(ru->ru_utime.tv_usec + ru->ru_stime.tv_usec);
    int hard = sig == SIGKILL && rl.rlim_max != RLIM_INFINITY && cpu_us >= (double)rl.rlim_max;
    if (sig == SIGXCPU || hard)
        snprintf(buf, size, ": ran %.3g s under SCHED_FIFO without blocking (real-time mode's RLIMIT_RTTIME %s limit %.3g s)",
                 cpu_us / 1e6, hard ? "hard" : "soft", (double)(hard ? rl.rlim_max : rl.rlim_cur) / 1e6);
    return buf;
}

/* Who sends a SIGKILL the launcher did not: the kernel at a memory limit (its OOM killer), at the
 * real-time mode's CPU bound only when there is one (a finite RLIMIT_RTTIME, inherited by the
 * modules: the build service's real-time mode), or another process */
static const char *sigkill_senders(void)
{
    struct rlimit rl;
    int rt_bound = getrlimit(RLIMIT_RTTIME, &rl) == 0 && rl.rlim_max != RLIM_INFINITY;
    return rt_bound ? "the kernel's at a memory limit or the real-time CPU bound, or another process's"
                    : "the kernel's at a memory limit, or another process's";
}

/* A module that died without writing its CSV log (a SIGKILL, an _exit): the records it had logged
 * and not written are written now, from its log buffers (runtime/src/log_recover.c). */
static void recover_log(const Child *c, pid_t pid)
{
    RecoveredLog r;
    if (!rt_log_recover(getenv("CONTRACT_LOG_DIR"), (long)pid, &r) || r.records == 0) return;
    say("module %s: %llu record(s) it had logged and not written when it ended were written to its log %s from its log buffers%s",
        c->name, r.records, r.log, r.dropped ? " (the log's bound, CONTRACT_LOG_MAX_BYTES, left out the rest)" : "");
}

static void reap(void)
{
    int status;
    pid_t pid;
    struct rusage ru;
    while ((pid = wait4(-1, &status, WNOHANG, &ru)) > 0) {
        for (int i = 0; i < n_children; i++) {
            Child *c = &children[i];
            if (c->pid != pid) continue;
            c->alive = 0;
            /* a module the launcher signalled at the stop ended by that; any other end while the run
             * stops (a crash in its exit region, a non-zero exit) is its own, as before the stop */
            const char *when = stopping ? " while the run stopped" : "";
            if (WIFSIGNALED(status)) {
                int sig = WTERMSIG(status);
                int ours = c->signalled != 0;
                c->end_signal = sig;
                if (!ours) c->failed = 1;
                if (!ours && sig == SIGKILL) c->killed = 1;
                if (!ours) { c->crashed = 1; save_crash(c); }
                char note[160];
                say("module %s (pid %ld) %s by signal %d (%s)%s%s", c->name, (long)pid, ours ? "terminated" : "died",
                    sig, strsignal(sig), rttime_note(sig, &ru, note, sizeof note), ours ? "" : when);
            } else {
                int code = WEXITSTATUS(status);
                c->end_signal = 0;
                c->end_status = code;
                if (code != 0 && !c->signalled) c->failed = 1;
                /* a module that ends with status 0 before the stop: its own code ended it (exit(0)) */
                say("module %s (pid %ld) exited with status %d%s", c->name, (long)pid, code,
                    c->signalled ? "" : stopping ? (code ? when : "") : code ? "" : " before the run's end");
            }
            remove_module_files(run_dir, c->name);
            /* after its files are gone (nothing waits on its log) */
            recover_log(c, pid);
        }
    }
}

static int alive_count(void)
{
    int n = 0;
    for (int i = 0; i < n_children; i++) n += children[i].alive;
    return n;
}

/* 1 if `name` is one of the --stop-first names. */
static int stops_first(const char *name)
{
    size_t n = strlen(name);
    for (const char *p = stop_first; p && *p;) {
        p += strspn(p, " ,");
        size_t l = strcspn(p, " ,");
        if (l == n && l > 0 && strncmp(p, name, n) == 0) return 1;
        p += l;
    }
    return 0;
}

/* What a run_loop waits for (besides its deadline and a stop signal). */
static int all_ready(void)
{
    scan_ready();
    for (int i = 0; i < n_children; i++)
        if (children[i].alive && !children[i].ready) return 0;
    return 1;
}
static int all_ended(void) { return alive_count() == 0; }
static int first_ended(void)
{
    for (int i = 0; i < n_children; i++)
        if (children[i].alive && stops_first(children[i].name)) return 0;
    return 1;
}

/* Forwards what the modules have already written (their pipes are non-blocking): a module's
 * output from before what the launcher does next (its `init done` before `started P.mission`)
 * comes out before the launcher's line about it. Bounded: a module that writes without end
 * does not hold the launcher here. */
static void drain_output(void)
{
    for (int round = 0; round < 64; round++) {
        struct pollfd pfd[2 * MAX_MODULES];
        int idx[2 * MAX_MODULES];
        int n = poll_outputs(pfd, idx, 2 * MAX_MODULES);
        if (n == 0 || poll(pfd, (nfds_t)n, 0) <= 0) return;
        for (int k = 0; k < n; k++)
            if (pfd[k].revents) pump(&children[idx[k] / 2], idx[k] % 2);
    }
}

/* Who sent a stop signal, in words: `make kill (contract-launch --kill, pid N)`, `SIGINT from the
 * terminal` (pid 0: the terminal's Ctrl-C, or the kernel's), `SIGTERM from module ORD (pid N)` (a
 * module passes a stop signal it got on to the launcher), `SIGTERM from pid N`. */
static void describe_stop_signal(const struct signalfd_siginfo *si, char *buf, size_t size)
{
    const char *name = si->ssi_signo == SIGINT ? "SIGINT" : si->ssi_signo == SIGHUP ? "SIGHUP" : "SIGTERM";
    if (si->ssi_signo == SIGTERM && si->ssi_code == SI_QUEUE && si->ssi_int == KILL_MODE_SIGNAL_VALUE) {
        snprintf(buf, size, "make kill (contract-launch --kill, pid %u)", si->ssi_pid);
        return;
    }
    if (si->ssi_pid == 0) {
        snprintf(buf, size, "%s%s", name, si->ssi_signo == SIGTERM ? "" : " from the terminal");
        return;
    }
    for (int i = 0; i < n_children; i++)
        if ((uint32_t)children[i].pid == si->ssi_pid) {
            snprintf(buf, size, "%s from module %s (pid %u)", name, children[i].name, si->ssi_pid);
            return;
        }
    snprintf(buf, size, "%s from pid %u", name, si->ssi_pid);
}

/* A stop signal while the run already stops (a service manager's stop sends SIGTERM to make, the
 * launcher and every module at once: make passes its own on, each module started by the launcher
 * passes its own on too, core.c): the stop goes on as it is, supervisors first, bounded by its
 * waits (stop_waits); it is said once, with who sent it. */
static void stop_signal_while_stopping(const struct signalfd_siginfo *si)
{
    static int said;
    if (said++) return;
    char who[160];
    describe_stop_signal(si, who, sizeof who);
    say("%s while the run stops: the stop goes on in order (the supervisors first, then the others)", who);
}

/* Poll outputs and signals until `deadline`, until `reached()` (may be NULL) or until stop is asked.
 * Returns 1 if a stop signal came; while the run stops (stop_all), a stop signal ends no wait. */
static int run_loop(int sfd, RTIME deadline, int (*reached)(void))
{
    for (;;) {
        if (reached && reached()) {
            drain_output();
            return 0;
        }
        RTIME now = now_ns();
        if (deadline != INT64_MAX && now >= deadline) return 0;
        struct pollfd pfd[2 * MAX_MODULES + 1];
        int idx[2 * MAX_MODULES + 1];
        pfd[0].fd = sfd; pfd[0].events = POLLIN; idx[0] = -1;
        int n = 1 + poll_outputs(pfd + 1, idx + 1, 2 * MAX_MODULES);
        int timeout = 100;
        if (deadline != INT64_MAX && (deadline - now) / 1000000 < timeout) timeout = (int)((deadline - now) / 1000000) + 1;
        int r = poll(pfd, (nfds_t)n, timeout);
        if (r < 0 && errno != EINTR) { say("poll: %s", strerror(errno)); return 1; }
        int stop = 0;
        for (int k = 0; r > 0 && k < n; k++) {
            if (!pfd[k].revents) continue;
            if (idx[k] >= 0) { pump(&children[idx[k] / 2], idx[k] % 2); continue; }
            struct signalfd_siginfo si;
            while (read(sfd, &si, sizeof si) == (ssize_t)sizeof si) {
                if (si.ssi_signo == SIGCHLD) reap();
                else if (stopping) stop_signal_while_stopping(&si);
                else {
                    stop = stop_signalled = 1;
                    if (si.ssi_signo == SIGTERM && si.ssi_code == SI_QUEUE && !stop_why) stop_why = stop_reason(si.ssi_int);
                    if (!stop_cause[0]) describe_stop_signal(&si, stop_cause, sizeof stop_cause);
                }
            }
        }
        reap();
        if (stop) return 1;
    }
}

/* Sends KILL to the running modules of one group (those --stop-first names, or the others);
 * returns how many. */
static int send_kills(int first)
{
    int sent = 0;
    for (int i = 0; i < n_children; i++)
        if (children[i].alive && children[i].named && stops_first(children[i].name) == first &&
            ModuleState(children[i].name) == CONTRACT_OK) {
            if (stop_why) SendKillWhy(children[i].name, stop_why);
            else SendKill(children[i].name, ACK_NOTHING, -1);
            sent++;
        }
    return sent;
}

/* What the modules wrote last, until each output ends, for `ns` at most: a process a module
 * started that left its process group (setsid) is not killed with it and may hold the output
 * pipe open for ever; it is not waited for (said once per module). */
static void drain_outputs(RTIME ns)
{
    RTIME until = now_ns() + ns;
    for (;;) {
        struct pollfd pfd[2 * MAX_MODULES];
        int idx[2 * MAX_MODULES];
        int n = poll_outputs(pfd, idx, 2 * MAX_MODULES);
        RTIME now = now_ns();
        if (n == 0 || now >= until) break;
        int r = poll(pfd, (nfds_t)n, (int)((until - now) / 1000000) + 1);
        if (r < 0 && errno != EINTR) break;
        for (int k = 0; r > 0 && k < n; k++)
            if (pfd[k].revents) pump(&children[idx[k] / 2], idx[k] % 2);
    }
    for (int i = 0; i < n_children; i++) {
        Child *c = &children[i];
        if (c->out[0].fd < 0 && c->out[1].fd < 0) continue;
        close_output(c, 0);
        close_output(c, 1);
        say("module %s: a process it started still holds its output after it ended (it left the module's process group): not waited for", c->name);
    }
}

/* The waits of a stop: for the supervisors (--stop-first), for the others' KILL, after SIGTERM,
 * after SIGKILL. A stop by a signal under CONTRACT_STOP_BUDGET_MS (the build service's cancel
 * grace: what still runs after it is killed from outside) fits them in that budget, 30 %, 40 %,
 * 20 % and 10 % of it, so that a module that does not answer its KILL is still terminated by the
 * launcher (SIGTERM: it writes its last records, and the launcher says so) before the grace ends. */
typedef struct { RTIME first, kill, term, last; } StopWaits;

static StopWaits stop_waits(void)
{
    if (stop_signalled && stop_budget_ns > 0)
        return (StopWaits){ stop_budget_ns * 3 / 10, stop_budget_ns * 4 / 10, stop_budget_ns / 5, stop_budget_ns / 10 };
    return (StopWaits){ 2000000000LL, 2000000000LL, 1000000000LL, 1000000000LL };
}

static void stop_all(int sfd)
{
    stopping = 1;
    mark_stopping();
    StopWaits w = stop_waits();
    if (send_kills(1) > 0) {
        RTIME until = now_ns() + w.first;
        run_loop(sfd, until, first_ended);
        int waited = now_ns() >= until; /* else the wait ended early (poll failed): said as such */
        for (int i = 0; i < n_children; i++)
            if (children[i].alive && stops_first(children[i].name)) {
                if (waited) say("module %s did not end within %g s: stopping the others", children[i].name, (double)w.first / 1e9);
                else say("module %s has not ended yet: stopping the others (the wait for it could not go on)", children[i].name);
            }
    }
    send_kills(0);
    run_loop(sfd, now_ns() + w.kill, all_ended);
    for (int i = 0; i < n_children; i++)
        if (children[i].alive) {
            say("module %s did not end on its KILL request within %g s: terminating it (SIGTERM)", children[i].name, (double)w.kill / 1e9);
            children[i].signalled = SIGTERM;
            kill(-children[i].pid, SIGTERM);
        }
    run_loop(sfd, now_ns() + w.term, all_ended);
    for (int i = 0; i < n_children; i++)
        if (children[i].alive) { children[i].signalled = SIGKILL; kill(-children[i].pid, SIGKILL); }
    run_loop(sfd, now_ns() + w.last, all_ended);
    for (int i = 0; i < n_children; i++) if (children[i].alive) { children[i].signalled = SIGKILL; kill(-children[i].pid, SIGKILL); }
    /* leftover children of modules (same process group) */
    for (int i = 0; i < n_children; i++) kill(-children[i].pid, SIGKILL);
    drain_outputs(w.last);
}

/* --require-realtime ($CONTRACT_REQUIRE_REALTIME=1): whether a process of this user, here, may take
 * SCHED_FIFO (a child tries it: the launcher's own policy is left as it is). 0 when it may; else
 * the reason said, and the architecture is not started. */
static int check_realtime_permitted(void)
{
    const char *mode = getenv("CONTRACT_SCHED");
    if (mode && strcmp(mode, "other") == 0) {
        say("real-time is required (--require-realtime, %s=1) but CONTRACT_SCHED=other asks the modules for nice levels: nothing started",
            CONTRACT_REQUIRE_REALTIME_ENV);
        return -1;
    }
    pid_t pid = fork();
    if (pid < 0) { say("fork: %s", strerror(errno)); return -1; }
    if (pid == 0) {
        struct sched_param sp = { .sched_priority = 1 };
        _exit(sched_setscheduler(0, SCHED_FIFO, &sp) == 0 ? 0 : errno & 0xff);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return 0;
    int err = WIFEXITED(status) ? WEXITSTATUS(status) : EPERM;
    struct rlimit rl;
    char limit[48] = "";
    if (getrlimit(RLIMIT_RTPRIO, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
        snprintf(limit, sizeof limit, "; RLIMIT_RTPRIO is %llu", (unsigned long long)rl.rlim_cur);
    say("real-time is required (--require-realtime, %s=1) but SCHED_FIFO is not permitted here (%s%s): nothing started. %s",
        CONTRACT_REQUIRE_REALTIME_ENV, strerror(err), limit, CONTRACT_REALTIME_HOWTO);
    return -1;
}

/* The run's end: `deadline` (its duration from the start request), or CONTRACT_END_BY_S after the
 * launch when that comes first: the build service's run time limit counts from the launch, and
 * the modules' inits (up to the ready timeout) come before the start, so that a run asked for the
 * longest duration whose inits were slow still ends on its own, said, instead of at the limit. */
static RTIME end_by_deadline(RTIME deadline, RTIME launched, double duration)
{
    if (end_by_s <= 0 || duration < 0) return deadline; /* a run without a duration runs until stopped */
    RTIME end = launched + (RTIME)(end_by_s * 1e9);
    if (end >= deadline) return deadline;
    RTIME now = now_ns();
    say("the run stops %.1f s before the end of its %g s: its start came %.1f s after the launch (the modules' inits), and it must end %g s after the launch (the run time limit)",
        (double)(deadline - end) / 1e9, duration, (double)(now - launched) / 1e9, end_by_s);
    return end;
}

/* --start 'SUP.function(p=v,...)': 0 when sent (started, or no acknowledgement within 2 s), -1 when it
 * could not be (a bad spec, a supervisor not there) or the supervisor refused it (ACK_NOTDONE). */
static int send_start(const char *spec)
{
    char sup[CONTRACT_NAME_MAX], fn[CONTRACT_FUNCTION_MAX];
    const char *dot = strchr(spec, '.');
    const char *open = strchr(spec, '(');
    if (!dot || (open && open < dot) || (size_t)(dot - spec) >= sizeof sup) {
        say("--start '%s': expected SUP.function(p=v,...)", spec);
        return -1;
    }
    snprintf(sup, sizeof sup, "%.*s", (int)(dot - spec), spec);
    const char *fn_end = open ? open : spec + strlen(spec);
    if ((size_t)(fn_end - dot - 1) >= sizeof fn || fn_end == dot + 1) { say("--start '%s': bad function name", spec); return -1; }
    snprintf(fn, sizeof fn, "%.*s", (int)(fn_end - dot - 1), dot + 1);
    char args[CONTRACT_REQUEST_DATA_MAX];
    args[0] = '\0';
    if (open) {
        const char *close = strrchr(spec, ')');
        if (!close || close < open) { say("--start '%s': missing ')'", spec); return -1; }
        snprintf(args, sizeof args, "%.*s", (int)(close - open - 1), open + 1);
    }
    int rc = SendStartFunction(sup, fn, args, ACK_START | ACK_NOTDONE, 1);
    if (rc != CONTRACT_OK) { say("cannot start %s.%s: %s", sup, fn, ContractStrError(rc)); return -1; }
    RequestMessage *ack = malloc(sizeof *ack);
    if (!ack) return -1;
    int r = WaitForAck(sup, 1, ACK_START | ACK_NOTDONE, GetTime() + 2000000000LL, ack);
    int refused = r == 1 && ack->Param.Ack.Ack == ACK_NOTDONE;
    if (refused) say("%s refused to start %s(%s)", sup, fn, args);
    else if (r == 1) say("started %s.%s(%s)", sup, fn, args);
    else say("sent the start request to %s.%s(%s) (no acknowledgement within 2 s)", sup, fn, args);
    free(ack);
    return refused ? -1 : 0;
}

int main(int argc, char *argv[])
{
    const char *dir_opt = NULL, *log_dir = NULL, *start = NULL;
    const char *cpus = getenv("CONTRACT_CPUS"), *pm_qos = getenv("CONTRACT_PM_QOS_US");
    const char *budget = getenv("CONTRACT_STOP_BUDGET_MS");
    if (budget && *budget) {
        char *end;
        long ms = strtol(budget, &end, 10);
        if (*end || ms < 100 || ms > 60000) say("warning: CONTRACT_STOP_BUDGET_MS=%.20s is not 100..60000 (ms): the stop keeps its own waits", budget);
        else stop_budget_ns = ms * 1000000LL;
    }
    const char *out_limit = getenv("CONTRACT_OUTPUT_LIMIT_BYTES");
    if (out_limit && *out_limit) {
        char *end;
        long long v = strtoll(out_limit, &end, 10);
        if (*end || v < 0) say("warning: CONTRACT_OUTPUT_LIMIT_BYTES=%.20s is not a number of bytes: ignored", out_limit);
        else output_limit = v;
    }
    const char *end_by = getenv("CONTRACT_END_BY_S");
    if (end_by && *end_by) {
        char *end;
        double v = strtod(end_by, &end);
        if (*end || !(v > 0 && v <= 1e6)) say("warning: CONTRACT_END_BY_S=%.20s is not a number of seconds: ignored", end_by);
        else end_by_s = v;
    }
    RTIME launched = now_ns();
    double duration = -1, ready_timeout = 10;
    int require_realtime = rt_realtime_required();
    int check_only = 0; /* --check-realtime: only the real-time check, nothing started */
    int i = 1;
    for (; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--kill") == 0) {
            if (i + 1 >= argc) { usage(); return 2; }
            return kill_mode(argv[i + 1]);
        }
        if (strcmp(a, "--term-why") == 0) {
            if (i + 2 >= argc) { usage(); return 2; }
            return term_why_mode(argv[i + 1], argv[i + 2]);
        }
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) { usage(); return 0; }
        if (strcmp(a, "--require-realtime") == 0) { require_realtime = 1; continue; }
        if (strcmp(a, "--check-realtime") == 0) { check_only = 1; continue; }
        if (a[0] != '-' || strcmp(a, "--") == 0) { if (strcmp(a, "--") == 0) i++; break; }
        if (i + 1 >= argc) { say("option %s needs a value", a); usage(); return 2; }
        const char *v = argv[++i];
        char *end;
        if (strcmp(a, "--run-dir") == 0) dir_opt = v;
        else if (strcmp(a, "--log-dir") == 0) log_dir = v;
        else if (strcmp(a, "--start") == 0) start = v;
        else if (strcmp(a, "--stop-first") == 0) stop_first = v;
        else if (strcmp(a, "--duration") == 0) {
            duration = strtod(v, &end);
            if (*end || duration < 0) { say("--duration '%s': expected a number of seconds", v); return 2; }
        } else if (strcmp(a, "--ready-timeout") == 0) {
            ready_timeout = strtod(v, &end);
            if (*end || ready_timeout <= 0) { say("--ready-timeout '%s': expected a number of seconds", v); return 2; }
        } else if (strcmp(a, "--cpus") == 0) cpus = v;
        else if (strcmp(a, "--pm-qos-us") == 0) pm_qos = v;
        else if (strcmp(a, "--stdin") == 0) {
            const char *eq = strchr(v, '=');
            if (!eq || eq == v || !eq[1]) { say("--stdin '%s': expected NAME=FILE (the module's name, the file it reads on its stdin)", v); return 2; }
            if (n_stdin_files >= MAX_MODULES) { say("--stdin: more than %d given", MAX_MODULES); return 2; }
            stdin_files[n_stdin_files++] = (StdinFile){ v, (size_t)(eq - v), eq + 1, -1 };
        }
        else { say("unknown option %s", a); usage(); return 2; }
    }
    char rt_err[256];
    int pm_qos_us = -1;
    if (cpus && *cpus) {
        if (rt_parse_cpus(cpus, &module_cpus, rt_err, sizeof rt_err) != 0) { say("%s", rt_err); return 2; }
        pin_modules = 1;
    }
    if (pm_qos && *pm_qos && rt_parse_pm_qos_us(pm_qos, &pm_qos_us, rt_err, sizeof rt_err) != 0) { say("%s", rt_err); return 2; }
    if (require_realtime) {
        if (check_realtime_permitted() != 0) return 2;
        setenv(CONTRACT_REQUIRE_REALTIME_ENV, "1", 1); /* each module asks it at its own priority (priority.c) */
    }
    if (check_only) return 0;
    if (i >= argc) { say("no module executable given"); usage(); return 2; }
    if (argc - i > MAX_MODULES) { say("too many modules: %d module executables given, at most %d (ORD and the supervisors count)", argc - i, MAX_MODULES); return 2; }
    for (int k = i; k < argc; k++) {
        if (access(argv[k], X_OK) != 0) { say("%s: %s", argv[k], strerror(errno)); return 2; }
    }
    if (open_stdin_files(argv + i, argc - i) != 0) return 2;

    if (dir_opt && *dir_opt) {
        if (mkdir_p(dir_opt) != 0 || realpath(dir_opt, run_dir) == NULL) { say("run directory %s: %s", dir_opt, strerror(errno)); return 2; }
    } else {
        const char *tmp = getenv("TMPDIR");
        snprintf(run_dir, sizeof run_dir, "%s/contract-run-XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (!mkdtemp(run_dir)) { say("cannot create a run directory: %s", strerror(errno)); return 2; }
    }
    char lp_path[PATH_MAX + 32];
    snprintf(lp_path, sizeof lp_path, "%s/launcher.pid", run_dir);
    long other = read_pid_file(lp_path);
    if (other > 0 && other != getpid() && kill((pid_t)other, 0) == 0) {
        say("an architecture already runs in %s (launcher pid %ld); stop it with contract-launch --kill %s", run_dir, other, run_dir);
        return 2;
    }
    FILE *lp = fopen(lp_path, "w");
    if (!lp) { say("cannot write %s: %s", lp_path, strerror(errno)); return 2; }
    fprintf(lp, "%ld\n", (long)getpid());
    fclose(lp);
    setenv("CONTRACT_RUN_DIR", run_dir, 1);
    { /* the modules leave a stop signal another process sends them to the launcher (core.c) */
        char pid_text[24];
        snprintf(pid_text, sizeof pid_text, "%ld", (long)getpid());
        setenv(CONTRACT_LAUNCHER_PID_ENV, pid_text, 1);
    }
    { /* a launcher that died while stopping left its mark: this run is not stopping */
        char stale[PATH_MAX + 32];
        if (stopping_file(stale, sizeof stale)) unlink(stale);
    }
    if (log_dir && *log_dir) {
        if (mkdir_p(log_dir) != 0) { say("log directory %s: %s", log_dir, strerror(errno)); unlink(lp_path); return 2; }
        setenv("CONTRACT_LOG_DIR", log_dir, 1);
        open_own_lines(log_dir);
    }
    setvbuf(stdout, NULL, _IOLBF, 0);
    say("run directory %s", run_dir);
    if (pin_modules) say("modules pinned to CPUs %s", cpus);
    int pm_qos_fd = -1; /* held open until the launcher exits */
    if (pm_qos_us >= 0) {
        pm_qos_fd = rt_hold_pm_qos(pm_qos_us, rt_err, sizeof rt_err);
        if (pm_qos_fd < 0) say("%s", rt_err);
        else say("CPU wake-up latency held at %d us (PM QoS) while the architecture runs", pm_qos_us);
    }

    sigset_t mask, oldmask;
    sigemptyset(&mask);
    sigaddset(&mask, SIGINT);
    sigaddset(&mask, SIGTERM);
    sigaddset(&mask, SIGHUP);
    sigaddset(&mask, SIGCHLD);
    sigprocmask(SIG_BLOCK, &mask, &oldmask);
    signal(SIGPIPE, SIG_IGN);
    int sfd = signalfd(-1, &mask, SFD_CLOEXEC | SFD_NONBLOCK);
    if (sfd < 0) { say("signalfd: %s", strerror(errno)); return 2; }
    if (ContractClientInit("contract-launch") != 0) { unlink(lp_path); return 2; }
    /* its START and KILL requests never wait on a full mailbox: a module that does not read its
     * mailbox (a looping region) would hold the whole stop 2 s per request; such a module is
     * terminated after the stop's wait instead, as one that does not answer its KILL */
    ContractSetNonBlockingSends(1);

    for (int k = i; k < argc; k++) {
        Child *c = &children[n_children++];
        memset(c, 0, sizeof *c);
        c->exe = argv[k];
        c->out[0].fd = c->out[1].fd = -1;
        derive_name(c);
        remove_old_crash_file(c);
        c->stdin_fd = stdin_file_of(c->name);
        if (spawn(c, &oldmask) != 0) { n_children--; stop_all(sfd); clean_run_dir(run_dir); return 2; }
    }
    /* A run may start at SCHED_FIFO (the build service's real-time mode, docs/sandbox.md "Real-time
     * mode"): the modules have it from us now; the launcher only forwards their output, and runs
     * SCHED_OTHER as it does on the host, never above the architecture. */
    if ((sched_getscheduler(0) & ~SCHED_RESET_ON_FORK) == SCHED_FIFO) {
        struct sched_param other = {0};
        if (sched_setscheduler(0, SCHED_OTHER, &other) != 0) say("could not leave SCHED_FIFO: %s", strerror(errno));
    }
    int stop = run_loop(sfd, now_ns() + (RTIME)(ready_timeout * 1e9), all_ready);
    int not_ready = 0;
    /* a module is ready once it looks for its first request (libmodule writes <NAME>.ready then):
     * its init region has returned. One that is not, after the ready timeout, loops or blocks in
     * it: the architecture would never start, so the run stops here, its start not sent. */
    for (int k = 0; k < n_children && !stop; k++) /* (a stop signal during the wait: no module is late) */
        if (children[k].alive && !children[k].ready) {
            not_ready++;
            say("module %s is not ready after %g s: its init has not returned (does its init region loop or block?); the run stops without its start request",
                children[k].name, ready_timeout);
        }
    if (not_ready) { stop = 1; snprintf(stop_cause, sizeof stop_cause, "%d module(s) not ready", not_ready); }
    /* required real time: a module refused SCHED_FIFO at its priority ended (it said why): the
     * architecture would run without it */
    for (int k = 0; k < n_children && !stop && require_realtime; k++)
        if (children[k].failed) {
            say("module %s ended before the start, and real-time is required: the architecture does not run without it; the run stops without its start request",
                children[k].name);
            stop = 1;
            snprintf(stop_cause, sizeof stop_cause, "module %s ended before the start, and real-time is required", children[k].name);
        }
    if (!stop) say("%d module(s) running", alive_count());
    int start_failed = !stop && start && *start && send_start(start) != 0;
    if (!stop) {
        RTIME deadline = duration >= 0 ? now_ns() + (RTIME)(duration * 1e9) : INT64_MAX;
        RTIME end = end_by_deadline(deadline, launched, duration);
        if (!run_loop(sfd, end, all_ended)) {
            if (alive_count() == 0) snprintf(stop_cause, sizeof stop_cause, "every module has ended");
            else if (end < deadline) snprintf(stop_cause, sizeof stop_cause, "the run time limit (CONTRACT_END_BY_S=%g s after the launch)", end_by_s);
            else snprintf(stop_cause, sizeof stop_cause, "the run's duration (%g s) is over", duration);
        }
    }
    /* the build service's reason when it gave one, else what stopped the run (a signal: who sent it) */
    if (stop_why) say("stopping: %s", stop_why);
    else if (stop_cause[0]) say("stopping: %s", stop_cause);
    else say("stopping");
    stop_all(sfd);
    ContractShutdown();
    int failed = 0;
    for (int k = 0; k < n_children; k++) {
        if (!children[k].failed) continue;
        failed++;
        /* what ended it, in the words of its end line above: a SIGKILL is no crash of its code, said
         * apart with who sends one (with a limit, the `stopping: ...` line says which); an exit with
         * a status is no crash either (its init refused to start, its code called exit(3)) */
        if (children[k].killed)
            say("FAILED: module %s was killed (a SIGKILL the launcher did not send: %s)", children[k].name, sigkill_senders());
        else if (children[k].end_signal)
            say("FAILED: module %s died by signal %d (%s)", children[k].name, children[k].end_signal, strsignal(children[k].end_signal));
        else
            say("FAILED: module %s exited with status %d", children[k].name, children[k].end_status);
    }
    /* "cleanly" only when every module ended on its KILL request: one the launcher had to terminate
     * (it did not answer) is named again, after the lines of the others' last output */
    char terminated[256] = "";
    size_t used = 0;
    for (int k = 0; k < n_children; k++)
        if (children[k].signalled && !children[k].failed && used < sizeof terminated)
            used += (size_t)snprintf(terminated + used, sizeof terminated - used, "%s%s", used ? ", " : "", children[k].name);
    if (failed) say("all modules stopped");
    else if (terminated[0]) say("all modules stopped (terminated at the stop: %s)", terminated);
    else say("all modules stopped cleanly");
    if (pm_qos_fd >= 0) close(pm_qos_fd);
    clean_run_dir(run_dir); /* removes launcher.pid last: `--kill` waits for that */
    return failed ? 1 : start_failed ? EXIT_START_REFUSED : 0;
}
