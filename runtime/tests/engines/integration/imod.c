/*
 * imod.c — a synchronous module for the engines' integration test, built three times
 * (-DIMOD_NAME='"IMA"' ...). Request loop in the style of the report's skeleton: each START
 * is one activation: it drains its input data port, works IMOD_WORK_NS (clock_nanosleep), posts
 * an activation counter on its output data port and acks ACK_FINISHED with the START's AckID.
 * With -DIMOD_SLOW_AT=n, its n-th activation first posts n on its output event port 0 ("I am
 * in my slow run") and then works IMOD_SLOW_NS instead. With -DIMOD_STUCK_AT=n, its n-th
 * activation never returns (a stuck exec region, asleep so as not to take a CPU): it no longer
 * reads its mailbox, and ends only on the launcher's SIGTERM. With -DIMOD_KILLED_AT=n, its n-th
 * activation is killed (SIGKILL, as by the OOM killer: its mailbox stays, stale, never read
 * again). It writes what it observes to
 * $ITEST_OUT/<name>.trace: "start <ns> <AckID>", "slow", "stuck", "killed", "got <value>", "end <ns>",
 * "param <v>".
 */
#define _GNU_SOURCE
#include <libmodule/libmodule.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "imodule.h"

#ifndef IMOD_NAME
#define IMOD_NAME "IMA"
#endif
#ifndef IMOD_WORK_NS
#define IMOD_WORK_NS 300000 /* simulated work per activation */
#endif
#ifndef IMOD_SLOW_AT
#define IMOD_SLOW_AT 0 /* 0: no slow activation */
#endif
#ifndef IMOD_STUCK_AT
#define IMOD_STUCK_AT 0 /* 0: never stuck */
#endif
#ifndef IMOD_KILLED_AT
#define IMOD_KILLED_AT 0 /* 0: never killed */
#endif
#ifndef IMOD_SLOW_NS
#define IMOD_SLOW_NS 300000000L /* work of the slow activation: many periods of the tests */
#endif

MODULE_DESCRIPTION("engines integration test module");
MODULE_AUTHOR("engines tests");

static long in_value, out_value, param_gain, slow_event;
char MODULE_NAME[] = IMOD_NAME;
int MODULE_PRIORITY = 50;
ModuleUse IUSE[] = {{&in_value, 0, sizeof(long), "---", 0, 1}, IUSE_TERM};
ModuleProduce IPRODUCE[] = {{&out_value, 0, sizeof(long)}, IPRODUCE_TERM};
ModuleReact IREACT[] = {IREACT_TERM};
ModuleDetect IDETECT[] = {{&slow_event, 0, sizeof(long)}, IDETECT_TERM};
size_t PARAM_SIZE_IN[] = {sizeof(long), PARAM_SIZE_TERM};
size_t PARAM_SIZE_OUT[] = {PARAM_SIZE_TERM};

int ModuleMain(int argc, const char *argv[]) {
    (void)argc;
    (void)argv;
    FILE *trace = imodule_open_trace(MODULE_NAME);
    RequestMessage *m = malloc(sizeof *m);
    if (!m) return 1;
    RTIME pt, rt;
    long activations = 0;
    for (;;) {
        if (!WaitForRequest(m)) break;
        if (imodule_connect(m)) continue;
        switch (m->Type) {
        case REQ_START: {
            if (trace) fprintf(trace, "start %lld %d\n", (long long)GetTime(), m->Param.Start.AckID);
            while (GetData(&in_value, &pt, &rt) == 1)
                if (trace) fprintf(trace, "got %ld\n", in_value);
            long work_ns = IMOD_WORK_NS;
            if (++activations == IMOD_STUCK_AT) {
                if (trace) fprintf(trace, "stuck\n");
                for (;;) pause();
            }
            if (activations == IMOD_KILLED_AT) {
                if (trace) fprintf(trace, "killed\n");
                raise(SIGKILL);
            }
            if (activations == IMOD_SLOW_AT) {
                if (trace) fprintf(trace, "slow\n");
                slow_event = activations;
                PostEvent(&slow_event);
                work_ns = IMOD_SLOW_NS;
            }
            struct timespec work = {work_ns / 1000000000L, work_ns % 1000000000L};
            clock_nanosleep(CLOCK_MONOTONIC, 0, &work, NULL);
            out_value = activations;
            PostData(&out_value);
            if (trace) fprintf(trace, "end %lld\n", (long long)GetTime());
            SendAck(m->Param.Start.ModAck, m->Param.Start.WantedAck, ACK_FINISHED, m->Param.Start.AckID);
            break;
        }
        case REQ_SETPARAM:
            if (GetDataFromSetParamRequest(m, &param_gain, sizeof param_gain, &pt, &rt) == 0 && trace)
                fprintf(trace, "param %ld\n", param_gain);
            break;
        case REQ_STOP:
            SendAck(m->Param.Stop.ModAck, m->Param.Stop.WantedAck, ACK_NOTDONE, m->Param.Stop.AckID);
            break;
        case REQ_KILL:
            SendAck(m->Param.Kil.ModAck, m->Param.Kil.WantedAck, ACK_KILLED, m->Param.Kil.AckID);
            if (trace) fclose(trace);
            free(m);
            return 0;
        default:
            break;
        }
    }
    if (trace) fclose(trace);
    free(m);
    return 0;
}
