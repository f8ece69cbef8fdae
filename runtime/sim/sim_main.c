/*
 * sim_main.c — the simulation executable of one project (docs/simulation.md): the engine cores
 * and this harness (build/sim/libcontractsim.a) linked with the project's generated tables and
 * `sim_tables.c`, which the runner writes:
 *
 *     const ContractSupervisorVocabulary *const SIM_SUPERVISORS[] = {&SUP_VOCABULARY, ..., NULL};
 *     const ContractOrdVocabulary *const SIM_ORD = &ORD_VOCABULARY;   (or NULL)
 *
 * Reads the steps on stdin, writes one JSON record per step on stdout (sim_protocol.h). What the
 * user functions of the datatype files print goes to a temporary file, read back into each
 * step's "output". Exit 0 when every expectation passed, 1 otherwise, 2 on a setup error.
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim_protocol.h"

extern const ContractSupervisorVocabulary *const SIM_SUPERVISORS[];
extern const ContractOrdVocabulary *const SIM_ORD;

/* The session whose virtual clock GetTime() reads. */
static SimSession *g_session;

/* libmodule's clock (RTIME GetTime(void), RTIME = int64_t), for the project's test and compute
 * functions: in a simulation it is the virtual time, ns since the simulation started. */
int64_t GetTime(void);
int64_t GetTime(void) { return g_session ? sim_session_now(g_session) : 0; }

int main(void) {
    /* our records go to the real stdout; fd 1 becomes the capture file for user prints */
    int out_fd = dup(1);
    FILE *out = out_fd >= 0 ? fdopen(out_fd, "w") : NULL;
    FILE *cap = tmpfile();
    if (!out || !cap) {
        fprintf(stderr, "contract-sim: cannot set up its output\n");
        return 2;
    }
    fflush(stdout);
    if (dup2(fileno(cap), 1) < 0) {
        fprintf(stderr, "contract-sim: cannot capture stdout\n");
        return 2;
    }
    int nsups = 0;
    while (SIM_SUPERVISORS[nsups]) nsups++;
    char err[512] = "";
    SimSession *s = sim_session_create(SIM_SUPERVISORS, nsups, SIM_ORD, out, 1, err, sizeof err);
    if (!s) {
        fprintf(stderr, "contract-sim: %s\n", err);
        return 2;
    }
    g_session = s;
    char *line = malloc(SIM_MAX_LINE + 2);
    if (!line) return 2;
    int ended = 0;
    while (!ended && fgets(line, SIM_MAX_LINE + 2, stdin)) {
        size_t n = strlen(line);
        if (n && line[n - 1] == '\n') line[--n] = '\0';
        else if (n > SIM_MAX_LINE) { /* too long: skip the rest of it, refuse it */
            int c;
            while ((c = getchar()) != EOF && c != '\n') {}
            strcpy(line, "0\t0\ttoo-long");
        }
        ended = sim_session_line(s, line);
    }
    int failures = sim_session_failures(s);
    g_session = NULL;
    sim_session_destroy(s);
    free(line);
    fclose(out);
    return failures ? 1 : 0;
}
