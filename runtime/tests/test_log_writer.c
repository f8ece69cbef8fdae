/* The CSV log's writer thread (csvlog.c): a module never waits in write(). The runner is linked
 * with -Wl,--wrap=write: a write from any thread but the test's own can be made slow, as a disk
 * stall makes it; and with -Wl,--wrap=pthread_create: a thread can be refused, as the process
 * limit refuses it. In process, on the tester's own log. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/statvfs.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "harness.h"
#include "internal.h"
#include "log_mark.h"

ssize_t __real_write(int fd, const void *buf, size_t len);
ssize_t __wrap_write(int fd, const void *buf, size_t len);
int __real_pthread_create(pthread_t *thread, const pthread_attr_t *attr, void *(*start)(void *), void *arg);
int __wrap_pthread_create(pthread_t *thread, const pthread_attr_t *attr, void *(*start)(void *), void *arg);

/* While set, pthread_create fails with EAGAIN, as at the process limit (RLIMIT_NPROC, the pids cgroup). */
static int threads_refused;

int __wrap_pthread_create(pthread_t *thread, const pthread_attr_t *attr, void *(*start)(void *), void *arg)
{
    if (__atomic_load_n(&threads_refused, __ATOMIC_ACQUIRE)) return EAGAIN;
    return __real_pthread_create(thread, attr, start, arg);
}

/* A disk with this many bytes free (>= 0) as fstatvfs tells it; -1: the real answer. */
static long long disk_free = -1;
static int disk_looks; /* fstatvfs calls while disk_free is set */
/* A disk that fills as the log writes: while not 0, each byte written to a file takes this many
 * (counted in disk_filled) from disk_free (1: the log alone on it; k: k logs writing as much at once). */
static long long disk_fill_per_byte;
static long long disk_filled;

static long long write_delay_ns; /* 0: writes as they are */
static pthread_t test_thread;
static int writes_stalling; /* writes made slow so far (a test waits for its writer to be in one) */

/* A full disk: while armed (>= 0), writes to a file (fd > 2) take at most this many more bytes,
 * then fail with ENOSPC. */
static long long write_room = -1;

ssize_t __wrap_write(int fd, const void *buf, size_t len)
{
    long long room = __atomic_load_n(&write_room, __ATOMIC_ACQUIRE);
    if (room >= 0 && fd > 2) {
        if (room == 0) {
            errno = ENOSPC;
            return -1;
        }
        size_t n = len < (size_t)room ? len : (size_t)room;
        ssize_t w = __real_write(fd, buf, n);
        if (w > 0) __atomic_store_n(&write_room, room - w, __ATOMIC_RELEASE);
        return w;
    }
    long long d = __atomic_load_n(&write_delay_ns, __ATOMIC_ACQUIRE);
    if (d > 0 && !pthread_equal(pthread_self(), test_thread)) {
        struct timespec ts = { (time_t)(d / 1000000000LL), (long)(d % 1000000000LL) };
        __atomic_add_fetch(&writes_stalling, 1, __ATOMIC_ACQ_REL);
        nanosleep(&ts, NULL);
    }
    ssize_t w = __real_write(fd, buf, len);
    long long fill = __atomic_load_n(&disk_fill_per_byte, __ATOMIC_ACQUIRE);
    if (fill && w > 0 && fd > 2) __atomic_add_fetch(&disk_filled, fill * (long long)w, __ATOMIC_ACQ_REL);
    return w;
}

int __real_fstatvfs(int fd, struct statvfs *s);
int __wrap_fstatvfs(int fd, struct statvfs *s);

int __wrap_fstatvfs(int fd, struct statvfs *s)
{
    int r = __real_fstatvfs(fd, s);
    long long f = __atomic_load_n(&disk_free, __ATOMIC_ACQUIRE);
    if (r == 0 && f >= 0) {
        f -= __atomic_load_n(&disk_filled, __ATOMIC_ACQUIRE);
        if (f < 0) f = 0;
        s->f_frsize = 4096;
        s->f_bavail = (fsblkcnt_t)(f / 4096);
        __atomic_add_fetch(&disk_looks, 1, __ATOMIC_ACQ_REL);
    }
    return r;
}

static void slow_writes(long long ns)
{
    test_thread = pthread_self();
    __atomic_store_n(&writes_stalling, 0, __ATOMIC_RELEASE);
    __atomic_store_n(&write_delay_ns, ns, __ATOMIC_RELEASE);
}

/* Waits (up to 2 s) until the writer thread took the buffer handed to it and stalls in its slow
 * write: on a loaded machine the writer may not run for a while, and a crash handler or the
 * recovery would then find the buffer not begun, which is another case. 1 once it does. */
static int wait_writer_stalled(void)
{
    for (int w = 0; w < 1000 && __atomic_load_n(&writes_stalling, __ATOMIC_ACQUIRE) == 0; w++) usleep(2000);
    return __atomic_load_n(&writes_stalling, __ATOMIC_ACQUIRE) > 0;
}

static unsigned long long mark_word(int fd)
{
    unsigned long long w = 7;
    if (pread(fd, &w, sizeof w, 0) != (ssize_t)sizeof w) return 7;
    return w;
}

/* Records handed off while the writer is stalled in write(): the module goes on at once, the mark
 * keeps naming the oldest record not in the file, the next hand-off waits for the next boundary
 * instead of spinning, and after the stall every record is in the file, in order, once. */
