/* The disk reserve of the CSV logs (CONTRACT_LOG_DISK_RESERVE_BYTES, docs/runtime-api.md "CSV
 * log"): CONTRACT_LOG_MAX_BYTES bounds each log by itself, so several logs growing together filled
 * the build service's work dir (and the run was killed by its disk limit) before any of them
 * reached its bound. With a reserve R, a log also stops — as at its bound, a `log-capped` record
 * saying why — once the file system it is on has less than R bytes free; ORD's (deadline
 * misses) only below CONTRACT_LOG_ENGINE_DISK_RESERVE_BYTES (default R/4), and a supervisor's
 * (rule changes: few records, the run's story and its end) below
 * CONTRACT_LOG_SUPERVISOR_DISK_RESERVE_BYTES (default R/8), so that they go on after the modules'
 * logs stopped, a supervisor's after ORD's, and every log keeps room for its last records. The build service gives
 * both (docs/sandbox.md "The disk limit"): they also keep the part of the work dir that its memory
 * limit cannot hold (a tmpfs's files are memory) out of the logs' reach.
 * The free space is asked of the kernel (fstatvfs) before a write, not per record: once per
 * LOG_RESERVE_CHECK_BYTES written while the disk has room, more often as it nears the reserve (a
 * log then writes at most 1/LOG_RESERVE_SHARERS of what is left above it before it looks again),
 * and a write that would leave less than the reserve is not made: the logs of a run, all flooding,
 * go past the reserve only by what they wrote between a look and their write, where each could go
 * 128 KiB past it (a look per 64 KiB, after it a 64 KiB buffer).
 * 0 or unset: no reserve (the bound alone, as contract-launch run by hand on a disk of its own). */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/statvfs.h>
#include "internal.h"
#include "log_reserve.h"

/* A byte count from the environment; `fallback` when unset or wrong (said on stderr when `warn`). */
static unsigned long long env_bytes(const char *name, unsigned long long fallback, int warn)
{
    const char *v = getenv(name);
    if (!v || !*v) return fallback;
    char *end;
    errno = 0;
    unsigned long long n = strtoull(v, &end, 10);
    if (errno || *end || *v == '-' || *v == ' ') {
        if (warn) fprintf(stderr, "%s: warning: %s='%s' is not a byte count: using %llu\n", g_rt.name, name, v, fallback);
        return fallback;
    }
    return n;
}

void rt_log_reserve_read(LogReserve *r, int warn)
{
    r->modules = env_bytes("CONTRACT_LOG_DISK_RESERVE_BYTES", 0, warn);
    r->engines = env_bytes("CONTRACT_LOG_ENGINE_DISK_RESERVE_BYTES", r->modules / 4, warn);
    r->supervisors = env_bytes("CONTRACT_LOG_SUPERVISOR_DISK_RESERVE_BYTES", r->modules / 8, warn);
}

const char *rt_log_reserve_name(int engine)
{
    return engine == RT_ENGINE_NONE ? "CONTRACT_LOG_DISK_RESERVE_BYTES"
           : engine == RT_ENGINE_ORD ? "CONTRACT_LOG_ENGINE_DISK_RESERVE_BYTES"
                                     : "CONTRACT_LOG_SUPERVISOR_DISK_RESERVE_BYTES";
}

unsigned long long rt_log_reserve_for(const LogReserve *r, int engine)
{
    return engine == RT_ENGINE_NONE ? r->modules : engine == RT_ENGINE_ORD ? r->engines : r->supervisors;
}

int rt_log_reserve_reached(int fd, unsigned long long reserve, unsigned long long len, unsigned long long *free_bytes,
                           unsigned long long *budget)
{
    /* far from the reserve, a look per LOG_RESERVE_CHECK_BYTES written, these `len` among them */
    *budget = len < LOG_RESERVE_CHECK_BYTES ? LOG_RESERVE_CHECK_BYTES - len : 0;
    if (reserve == 0 || fd < 0) return 0;
    struct statvfs s;
    if (fstatvfs(fd, &s) != 0) return 0; /* not known: the bound and the disk's own refusal still hold */
    unsigned long long unit = s.f_frsize ? (unsigned long long)s.f_frsize : (unsigned long long)s.f_bsize;
    unsigned long long avail = (unsigned long long)s.f_bavail * unit;
    if (free_bytes) *free_bytes = avail;
    if (avail < reserve + len) return 1;
    unsigned long long share = (avail - reserve - len) / LOG_RESERVE_SHARERS;
    if (share < *budget) *budget = share;
    return 0;
}
