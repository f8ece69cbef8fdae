/* Minimal C test harness: a registry of test functions, CHECK macros, and helpers that start
 * module executables in a fresh run directory and talk to them as the client "tester". */
#ifndef TEST_HARNESS_H
#define TEST_HARNESS_H
#include <stddef.h>
#include <sys/types.h>
#include "libmodule/libmodule.h"

typedef void (*TestFn)(void);
typedef struct { const char *name; TestFn fn; } TestCase;

extern int h_failures;
extern int h_active;            /* set by h_setup, cleared by h_teardown (the runner tears down after a REQUIRE) */          /* failures of the current test */
extern const char *h_bin_dir;   /* where the test executables are (argv[1] of the runner) */
extern char h_run_dir[600], h_log_dir[600], h_work_dir[512];

#define CHECK(cond) do { if (!(cond)) { h_fail(__FILE__, __LINE__, #cond); } } while (0)
#define CHECK_MSG(cond, ...) do { if (!(cond)) { h_failf(__FILE__, __LINE__, __VA_ARGS__); } } while (0)
#define REQUIRE(cond) do { if (!(cond)) { h_fail(__FILE__, __LINE__, #cond); return; } } while (0)

void h_fail(const char *file, int line, const char *what);
void h_failf(const char *file, int line, const char *fmt, ...) __attribute__((format(printf, 3, 4)));

/* Fresh work dir with run/ and logs/, CONTRACT_* env set, client mailbox "tester". */
int h_setup(const char *test);
/* Kill what is left, check that the run directory holds no runtime file, remove the work dir. */
void h_teardown(void);
/* Start a module executable (h_bin_dir/<exe>) and wait until its mailbox answers. */
pid_t h_spawn_module(const char *exe, const char *name);
/* Run a command (argv[0] relative to h_bin_dir if it has no '/'), output to file; returns exit status (or 128+signal). */
int h_run(char *const argv[], const char *out_file, int timeout_ms);
/* Wait for a REQ_EVENT from module `from` on target port `port`. 1 found, 0 timeout. */
int h_wait_event(const char *from, int port, int timeout_ms, RequestMessage *msg);
/* Wait for an ack; 1 found, 0 timeout. */
int h_wait_ack(const char *from, int ackId, int mask, int timeout_ms, RequestMessage *msg);
/* Did this process exit within timeout_ms? Returns exit status, 128+signal, or -1 if still running. */
int h_wait_exit(pid_t pid, int timeout_ms);
/* 1 when the tests are built with AddressSanitizer and it reports crash signal `sig` itself
   (SIGSEGV, SIGBUS, SIGFPE: its defaults): the module's crash then ends with ASan's report and exit
   status 1, not the crash report and the signal (core.c) */
int h_asan_reports(int sig);
/* How a module that crashes by `sig` ends, as h_wait_exit says it: 128 + sig, or 1 when ASan reports it */
int h_crash_status(int sig);
/* Whole file into a malloc'd string (NULL if missing). */
char *h_read_file(const char *path);
/* Path of the first file of h_log_dir whose name starts with `prefix` and ends with `suffix` (0: none). */
int h_find_log_file(const char *prefix, const char *suffix, char *out, size_t cap);
/* Concatenation of every file of h_log_dir whose name starts with prefix. */
char *h_read_logs(const char *prefix);
/* This process's stderr into <work dir>/stderr.txt (its path in path): the fd to give back to
 * h_stderr_back, -1 when it could not. */
int h_stderr_to_file(char *path, size_t cap);
/* stderr back where it was (the fd h_stderr_to_file gave). */
void h_stderr_back(int saved);
/* Number of entries in a directory (-1 if it does not exist). */
int h_count_entries(const char *dir);
/* 1 if /proc/net/unix lists a socket whose path contains `text`. */
int h_unix_socket_listed(const char *text);
RequestMessage *h_msg(void);  /* a heap RequestMessage, freed at teardown */

#endif