void test_csv_log_writer_thread(void)
{
    REQUIRE(h_setup("logwriter") == 0);
    setenv("CONTRACT_LOG_MARK", "1", 1);
    REQUIRE(rt_log_open() == 0);
    unsetenv("CONTRACT_LOG_MARK");
    char csv[1024], mark[1024];
    REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
    REQUIRE(h_find_log_file("tester_", ".csv.mark", mark, sizeof mark));
    int fd = open(mark, O_RDONLY | O_CLOEXEC);
    REQUIRE(fd >= 0);

    const long long stall = 300000000LL; /* 300 ms in write() */
    slow_writes(stall);
    char detail[32];
    for (int i = 0; i < 100; i++) {
        snprintf(detail, sizeof detail, "first %d", i);
        ContractLog("test_record", "", -1, 0, detail);
    }
    RTIME first = ContractLogPendingSince();
    REQUIRE(first > 0);
    CHECK(mark_word(fd) == (unsigned long long)first);
    RTIME t0 = GetTime();
    CHECK(rt_log_hand_off(0) == 1);
    RTIME handed = GetTime() - t0;
    CHECK_MSG(handed < 50000000LL, "the module waited %lld ms for a stalled write", (long long)(handed / 1000000));
    CHECK(ContractLogPendingSince() == 0);
    CHECK_MSG(mark_word(fd) == (unsigned long long)first, "the mark says %llu while the first records are not written", mark_word(fd));

    /* the module logs on; its next hand-off finds the writer busy: no wait, tried again later */
    for (int i = 0; i < 50; i++) {
        snprintf(detail, sizeof detail, "second %d", i);
        ContractLog("test_record", "", -1, 0, detail);
    }
    RTIME second = ContractLogPendingSince();
    CHECK(second > first);
    CHECK_MSG(mark_word(fd) == (unsigned long long)first, "the mark moved to a younger record while older ones wait");
    const RTIME delay = 10000000LL;
    t0 = GetTime();
    ContractLogFlushIfDue(GetTime() + 10 * delay, delay);
    CHECK_MSG(GetTime() - t0 < 50000000LL, "a due hand-off waited for the stalled writer");
    CHECK_MSG(ContractLogPendingSince() == second, "the records were taken while the writer was busy");
    RTIME due = ContractLogFlushDue(delay);
    RTIME now = GetTime();
    CHECK_MSG(due > now && due - now <= delay, "due %lld ns from now while the writer is busy: a waiting module would spin",
              (long long)(due - now));

    /* ContractLogFlush waits for both buffers; nothing is lost, nothing doubled, order kept */
    t0 = GetTime();
    ContractLogFlush();
    CHECK_MSG(GetTime() - t0 >= stall / 2, "ContractLogFlush returned before the stalled write ended");
    CHECK(mark_word(fd) == 0);
    slow_writes(0);
    char *log = h_read_file(csv);
    REQUIRE(log);
    const char *at = log;
    for (int i = 0; i < 150; i++) {
        char want[40];
        snprintf(want, sizeof want, ",%s %d\n", i < 100 ? "first" : "second", i < 100 ? i : i - 100);
        const char *found = strstr(at, want);
        CHECK_MSG(found != NULL, "record %s missing or out of order", want);
        if (!found) break;
        CHECK_MSG(strstr(found + 1, want) == NULL, "record %s written twice", want);
        at = found + strlen(want) - 1;
    }
    free(log);
    rt_log_close();
    close(fd);
    h_teardown();
}

/* A log writer thread the process limit refuses (EAGAIN): the module's warning names that limit as
 * the likely cause (it said only "Resource temporarily unavailable"), and the module writes its
 * log itself, every record kept. */
void test_csv_log_writer_refused(void)
{
    REQUIRE(h_setup("logrefused") == 0);
    char said[1024];
    int saved = h_stderr_to_file(said, sizeof said);
    REQUIRE(saved >= 0);
    __atomic_store_n(&threads_refused, 1, __ATOMIC_RELEASE);
    int opened = rt_log_open();
    __atomic_store_n(&threads_refused, 0, __ATOMIC_RELEASE);
    h_stderr_back(saved);
    REQUIRE(opened == 0);
    char *text = h_read_file(said);
    REQUIRE(text);
    CHECK_MSG(strstr(text, "warning: no log writer thread (Resource temporarily unavailable: a new thread was refused, most likely by the process limit, "
                           "which counts threads: 2 per module; a build service run raises it with --limit processes=N): the module writes its log itself\n") != NULL,
              "the warning does not name the process limit: %s", text);
    free(text);
    ContractLog("test_record", "", -1, 0, "written without the thread");
    ContractLogFlush();
    char csv[1024];
    REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
    char *log = h_read_file(csv);
    REQUIRE(log);
    CHECK(strstr(log, ",written without the thread\n") != NULL);
    free(log);
    rt_log_close();
    h_teardown();
}

/* A child forked by module code does not write the parent's records (nor its own) to the
 * parent's log, and its exit does not wait for a writer thread it does not have. */
void test_csv_log_fork_child(void)
{
    REQUIRE(h_setup("logfork") == 0);
    REQUIRE(rt_log_open() == 0);
    char csv[1024];
    REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
    ContractLog("test_record", "", -1, 0, "before fork");
    pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        ContractLog("test_record", "", -1, 0, "in the child");
        ContractLogFlush();
        rt_log_close();
        _exit(0);
    }
    int status = 0;
    RTIME t0 = GetTime();
    int exited = 0;
    while (!exited && GetTime() - t0 < 5000000000LL) {
        if (waitpid(pid, &status, WNOHANG) == pid) exited = 1;
        else usleep(5000);
    }
    if (!exited) {
        kill(pid, SIGKILL);
        waitpid(pid, &status, 0);
    }
    CHECK_MSG(exited && WIFEXITED(status) && WEXITSTATUS(status) == 0, "the forked child did not end by itself");
    ContractLog("test_record", "", -1, 0, "after fork");
    rt_log_close();
    char *log = h_read_file(csv);
    REQUIRE(log);
    const char *b = strstr(log, ",before fork\n");
    CHECK(b != NULL);
    CHECK_MSG(b && strstr(b + 1, ",before fork\n") == NULL, "the parent's record was written twice");
    CHECK_MSG(strstr(log, "in the child") == NULL, "the child wrote to the parent's log");
    CHECK(strstr(log, ",after fork\n") != NULL);
    free(log);
    h_teardown();
}

