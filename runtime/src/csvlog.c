/* The per-module CSV log: <LOG_DIR>/<MODULE>_<d>-<Mon>-<Y>-<H>h<M>m<S>s.csv (report section 8.2
 * naming, without the space). Columns: see docs/runtime-api.md. Records are formatted by hand
 * into a 64 KiB buffer (no stdio on the hot path) and handed to the log's writer thread when the
 * module waits and its flush boundary came (below), when the buffer fills, and at exit.
 *
 * The writer thread: the module's own thread (maybe SCHED_FIFO, a period to keep) never waits in
 * write(): a disk stall held a 1 kHz scheduler 67 ms in its log write. The module fills one buffer
 * while the writer (SCHED_OTHER, all signals blocked) writes the other. A hand-off at a flush
 * boundary that finds the writer still busy is tried again at the next boundary; only a module
 * that fills a whole buffer while the writer still writes the previous one waits for it (nothing
 * is lost). Without the thread (pthread_create failed) the module writes itself, as before. A
 * child forked by module code does not log (its copy of the buffers is dropped, not written twice).
 *
 * The file is bounded (CONTRACT_LOG_MAX_BYTES, default LOG_MAX_DEFAULT): a module that loops
 * (an exec region that never sets *stateindex = -1) must not fill the disk nor make the whole
 * log too big to collect. At the bound the log keeps its whole records, then one `log-capped`
 * record; later records are only counted, and a last `log-capped` record at exit says how many
 * were not written (docs/runtime-api.md "CSV log"). The file never exceeds the bound.
 *
 * The flush mark (CONTRACT_LOG_MARK=1, set by the build service for its live trace channel):
 * <log>.mark, one page mapped shared, whose first 64-bit word says what the log file lacks —
 * 0: nothing (every record logged so far is in the file), 1: a record is being logged,
 * otherwise the mono_ns of the oldest record not written yet. A reader that reads the word
 * (after taking CLOCK_MONOTONIC) and then the file knows the module's log is whole up to that
 * time, so it can put several modules' logs in time order without guessing how long a module
 * holds its records (docs/build-service-api.md "Trace channel"). The word covers both buffers: it
 * is the oldest record of the one being written, else of the one being filled; the writer sets it
 * after its write, under the lock the module takes when its buffer goes from empty to dirty. Cost:
 * that lock and two stores when the buffer goes from empty to dirty, one store at each write.
 * Removed at close. Its second word is
 * the reader's: while a client watches the live trace the build service writes there the flush
 * delay it wants (25 ms), and the module writes its records that much sooner than LOG_FLUSH_NS
 * (50 ms) when it waits; 0 (nobody watches): LOG_FLUSH_NS. The file also holds the two log buffers
 * (log_mark.h), and words that say which bytes of the module's records each holds and how many
 * bytes the file held before the first: a module killed by SIGKILL (the OOM killer) leaves its
 * records there, and contract-launch writes the ones the log lacks (log_recover.c). Cost: one more
 * store per record, and each buffer's words at a hand-off.
 *
 * Flush boundaries: a module that waits writes its records at the first multiple of the flush
 * delay on CLOCK_MONOTONIC after its oldest unwritten record (ContractLogFlushDue), not a delay
 * after it. Every module of a run counts from the same clock, so they write at the same instants:
 * a reader that puts the logs in time order waits for the last of them once per delay, instead of
 * for modules writing at phases of their own (up to one more delay).
 *
 * A crash (core.c on_crash_signal: SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) must not lose the
 * records that explain it: rt_log_at_signal, async-signal-safe, writes what the log holds and has not
 * written, in file order — the buffer handed to the writer (the handler writes it itself when the
 * writer has not begun it, pending_owner decides; else it waits up to CRASH_WAIT_NS for the
 * writer's write to end, and writes anyway after that), then the whole records of the buffer being
 * filled (log_len is stored once a record is whole; log_busy says when the buffers are changing
 * hands, or the module writes one itself: then skipped), then a `module_crashed` record — within
 * the bound and log-capped as any write, the mark then 0. Records are formatted without a lock or
 * stdio for that (put_record, write_records_r). A stop signal (core.c on_fatal_signal: SIGTERM,
 * SIGINT, SIGHUP) writes the same records, without one of its own. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "internal.h"
#include "log_mark.h"
#include "log_reserve.h"

#define CSV_HEADER "mono_ns,wall_time,module,event,peer,port,size,detail\n"
#define EVENT_MAX 64     /* bytes of a record's event name: a longer one is cut (one warning) */
#define DETAIL_MAX 400   /* bytes of a record's detail: a longer one is cut, ending with `…` */
#define LOG_MAX_DEFAULT (256ULL * 1024 * 1024)

#define WRITER_STACK (256 * 1024) /* locked with the rest by mlockall: not the default 8 MiB */

static int log_fd = -1;
static char log_store[2][LOG_BUF];      /* the buffers when there is no mark to hold them   */
static char *log_bufs[2] = { log_store[0], log_store[1] }; /* in the mark's file when it has one */
static char *log_buf = log_store[0];    /* the buffer the module fills ...                  */
static int log_cur;                     /* ... its index                                    */
static unsigned long long log_start[2]; /* each buffer's first byte in the module's records */
static size_t log_len;
static char log_path[PATH_MAX];
static unsigned long long log_max;      /* bound of the file, bytes                         */
static unsigned long long log_written;  /* bytes in the file (the writer's)                 */
static int log_failed;                  /* the errno that stopped the log (0: none, or the bound) */
static int log_capped;                  /* the bound was reached: records are only counted;
                                           set by the writer, read by the module (atomic)   */
