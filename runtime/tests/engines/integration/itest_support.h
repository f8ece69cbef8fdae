/*
 * itest_support.h — what the integration scenarios share: the pass/fail counters, running
 * contract-launch on a set of executables, and reading what the processes left behind
 * (module traces written by imod.c/amod.c, launcher output, CSV logs of libmodule).
 */
#ifndef ITEST_SUPPORT_H
#define ITEST_SUPPORT_H

#include <stddef.h>
#include <sys/types.h>

/** Records one check ("ok  " / "FAIL" line on stdout). Returns ok. */
int check(int ok, const char *what);
/** Number of failed checks so far. */
int itest_failed(void);
/** Number of passed checks so far. */
int itest_passed(void);

/** One scenario's paths, all under the test's root directory. */
typedef struct Scenario {
    char run[512];     /* run directory given to the launcher                    */
    char logs[512];    /* CSV log directory (one per scenario: names hold the second) */
    char out[512];     /* ITEST_OUT: the modules' traces                         */
    char launch[512];  /* the launcher's stdout + stderr                         */
    char stats[600];   /* CONTRACT_ORD_STATS: ORD's figures (out/ord.json)        */
    int failed_before; /* itest_failed() when the scenario began                  */
    const char *stop_first; /* contract-launch --stop-first (NULL: none; scenario_begin) */
} Scenario;

/** Makes root/<name>/{out,logs}, sets ITEST_OUT and CONTRACT_ORD_STATS for the processes to
 *  come. Returns 1, or 0 after a failed check naming the scenario. */
int scenario_begin(Scenario *s, const char *root, const char *name);
/** 1 if a check of this scenario failed (then print what helps to understand it). */
int scenario_failed(const Scenario *s);
/** Starts contract-launch as scenario_launch does (`duration` NULL: none, it runs until stopped),
 *  without waiting for it; its pid, or -1. */
pid_t scenario_spawn(const Scenario *s, const char *bin_dir, const char *launcher, const char *start,
                     const char *duration, const char *const *names);
/** Runs contract-launch with `start` for `duration` seconds on the executables `names` (NULL
 *  terminated) of `bin_dir`. Returns 1 if the launcher exited 0. */
int scenario_launch(const Scenario *s, const char *bin_dir, const char *launcher, const char *start,
                    const char *duration, const char *const *names);

/** A file's contents (up to 1 MiB, NUL-terminated) or NULL; free() it. */
char *slurp(const char *path);
/** Prints on stderr the last `max` bytes of a failed scenario's launcher output `txt` (NULL: none). */
void say_output_tail(const char *scenario, const char *txt, size_t max);
/** The contents of `module`'s CSV log in s->logs (the first file named <module>_*.csv), or NULL. */
char *read_csv_log(const Scenario *s, const char *module);
/** The integer value of "key" in a flat JSON object (ORD's stats), or -1. */
long json_number(const char *json, const char *key);
/** mono_ns of the first CSV record at or after `from` (a position in csv) whose line contains
 *  `text`; -1 if none. *at (may be NULL) receives the position after that line. */
long long csv_time_of(const char *csv, const char *from, const char *text, const char **at);
/** How many times `text` occurs in s (NULL: 0). */
int count_of(const char *s, const char *text);
/** How many lines of s contain both a and b. */
int lines_with(const char *s, const char *a, const char *b);
/* The sum of the `key=N` values of the lines of s that hold text (0 for a line without key). */
long long sum_of_key(const char *s, const char *text, const char *key);

/** What imod.c writes to <out>/<name>.trace. */
#define TRACE_MAX 256
typedef struct Trace {
    long long start[TRACE_MAX], end[TRACE_MAX];
    long id[TRACE_MAX];   /* the AckID (release id) of each START */
    long got[TRACE_MAX], param;
    int nstart, nend, ngot;
    int slow;             /* index of the slow activation (IMOD_SLOW_AT), or -1 */
} Trace;
int read_trace(const char *dir, const char *name, Trace *t);

#endif