/* A store through a null pointer (not UBSan's to report in the sanitizer build: the crash is the point). */
__attribute__((no_sanitize("undefined"))) static void null_store(void)
{
    volatile int *volatile p = 0;
    *p = 1;
}

/* A crash while the writer thread still writes the buffer handed to it: the crash handler waits
 * for that write (up to 100 ms), then writes the records of the buffer being filled after it, in
 * order, and a `module_crashed` record; a writer stalled longer does not hold the dying process:
 * the handler writes anyway, and the crash record's `records=K` counts what the file lacks. In a
 * forked child (the crash ends it), on the tester's own log. */
void test_csv_log_crash_writer_busy(void)
{
    static const long long stalls[] = { 60000000LL, 2000000000LL }; /* within the wait, and beyond it */
    for (int s = 0; s < 2; s++) {
        REQUIRE(h_setup("logcrashbusy") == 0);
        RTIME t0 = GetTime();
        pid_t pid = fork();
        REQUIRE(pid >= 0);
        if (pid == 0) {
            rt_install_signal_cleanup();
            if (rt_log_open() != 0) _exit(3);
            slow_writes(stalls[s]);
            char detail[32];
            for (int i = 0; i < 100; i++) {
                snprintf(detail, sizeof detail, "first %d", i);
                ContractLog("test_record", "", -1, 0, detail);
            }
            if (rt_log_hand_off(0) != 1) _exit(4);
            if (!wait_writer_stalled()) _exit(6);
            for (int i = 0; i < 50; i++) {
                snprintf(detail, sizeof detail, "second %d", i);
                ContractLog("test_record", "", -1, 0, detail);
            }
            null_store();
            _exit(5);
        }
        int status = 0, ended = 0;
        while (!ended && GetTime() - t0 < 5000000000LL) {
            if (waitpid(pid, &status, WNOHANG) == pid) ended = 1;
            else usleep(5000);
        }
        if (!ended) {
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
        }
        RTIME took = GetTime() - t0;
        int as_crash = h_asan_reports(SIGSEGV) ? WIFEXITED(status) && WEXITSTATUS(status) == 1 : WIFSIGNALED(status) && WTERMSIG(status) == SIGSEGV;
        CHECK_MSG(ended && as_crash, "stall %d: the child did not end as a SIGSEGV's crash (status %#x)", s, status);
        if (s == 0) CHECK_MSG(took >= stalls[0], "the child died after %lld ms: before its writer's write ended", (long long)(took / 1000000));
        /* under ASan its report (symbolized) comes after the log's records: its time is not the writer's */
        if (s == 1) CHECK_MSG(took < (h_asan_reports(SIGSEGV) ? 3000000000LL : 1000000000LL), "a stalled writer held the dying process %lld ms", (long long)(took / 1000000));
        char csv[1024];
        REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
        char *log = h_read_file(csv);
        REQUIRE(log);
        const char *at = log;
        for (int i = s == 0 ? 0 : 100; i < 150; i++) {
            char want[40];
            snprintf(want, sizeof want, ",%s %d\n", i < 100 ? "first" : "second", i < 100 ? i : i - 100);
            const char *found = strstr(at, want);
            CHECK_MSG(found != NULL, "stall %d: record %s missing or out of order", s, want);
            if (!found) break;
            CHECK_MSG(strstr(found + 1, want) == NULL, "stall %d: record %s written twice", s, want);
            at = found + strlen(want);
        }
        /* then the crash record, last, counting the 150 records and itself */
        const char *crash = strstr(at, ",tester,module_crashed,,,0,signal 11 (SIGSEGV) records=151\n");
        CHECK_MSG(crash != NULL && crash[strlen(",tester,module_crashed,,,0,signal 11 (SIGSEGV) records=151\n")] == '\0',
                  "stall %d: no crash record at the end: '%s'", s, at);
        if (s == 1) CHECK_MSG(strstr(log, ",first 0\n") == NULL, "the stalled writer's records are in the file after all");
        free(log);
        h_teardown();
    }
}

/* A record whose fields are at their bounds and made of characters the CSV must quote (every one
 * doubled) fits the record's room: the log's buffer and the crash handler's record buffer are never
 * overrun (ASan), and each record reads back whole. A detail longer than its bound is cut there, and
 * says so (`…`, never inside a UTF-8 character); a name longer than its bound is cut too. */
