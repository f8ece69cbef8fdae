/* The CSV logs' disk reserve (log_reserve.c; docs/runtime-api.md "CSV log"). Library-internal. */
#ifndef CONTRACT_LOG_RESERVE_H
#define CONTRACT_LOG_RESERVE_H

/* Bytes written to a log between two looks at its file system's free space, at most: far from the
 * reserve. */
#define LOG_RESERVE_CHECK_BYTES (64ULL * 1024)
/* Near it, a log writes at most 1/LOG_RESERVE_SHARERS of what is left above the reserve before it
 * looks again (the logs of a run share what is left: that many writing at once cannot all go past
 * it unseen), so the looks come closer as the free space nears the reserve: at every write once
 * less than LOG_RESERVE_SHARERS bytes are left. */
#define LOG_RESERVE_SHARERS 16ULL

typedef struct {
    unsigned long long modules; /* CONTRACT_LOG_DISK_RESERVE_BYTES (0 when unset: none)              */
    unsigned long long engines; /* ORD's: CONTRACT_LOG_ENGINE_DISK_RESERVE_BYTES (unset: a quarter of modules') */
    unsigned long long supervisors; /* CONTRACT_LOG_SUPERVISOR_DISK_RESERVE_BYTES (unset: an eighth of modules') */
} LogReserve;

/* Reads both (a wrong value: its default, said on stderr when `warn`). */
void rt_log_reserve_read(LogReserve *r, int warn);
/* The reserve a process keeps (engine: RT_ENGINE_*): ORD's log goes on below the modules' one, a
 * supervisor's below ORD's. */
unsigned long long rt_log_reserve_for(const LogReserve *r, int engine);
/* The environment variable that gives it. */
const char *rt_log_reserve_name(int engine);
/* 1 when the file system of `fd` has fewer than `reserve` + `len` bytes free for an unprivileged
 * writer: writing `len` more bytes would leave less than the reserve (`*free_bytes` then says how
 * many it has); 0 when it has more, when reserve is 0, or when it cannot tell. `*budget`: the bytes
 * the log may write after these `len` before it looks again (LOG_RESERVE_CHECK_BYTES with these
 * `len`, less near the reserve: LOG_RESERVE_SHARERS). One fstatvfs. */
int rt_log_reserve_reached(int fd, unsigned long long reserve, unsigned long long len, unsigned long long *free_bytes,
                           unsigned long long *budget);

#endif
