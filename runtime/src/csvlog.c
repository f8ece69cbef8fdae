/* The per-module CSV log: <LOG_DIR>/<MODULE>_<d>-<Mon>-<Y>-<H>h<M>m<S>s.csv (report section 8.2
 * naming, without the space). Columns: see docs/runtime-api.md. Records are formatted by hand
 * into a 64 KiB buffer (no stdio on the hot path) and written when the module waits and the
 * oldest unwritten record is older than LOG_FLUSH_NS, when the buffer fills, and at exit. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include "internal.h"

#define CSV_HEADER "mono_ns,wall_time,module,event,peer,port,size,detail\n"
#define LOG_BUF 65536
#define RECORD_MAX 1024

static int log_fd = -1;
static char log_buf[LOG_BUF];
static size_t log_len;

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
    char path[PATH_MAX];
    snprintf(path, sizeof path, "%s/%s_%d-%s-%d-%02dh%02dm%02ds.csv", dir, g_rt.name, tm.tm_mday, months[tm.tm_mon],
             tm.tm_year + 1900, tm.tm_hour, tm.tm_min, tm.tm_sec);
    log_fd = open(path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (log_fd < 0) {
        fprintf(stderr, "%s: warning: cannot open log %s: %s (no CSV log)\n", g_rt.name, path, strerror(errno));
        return -1;
    }
    struct stat st;
    if (fstat(log_fd, &st) == 0 && st.st_size == 0 && write(log_fd, CSV_HEADER, sizeof CSV_HEADER - 1) < 0)
        fprintf(stderr, "%s: warning: cannot write log %s: %s\n", g_rt.name, path, strerror(errno));
    log_len = 0;
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

/* CSV field of at most `max` characters, quoted when it holds a comma, quote or line break. */
static char *put_field(char *p, const char *s, size_t max)
{
    if (!s) return p;
    size_t n = strnlen(s, max);
    if (!memchr(s, ',', n) && !memchr(s, '"', n) && !memchr(s, '\n', n) && !memchr(s, '\r', n)) {
        memcpy(p, s, n);
        return p + n;
    }
    *p++ = '"';
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '"') *p++ = '"';
        *p++ = (s[i] == '\n' || s[i] == '\r') ? ' ' : s[i];
    }
    *p++ = '"';
    return p;
}

void ContractLog(const char *event, const char *peer, int port, size_t size, const char *detail)
{
    if (log_fd < 0) return;
    if (log_len + RECORD_MAX > LOG_BUF) ContractLogFlush();
    RTIME mono = GetTime();
    struct timespec wall;
    clock_gettime(CLOCK_REALTIME, &wall);
    static time_t cached_sec = -1;
    static char cached_text[80];
    if (wall.tv_sec != cached_sec) { /* calendar conversion once per second */
        struct tm tm;
        gmtime_r(&wall.tv_sec, &tm);
        snprintf(cached_text, sizeof cached_text, "%04d-%02d-%02dT%02d:%02d:%02d.", tm.tm_year + 1900, tm.tm_mon + 1,
                 tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec);
        cached_sec = wall.tv_sec;
    }
    char *p = log_buf + log_len;
    p = put_u64(p, (unsigned long long)mono);
    *p++ = ',';
    p = put_str(p, cached_text);
    long us = wall.tv_nsec / 1000;
    for (long div = 100000; div > 0; div /= 10) *p++ = (char)('0' + (us / div) % 10);
    *p++ = 'Z';
    *p++ = ',';
    p = put_str(p, g_rt.name);
    *p++ = ',';
    p = put_field(p, event, 64);
    *p++ = ',';
    p = put_field(p, peer, CONTRACT_NAME_MAX);
    *p++ = ',';
    if (port >= 0) p = put_u64(p, (unsigned long long)port);
    *p++ = ',';
    p = put_u64(p, (unsigned long long)size);
    *p++ = ',';
    p = put_field(p, detail, 400);
    *p++ = '\n';
    log_len = (size_t)(p - log_buf);
    if (!g_rt.log_dirty_since) g_rt.log_dirty_since = mono;
}

void ContractLogFlush(void)
{
    size_t off = 0;
    while (log_fd >= 0 && off < log_len) {
        ssize_t n = write(log_fd, log_buf + off, log_len - off);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break; /* disk full: the records are lost, the module goes on */
        off += (size_t)n;
    }
    log_len = 0;
    g_rt.log_dirty_since = 0;
}

void ContractLogFlushIfOlder(RTIME ageNs)
{
    if (g_rt.log_dirty_since && GetTime() - g_rt.log_dirty_since >= ageNs) ContractLogFlush();
}

void rt_log_maybe_flush(RTIME now)
{
    if (g_rt.log_dirty_since && now - g_rt.log_dirty_since >= LOG_FLUSH_NS) ContractLogFlush();
}

void rt_log_close(void)
{
    if (log_fd < 0) return;
    ContractLogFlush();
    close(log_fd);
    log_fd = -1;
}