void test_csv_log_record_bounds(void)
{
    REQUIRE(h_setup("logbounds") == 0);
    REQUIRE(rt_log_open() == 0);
    char csv[1024];
    REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
    char event[65], peer[65], detail[401];
    memset(event, '"', 64); event[64] = '\0';
    memset(peer, '"', 64); peer[64] = '\0';
    memset(detail, '"', 400); detail[400] = '\0';
    /* records of many sizes, so that one starts anywhere near a 64 KiB buffer's end */
    for (int i = 0; i < 4000; i++) ContractLog(event, peer, 7, 9, detail + (i % 97));
    /* 500 bytes: cut to 400 with the mark that says so (397 bytes of text, then the 3-byte mark);
     * a 3-byte character across the cut is not split */
    char longer[501];
    memset(longer, 'x', 500); longer[500] = '\0';
    memcpy(longer + 396, "\xe2\x82\xac", 3); /* a euro sign on bytes 396..398 */
    ContractLog("long_detail", "", -1, 0, longer);
    char plain[501];
    memset(plain, 'z', 500); plain[500] = '\0';
    ContractLog("plain_long_detail", "", -1, 0, plain);
    char exact[401];
    memset(exact, 'y', 400); exact[400] = '\0';
    ContractLog("exact_detail", "", -1, 0, exact);
    char name[80];
    memset(name, 'n', 79); name[79] = '\0';
    ContractLog(name, "", -1, 0, "long name");
    ContractLogFlush();
    char *log = h_read_file(csv);
    REQUIRE(log);
    int whole = 0;
    for (const char *l = strstr(log, "\n") + 1; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
        if (strncmp(strchr(strchr(strchr(l, ',') + 1, ',') + 1, ',') + 1, "\"\"\"", 3) != 0) continue;
        const char *end = strchr(l, '\n');
        CHECK_MSG(end && (size_t)(end - l) > 2 * 304 + 2 * 64 * 2, "a quoted record was cut: %.80s", l);
        whole++;
    }
    CHECK_MSG(whole == 4000, "%d of 4000 quoted records read back", whole);
    char want[500];
    memset(want, 'x', 396);
    memcpy(want + 396, "\xe2\x80\xa6\n", 5); /* 396 x, then … (the euro sign would not fit whole) */
    const char *cut = strstr(log, ",long_detail,,,0,");
    CHECK(cut && strncmp(cut + strlen(",long_detail,,,0,"), want, 396 + 4) == 0);
    memset(want, 'z', 397);
    memcpy(want + 397, "\xe2\x80\xa6\n", 5); /* 397 z, then …: 400 bytes, the mark included */
    const char *plain_cut = strstr(log, ",plain_long_detail,,,0,");
    CHECK(plain_cut && strncmp(plain_cut + strlen(",plain_long_detail,,,0,"), want, 397 + 4) == 0);
    const char *ex = strstr(log, ",exact_detail,,,0,");
    CHECK(ex && strncmp(ex + strlen(",exact_detail,,,0,"), exact, 400) == 0 && ex[strlen(",exact_detail,,,0,") + 400] == '\n');
    memset(want, 'n', 64);
    memcpy(want + 64, ",,,0,long name\n", 16);
    CHECK(strstr(log, want) != NULL);
    free(log);
    rt_log_close();
    h_teardown();
}

/* An event name that is no word (`9bad`: the readers take its line as unreadable) is written as
 * given, nothing lost, and said on stderr at run time (once however often it is logged), not first
 * by the trace's reader. */
void test_csv_log_event_not_a_word(void)
{
    REQUIRE(h_setup("lognoword") == 0);
    REQUIRE(rt_log_open() == 0);
    char said[1024];
    int saved = h_stderr_to_file(said, sizeof said);
    REQUIRE(saved >= 0);
    ContractLog("fine_name.v2-b", "", -1, 0, "a word");
    for (int i = 0; i < 3; i++) ContractLog("9bad", "", -1, 0, "bad name");
    ContractLog("has space", "", -1, 0, "bad too");
    h_stderr_back(saved);
    ContractLogFlush();
    char *err = h_read_file(said);
    REQUIRE(err);
    const char *first = strstr(err, "warning: ContractLog: the event name '9bad' is no word");
    CHECK_MSG(first != NULL && strchr(first, '\n') && strstr(strchr(first, '\n'), "'9bad'") == NULL, "said once: %s", err);
    CHECK_MSG(strstr(err, "the event name 'has space' is no word") != NULL, "stderr: %s", err);
    CHECK_MSG(strstr(err, "fine_name") == NULL, "a word is not said: %s", err);
    free(err);
    char csv[1024];
    REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
    char *log = h_read_file(csv);
    REQUIRE(log);
    CHECK(strstr(log, ",9bad,,,0,bad name\n") != NULL && strstr(log, ",has space,,,0,bad too\n") != NULL);
    free(log);
    rt_log_close();
    h_teardown();
}

/* A full disk (a write that takes part of a record, then ENOSPC): the log ends at its last whole
 * record (the part written is cut off again), later records are only counted, even once the disk
 * has room again (a gap in the file would read as whole), said once on stderr, and the last
 * log-capped record at the close says how many were not written and why. */