static LogReserve log_reserve;          /* the logs' disk reserve (all 0: none, log_reserve.c) */
static unsigned long long log_budget;   /* bytes the log may write before it looks at the free space */
static int log_low;                     /* the free space fell below the reserve: the log stopped */
static unsigned long long log_dropped;  /* records not written since, counted by the module */
static unsigned long long log_dropped_w; /* ... and by the writer                           */
static unsigned long long log_records;  /* records logged (written or not) since the open   */
static unsigned long long *log_mark;    /* the flush mark's word, NULL when there is none   */
static char mark_path[PATH_MAX + 8];

/* The writer thread and what it shares with the module, under log_lock (priority inheritance:
 * a SCHED_FIFO module never waits on a preempted SCHED_OTHER writer holding it). */
static pthread_once_t log_once = PTHREAD_ONCE_INIT;
static pthread_mutex_t log_lock;
static pthread_cond_t log_work, log_idle;
static pthread_t writer;
static int writer_on;                   /* the thread runs (the module's view)              */
static int writer_stop;
static const char *pending_buf;         /* the buffer being written ...                     */
static size_t pending_len;              /* ... its length, 0 = none (atomic)                */

/* For the crash handler (rt_log_at_signal), which may run on the module's thread anywhere in this
 * code: who writes the pending buffer (the writer claims it before writing, the handler takes it
 * when the writer has not), and what the module's thread is doing with its buffers. A record
 * being formatted is no concern: log_len grows only once the record is whole. */
enum { OWNER_NONE, OWNER_WRITER, OWNER_WROTE, OWNER_CRASH };
static int pending_owner;               /* OWNER_*, of the buffer pending_len names (atomic) */
enum { BUSY_NONE, BUSY_SWAP, BUSY_WRITE };
static int log_busy;                    /* BUSY_SWAP: the buffers change hands; BUSY_WRITE: the
                                           module writes its buffer itself (no writer thread) */
static _Thread_local int on_writer;     /* this thread is the writer                        */
#define CRASH_WAIT_NS 100000000LL       /* the handler waits this long for a busy writer    */

static void writer_start(void);

static void mark_set(unsigned long long v)
{
    if (log_mark) __atomic_store_n(log_mark, v, __ATOMIC_SEQ_CST);
}

/* A word of the mark's page for log_recover.c (log_mark.h). Release: a SIGKILL between two of
 * these stores leaves the earlier ones, and the record bytes before them, in the file. */
static void mark_put(int word, unsigned long long v)
{
    if (log_mark) __atomic_store_n(&log_mark[word], v, __ATOMIC_RELEASE);
}

/* Buffer i begins the module's records anew at byte `start` (empty first: a SIGKILL in between
 * leaves it empty). */
static void buffer_begin(int i, unsigned long long start)
{
    mark_put(MARK_WORD_LEN(i), 0);
    log_start[i] = start;
    mark_put(MARK_WORD_START(i), start);
}

/* The log file now holds bytes that are not the module's records in order: no recovery. */
static void mark_broken(void) { mark_put(MARK_WORD_BROKEN, 1); }

/* Creates <log>.mark when CONTRACT_LOG_MARK=1 (no mark, silently, when it cannot). */
static void mark_open(void)
{
    const char *on = getenv("CONTRACT_LOG_MARK");
    if (!on || strcmp(on, "1") != 0) return;
    snprintf(mark_path, sizeof mark_path, "%s.mark", log_path);
    int fd = open(mark_path, O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) return;
    struct stat st;
    void *p = MAP_FAILED;
    if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && (st.st_size >= MARK_FILE_BYTES || ftruncate(fd, MARK_FILE_BYTES) == 0))
        p = mmap(NULL, MARK_FILE_BYTES, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    close(fd);
    if (p == MAP_FAILED) {
        unlink(mark_path);
        return;
    }
    log_mark = p;
    mark_put(MARK_WORD_MAGIC, 0); /* a page an earlier module left: not this one's until rt_log_open sets it */
    mark_set(0);
    log_bufs[0] = (char *)p + MARK_PAGE; /* the records are formatted in the file: a SIGKILL keeps them */
    log_bufs[1] = (char *)p + MARK_PAGE + LOG_BUF;
}

/* The mark's words for recovery, once the log is open (`base`: the bytes the file holds). */
static void mark_ready(unsigned long long base)
{
    if (!log_mark) return;
    mark_put(MARK_WORD_PID, (unsigned long long)getpid());
    mark_put(MARK_WORD_BASE, base);
    mark_put(MARK_WORD_BROKEN, 0);
    buffer_begin(0, 0);
    buffer_begin(1, 0);
    mark_put(MARK_WORD_MAGIC, MARK_MAGIC);
}

static void mark_close(void)
{
    if (!log_mark) return;
    mark_put(MARK_WORD_MAGIC, 0);
    mark_set(0);
    log_bufs[0] = log_store[0];
    log_bufs[1] = log_store[1];
    log_buf = log_bufs[log_cur];
    munmap(log_mark, MARK_FILE_BYTES);
    log_mark = NULL;
    unlink(mark_path);
}

unsigned long long rt_log_records(void) { return log_records; }

/* CONTRACT_LOG_MAX_BYTES: a byte count (at least 4 records' room); otherwise the default (said on
 * stderr when `warn`). */
static unsigned long long log_bound(int warn)
{
    const char *v = getenv("CONTRACT_LOG_MAX_BYTES");
    if (!v || !*v) return LOG_MAX_DEFAULT;
    char *end;
    errno = 0;
    unsigned long long n = strtoull(v, &end, 10);
    if (errno || *end || n < 4 * RECORD_MAX) {
        if (warn)
            fprintf(stderr, "%s: warning: CONTRACT_LOG_MAX_BYTES='%s' is not a byte count >= %d: using %llu\n", g_rt.name, v,
                    4 * RECORD_MAX, LOG_MAX_DEFAULT);
        return LOG_MAX_DEFAULT;
    }
    return n;
}

