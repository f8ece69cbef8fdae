/* Test module built several times under different names (-DTMOD_NAME='"P"'): it uses the
 * report's request-loop skeleton and reports what it observes to the test driver ("tester"
 * or $TMOD_REPORT) as events:
 *   port 1: the values it drained from its input data port at the start of a run (long[])
 *   port 2: an event it received (long), sourcePort = the input event port
 *   port 3: the parameter it accepted (TestParam); port 4: a refused setparam (no data)
 * Behaviour flags in TestParam.flags: 1 post an event each run, 2 abort() at the next run,
 * 4 report inputs each run, 8 read inputs with GetLatestData, 16 each state after the first
 * sleeps 100 ms (a module busy in its own code reads its mailbox once per state), 32 the run burns
 * run_ms of its thread's CPU time in one state (a busy loop on CLOCK_THREAD_CPUTIME_ID), 64 the run
 * sleeps run_ms in one state. TestParam.run_ms: how long a run lasts (interruptible by STOP).
 * $TMOD_CRASH_NAME equal to the module name: abort() 200 ms after start-up.
 * $TMOD_CRASH_LOG equal to `NAME:how`: at its first START the module named logs 5 `crash_test`
 * records (detail `before crash 1`..`5`) and crashes at once (well inside the log's flush delay):
 * how = `segv` (a store through a null pointer), `abort`, `fpe` (integer division by zero),
 * `stack` (endless recursion: a stack overflow), `inlog` (a sixth record whose detail is
 * unreadable memory: the crash is inside ContractLog), `many` (3000 records, more than the log's
 * two buffers hold, then the segv), `block` (no crash: it blocks for ever, until a SIGTERM).
 * $TMOD_END equal to `NAME:how`: what the module named does instead of a clean end, `exit0` 200 ms
 * after start-up (its own code ends it mid-run), and at its KILL (the run's stop) `crash` (abort(),
 * a crash in its exit code), `exit3` (exit status 3), `hang` (never ends: the launcher must
 * terminate it); `daemon`: at start-up, leaves a process in a session of its own holding its
 * output 8 s (forked at the end, it could be killed with the module's group before its setsid);
 * `inithang`: never leaves its init (it never looks for a request: the launcher must find it not
 * ready, stop the run without its start, and terminate it); `slowinit`: 300 ms in its init, then
 * `NAME init done` (the run's start request must come after); `sigkill`: 200 ms after start-up,
 * a SIGKILL to itself (what the kernel's OOM killer sends: not the launcher's); `outputs`: at
 * start-up, `NAME out-part ` on stdout with no line end, `NAME err line` on stderr, `NAME out-end`
 * on stdout, then `NAME nul:before<NUL>after` on stdout (the launcher keeps its streams apart and
 * a line's bytes whole); `flood`: at start-up, 200,000 lines `NAME flood line N` on stdout, then
 * `NAME flood done` on stderr (past the run's output limit the launcher must drain it). */
#define _GNU_SOURCE
#include <libmodule/libmodule.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>
#include <unistd.h>
#include "tmod.h"

#ifndef TMOD_NAME
#define TMOD_NAME "TMOD"
#endif
#ifndef TMOD_PRIORITY
#define TMOD_PRIORITY 30
#endif

MODULE_DESCRIPTION("libmodule test module");
MODULE_AUTHOR("runtime tests");

long in_value = 0, out_value = 0, ev_in = 0, ev_out = 0;
TestParam param = { { 0.0, 0.0, 0.0 }, 0, 0, "" };

char MODULE_NAME[] = TMOD_NAME;
int MODULE_PRIORITY = TMOD_PRIORITY;
ModuleUse IUSE[] = { { &in_value, 0, sizeof(long), "---", 0, 1 }, IUSE_TERM };
ModuleProduce IPRODUCE[] = { { &out_value, 0, sizeof(long) }, IPRODUCE_TERM };
ModuleReact IREACT[] = { { &ev_in, 0, sizeof(long), "---", 0, 0 }, IREACT_TERM };
ModuleDetect IDETECT[] = { { &ev_out, 0, sizeof(long) }, IDETECT_TERM };
size_t PARAM_SIZE_IN[] = { sizeof(TestParam), PARAM_SIZE_TERM };
size_t PARAM_SIZE_OUT[] = { PARAM_SIZE_TERM };