void test_csv_log_disk_full(void)
{
    REQUIRE(h_setup("logfull") == 0);
    REQUIRE(rt_log_open() == 0);
    char csv[1024], err_path[700];
    REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
    int saved = h_stderr_to_file(err_path, sizeof err_path);
    REQUIRE(saved >= 0);
    for (int i = 0; i < 5; i++) ContractLog("before", "", -1, 0, "room");
    ContractLogFlush();
    __atomic_store_n(&write_room, 150, __ATOMIC_RELEASE); /* the disk fills inside the second record */
    for (int i = 0; i < 100; i++) ContractLog("during", "", i, 0, "the disk fills");
    ContractLogFlush();
    __atomic_store_n(&write_room, -1, __ATOMIC_RELEASE); /* room again: the log stays stopped */
    for (int i = 0; i < 10; i++) ContractLog("after", "", -1, 0, "room again");
    ContractLogFlush();
    rt_log_close();
    h_stderr_back(saved);
    char *log = h_read_file(csv), *err = h_read_file(err_path);
    REQUIRE(log);
    int lines = 0, during = 0, cut = 0;
    for (const char *l = log; *l;) {
        const char *end = strchr(l, '\n');
        if (!end) { cut = 1; break; }
        int commas = 0;
        for (const char *c = l; c < end; c++) commas += *c == ',';
        if (commas < 7) cut = 1;
        lines++;
        if (strstr(l, ",during,") && strstr(l, ",during,") < end) during++;
        l = end + 1;
    }
    CHECK_MSG(!cut, "the log holds a cut line:\n%s", log);
    CHECK_MSG(during == 1 && !strstr(log, ",after,"), "records written after the disk filled: %d during (expected the 1 whole in 150 bytes), after: %s",
              during, strstr(log, ",after,") ? "yes" : "no");
    const char *last = strstr(log, ",log-capped,");
    CHECK_MSG(last && strstr(last, "109 records not written after the log could not be written past ") &&
                  strstr(last, " bytes (No space left on device)\n"),
              "the last records: %s", last ? last : "(no log-capped record)");
    CHECK_MSG(err && strstr(err, "tester: warning: CSV log ") &&
                  strstr(err, "bytes (No space left on device); it ends at its last whole record, later records are not written") &&
                  !strstr(strstr(err, "warning: CSV log") + 1, "warning: CSV log"),
              "stderr: %s", err ? err : "(none)");
    (void)lines;
    free(log);
    free(err);
    h_teardown();
}

/* The logs' disk reserve (CONTRACT_LOG_DISK_RESERVE_BYTES): a log whose disk has less free than
 * the reserve stops as at its bound — whole records, a log-capped record saying why, later records
 * only counted, the count at the close — looked at once per 64 KiB written, not per record; ORD's
 * log (and a supervisor's) keeps going down to a quarter of it. Several logs growing together
 * filled the work dir before any reached its own bound, and the disk limit killed the run. */
static void reserve_run(int engine, long long free_then, int *looks, char *err_out, size_t err_size, char **log_out)
{
    *log_out = NULL;
    REQUIRE(h_setup(engine ? "logreserve-ord" : "logreserve") == 0);
    setenv("CONTRACT_LOG_DISK_RESERVE_BYTES", "1000000", 1);
    int r = rt_log_open();
    unsetenv("CONTRACT_LOG_DISK_RESERVE_BYTES");
    REQUIRE(r == 0);
    g_rt.engine = engine;
    char csv[1024], err_path[700];
    REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
    int saved = h_stderr_to_file(err_path, sizeof err_path);
    REQUIRE(saved >= 0);
    __atomic_store_n(&disk_looks, 0, __ATOMIC_RELEASE);
    __atomic_store_n(&disk_free, 4000000, __ATOMIC_RELEASE); /* room: written */
    for (int i = 0; i < 2000; i++) ContractLog("before", "", i, 0, "the disk has room");
    ContractLogFlush();
    __atomic_store_n(&disk_free, free_then, __ATOMIC_RELEASE);
    for (int i = 0; i < 2000; i++) ContractLog("during", "", i, 0, "the disk has less than the reserve");
    ContractLogFlush();
    *looks = __atomic_load_n(&disk_looks, __ATOMIC_ACQUIRE);
    rt_log_close();
    __atomic_store_n(&disk_free, -1, __ATOMIC_RELEASE);
    g_rt.engine = RT_ENGINE_NONE;
    h_stderr_back(saved);
    char *err = h_read_file(err_path);
    snprintf(err_out, err_size, "%s", err ? err : "");
    free(err);
    *log_out = h_read_file(csv);
    h_teardown();
}

void test_csv_log_disk_reserve(void)
{
    int looks = 0;
    char err[2048];
    /* a module: 600,000 bytes free is below its 1,000,000-byte reserve */
    char *log;
    reserve_run(RT_ENGINE_NONE, 600000, &looks, err, sizeof err, &log);
    REQUIRE(log);
    int before = 0, during = 0, cut = 0;
    for (const char *l = log; *l;) {
        const char *end = strchr(l, '\n');
        if (!end) { cut = 1; break; }
        const char *b = strstr(l, ",before,"), *d = strstr(l, ",during,");
        before += b && b < end;
        during += d && d < end;
        l = end + 1;
    }
    CHECK_MSG(!cut, "the log holds a cut line");
    CHECK_MSG(before == 2000, "%d records written while the disk had room, expected 2000", before);
    /* at most 64 KiB and one buffer past the moment the disk went below the reserve */
    CHECK_MSG(during < 2000, "every record was written below the reserve (%d)", during);
    /* one look per 64 KiB written: a few for 300 KB, not one per record */
    CHECK_MSG(looks >= 1 && looks <= 8, "%d looks at the free space for about 150 KB written below the reserve", looks);
    const char *cap = strstr(log, ",log-capped,");
    const char *cap_end = cap ? strchr(cap, '\n') : NULL;
    const char *why = cap ? strstr(cap, "bytes: its disk had 598016 bytes free; less than the logs' 1000000-byte reserve (CONTRACT_LOG_DISK_RESERVE_BYTES) and the ") : NULL;
    CHECK_MSG(why && why < cap_end && strstr(why, " bytes to write: later records are not written\n") < cap_end, "the cap record: %s", cap ? cap : "(none)");
    char want[128];
    snprintf(want, sizeof want, "%d records not written after the log stopped at ", 2000 - during);
    const char *last = cap ? strstr(cap + 1, ",log-capped,") : NULL;
    CHECK_MSG(last && strstr(last, want) && strstr(last, " bytes (its disk below the logs' 1000000-byte reserve)\n"), "the last records: %s", cap ? cap : "(none)");
    CHECK_MSG(strstr(err, "tester: warning: CSV log ") && strstr(err, "less than the logs' 1000000-byte reserve (CONTRACT_LOG_DISK_RESERVE_BYTES) and the ") &&
                  strstr(err, " bytes to write; later records are not written"),
              "stderr: %s", err);
    free(log);
    /* ORD (and a supervisor) keep going down to a quarter of it: 600,000 bytes free is room */
    reserve_run(RT_ENGINE_ORD, 600000, &looks, err, sizeof err, &log);
    REQUIRE(log);
    during = 0;
    for (const char *d = log; (d = strstr(d, ",during,")) != NULL; d++) during++;
    CHECK_MSG(during == 2000 && !strstr(log, ",log-capped,"), "ORD's log: %d records written at 600000 bytes free, %s", during,
              strstr(log, ",log-capped,") ? "capped" : "not capped");
    free(log);
    reserve_run(RT_ENGINE_ORD, 200000, &looks, err, sizeof err, &log);
    REQUIRE(log);
    cap = strstr(log, ",log-capped,");
    CHECK_MSG(cap && strstr(cap, "bytes free; less than the logs' 250000-byte reserve (CONTRACT_LOG_ENGINE_DISK_RESERVE_BYTES)"), "ORD's cap record at 200000 bytes free: %s", cap ? cap : "(none)");
    free(log);
    /* a supervisor (rule changes, its end) keeps going below ORD's, down to an eighth of it */
    reserve_run(RT_ENGINE_SUPERVISOR, 200000, &looks, err, sizeof err, &log);
    REQUIRE(log);
    CHECK_MSG(!strstr(log, ",log-capped,"), "the supervisor's log was capped at 200000 bytes free");
    free(log);
    reserve_run(RT_ENGINE_SUPERVISOR, 100000, &looks, err, sizeof err, &log);
    REQUIRE(log);
    cap = strstr(log, ",log-capped,");
    CHECK_MSG(cap && strstr(cap, "less than the logs' 125000-byte reserve (CONTRACT_LOG_SUPERVISOR_DISK_RESERVE_BYTES)"), "the supervisor's cap record at 100000 bytes free: %s", cap ? cap : "(none)");
    free(log);
}

