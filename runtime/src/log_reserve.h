/* The CSV logs' disk reserve (log_reserve.c; docs/runtime-api.md "CSV log"). Library-internal. */
#ifndef CONTRACT_LOG_RESERVE_H
#define CONTRACT_LOG_RESERVE_H

/* Bytes written to a log between two looks at its file system's free space. */
#define LOG_RESERVE_CHECK_BYTES (64ULL * 1024)

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
/* 1 when the file system of `fd` has fewer than `reserve` bytes free for an unprivileged writer
 * (`*free_bytes` then says how many); 0 when it has more, when reserve is 0, or when it cannot
 * tell. One fstatvfs. */
int rt_log_reserve_reached(int fd, unsigned long long reserve, unsigned long long *free_bytes);

#endif