unsigned long long rt_log_max_bytes(void) { return log_bound(0); }

int rt_log_enabled(void) { return log_fd >= 0; }

int rt_log_open(void)
{
    const char *off = getenv("CONTRACT_LOG");
    if (off && strcmp(off, "off") == 0) return 0;
    const char *dir = getenv("CONTRACT_LOG_DIR");
    if (!dir || !*dir) dir = ".";
    if (mkdir(dir, 0755) != 0 && errno != EEXIST) {
        fprintf(stderr, "%s: warning: cannot create log directory %s: %s (no CSV log)\n", g_rt.name, dir, strerror(errno));
        return -1;
    }
    static const char *months[] = { "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec" };
    time_t t = time(NULL);
    struct tm tm;
    localtime_r(&t, &tm);
    char *path = log_path;
    snprintf(log_path, sizeof log_path, "%s/%s_%d-%s-%d-%02dh%02dm%02ds.csv", dir, g_rt.name, tm.tm_mday,
             months[tm.tm_mon], tm.tm_year + 1900, tm.tm_hour, tm.tm_min, tm.tm_sec);
    mark_open(); /* before the log: a reader that sees the log finds its mark */
    log_fd = open(path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (log_fd < 0) {
        mark_close();
        fprintf(stderr, "%s: warning: cannot open log %s: %s (no CSV log)\n", g_rt.name, path, strerror(errno));
        return -1;
    }
    log_max = log_bound(1);
    rt_log_reserve_read(&log_reserve, 1);
    log_budget = 0; /* the first write looks */
    log_low = 0;
    log_capped = 0;
    log_failed = 0;
    log_dropped = 0;
    log_dropped_w = 0;
    log_records = 0;
    log_written = 0;
    struct stat st;
    if (fstat(log_fd, &st) == 0) log_written = (unsigned long long)st.st_size;
    if (log_written == 0) {
        if (write(log_fd, CSV_HEADER, sizeof CSV_HEADER - 1) < 0)
            fprintf(stderr, "%s: warning: cannot write log %s: %s\n", g_rt.name, path, strerror(errno));
        else
            log_written = sizeof CSV_HEADER - 1;
    }
    log_len = 0;
    log_cur = 0;
    log_buf = log_bufs[0];
    mark_ready(log_written);
    writer_start();
    return 0;
}

static char *put_str(char *p, const char *s)
{
    while (*s) *p++ = *s++;
    return p;
}

static char *put_u64(char *p, unsigned long long v)
{
    char tmp[24];
    int n = 0;
    do tmp[n++] = (char)('0' + v % 10); while ((v /= 10) != 0);
    while (n) *p++ = tmp[--n];
    return p;
}

/* The CUT_MARK a detail longer than DETAIL_MAX ends with (U+2026 HORIZONTAL ELLIPSIS, 3 bytes). */
#define CUT_MARK "\xe2\x80\xa6"

/* At most `max` bytes of s as a CSV field (quoted, quotes doubled, line ends as spaces: at most
 * 2 * max + 2 bytes). `mark`: a longer s is cut before the UTF-8 character the bound less CUT_MARK's
 * 3 bytes would split, and ends with CUT_MARK (the reader sees the cut: max bytes at most, the mark
 * included); else it is cut at `max`. */
static char *put_field(char *p, const char *s, size_t max, int mark)
{
    if (!s) return p;
    size_t n = strnlen(s, max + 1);
    int cut = n > max;
    if (cut) {
        /* with its mark the field stays within max bytes: the text is cut at max - 3 */
        n = mark ? max - (sizeof CUT_MARK - 1) : max;
        if (mark) while (n > 0 && ((unsigned char)s[n] & 0xC0) == 0x80) n--; /* s[n]: inside a character */
    }
    const char *tail = cut && mark ? CUT_MARK : "";
    if (!memchr(s, ',', n) && !memchr(s, '"', n) && !memchr(s, '\n', n) && !memchr(s, '\r', n)) {
        memcpy(p, s, n);
        return put_str(p + n, tail);
    }
    *p++ = '"';
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '"') *p++ = '"';
        *p++ = (s[i] == '\n' || s[i] == '\r') ? ' ' : s[i];
    }
    p = put_str(p, tail);
    *p++ = '"';
    return p;
}

/* v in decimal, at least `width` digits (zero-padded). */
static char *put_dec(char *p, unsigned long long v, int width)
{
    char tmp[24];
    int n = 0;
    do tmp[n++] = (char)('0' + v % 10); while ((v /= 10) != 0);
    while (n < width) tmp[n++] = '0';
    while (n) *p++ = tmp[--n];
    return p;
}

/* `YYYY-MM-DDTHH:MM:SS.` of a UTC time, as gmtime_r would give it, by hand: gmtime_r may take a lock
 * (glibc's tz lock), and the crash handler formats a record too (H. Hinnant's civil_from_days). */
static void put_utc(char *p, time_t t)
{
    long long days = (long long)t / 86400, secs = (long long)t % 86400;
    if (secs < 0) { secs += 86400; days--; }
    long long z = days + 719468;
    long long era = (z >= 0 ? z : z - 146096) / 146097;
    long long doe = z - era * 146097;
    long long yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    long long doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    long long mp = (5 * doy + 2) / 153;
    long long day = doy - (153 * mp + 2) / 5 + 1, month = mp < 10 ? mp + 3 : mp - 9;
    long long year = yoe + era * 400 + (month <= 2);
    p = put_dec(p, (unsigned long long)(year > 0 ? year : 0), 4);
    *p++ = '-';
    p = put_dec(p, (unsigned long long)month, 2);
    *p++ = '-';
    p = put_dec(p, (unsigned long long)day, 2);
    *p++ = 'T';
    p = put_dec(p, (unsigned long long)(secs / 3600), 2);
    *p++ = ':';
    p = put_dec(p, (unsigned long long)(secs / 60 % 60), 2);
    *p++ = ':';
    p = put_dec(p, (unsigned long long)(secs % 60), 2);
    *p++ = '.';
    *p = '\0';
}

