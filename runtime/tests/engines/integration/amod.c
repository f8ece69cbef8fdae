/*
 * amod.c — an asynchronous module for the engines' integration test (AMX; built again as AMY
 * with -DAMOD_NAME='"AMY"'): once started it posts a counter 1, 2, 3, ... on its output event
 * port 0 every 10 ms until it is stopped; events on its input event port 0 are recorded.
 * Waiting uses WaitForRequestUntil on absolute deadlines. It writes "param <v>", "start",
 * "post <v>", "got <v>" and "stop" lines to $ITEST_OUT/<name>.trace. Built with
 * -DAMOD_BUSY_MS=N (AMB), each START first runs N ms of its own code without reading its
 * mailbox (a requested priority is answered after); with -DAMOD_BUSY_ALWAYS too (AMD, AME),
 * each post is followed by those N ms as well: the module is almost always busy. Built with
 * -DAMOD_PERIOD_NS=0 (AMF) it posts as fast as its consumers take its events (PostEvent waits
 * for room), reading its mailbox between posts; with -DAMOD_EVENT_MS=N (AMC) each event it
 * receives takes N ms of its own code: a producer flooding a consumer (event-flood scenario).
 */
#define _GNU_SOURCE
#include <libmodule/libmodule.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "imodule.h"

MODULE_DESCRIPTION("engines integration test asynchronous module");
MODULE_AUTHOR("engines tests");

#ifndef AMOD_NAME
#define AMOD_NAME "AMX"
#endif
#ifndef AMOD_BUSY_MS
#define AMOD_BUSY_MS 0
#endif
#ifndef AMOD_BUSY_ALWAYS
#define AMOD_BUSY_ALWAYS 0
#endif
#ifndef AMOD_PERIOD_NS
#define AMOD_PERIOD_NS 10000000LL
#endif
#ifndef AMOD_EVENT_MS
#define AMOD_EVENT_MS 0
#endif

/* AMOD_BUSY_MS of the module's own code: no mailbox read meanwhile */
static void busy_ms(long ms) {
    struct timespec left = {ms / 1000, (ms % 1000) * 1000000L};
    while (nanosleep(&left, &left) != 0) {
    }
}
static void busy(void) { busy_ms(AMOD_BUSY_MS); }

static long counter, received, param_step = 1;
char MODULE_NAME[] = AMOD_NAME;
int MODULE_PRIORITY = 40;
ModuleUse IUSE[] = {IUSE_TERM};
ModuleProduce IPRODUCE[] = {IPRODUCE_TERM};
ModuleReact IREACT[] = {{&received, 0, sizeof(long), "---", -1, 0}, IREACT_TERM};
ModuleDetect IDETECT[] = {{&counter, 0, sizeof(long)}, IDETECT_TERM};
size_t PARAM_SIZE_IN[] = {sizeof(long), PARAM_SIZE_TERM};
size_t PARAM_SIZE_OUT[] = {PARAM_SIZE_TERM};

int ModuleMain(int argc, const char *argv[]) {
    (void)argc;
    (void)argv;
    FILE *trace = imodule_open_trace(MODULE_NAME);
    RequestMessage *m = malloc(sizeof *m);
    if (!m) return 1;
    int running = 0;
    RTIME next = INT64_MAX, pt, rt;
    for (;;) {
        int got = WaitForRequestUntil(m, running ? next : INT64_MAX);
        if (got < 0) continue;
        if (got == 0) { /* period elapsed: post the next value */
            counter += param_step;
            if (trace) fprintf(trace, "post %ld\n", counter);
            PostEvent(&counter);
            if (AMOD_BUSY_ALWAYS) busy();
            next += AMOD_PERIOD_NS;
            if (AMOD_BUSY_ALWAYS && next < GetTime()) next = GetTime() + AMOD_PERIOD_NS;
            continue;
        }
        if (imodule_connect(m)) continue;
        switch (m->Type) {
        case REQ_START:
            if (trace) fprintf(trace, "start\n");
            if (AMOD_BUSY_MS > 0) busy();
            running = 1;
            counter = 0;
            next = GetTime() + AMOD_PERIOD_NS;
            break;
        case REQ_STOP:
            if (trace) fprintf(trace, "stop\n");
            SendAck(m->Param.Stop.ModAck, m->Param.Stop.WantedAck, running ? ACK_STOPPED : ACK_NOTDONE,
                    m->Param.Stop.AckID);
            running = 0;
            break;
        case REQ_SETPARAM:
            if (GetDataFromSetParamRequest(m, &param_step, sizeof param_step, &pt, &rt) == 0 && trace)
                fprintf(trace, "param %ld\n", param_step);
            break;
        case REQ_EVENT:
            if (GetEventId(NULL, NULL) == 0 && trace) fprintf(trace, "got %ld\n", received);
            if (AMOD_EVENT_MS > 0) busy_ms(AMOD_EVENT_MS);
            break;
        case REQ_KILL:
            if (trace) fclose(trace);
            free(m);
            return 0;
        default:
            break;
        }
    }
}