static RTIME run_start;
static RTIME productionTime, receptionTime;

static const char *tester(void)
{
    const char *t = getenv("TMOD_REPORT");
    return t && *t ? t : "tester";
}

/* What $TMOD_END asks of this module ("" when nothing). */
static const char *end_how(void)
{
    const char *e = getenv("TMOD_END");
    size_t n = strlen(MODULE_NAME);
    return e && strncmp(e, MODULE_NAME, n) == 0 && e[n] == ':' ? e + n + 1 : "";
}

/* What $TMOD_CRASH_LOG asks of this module ("" when nothing). */
static const char *crash_how(void)
{
    const char *e = getenv("TMOD_CRASH_LOG");
    size_t n = strlen(MODULE_NAME);
    return e && strncmp(e, MODULE_NAME, n) == 0 && e[n] == ':' ? e + n + 1 : "";
}

static volatile int recursing = 1;

static int deep(int n)
{
    volatile char pad[4096];
    pad[0] = (char)n;
    if (!recursing) return pad[0];
    return deep(n + 1) + pad[0];
}

/* The faults themselves (not UBSan's to report in the sanitizer build: the crash is the point). */
__attribute__((no_sanitize("undefined"))) static void null_store(void)
{
    volatile int *volatile p = 0;
    *p = 1;
}

__attribute__((no_sanitize("undefined"))) static void divide_by_zero(void)
{
    volatile int zero = 0, seven = 7; /* (1 / x is no division for gcc) */
    volatile int q = seven / zero;
    (void)q;
}

static void crash_after_logging(const char *how)
{
    int n = strcmp(how, "many") == 0 ? 3000 : 5;
    char detail[40];
    for (int i = 1; i <= n; i++) {
        snprintf(detail, sizeof detail, "before crash %d", i);
        ContractLog("crash_test", "", -1, 0, detail);
    }
    if (strcmp(how, "block") == 0) for (;;) pause(); /* blocked in its own code: the launcher's SIGTERM ends it */
    if (strcmp(how, "abort") == 0) abort();
    if (strcmp(how, "fpe") == 0) divide_by_zero();
    if (strcmp(how, "stack") == 0) recursing = deep(0);
    if (strcmp(how, "inlog") == 0) {
        char *page = mmap(NULL, 4096, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (page != MAP_FAILED) ContractLog("crash_test", "", -1, 0, page);
    }
    null_store();
}

/* The calling thread's CPU time in ms (CLOCK_THREAD_CPUTIME_ID). */
static double thread_cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec / 1e6;
}

static void exec_state(int *state)
{
    if (*state == 0) {
        if (param.flags & 2) abort();
        if (*crash_how()) crash_after_logging(crash_how());
        long vals[64];
        int n = 0;
        if (param.flags & 8) { /* newest only */
            if (GetLatestData(&in_value, &productionTime, &receptionTime) == 1) vals[n++] = in_value;
        } else {
            while (n < 64 && GetData(&in_value, &productionTime, &receptionTime) == 1) vals[n++] = in_value;
        }
        if (param.flags & 4) SendEvent(tester(), 1, 0, vals, (size_t)n * sizeof(long));
        out_value = ContractActivations();
        PostData(&out_value);
        if (param.flags & 1) { ev_out = out_value; PostEvent(&ev_out); }
        run_start = GetTime();
        *state = 1;
    } else {
        if (param.flags & 16) usleep(100000); /* busy in its own code between two reads */
        if (param.flags & 32) { /* run_ms of its own CPU time, then the run's end */
            double c0 = thread_cpu_ms();
            while (thread_cpu_ms() - c0 < (double)param.run_ms) {}
            *state = -1;
            return;
        }
        if (param.flags & 64) { /* run_ms asleep: no CPU time, then the run's end */
            usleep((useconds_t)param.run_ms * 1000);
            *state = -1;
            return;
        }
        if (GetTime() - run_start >= param.run_ms * 1000000L) *state = -1;
    }
}