/* Formats one record at p (at most RECORD_MAX bytes); returns its end. Async-signal-safe (the
 * crash handler's record): no lock, no stdio, no allocation. */
static char *put_record(char *p, RTIME mono, const char *event, const char *peer, int port, size_t size,
                        const char *detail)
{
    struct timespec wall;
    clock_gettime(CLOCK_REALTIME, &wall);
    static _Thread_local time_t cached_sec = -1; /* the writer formats its log-capped record too */
    static _Thread_local char cached_text[80];
    if (wall.tv_sec != cached_sec) { /* calendar conversion once per second */
        put_utc(cached_text, wall.tv_sec);
        cached_sec = wall.tv_sec;
    }
    p = put_u64(p, (unsigned long long)mono);
    *p++ = ',';
    p = put_str(p, cached_text);
    long us = wall.tv_nsec / 1000;
    for (long div = 100000; div > 0; div /= 10) *p++ = (char)('0' + (us / div) % 10);
    *p++ = 'Z';
    *p++ = ',';
    p = put_str(p, g_rt.name);
    *p++ = ',';
    p = put_field(p, event, EVENT_MAX, 0);
    *p++ = ',';
    p = put_field(p, peer, CONTRACT_NAME_MAX, 0);
    *p++ = ',';
    if (port >= 0) p = put_u64(p, (unsigned long long)port);
    *p++ = ',';
    p = put_u64(p, (unsigned long long)size);
    *p++ = ',';
    p = put_field(p, detail, DETAIL_MAX, 1);
    *p++ = '\n';
    return p;
}

/* The module's thread marks what it does for a crash handler running on the same thread (compiler
 * barriers: the handler sees the flag set before the buffers change, and cleared after). */
static int busy_enter(int what)
{
    int was = __atomic_load_n(&log_busy, __ATOMIC_RELAXED);
    __atomic_store_n(&log_busy, what, __ATOMIC_RELAXED);
    __atomic_signal_fence(__ATOMIC_SEQ_CST);
    return was;
}

static void busy_leave(int was)
{
    __atomic_signal_fence(__ATOMIC_SEQ_CST);
    __atomic_store_n(&log_busy, was, __ATOMIC_RELAXED);
}

static void lock(void) { pthread_mutex_lock(&log_lock); }
static void unlock(void) { pthread_mutex_unlock(&log_lock); }
static size_t pending(void) { return __atomic_load_n(&pending_len, __ATOMIC_ACQUIRE); }

/* An event name longer than EVENT_MAX is cut to it: said once per process, on stderr (two long names
 * with the same first 64 bytes become one event in the trace). */
static void warn_long_event(const char *event)
{
    static int said;
    if (__atomic_exchange_n(&said, 1, __ATOMIC_RELAXED)) return;
    fprintf(stderr, "%s: warning: ContractLog: an event name longer than %d bytes is cut to them: '%.*s...' (give your records shorter names)\n",
            g_rt.name[0] ? g_rt.name : "libmodule", EVENT_MAX, EVENT_MAX, event);
}

/* Whether `event` is a word the trace readers take as a record's event: a letter or `_`, then
 * letters, digits, `_`, `.` or `-` (docs/runtime-api.md, the `user` kind). */
static int event_is_word(const char *event)
{
    /* ASCII only, whatever the locale (the readers' isUserEventName) */
    for (const char *q = event; *q; q++) {
        char c = *q;
        int letter = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
        if (!(letter || (q > event && ((c >= '0' && c <= '9') || c == '.' || c == '-')))) return 0;
    }
    return event[0] != '\0';
}

/* An event name that is no word is written as given (nothing of it is lost), but the readers cannot
 * take its line as a record: said on stderr for each new such name, the first 8 of a process (a name
 * logged again and again is said once: the last one said is remembered). */
#define NO_WORD_WARNINGS 8
static void warn_no_word(const char *event)
{
    static char last[EVENT_MAX + 1];
    static int said;
    if (said >= NO_WORD_WARNINGS || strncmp(last, event, EVENT_MAX) == 0) return;
    said++;
    snprintf(last, sizeof last, "%s", event);
    fprintf(stderr, "%s: warning: ContractLog: the event name '%.*s' is no word (a letter or '_', then letters, digits, '_', '.' or '-'): "
            "contract trace and the Monitor will read its records as unreadable lines (give your records names that are words)\n",
            g_rt.name[0] ? g_rt.name : "libmodule", EVENT_MAX, event);
}

/* The engine whose own record kind `event` is (RT_ENGINE_NONE: anyone's). The trace readers take
 * these kinds from that engine only (docs/runtime-api.md "Whose records, and their times"). */
void rt_log_engine(int engine) { g_rt.engine = engine; }

static int engine_kind(const char *event)
{
    static const char *const ord[] = { "scheduler", "ord_release", "ord_finished", "ord_complete", "ord_deadline_miss" };
    static const char *const sup[] = { "supervisor", "sup_rule", "module_hold", "flow_hold", "module_priority", "priority_kept" };
    if (!event) return RT_ENGINE_NONE;
    for (size_t i = 0; i < sizeof ord / sizeof ord[0]; i++)
        if (strcmp(event, ord[i]) == 0) return RT_ENGINE_ORD;
    for (size_t i = 0; i < sizeof sup / sizeof sup[0]; i++)
        if (strcmp(event, sup[i]) == 0) return RT_ENGINE_SUPERVISOR;
    return RT_ENGINE_NONE;
}