/* A disk that fills as the logs write, `margin` bytes above a module's 1,000,000-byte reserve when
 * the log opens; `fill`: bytes it loses per byte this log writes (1: the log alone; k: k logs
 * flooding together as it does). The log floods it (20,000 records, about 1.6 MB, in 64 KiB
 * buffers). `*left`: the bytes the disk has left (less than 1,000,000: the logs went past the
 * reserve); `*looks`: the fstatvfs calls; `*capped`: the log stopped with its log-capped record. */
static void reserve_flood(long long margin, long long fill, long long *left, int *looks, int *capped)
{
    *left = -1;
    *capped = 0;
    REQUIRE(h_setup("logreserve-flood") == 0);
    setenv("CONTRACT_LOG_DISK_RESERVE_BYTES", "1000000", 1);
    int r = rt_log_open();
    unsetenv("CONTRACT_LOG_DISK_RESERVE_BYTES");
    REQUIRE(r == 0);
    char csv[1024], err_path[700];
    REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
    int saved = h_stderr_to_file(err_path, sizeof err_path);
    REQUIRE(saved >= 0);
    __atomic_store_n(&disk_looks, 0, __ATOMIC_RELEASE);
    __atomic_store_n(&disk_filled, 0, __ATOMIC_RELEASE);
    __atomic_store_n(&disk_free, 1000000 + margin, __ATOMIC_RELEASE);
    __atomic_store_n(&disk_fill_per_byte, fill, __ATOMIC_RELEASE);
    for (int i = 0; i < 20000; i++) ContractLog("flood", "", i, 0, "a module logging as fast as it can");
    ContractLogFlush();
    rt_log_close();
    __atomic_store_n(&disk_fill_per_byte, 0, __ATOMIC_RELEASE);
    *left = 1000000 + margin - __atomic_load_n(&disk_filled, __ATOMIC_ACQUIRE);
    *looks = __atomic_load_n(&disk_looks, __ATOMIC_ACQUIRE);
    __atomic_store_n(&disk_free, -1, __ATOMIC_RELEASE);
    __atomic_store_n(&disk_filled, 0, __ATOMIC_RELEASE);
    h_stderr_back(saved);
    char *log = h_read_file(csv);
    *capped = log && strstr(log, ",log-capped,") != NULL;
    free(log);
    h_teardown();
}

/* How far past the disk reserve flooding logs go: a log alone not at all (it looks before a write
 * that would go past, more often as the free space nears the reserve), k logs flooding together at
 * most what the k-1 others wrote between its look and its write (a buffer each), where each went up
 * to 128 KiB past it (a look per 64 KiB written, then a 64 KiB buffer). Far from the reserve the
 * looks stay one per 64 KiB written. */
void test_csv_log_reserve_overshoot(void)
{
    int looks = 0, capped = 0;
    long long left = 0;
    for (long long margin = 40000; margin <= 400000; margin += 60000) {
        reserve_flood(margin, 1, &left, &looks, &capped);
        CHECK_MSG(capped, "margin %lld: the log was not capped", margin);
        CHECK_MSG(left >= 1000000, "margin %lld: a log alone went %lld bytes past the 1000000-byte reserve", margin, 1000000 - left);
        /* near it a look per write: about one per 64 KiB buffer of the margin, a few more */
        CHECK_MSG(looks <= (int)(margin / 65536) + 8, "margin %lld: %d looks", margin, looks);
    }
    for (long long margin = 100000; margin <= 1000000; margin += 300000) {
        reserve_flood(margin, 4, &left, &looks, &capped);
        CHECK_MSG(capped, "4 logs, margin %lld: the log was not capped", margin);
        CHECK_MSG(left >= 1000000 - 3 * LOG_BUF, "margin %lld: 4 logs went %lld bytes past the 1000000-byte reserve (at most 3 buffers)", margin, 1000000 - left);
    }
    /* far from the reserve (100 MB free): one look per 64 KiB, as before */
    reserve_flood(100000000, 1, &left, &looks, &capped);
    CHECK_MSG(!capped && left > 1000000, "100 MB free: the log was capped");
    long long written = 1000000 + 100000000 - left, per64k = written / 65536;
    CHECK_MSG(looks >= per64k - 1 && looks <= per64k + 2, "%d looks for %lld bytes written far from the reserve (one per 64 KiB: %lld)", looks, written, per64k);
}

