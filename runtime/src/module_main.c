/* `main` of every module executable: checks the generated interface tables, creates the
 * mailbox and input queues in the run directory, opens the CSV log, sets the priority, then
 * calls the generated ModuleMain. Everything it created is removed when the process ends. */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "internal.h"

static void shutdown_at_exit(void) { ContractShutdown(); }

static int check_size(const char *table, int port, size_t size, size_t max)
{
    if (size == 0 || size > max) {
        fprintf(stderr, "%s: error: %s port %d has size %zu: it must be between 1 and %zu bytes (runtime limit)\n",
                MODULE_NAME, table, port, size, max);
        return -1;
    }
    return 0;
}

#define COUNT_AND_CHECK(table, var_n, max)                                                       \
    for (var_n = 0; table[var_n].Variable != NULL; var_n++) {                                   \
        if (check_size(#table, table[var_n].Port, table[var_n].Size, max) != 0) bad = 1;        \
        for (int j = 0; j < var_n; j++)                                                           \
            if (table[j].Port == table[var_n].Port) {                                             \
                fprintf(stderr, "%s: error: %s lists port %d twice\n", MODULE_NAME, #table, table[j].Port); \
                bad = 1;                                                                          \
            }                                                                                     \
    }

static int bind_tables(void)
{
    int bad = 0;
    g_rt.iuse = IUSE; g_rt.iproduce = IPRODUCE; g_rt.ireact = IREACT; g_rt.idetect = IDETECT;
    g_rt.param_in = PARAM_SIZE_IN; g_rt.param_out = PARAM_SIZE_OUT;
    COUNT_AND_CHECK(IUSE, g_rt.n_iuse, (size_t)CONTRACT_DATA_PORT_MAX)
    COUNT_AND_CHECK(IPRODUCE, g_rt.n_iproduce, (size_t)CONTRACT_DATA_PORT_MAX)
    COUNT_AND_CHECK(IREACT, g_rt.n_ireact, (size_t)CONTRACT_REQUEST_DATA_MAX)
    COUNT_AND_CHECK(IDETECT, g_rt.n_idetect, (size_t)CONTRACT_REQUEST_DATA_MAX)
    for (int i = 0; PARAM_SIZE_IN[i] != PARAM_SIZE_TERM; i++)
        if (check_size("PARAM_SIZE_IN", i, PARAM_SIZE_IN[i], CONTRACT_REQUEST_DATA_MAX) != 0) bad = 1;
    for (int i = 0; PARAM_SIZE_OUT[i] != PARAM_SIZE_TERM; i++)
        if (check_size("PARAM_SIZE_OUT", i, PARAM_SIZE_OUT[i], CONTRACT_REQUEST_DATA_MAX) != 0) bad = 1;
    g_rt.is_module = 1;
    return bad ? -1 : 0;
}

int main(int argc, char *argv[])
{
    setvbuf(stdout, NULL, _IOLBF, 0); /* lines reach the launcher as they are printed */
    if (!rt_valid_name(MODULE_NAME)) {
        fprintf(stderr, "libmodule: error: MODULE_NAME '%s' is not a valid module name\n", MODULE_NAME);
        return 2;
    }
    snprintf(g_rt.name, sizeof g_rt.name, "%s", MODULE_NAME);
    if (bind_tables() != 0) return 2;
    if (rt_init_run_dir() != 0) return 2;
    rt_install_signal_cleanup();
    atexit(shutdown_at_exit);
    if (rt_bind_mailbox() != 0) return 2;
    if (rt_dataflow_setup() != 0 || rt_eventflow_setup() != 0) return 2;
    rt_log_open();
    char detail[64];
    snprintf(detail, sizeof detail, "pid=%ld priority=%d", (long)getpid(), MODULE_PRIORITY);
    ContractLog("module_started", "", -1, 0, detail);
    if (ContractSetPriority(MODULE_PRIORITY) == 1) rt_lock_memory(); /* real time: no page faults */
    /* the process is there (the launcher learns its name, `--kill` finds it); it is ready, for the
     * launcher, once it first looks for a request: <NAME>.ready (rt_mark_ready) */
    if (rt_write_pid_file() != 0) return 2;
    int rc = ModuleMain(argc, (const char **)argv);
    rt_outbox_drain(); /* its records before the last one */
    rt_eventflow_say_waits(); /* PostEvent's waits not told yet */
    /* records=N counts this record too: a reader of the log can tell none is missing */
    snprintf(detail, sizeof detail, "status=%d records=%llu", rc, rt_log_records() + 1);
    ContractLog("module_exit", "", -1, 0, detail);
    ContractShutdown();
    return rc;
}