void ContractLog(const char *event, const char *peer, int port, size_t size, const char *detail)
{
    if (log_fd < 0) return;
    int engine = engine_kind(event);
    if (engine != RT_ENGINE_NONE && engine != g_rt.engine) {
        /* a module's code logging under an engine's own kind (ORD's deadline miss, a supervisor's
         * rule change): refused, logged as an error record of this module that says so, the first
         * one said on stderr (rt_error counts the repeats) */
        char text[600];
        snprintf(text, sizeof text, "ContractLog: '%s' is %s own record kind: refused in %s, which is %s (give your records names of their own); its detail: %.300s",
                 event, engine == RT_ENGINE_ORD ? "ORD's" : "the supervisors'", g_rt.name[0] ? g_rt.name : "this process",
                 engine == RT_ENGINE_ORD ? "not ORD" : "no supervisor", detail ? detail : "");
        rt_error("%s", text);
        return;
    }
    if (event && strnlen(event, EVENT_MAX + 1) > EVENT_MAX) warn_long_event(event);
    if (event && !event_is_word(event)) warn_no_word(event);
    if (__atomic_load_n(&log_capped, __ATOMIC_RELAXED)) {
        log_records++;
        log_dropped++;
        return;
    }
    if (log_len + RECORD_MAX > LOG_BUF) rt_log_hand_off(1);
    RTIME mono;
    if (!g_rt.log_dirty_since) {
        /* the mark says "being logged" before the record's time is taken: a reader that saw it clean
         * took its time before that, so this record is younger than what the reader concluded. While
         * the writer holds the other buffer the mark already names an older record: left as it is. */
        if (writer_on) lock();
        int quiet = !pending();
        if (quiet) mark_set(1);
        mono = GetTime();
        g_rt.log_dirty_since = mono;
        if (quiet) mark_set((unsigned long long)mono);
        if (writer_on) unlock();
    } else {
        mono = GetTime();
    }
    char *p = put_record(log_buf + log_len, mono, event, peer, port, size, detail);
    __atomic_store_n(&log_len, (size_t)(p - log_buf), __ATOMIC_RELEASE); /* whole: a crash handler may write it */
    mark_put(MARK_WORD_LEN(log_cur), (unsigned long long)(p - log_buf)); /* ... and the launcher after a SIGKILL */
    log_records++; /* counted once in the buffer (a crash inside the record does not count it) */
}

/* Counts the records (lines) of buf[0..len). */
static unsigned long long count_records(const char *buf, size_t len)
{
    unsigned long long n = 0;
    for (const char *p = buf, *e = buf + len; (p = memchr(p, '\n', (size_t)(e - p))) != NULL; p++) n++;
    return n;
}

/* Writes buf[0..len), whole records. A write that fails (a full disk, a quota) leaves the file at
 * the end of its last whole record (the part of a record written is cut off again: no line of it
 * is spliced to a later one) and returns the error; 0 when all was written. Async-signal-safe. */
static int write_or_cut(const char *buf, size_t len)
{
    size_t off = 0;
    int err = 0;
    while (log_fd >= 0 && off < len) {
        ssize_t n = write(log_fd, buf + off, len - off);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            err = n < 0 ? errno : ENOSPC;
            break;
        }
        off += (size_t)n;
    }
    if (err == 0) {
        log_written += off;
        return 0;
    }
    size_t keep = 0;
    for (size_t i = 0; i < off; i++)
        if (buf[i] == '\n') keep = i + 1;
    /* O_APPEND: later writes (the last log-capped record, when the disk takes it) go after it */
    if (keep == off || ftruncate(log_fd, (off_t)(log_written + keep)) == 0) off = keep;
    log_written += off;
    return err;
}

/* What a write error is, in words, without strerror (async-signal-safe). */
static const char *write_error_text(int err)
{
    switch (err) {
    case ENOSPC: return "No space left on device";
    case EDQUOT: return "Disk quota exceeded";
    case EFBIG: return "File too large";
    case EIO: return "Input/output error";
    default: return "write error";
    }
}

/* Writes one `log-capped` record (room for two is kept below the bound). Async-signal-safe. */
static void write_cap_record(const char *detail)
{
    char rec[RECORD_MAX];
    /* size: the bound; for a log stopped by a write error, the bytes it holds */
    size_t size = log_failed || log_low ? (size_t)log_written : (size_t)log_max;
    mark_broken();
    char *end = put_record(rec, GetTime(), "log-capped", "", -1, size, detail);
    (void)write_or_cut(rec, (size_t)(end - rec));
}

/* The log stops here for good (its bound, or a write the disk refused): later records are only
 * counted; a `log-capped` record says why (`record`) and one stderr line (`M: warning: CSV log
 * PATH <warning>`). Async-signal-safe. */
static void stop_log(const char *record, const char *warning)
{
    __atomic_store_n(&log_capped, 1, __ATOMIC_RELAXED);
    write_cap_record(record);
    char text[PATH_MAX + 400], *p = text;
    p = put_str(p, g_rt.name);
    p = put_str(p, ": warning: CSV log ");
    p = put_str(p, log_path);
    p = put_str(p, " ");
    p = put_str(p, warning);
    p = put_str(p, "\n");
    if (write(STDERR_FILENO, text, (size_t)(p - text)) < 0) { /* nothing more to say it with */ }
}

/* Writes whole records; a write error stops the log there for good (later records are only
 * counted, like past the bound: a file with a gap in it would read as whole), said once on stderr
 * and, when the disk takes it, by a `log-capped` record. Async-signal-safe. */