/* A child that logs `n` records (`<word> i`) on a log with its flush mark, hands them to its writer
 * after `handed` of them when that is not 0 (the writer stalls in its write for 2 s), then dies by
 * SIGKILL; returns its pid after its death (-1 when it did not die so). */
static pid_t killed_child(int n, int handed, int flush_at, const char *word)
{
    pid_t pid = fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        setenv("CONTRACT_LOG_MARK", "1", 1);
        if (rt_log_open() != 0) _exit(3);
        char detail[32];
        for (int i = 0; i < n; i++) {
            if (handed && i == handed) {
                slow_writes(2000000000LL);
                if (rt_log_hand_off(0) != 1) _exit(4);
                if (!wait_writer_stalled()) _exit(6);
            }
            if (flush_at && i == flush_at) ContractLogFlush();
            snprintf(detail, sizeof detail, "%s %d", word, i);
            ContractLog("test_record", "", -1, 0, detail);
        }
        raise(SIGKILL);
        _exit(5);
    }
    int status = 0;
    if (waitpid(pid, &status, 0) != pid || !WIFSIGNALED(status) || WTERMSIG(status) != SIGKILL) return -1;
    return pid;
}

/* The log holds `word 0` .. `word n-1`, each once, in order, each a whole line. */
static void check_records(const char *log, int n, const char *word, const char *what)
{
    const char *at = log;
    for (int i = 0; i < n; i++) {
        char want[48];
        snprintf(want, sizeof want, ",test_record,,,0,%s %d\n", word, i);
        const char *found = strstr(at, want);
        CHECK_MSG(found != NULL, "%s: record '%s %d' missing or out of order", what, word, i);
        if (!found) return;
        CHECK_MSG(strstr(found + 1, want) == NULL, "%s: record '%s %d' written twice", what, word, i);
        at = found + strlen(want);
    }
    CHECK_MSG(*at == '\0', "%s: the log goes on after the last record: '%.80s'", what, at);
}

/* A module killed by SIGKILL (the kernel's OOM killer) had logged records it had not written: the
 * launcher's rt_log_recover writes them from the buffers in its flush mark's file, to the byte,
 * once, in order, and removes the mark — with only the buffer being filled, with a buffer handed
 * to a writer stalled in its write, and with a write cut inside a record. A mark whose words do
 * not add up, or of a capped log, leaves the log as it is. */
