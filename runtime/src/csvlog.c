/* The per-module CSV log: <LOG_DIR>/<MODULE>_<d>-<Mon>-<Y>-<H>h<M>m<S>s.csv (report section 8.2
 * naming, without the space). Columns: see docs/runtime-api.md. Buffered; flushed when the
 * module waits and the oldest unflushed record is older than LOG_FLUSH_NS, and at exit. */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include "internal.h"

#define CSV_HEADER "mono_ns,wall_time,module,event,peer,port,size,detail\n"

static char log_buffer[1 << 16];

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
    g_rt.log = fopen(path, "a");
    if (!g_rt.log) {
        fprintf(stderr, "%s: warning: cannot open log %s: %s (no CSV log)\n", g_rt.name, path, strerror(errno));
        return -1;
    }
    setvbuf(g_rt.log, log_buffer, _IOFBF, sizeof log_buffer);
    if (ftell(g_rt.log) == 0) fputs(CSV_HEADER, g_rt.log);
    fflush(g_rt.log);
    return 0;
}

static void csv_field(FILE *f, const char *s)
{
    if (!s) return;
    if (strpbrk(s, ",\"\n\r") == NULL) { fputs(s, f); return; }
    fputc('"', f);
    for (; *s; s++) {
        if (*s == '"') fputc('"', f);
        fputc(*s == '\n' || *s == '\r' ? ' ' : *s, f);
    }
    fputc('"', f);
}

void ContractLog(const char *event, const char *peer, int port, size_t size, const char *detail)
{
    if (!g_rt.log) return;
    RTIME mono = GetTime();
    struct timespec wall;
    clock_gettime(CLOCK_REALTIME, &wall);
    struct tm tm;
    gmtime_r(&wall.tv_sec, &tm);
    fprintf(g_rt.log, "%lld,%04d-%02d-%02dT%02d:%02d:%02d.%06ldZ,%s,%s,", (long long)mono, tm.tm_year + 1900,
            tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, wall.tv_nsec / 1000, g_rt.name, event);
    csv_field(g_rt.log, peer);
    if (port >= 0) fprintf(g_rt.log, ",%d,%zu,", port, size); else fprintf(g_rt.log, ",,%zu,", size);
    csv_field(g_rt.log, detail);
    fputc('\n', g_rt.log);
    if (!g_rt.log_dirty_since) g_rt.log_dirty_since = mono;
}

void ContractLogFlush(void)
{
    if (g_rt.log) fflush(g_rt.log);
    g_rt.log_dirty_since = 0;
}

void rt_log_maybe_flush(RTIME now)
{
    if (g_rt.log_dirty_since && now - g_rt.log_dirty_since >= LOG_FLUSH_NS) ContractLogFlush();
}

void rt_log_close(void)
{
    if (!g_rt.log) return;
    fclose(g_rt.log);
    g_rt.log = NULL;
    g_rt.log_dirty_since = 0;
}