static void write_all(const char *buf, size_t len)
{
    unsigned long long before = log_written;
    int err = write_or_cut(buf, len);
    if (err == 0) return;
    mark_broken();
    size_t kept = (size_t)(log_written - before);
    log_dropped_w += count_records(buf + kept, len - kept);
    log_failed = err;
    char record[160], warning[200], *p = record; /* by hand: no stdio (a crash handler may be here) */
    p = put_str(p, "log could not be written past ");
    p = put_u64(p, log_written);
    p = put_str(p, " bytes (");
    p = put_str(p, write_error_text(err));
    p = put_str(p, "): later records are not written");
    *p = '\0';
    p = put_str(warning, "not written past ");
    p = put_u64(p, log_written);
    p = put_str(p, " bytes (");
    p = put_str(p, write_error_text(err));
    p = put_str(p, "); it ends at its last whole record, later records are not written");
    *p = '\0';
    stop_log(record, warning);
}

/* "<written> bytes: its disk had F bytes free; less than the logs' K-byte reserve (VAR) and the L
   bytes to write": why a log stopped at its disk's reserve, in its log-capped record and its stderr
   warning alike */
static char *put_reserve_reason(char *p, unsigned long long free_bytes, unsigned long long keep, const char *var, size_t len)
{
    p = put_u64(p, log_written);
    p = put_str(p, " bytes: its disk had ");
    p = put_u64(p, free_bytes);
    p = put_str(p, " bytes free; less than the logs' ");
    p = put_u64(p, keep);
    p = put_str(p, "-byte reserve (");
    p = put_str(p, var);
    p = put_str(p, ") and the ");
    p = put_u64(p, len);
    return put_str(p, " bytes to write");
}

/* The log's disk would go below its reserve with buf[0..len) (log_reserve.c; looked at once the
 * writes since the last look exceed what it allowed, log_budget): the log stops before buf[0..len)
 * as at its bound — these records only counted, a `log-capped` record and one stderr line saying
 * why. 1 when it stopped. */
static int stop_at_reserve(const char *buf, size_t len)
{
    if (log_reserve.modules == 0 && log_reserve.engines == 0 && log_reserve.supervisors == 0) return 0;
    if (len <= log_budget) {
        log_budget -= len;
        return 0;
    }
    unsigned long long keep = rt_log_reserve_for(&log_reserve, g_rt.engine), free_bytes = 0;
    if (!rt_log_reserve_reached(log_fd, keep, len, &free_bytes, &log_budget)) return 0;
    const char *var = rt_log_reserve_name(g_rt.engine);
    mark_broken(); /* the file ends before these records */
    log_low = 1;
    log_dropped_w += count_records(buf, len);
    char record[320], warning[320], *p;
    p = put_reserve_reason(put_str(record, "log stopped at "), free_bytes, keep, var, len);
    *put_str(p, ": later records are not written") = '\0';
    p = put_reserve_reason(put_str(warning, "stopped at "), free_bytes, keep, var, len);
    *put_str(p, "; later records are not written") = '\0';
    stop_log(record, warning);
    return 1;
}

/* Writes buf[0..len) to the file within its bound (the writer's, or the module's without one), as
 * if `reserve` more bytes were in the file (a crash handler's: those the stalled writer may still
 * write). Async-signal-safe (fstatvfs aside: one statfs system call). */
static void write_records_r(const char *buf, size_t len, unsigned long long reserve)
{
    if (__atomic_load_n(&log_capped, __ATOMIC_RELAXED)) { /* handed off before the bound was seen */
        log_dropped_w += count_records(buf, len);
        return;
    }
    if (stop_at_reserve(buf, len)) return;
    /* the room left before the bound, keeping two records' room for the markers */
    unsigned long long used = log_written + reserve + 2 * RECORD_MAX;
    unsigned long long room = used < log_max ? log_max - used : 0;
    if (len <= room) {
        write_all(buf, len);
        return;
    }
    size_t keep = 0; /* whole records only */
    for (size_t i = 0; i < (size_t)room; i++)
        if (buf[i] == '\n') keep = i + 1;
    mark_broken(); /* the file ends before these records */
    write_all(buf, keep);
    log_dropped_w += count_records(buf + keep, len - keep);
    if (log_failed) return; /* a write error stopped the log first: said by write_all */
    char record[160], warning[160], *p = record;
    p = put_str(p, "log reached its ");
    p = put_u64(p, log_max);
    p = put_str(p, "-byte bound (CONTRACT_LOG_MAX_BYTES): later records are not written");
    *p = '\0';
    p = put_str(warning, "capped at ");
    p = put_u64(p, log_max);
    p = put_str(p, " bytes (CONTRACT_LOG_MAX_BYTES); later records are not written");
    *p = '\0';
    stop_log(record, warning);
}

static void write_records(const char *buf, size_t len) { write_records_r(buf, len, 0); }

/* The last `log-capped` record: how many records were not written. Async-signal-safe. */
static void write_cap_final(void)
{
    char detail[200], *p = detail;
    p = put_u64(p, log_dropped + log_dropped_w);
    if (log_failed) {
        p = put_str(p, " records not written after the log could not be written past ");
        p = put_u64(p, log_written);
        p = put_str(p, " bytes (");
        p = put_str(p, write_error_text(log_failed));
        p = put_str(p, ")");
    } else if (log_low) {
        p = put_str(p, " records not written after the log stopped at ");
        p = put_u64(p, log_written);
        p = put_str(p, " bytes (its disk below the logs' ");
        p = put_u64(p, rt_log_reserve_for(&log_reserve, g_rt.engine));
        p = put_str(p, "-byte reserve)");
    } else {
        p = put_str(p, " records not written after the log reached its ");
        p = put_u64(p, log_max);
        p = put_str(p, "-byte bound");
    }
    *p = '\0';
    write_cap_record(detail);
}