void test_csv_log_killed(void)
{
    struct { int n, handed, flush_at; const char *word; } cases[] = {
        { 100, 0, 0, "filled" },   /* in the buffer being filled only */
        { 150, 100, 0, "stalled" }, /* 100 handed to the stalled writer, 50 in the other buffer */
        { 120, 0, 100, "cut" },     /* 100 written, 20 not; the file is then cut inside a record */
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        REQUIRE(h_setup("logkilled") == 0);
        pid_t pid = killed_child(cases[c].n, cases[c].handed, cases[c].flush_at, cases[c].word);
        REQUIRE(pid > 0);
        char csv[1024], mark[1024];
        REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
        REQUIRE(h_find_log_file("tester_", ".csv.mark", mark, sizeof mark));
        char *before = h_read_file(csv);
        REQUIRE(before);
        int lines = 0;
        for (const char *p = before; (p = strchr(p, '\n')) != NULL; p++) lines++;
        CHECK_MSG(lines == 1 + (cases[c].flush_at ? cases[c].flush_at : 0), "%s: the log held %d lines before recovery", cases[c].word, lines);
        size_t size = strlen(before);
        free(before);
        if (cases[c].flush_at) CHECK(truncate(csv, (off_t)(size - 7)) == 0); /* a write cut 7 bytes before its end */
        RecoveredLog r;
        CHECK(rt_log_recover(h_log_dir, (long)pid + 100000, &r) == 0); /* another pid: no mark names it */
        CHECK(rt_log_recover(h_log_dir, (long)pid, &r) == 1);
        unsigned long long want = (unsigned long long)(cases[c].n - cases[c].flush_at) + (cases[c].flush_at ? 1 : 0);
        CHECK_MSG(r.records == want && !r.broken && !r.dropped, "%s: %llu records recovered (want %llu), broken %d, dropped %d",
                  cases[c].word, r.records, want, r.broken, r.dropped);
        CHECK(strstr(csv, r.log) != NULL);
        char *log = h_read_file(csv);
        REQUIRE(log);
        CHECK(strncmp(log, "mono_ns,wall_time,module,event,peer,port,size,detail\n", 53) == 0);
        check_records(log, cases[c].n, cases[c].word, cases[c].word);
        free(log);
        CHECK_MSG(access(mark, F_OK) != 0, "%s: the mark is still there", cases[c].word);
        CHECK(rt_log_recover(h_log_dir, (long)pid, &r) == 0); /* once */
        h_teardown();
    }

    /* within the log's bound (the launcher has the modules' CONTRACT_LOG_MAX_BYTES): whole records,
     * the room for the writer's two `log-capped` records kept, the rest left out and said */
    {
        REQUIRE(h_setup("logkilledbound") == 0);
        setenv("CONTRACT_LOG_MAX_BYTES", "16384", 1);
        pid_t pid = killed_child(300, 0, 0, "bound");
        REQUIRE(pid > 0);
        RecoveredLog r;
        CHECK(rt_log_recover(h_log_dir, (long)pid, &r) == 1);
        unsetenv("CONTRACT_LOG_MAX_BYTES");
        char csv[1024];
        REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
        char *log = h_read_file(csv);
        REQUIRE(log);
        size_t size = strlen(log);
        CHECK_MSG(r.dropped && !r.broken && r.records > 100 && r.records < 300, "bound: %llu records, dropped %d, broken %d", r.records, r.dropped, r.broken);
        CHECK_MSG(size <= 16384 - 2 * 1280 && log[size - 1] == '\n', "bound: the log holds %zu bytes", size);
        check_records(log, (int)r.records, "bound", "bound");
        free(log);
        h_teardown();
    }

    /* hostile or broken marks: the log is left as it is */
    for (int k = 0; k < 3; k++) {
        REQUIRE(h_setup("logkilledbad") == 0);
        if (k == 2) setenv("CONTRACT_LOG_MAX_BYTES", "8192", 1); /* capped at its flush: the file is not its records in order */
        pid_t pid = killed_child(k == 2 ? 300 : 30, 0, k == 2 ? 200 : 0, "bad");
        REQUIRE(pid > 0);
        char csv[1024], mark[1024];
        REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
        REQUIRE(h_find_log_file("tester_", ".csv.mark", mark, sizeof mark));
        if (k == 0) { /* a length past its buffer */
            int fd = open(mark, O_WRONLY | O_CLOEXEC);
            REQUIRE(fd >= 0);
            unsigned long long len = 1ULL << 40;
            CHECK(pwrite(fd, &len, sizeof len, 7 * sizeof len) == (ssize_t)sizeof len);
            close(fd);
        }
        if (k == 1) { /* the mark is a link to another file: never followed */
            char other[1100];
            snprintf(other, sizeof other, "%s.elsewhere", mark);
            CHECK(rename(mark, other) == 0);
            CHECK(symlink(other, mark) == 0);
        }
        char *before = h_read_file(csv);
        REQUIRE(before);
        RecoveredLog r;
        int found = rt_log_recover(h_log_dir, (long)pid, &r);
        unsetenv("CONTRACT_LOG_MAX_BYTES");
        CHECK_MSG(found == (k == 1 ? 0 : 1), "bad mark %d: rt_log_recover said %d", k, found);
        CHECK_MSG(r.records == 0 && (k == 1 || r.broken), "bad mark %d: %llu records written, broken %d", k, r.records, r.broken);
        char *after = h_read_file(csv);
        REQUIRE(after);
        CHECK_MSG(strcmp(before, after) == 0, "bad mark %d: the log changed", k);
        free(before);
        free(after);
        h_teardown();
    }
}

/* A module's code logging under an engine's own kind (ORD's deadline miss, a supervisor's rule
 * change) through ContractLog: refused, an error record of this process says so (the trace readers
 * would not take it for the engine's either: docs/runtime-api.md "Whose records, and their times").
 * The engine itself logs them. */
void test_csv_log_engine_kinds(void)
{
    REQUIRE(h_setup("logengine") == 0);
    REQUIRE(rt_log_open() == 0);
    char csv[1024];
    REQUIRE(h_find_log_file("tester_", ".csv", csv, sizeof csv));
    ContractLog("ord_deadline_miss", "", -1, 0, "schema=schemaCommande1 cycle=99 tick_ns=1");
    ContractLog("sup_rule", "", -1, 0, "f.r active cause=elapsed=5ns");
    ContractLog("my_own", "", -1, 0, "kept");
    g_rt.engine = RT_ENGINE_ORD;
    ContractLog("ord_deadline_miss", "", -1, 0, "schema=S cycle=1 tick_ns=2");
    ContractLog("sup_rule", "", -1, 0, "f.r active cause=elapsed=6ns");
    g_rt.engine = RT_ENGINE_SUPERVISOR;
    ContractLog("sup_rule", "", -1, 0, "f.r active cause=elapsed=7ns");
    g_rt.engine = RT_ENGINE_NONE;
    ContractLogFlush();
    char *log = h_read_file(csv);
    REQUIRE(log);
    CHECK(strstr(log, ",ord_deadline_miss,,,0,schema=schemaCommande1") == NULL);
    CHECK(strstr(log, ",error,,,0,\"ContractLog: 'ord_deadline_miss' is ORD's own record kind: refused in ") != NULL);
    CHECK(strstr(log, "which is not ORD (give your records names of their own); its detail: schema=schemaCommande1 cycle=99 tick_ns=1") != NULL);
    CHECK(strstr(log, ",error,,,0,\"ContractLog: 'sup_rule' is the supervisors' own record kind") != NULL);
    CHECK(strstr(log, ",sup_rule,,,0,f.r active cause=elapsed=5ns") == NULL);
    CHECK(strstr(log, ",my_own,,,0,kept") != NULL);
    CHECK(strstr(log, ",ord_deadline_miss,,,0,schema=S cycle=1 tick_ns=2") != NULL);
    CHECK(strstr(log, ",sup_rule,,,0,f.r active cause=elapsed=6ns") == NULL);
    CHECK(strstr(log, ",sup_rule,,,0,f.r active cause=elapsed=7ns") != NULL);
    free(log);
    rt_log_close();
    h_teardown();
}
