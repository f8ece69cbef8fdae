/* After a module died without writing its CSV log (a SIGKILL: the kernel's OOM killer, the real-time
 * mode's RLIMIT_RTTIME; an _exit without its exit): contract-launch writes the records the module
 * had logged and not written, from the log buffers the module formatted them in, which live in its
 * flush mark's file (log_mark.h; CONTRACT_LOG_MARK=1, the build service's runs). The mark's words
 * say which bytes of the module's records each buffer holds and how many bytes of the file came
 * before its first record, so the file's size says exactly which bytes it lacks.
 *
 * Everything here was written by the sandboxed module: the folder is opened without following a
 * link, the mark and the log are regular files opened without following one nor waiting on a
 * FIFO, every word is checked against the buffers' size, only whole records are written (up to
 * the last line end), and the log's bound (CONTRACT_LOG_MAX_BYTES) holds. A mark whose words do
 * not add up is left alone: the log stays as the module left it. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "internal.h"
#include "log_mark.h"

/* Entries of the log folder looked at for the module's mark. */
#define RECOVER_ENTRIES 4096

/* Opens `name` in dfd: a regular file, no link followed, no wait on a FIFO; -1 otherwise. */
static int open_regular(int dfd, const char *name, int flags, struct stat *st)
{
    int fd = openat(dfd, name, flags | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return -1;
    if (fstat(fd, st) != 0 || !S_ISREG(st->st_mode)) {
        close(fd);
        return -1;
    }
    return fd;
}

/* The mark in dfd whose words name `pid` (its name in mark_name); -1 when there is none. */
static int find_mark(int dfd, long pid, unsigned long long *w, char *mark_name, size_t size)
{
    int lfd = dup(dfd);
    DIR *d = lfd >= 0 ? fdopendir(lfd) : NULL;
    if (!d) {
        if (lfd >= 0) close(lfd);
        return -1;
    }
    int found = -1;
    struct dirent *e;
    for (int seen = 0; found < 0 && seen < RECOVER_ENTRIES && (e = readdir(d)) != NULL; seen++) {
        size_t l = strlen(e->d_name);
        if (l <= 9 || l >= size || strcmp(e->d_name + l - 9, ".csv.mark") != 0) continue;
        struct stat st;
        int fd = open_regular(dfd, e->d_name, O_RDWR, &st);
        if (fd < 0) continue;
        if (st.st_size >= MARK_FILE_BYTES && pread(fd, w, MARK_WORDS * sizeof *w, 0) == (ssize_t)(MARK_WORDS * sizeof *w) &&
            w[MARK_WORD_MAGIC] == MARK_MAGIC && w[MARK_WORD_PID] == (unsigned long long)pid) {
            memcpy(mark_name, e->d_name, l + 1);
            found = fd;
        } else {
            close(fd);
        }
    }
    closedir(d);
    return found;
}

/* Writes all of buf (O_APPEND); 0 when it was. */
static int write_fully(int fd, const char *buf, size_t len)
{
    while (len > 0) {
        ssize_t n = write(fd, buf, len);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return -1;
        buf += n;
        len -= (size_t)n;
    }
    return 0;
}

static char recover_buf[LOG_BUF];

/* Each buffer's words name bytes within it (a hostile or torn page does not). */
static int buffers_in_bounds(const unsigned long long *w)
{
    for (int i = 0; i < 2; i++)
        if (w[MARK_WORD_LEN(i)] > LOG_BUF || w[MARK_WORD_START(i)] > (1ULL << 62)) return 0;
    return 1;
}

int rt_log_recover(const char *dir, long pid, RecoveredLog *out)
{
    memset(out, 0, sizeof *out);
    int dfd = open(dir && *dir ? dir : ".", O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (dfd < 0) return 0;
    unsigned long long w[MARK_WORDS];
    char mark_name[sizeof out->log];
    int mfd = find_mark(dfd, pid, w, mark_name, sizeof mark_name);
    if (mfd < 0) {
        close(dfd);
        return 0;
    }
    size_t name_len = strlen(mark_name) - 5; /* without ".mark" */
    memcpy(out->log, mark_name, name_len);
    out->log[name_len] = '\0';
    struct stat st;
    int lfd = -1;
    /* the buffers in the order of their bytes; each within its buffer */
    int first = w[MARK_WORD_START(0)] <= w[MARK_WORD_START(1)] ? 0 : 1;
    int order[2] = { first, !first };
    if (w[MARK_WORD_BROKEN] != 0 || !buffers_in_bounds(w)) {
        out->broken = 1; /* a capped log, a write error, a crash handler's own records: as it is */
        goto done;
    }
    lfd = open_regular(dfd, out->log, O_WRONLY | O_APPEND, &st);
    unsigned long long base = w[MARK_WORD_BASE];
    if (lfd < 0 || (unsigned long long)st.st_size < base) {
        out->broken = 1;
        goto done;
    }
    unsigned long long have = (unsigned long long)st.st_size - base; /* bytes of its records the file holds */
    /* within the log's bound, keeping the room its writer keeps for two `log-capped` records */
    unsigned long long room = rt_log_max_bytes(), used = (unsigned long long)st.st_size + 2 * RECORD_MAX;
    room = room > used ? room - used : 0;
    for (int k = 0; k < 2; k++) {
        int i = order[k];
        unsigned long long start = w[MARK_WORD_START(i)], len = w[MARK_WORD_LEN(i)];
        if (start + len <= have) continue; /* written */
        if (start > have) { /* a gap: the words do not add up */
            out->broken = 1;
            break;
        }
        size_t from = (size_t)(have - start), n = (size_t)(len - from);
        if (pread(mfd, recover_buf, n, (off_t)(MARK_PAGE + (size_t)i * LOG_BUF + from)) != (ssize_t)n) {
            out->broken = 1;
            break;
        }
        size_t whole = 0; /* up to the last line end within the bound: so many records */
        unsigned long long records = 0;
        for (size_t b = 0; b < n && b < room; b++)
            if (recover_buf[b] == '\n') {
                whole = b + 1;
                records++;
            }
        if (whole < n) out->dropped = 1;
        if (whole == 0) break;
        if (write_fully(lfd, recover_buf, whole) != 0) {
            out->broken = 1;
            break;
        }
        out->records += records;
        out->bytes += whole;
        have += whole;
        room -= whole;
        if (whole < n) break;
    }
done:
    if (lfd >= 0) close(lfd);
    /* the log is whole now, as far as it goes: its mark names nothing more (the live trace's reader
     * stops waiting for it), then goes, as the module's own close would remove it */
    unsigned long long zero = 0;
    if (pwrite(mfd, &zero, sizeof zero, MARK_WORD_MAGIC * sizeof zero) < 0 || pwrite(mfd, &zero, sizeof zero, 0) < 0) {
        /* a mark that cannot be written is removed all the same */
    }
    close(mfd);
    unlinkat(dfd, mark_name, 0);
    close(dfd);
    return 1;
}