static void *log_writer(void *unused)
{
    (void)unused;
    on_writer = 1;
    lock();
    for (;;) {
        while (!pending() && !writer_stop) pthread_cond_wait(&log_work, &log_lock);
        if (!pending()) break; /* stopped with nothing left */
        const char *buf = pending_buf;
        size_t len = pending();
        int none = OWNER_NONE;
        if (!__atomic_compare_exchange_n(&pending_owner, &none, OWNER_WRITER, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE))
            break; /* a crash handler took it: the process ends */
        unlock();
        write_records(buf, len);
        __atomic_store_n(&pending_owner, OWNER_WROTE, __ATOMIC_RELEASE);
        lock();
        /* after the write: the file holds every record but those of the buffer being filled
         * (before the buffer is free: a crash handler that saw it free finds the mark set) */
        mark_set((unsigned long long)g_rt.log_dirty_since);
        __atomic_store_n(&pending_len, 0, __ATOMIC_RELEASE);
        pthread_cond_broadcast(&log_idle);
    }
    unlock();
    return NULL;
}

int rt_log_hand_off(int wait)
{
    if (log_len == 0) return 1;
    if (!writer_on) {
        int was = busy_enter(BUSY_WRITE);
        write_records(log_buf, log_len);
        buffer_begin(log_cur, log_start[log_cur] + log_len);
        log_len = 0;
        g_rt.log_dirty_since = 0;
        mark_set(0); /* after the write: the file holds every record logged so far */
        busy_leave(was);
        return 1;
    }
    lock();
    while (pending()) {
        if (!wait) {
            unlock();
            return 0;
        }
        pthread_cond_wait(&log_idle, &log_lock);
    }
    /* the mark keeps naming this buffer's oldest record until the writer wrote it */
    int was = busy_enter(BUSY_SWAP);
    __atomic_store_n(&pending_owner, OWNER_NONE, __ATOMIC_RELAXED);
    pending_buf = log_buf;
    __atomic_store_n(&pending_len, log_len, __ATOMIC_RELEASE);
    __atomic_signal_fence(__ATOMIC_SEQ_CST);
    int next = !log_cur;
    buffer_begin(next, log_start[log_cur] + log_len); /* the handed buffer keeps its words: written or not */
    log_buf = log_bufs[next];
    log_cur = next;
    log_len = 0;
    busy_leave(was);
    g_rt.log_dirty_since = 0;
    pthread_cond_signal(&log_work);
    unlock();
    return 1;
}

void ContractLogFlush(void)
{
    rt_log_hand_off(1);
    if (!writer_on) return;
    lock();
    while (pending()) pthread_cond_wait(&log_idle, &log_lock);
    unlock();
}

void ContractLogFlushIfOlder(RTIME ageNs)
{
    if (g_rt.log_dirty_since && GetTime() - g_rt.log_dirty_since >= ageNs) rt_log_hand_off(0);
}

RTIME ContractLogPendingSince(void) { return log_fd >= 0 ? g_rt.log_dirty_since : 0; }

RTIME rt_log_flush_ns(void)
{
    if (!log_mark) return LOG_FLUSH_NS;
    unsigned long long asked = __atomic_load_n(&log_mark[1], __ATOMIC_RELAXED);
    return asked >= LOG_FLUSH_WATCHED_MIN_NS && asked < LOG_FLUSH_NS ? (RTIME)asked : LOG_FLUSH_NS;
}

RTIME ContractLogFlushDelay(void) { return rt_log_flush_ns(); }

/* The first multiple of delayNs after `since`: when records logged since then are due. */
static RTIME first_boundary(RTIME since, RTIME delayNs) { return (since / delayNs + 1) * delayNs; }

RTIME ContractLogFlushDue(RTIME delayNs)
{
    RTIME since = g_rt.log_dirty_since;
    if (!since || delayNs <= 0) return since;
    RTIME due = first_boundary(since, delayNs);
    if (pending()) { /* the writer still writes: try again at the next boundary, not at once */
        RTIME now = GetTime();
        if (due <= now) due = first_boundary(now, delayNs);
    }
    return due;
}

void ContractLogFlushIfDue(RTIME now, RTIME delayNs)
{
    RTIME since = g_rt.log_dirty_since;
    if (since && delayNs > 0 && now >= first_boundary(since, delayNs)) rt_log_hand_off(0);
}

void rt_log_maybe_flush(RTIME now)
{
    ContractLogFlushIfDue(now, rt_log_flush_ns());
}

/* In a child forked by module code: the parent's log is the parent's (its writer thread is not
 * in the child; its records would be written twice). */
static void log_forget_in_child(void)
{
    if (log_fd >= 0) close(log_fd);
    log_fd = -1;
    log_len = 0;
    log_mark = NULL; /* the parent's page and buffers: left mapped, never written */
    log_bufs[0] = log_store[0];
    log_bufs[1] = log_store[1];
    log_buf = log_store[0];
    log_cur = 0;
    writer_on = 0;
    __atomic_store_n(&pending_len, 0, __ATOMIC_RELAXED);
    __atomic_store_n(&pending_owner, OWNER_NONE, __ATOMIC_RELAXED);
    __atomic_store_n(&log_busy, BUSY_NONE, __ATOMIC_RELAXED);
    g_rt.log_dirty_since = 0;
    pthread_mutex_init(&log_lock, NULL);
    pthread_cond_init(&log_work, NULL);
    pthread_cond_init(&log_idle, NULL);
}

static void log_init_once(void)
{
    pthread_mutexattr_t a;
    pthread_mutexattr_init(&a);
    pthread_mutexattr_setprotocol(&a, PTHREAD_PRIO_INHERIT);
    pthread_mutex_init(&log_lock, &a);
    pthread_mutexattr_destroy(&a);
    pthread_cond_init(&log_work, NULL);
    pthread_cond_init(&log_idle, NULL);
    pthread_atfork(NULL, NULL, log_forget_in_child);
}