int ModuleMain(int argc, const char *argv[])
{
    (void)argc; (void)argv;
    const char *crash = getenv("TMOD_CRASH_NAME");
    if (crash && strcmp(crash, MODULE_NAME) == 0) { usleep(200000); abort(); }
    if (strcmp(end_how(), "exit0") == 0) { usleep(200000); exit(0); }
    if (strcmp(end_how(), "sigkill") == 0) { usleep(200000); raise(SIGKILL); }
    if (strcmp(end_how(), "outputs") == 0) {
        printf("%s out-part ", MODULE_NAME);
        fflush(stdout);
        usleep(50000);
        fprintf(stderr, "%s err line\n", MODULE_NAME);
        usleep(50000);
        printf("%s out-end\n", MODULE_NAME);
        char nul[64];
        int n = snprintf(nul, sizeof nul, "%s nul:before", MODULE_NAME);
        memcpy(nul + n, "\0after\n", 7);
        fwrite(nul, 1, (size_t)n + 7, stdout);
        fflush(stdout);
    }
    if (strcmp(end_how(), "flood") == 0) {
        for (long i = 0; i < 200000; i++) printf("%s flood line %ld\n", MODULE_NAME, i);
        fflush(stdout);
        fprintf(stderr, "%s flood done\n", MODULE_NAME);
    }
    /* in a session of its own from the start: the launcher's kill of the module's group at the stop cannot reach it */
    if (strcmp(end_how(), "daemon") == 0 && fork() == 0) { setsid(); sleep(8); _exit(0); }
    if (strcmp(end_how(), "inithang") == 0) for (;;) pause();
    if (strcmp(end_how(), "slowinit") == 0) { usleep(300000); printf("%s init done\n", MODULE_NAME); }
    printf("%s ready\n", MODULE_NAME);
    RequestMessage receivedMessage, registered;
    int end = 0, state = 0, interact, cycleRunning = 0;
    memset(&registered, 0, sizeof registered);
    receivedMessage.Type = REQ_UNKNOWN;
    while (!end) {
        switch (receivedMessage.Type) {
        case REQ_UNKNOWN:
            if (cycleRunning) {
                if (state != -1) {
                    receivedMessage.Type = REQ_START;
                    if ((registered.Param.Start.WantedAck & ACK_NOTHING) == 0)
                        strcpy(receivedMessage.Param.Start.ModAck, registered.Param.Start.ModAck);
                    receivedMessage.Param.Start.WantedAck = registered.Param.Start.WantedAck;
                    receivedMessage.Param.Start.AckID = registered.Param.Start.AckID;
                } else {
                    state = 0;
                    cycleRunning = 0; /* (the report's skeleton forgets this) */
                    if ((registered.Param.Start.WantedAck & ACK_STOPPED) != 0)
                        SendAck(registered.Param.Start.ModAck, registered.Param.Start.WantedAck, ACK_STOPPED, registered.Param.Start.AckID);
                    registered.Param.Start.WantedAck = ACK_NOTHING;
                    WaitForRequest(&receivedMessage);
                    break;
                }
            } else {
                WaitForRequest(&receivedMessage);
                break;
            }
            __attribute__((fallthrough));
        case REQ_START:
            /* a function it does not have (as a supervisor refuses one): ACK_NOTDONE, nothing started */
            if (strcmp(receivedMessage.Param.Start.Function, "nosuch") == 0) {
                if ((receivedMessage.Param.Start.WantedAck & ACK_NOTDONE) != 0)
                    SendAck(receivedMessage.Param.Start.ModAck, receivedMessage.Param.Start.WantedAck, ACK_NOTDONE, receivedMessage.Param.Start.AckID);
                receivedMessage.Type = REQ_UNKNOWN;
                break;
            }
            if (cycleRunning == 0 && (receivedMessage.Param.Start.WantedAck & ACK_START) != 0)
                SendAck(receivedMessage.Param.Start.ModAck, receivedMessage.Param.Start.WantedAck, ACK_START, receivedMessage.Param.Start.AckID);
            interact = 0;
            cycleRunning = 1;
            while (!interact) {
                exec_state(&state);
                if (state == -1) {
                    state = 0;
                    cycleRunning = 0;
                    interact = 1;
                    receivedMessage.Type = REQ_UNKNOWN;
                    if ((receivedMessage.Param.Start.WantedAck & ACK_FINISHED) != 0)
                        SendAck(receivedMessage.Param.Start.ModAck, receivedMessage.Param.Start.WantedAck, ACK_FINISHED, receivedMessage.Param.Start.AckID);
                }
                if (cycleRunning) {
                    registered.Type = receivedMessage.Type;
                    registered.Param.Start.WantedAck = receivedMessage.Param.Start.WantedAck;
                    registered.Param.Start.AckID = receivedMessage.Param.Start.AckID;
                    if ((registered.Param.Start.WantedAck & ACK_NOTHING) == 0)
                        strcpy(registered.Param.Start.ModAck, receivedMessage.Param.Start.ModAck);
                    if (LookForRequest(&receivedMessage) != NULL) interact = 1;
                }
            }
            break;
        case REQ_STOP:
            if (cycleRunning) {
                state = -1;
                if ((receivedMessage.Param.Stop.WantedAck & ACK_STOPPED) != 0)
                    SendAck(receivedMessage.Param.Stop.ModAck, receivedMessage.Param.Stop.WantedAck, ACK_STOPPED, receivedMessage.Param.Stop.AckID);
            } else if ((receivedMessage.Param.Stop.WantedAck & ACK_STOPPED) != 0) {
                SendAck(receivedMessage.Param.Stop.ModAck, receivedMessage.Param.Stop.WantedAck, ACK_NOTDONE, receivedMessage.Param.Stop.AckID);
            }
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        case REQ_KILL:
            end = 1;
            if ((receivedMessage.Param.Kil.WantedAck & ACK_KILLED) != 0)
                SendAck(receivedMessage.Param.Kil.ModAck, receivedMessage.Param.Kil.WantedAck, ACK_KILLED, receivedMessage.Param.Kil.AckID);
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        case REQ_EVENT: {
            int id = GetEventId(&productionTime, &receptionTime);
            if (id >= 0) SendEvent(tester(), 2, id, &ev_in, sizeof ev_in);
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        }
        case REQ_SETPARAM:
            if (receivedMessage.Param.SetParam.Port == 0 &&
                GetDataFromSetParamRequest(&receivedMessage, &param, sizeof param, &productionTime, &receptionTime) == 0)
                SendEvent(tester(), 3, 0, &param, sizeof param);
            else
                SendEvent(tester(), 4, 0, NULL, 0);
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        case REQ_SUBSCRIBE:
            SubscribeUser(receivedMessage.Param.Subscribe.SourcePort, receivedMessage.Param.Subscribe.TargetModule,
                          receivedMessage.Param.Subscribe.TargetPort, receivedMessage.Param.Subscribe.Periodicity,
                          receivedMessage.Param.Subscribe.isContextual);
            /* tell the driver the subscription is in place (it cannot see it otherwise) */
            SendAck(receivedMessage.Sender, 0, ACK_FINISHED, 900 + receivedMessage.Param.Subscribe.TargetPort);
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        case REQ_UNSUBSCRIBE:
            UnsubscribeUser(receivedMessage.Param.Unsubscribe.SourcePort, receivedMessage.Param.Unsubscribe.TargetModule,
                            receivedMessage.Param.Unsubscribe.TargetPort);
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        case REQ_SUB_EVENT:
            SubscribeUserToEvent(receivedMessage.Param.SubscribeEvent.targetModule, receivedMessage.Param.SubscribeEvent.targetPort,
                                 receivedMessage.Param.SubscribeEvent.sourcePort, receivedMessage.Param.SubscribeEvent.mode);
            SendAck(receivedMessage.Sender, 0, ACK_FINISHED, 800 + receivedMessage.Param.SubscribeEvent.targetPort);
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        case REQ_UNSUB_EVENT:
            UnsubscribeUserToEvent(receivedMessage.Param.UnsubscribeEvent.targetModule,
                                   receivedMessage.Param.UnsubscribeEvent.targetPort,
                                   receivedMessage.Param.UnsubscribeEvent.sourcePort);
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        case REQ_PURGE_MBX:
            PurgeData(NULL);
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        default:
            receivedMessage.Type = REQ_UNKNOWN;
            break;
        }
    }
    /* its exit code (the stop): what the test asks */
    const char *how = end_how();
    if (strcmp(how, "crash") == 0) abort();
    if (strcmp(how, "exit3") == 0) exit(3);
    if (strcmp(how, "hang") == 0) for (;;) pause();
    return 0;
}