/* Starts the writer: SCHED_OTHER, a small stack, every signal blocked (they are the module's). */
static void writer_start(void)
{
    pthread_once(&log_once, log_init_once);
    writer_stop = 0;
    pthread_attr_t attr;
    if (pthread_attr_init(&attr) != 0) return;
    struct sched_param sp = { .sched_priority = 0 };
    pthread_attr_setinheritsched(&attr, PTHREAD_EXPLICIT_SCHED);
    pthread_attr_setschedpolicy(&attr, SCHED_OTHER);
    pthread_attr_setschedparam(&attr, &sp);
    pthread_attr_setstacksize(&attr, WRITER_STACK);
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, &old);
    int r = pthread_create(&writer, &attr, log_writer, NULL);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    pthread_attr_destroy(&attr);
    /* EAGAIN: the kernel refused the thread, most likely at the process limit (RLIMIT_NPROC, the
     * pids cgroup), which counts threads: the line says so, the cause the run's other failures share */
    if (r == EAGAIN)
        fprintf(stderr, "%s: warning: no log writer thread (%s: a new thread was refused, most likely by the process limit, "
                        "which counts threads: 2 per module; a build service run raises it with --limit processes=N): "
                        "the module writes its log itself\n", g_rt.name, strerror(r));
    else if (r != 0)
        fprintf(stderr, "%s: warning: no log writer thread (%s): the module writes its log itself\n", g_rt.name, strerror(r));
    writer_on = r == 0;
}

static void writer_end(void)
{
    if (!writer_on) return;
    lock();
    writer_stop = 1;
    pthread_cond_signal(&log_work);
    unlock();
    pthread_join(writer, NULL);
    writer_on = 0;
}

void rt_log_close(void)
{
    if (log_fd < 0) return;
    ContractLogFlush();
    writer_end();
    if (log_capped) write_cap_final();
    close(log_fd);
    log_fd = -1;
    mark_close();
}

/* The crash handler's part (core.c on_crash_signal; async-signal-safe: write, clock_gettime,
 * nanosleep, atomics; no lock, no stdio, no allocation). Writes what the log holds and has not
 * written, in order: the buffer handed to the writer (itself if the writer has not begun it, else
 * it waits up to CRASH_WAIT_NS for the writer to end it), then the buffer being filled (unless the
 * module's thread was changing buffers or writing it itself: those records are skipped), then a
 * `module_crashed` record when `crashed` (a stop signal's handler, core.c on_fatal_signal: none);
 * within the bound (log-capped, as at exit); then the mark says 0. */
void rt_log_at_signal(int sig, int crashed)
{
    if (log_fd < 0) return;
    /* what this writes may interleave with a stalled writer's, and ends with records of its own:
     * a SIGKILL from here on is not recovered from the buffers */
    mark_broken();
    int busy = __atomic_load_n(&log_busy, __ATOMIC_RELAXED);
    __atomic_signal_fence(__ATOMIC_SEQ_CST);
    unsigned long long reserve = 0; /* bytes the writer may still write (it stalled) */
    size_t plen = pending();
    if (plen) {
        const char *pbuf = pending_buf;
        int none = OWNER_NONE;
        if (__atomic_compare_exchange_n(&pending_owner, &none, OWNER_CRASH, 0, __ATOMIC_ACQ_REL, __ATOMIC_ACQUIRE)) {
            write_records(pbuf, plen); /* the writer had not begun it */
        } else {
            /* the writer writes it: wait for the end of its write and its mark (file order), not
             * for ever (nanosleep: a SCHED_FIFO module leaves the CPU to it) */
            struct timespec step = { 0, 1000000 };
            for (RTIME waited = 0; !on_writer && waited < CRASH_WAIT_NS && pending(); waited += step.tv_nsec)
                nanosleep(&step, NULL);
            /* still writing (a stalled disk, or the crash is the writer's): written anyway, the room
             * counting its buffer as written */
            if (__atomic_load_n(&pending_owner, __ATOMIC_ACQUIRE) == OWNER_WRITER) reserve = plen;
        }
    }
    /* the buffer being filled: whole records up to log_len (a record being formatted is not in
     * it); skipped while it changes hands (unless not handed yet) or the module writes it itself */
    if (busy == BUSY_NONE || (busy == BUSY_SWAP && plen == 0)) {
        size_t len = __atomic_load_n(&log_len, __ATOMIC_ACQUIRE);
        if (len) write_records_r(log_buf, len, reserve);
    }
    /* a stop signal (SIGTERM, SIGINT, SIGHUP: the launcher terminating a module that did not end on
     * its KILL request): the records are kept, no record of its own (the launcher says it) */
    if (!crashed) {
        if (__atomic_load_n(&log_capped, __ATOMIC_RELAXED)) write_cap_final();
        mark_set(0);
        return;
    }
    /* the crash, a record like module_exit: `records=K` counts every record logged, this one included */
    log_records++;
    char detail[96], *d = detail;
    d = put_str(d, "signal ");
    d = put_u64(d, (unsigned long long)sig);
    d = put_str(d, " (");
    d = put_str(d, rt_crash_signal_name(sig));
    d = put_str(d, ") records=");
    d = put_u64(d, log_records);
    *d = '\0';
    if (__atomic_load_n(&log_capped, __ATOMIC_RELAXED)) {
        log_dropped++;
    } else {
        char rec[RECORD_MAX];
        char *end = put_record(rec, GetTime(), "module_crashed", "", -1, 0, detail);
        write_records_r(rec, (size_t)(end - rec), reserve);
    }
    if (__atomic_load_n(&log_capped, __ATOMIC_RELAXED)) write_cap_final();
    mark_set(0); /* nothing more will be written */
}
