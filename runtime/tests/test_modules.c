/* Modules driven through their mailboxes: the report's MSC and the test module (tmod.c). */
#define _GNU_SOURCE
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "engines/engine_wire.h"
#include "harness.h"
#include "internal.h"
#include "modules/tmod.h"

/* Same layouts as the report's TypeA / TypeD (SharedType*.h define functions: one TU only). */
typedef struct { double i, j, k; } TypeA;
typedef struct { char dataname[256]; long datavalue; } TypeD;

static int set_param(const char *module, long flags, long run_ms)
{
    TestParam p;
    memset(&p, 0, sizeof p);
    p.flags = flags;
    p.run_ms = run_ms;
    if (SendSetParam(module, 0, &p, sizeof p, ACK_NOTHING, -1) != 0) return 0;
    return h_wait_event(module, 3, 2000, h_msg());
}

static int run_once(const char *module, int id)
{
    if (SendStart(module, ACK_FINISHED, id) != 0) return 0;
    return h_wait_ack(module, id, ACK_FINISHED, 3000, NULL);
}

static int subscribe_data(const char *producer, const char *consumer, int k)
{
    if (SendSubscribe(producer, 0, consumer, 0, k, 1) != 0) return 0;
    return h_wait_ack(producer, 900, ACK_FINISHED, 2000, NULL);
}

void test_msc_request_loop(void)
{
    REQUIRE(h_setup("loop") == 0);
    RequestMessage *m = h_msg();
    pid_t pid = h_spawn_module("MSC", "MSC");
    REQUIRE(pid > 0);
    CHECK(SendStart("MSC", ACK_START | ACK_FINISHED, 11) == CONTRACT_OK);
    CHECK(h_wait_ack("MSC", 11, ACK_START | ACK_FINISHED, 2000, m) && m->Param.Ack.Ack == ACK_START);
    CHECK(h_wait_ack("MSC", 11, ACK_START | ACK_FINISHED, 2000, m) && m->Param.Ack.Ack == ACK_FINISHED);
    CHECK(SendStop("MSC", ACK_STOPPED, 12) == CONTRACT_OK);
    CHECK(h_wait_ack("MSC", 12, ACK_STOPPED | ACK_NOTDONE, 2000, m) && m->Param.Ack.Ack == ACK_NOTDONE);
    CHECK(strcmp(m->Param.Ack.Module, "MSC") == 0);
    /* no ack wanted: nothing comes back */
    CHECK(SendStart("MSC", ACK_NOTHING, 14) == CONTRACT_OK);
    CHECK(!h_wait_ack("MSC", 14, 0xff, 300, m));
    CHECK(SendKill("MSC", ACK_KILLED, 13) == CONTRACT_OK);
    CHECK(h_wait_ack("MSC", 13, ACK_KILLED, 2000, m) && m->Param.Ack.Ack == ACK_KILLED);
    CHECK(h_wait_exit(pid, 2000) == 0);
    char *log = h_read_logs("MSC_");
    CHECK(log && strncmp(log, "mono_ns,wall_time,module,event,peer,port,size,detail\n", 52) == 0);
    CHECK(log && strstr(log, ",MSC,run_started,tester,,0,activation=1"));
    /* run_finished says the CPU time the run took in the module's thread: cpu_ns >= 0, before the ack */
    const char *fin = log ? strstr(log, ",MSC,run_finished,,,0,activation=1 cpu_ns=") : NULL;
    CHECK(fin != NULL);
    if (fin) {
        char *end = NULL;
        long long cpu = strtoll(fin + strlen(",MSC,run_finished,,,0,activation=1 cpu_ns="), &end, 10);
        CHECK_MSG(cpu >= 0 && end && strncmp(end, " ACK_FINISHED\n", 14) == 0, "run_finished: %.80s", fin);
    }
    CHECK(log && strstr(log, ",MSC,request_received,tester,,0,KILL"));
    CHECK(log && strstr(log, ",MSC,ack_sent,tester,,0,ACK_NOTDONE id=12"));
    CHECK(log && strstr(log, ",MSC,module_exit,"));
    /* module_exit says how many records the module logged: every one of them is in the file */
    const char *exit_rec = log ? strstr(log, ",MSC,module_exit,,,0,status=0 records=") : NULL;
    CHECK(exit_rec != NULL);
    if (exit_rec && log) {
        unsigned long long n = strtoull(strstr(exit_rec, "records=") + 8, NULL, 10);
        unsigned long long lines = 0;
        for (const char *p = log; (p = strchr(p, '\n')) != NULL; p++) lines++;
        CHECK_MSG(n == lines - 1, "module_exit says %llu records, the log holds %llu", n, lines - 1);
    }
    free(log);
    h_teardown();
}

/* The cpu_ns of a release's run_finished of the test module C1, or -2 when there is none. */
static long long run_cpu_ns(const char *log, int activation)
{
    char key[80];
    snprintf(key, sizeof key, ",C1,run_finished,,,0,activation=%d cpu_ns=", activation);
    const char *at = log ? strstr(log, key) : NULL;
    return at ? strtoll(at + strlen(key), NULL, 10) : -2;
}

/* run_finished's cpu_ns is the CPU time of the run's thread, not the run's length: a run burning
   20 ms of CPU says about 20 ms (15 to 60: a real process, its own reads of the clock and its
   mailbox included), a run asleep for 20 ms says under 5 ms (docs/runtime-api.md "A release's CPU time"). */
void test_run_cpu_time(void)
{
    REQUIRE(h_setup("runcpu") == 0);
    pid_t pid = h_spawn_module("C1", "C1");
    REQUIRE(pid > 0);
    REQUIRE(set_param("C1", 32, 20));
    CHECK(run_once("C1", 1));
    REQUIRE(set_param("C1", 64, 20));
    CHECK(run_once("C1", 2));
    CHECK(SendKill("C1", ACK_KILLED, 3) == CONTRACT_OK);
    CHECK(h_wait_ack("C1", 3, ACK_KILLED, 2000, NULL));
    CHECK(h_wait_exit(pid, 2000) == 0);
    char *log = h_read_logs("C1_");
    long long burnt = run_cpu_ns(log, 1), slept = run_cpu_ns(log, 2);
    CHECK_MSG(burnt >= 15000000 && burnt <= 60000000, "a run burning 20 ms of CPU said cpu_ns=%lld", burnt);
    CHECK_MSG(slept >= 0 && slept < 5000000, "a run asleep for 20 ms said cpu_ns=%lld", slept);
    free(log);
    h_teardown();
}

void test_msc_setparam_event(void)
{
    REQUIRE(h_setup("mscev") == 0);
    RequestMessage *m = h_msg();
    REQUIRE(h_spawn_module("MSC", "MSC") > 0);
    CHECK(SendSubscribeEvent("MSC", 1, "tester", 5, EVENT_CONTINUOUS) == CONTRACT_OK);
    TypeA p = { 20.0, 20.0, 20.0 };
    CHECK(SendSetParam("MSC", 0, &p, sizeof p, ACK_NOTHING, -1) == CONTRACT_OK);
    CHECK(SendStart("MSC", ACK_FINISHED, 1) == CONTRACT_OK);
    CHECK(h_wait_event("MSC", 5, 2000, m));
    if (m->Type == REQ_EVENT) {
        TypeD d;
        CHECK(m->DataSize == sizeof d);
        memcpy(&d, m->Data, sizeof d);
        CHECK(strcmp(d.dataname, "problem") == 0);
        CHECK_MSG(d.datavalue == -30, "datavalue %ld", d.datavalue);
        CHECK(m->Param.Event.sourcePort == 1 && strcmp(m->Param.Event.sourceModule, "MSC") == 0);
        CHECK(m->ReceptionTime >= m->ProductionTime && m->ProductionTime > 0);
    }
    CHECK(h_wait_ack("MSC", 1, ACK_FINISHED, 2000, NULL));
    /* a parameter of the wrong size is refused, the module keeps running */
    CHECK(SendSetParam("MSC", 0, &p, sizeof p - 1, ACK_NOTHING, -1) == CONTRACT_OK);
    CHECK(run_once("MSC", 2));
    CHECK(SendKill("MSC", ACK_NOTHING, -1) == CONTRACT_OK);
    usleep(100000);
    ContractLogFlush();
    char *log = h_read_logs("MSC_");
    CHECK(log && strstr(log, ",MSC,setparam,tester,0,24,"));
    CHECK(log && strstr(log, ",MSC,event_posted,tester,1,"));
    CHECK(log && strstr(log, "refused: 23 bytes received, the parameter holds 24 bytes"));
    free(log);
    h_teardown();
}

void test_stop_running_cycle(void)
{
    REQUIRE(h_setup("stop") == 0);
    RequestMessage *m = h_msg();
    REQUIRE(h_spawn_module("C1", "C1") > 0);
    REQUIRE(set_param("C1", 0, 3000));
    CHECK(SendStart("C1", ACK_START | ACK_STOPPED | ACK_FINISHED, 1) == CONTRACT_OK);
    CHECK(h_wait_ack("C1", 1, ACK_START, 2000, m));
    CHECK(SendStop("C1", ACK_STOPPED, 2) == CONTRACT_OK);
    CHECK(h_wait_ack("C1", 2, ACK_STOPPED, 1000, m)); /* to the one who stopped it */
    CHECK(h_wait_ack("C1", 1, ACK_STOPPED | ACK_FINISHED, 1000, m) && m->Param.Ack.Ack == ACK_STOPPED); /* to the starter */
    CHECK(!h_wait_ack("C1", 1, ACK_FINISHED, 300, m));
    /* a second START runs again (activation 2) */
    CHECK(set_param("C1", 0, 0));
    CHECK(run_once("C1", 3));
    CHECK(ContractActivations() == 0); /* the tester itself was never started */
    h_teardown();
}

static int report_values(const char *module, long *vals, int max)
{
    /* a START that arrives during a run joins that run (report skeleton): wait for the end */
    static int id = 500;
    RequestMessage *m = h_msg();
    if (SendStart(module, ACK_FINISHED, ++id) != 0) return -1;
    if (!h_wait_event(module, 1, 2000, m)) return -1;
    int n = (int)(m->DataSize / sizeof(long));
    if (n > max) n = max;
    memcpy(vals, m->Data, (size_t)n * sizeof(long));
    if (!h_wait_ack(module, id, ACK_FINISHED, 2000, NULL)) return -2;
    return n;
}

void test_data_periodicity(void)
{
    REQUIRE(h_setup("period") == 0);
    REQUIRE(h_spawn_module("P", "P") > 0);
    REQUIRE(h_spawn_module("C1", "C1") > 0);
    REQUIRE(h_spawn_module("C2", "C2") > 0);
    CHECK(set_param("C1", 4, 0) && set_param("C2", 4, 0));
    CHECK(subscribe_data("P", "C1", 1));
    CHECK(subscribe_data("P", "C2", 3));
    for (int i = 1; i <= 6; i++) CHECK(run_once("P", i));
    long v[16];
    int n = report_values("C1", v, 16);
    CHECK_MSG(n == 6, "C1 got %d values", n);
    for (int i = 0; i < n && i < 6; i++) CHECK(v[i] == i + 1);
    n = report_values("C2", v, 16);
    CHECK_MSG(n == 2 && v[0] == 3 && v[1] == 6, "C2 got %d values (%ld, %ld)", n, n > 0 ? v[0] : 0, n > 1 ? v[1] : 0);
    /* GetLatestData keeps the newest only */
    CHECK(set_param("C1", 4 | 8, 0));
    for (int i = 7; i <= 9; i++) CHECK(run_once("P", i));
    n = report_values("C1", v, 16);
    CHECK_MSG(n == 1 && v[0] == 9, "C1 latest: %d values, first %ld", n, n > 0 ? v[0] : 0);
    n = report_values("C1", v, 16); /* consumed: nothing left */
    CHECK_MSG(n == 0, "C1 again: %d values, first %ld", n, n > 0 ? v[0] : 0);
    /* unsubscribe: no more data */
    CHECK(SendUnsubscribe("P", 0, "C1", 0) == 0);
    CHECK(run_once("P", 10));
    n = report_values("C1", v, 16);
    CHECK(n == 0);
    n = report_values("C2", v, 16); /* 7..10: only 9 is a multiple of 3 */
    CHECK_MSG(n == 1 && v[0] == 9, "C2 got %d values", n);
    /* purge */
    CHECK(subscribe_data("P", "C1", 1));
    CHECK(run_once("P", 11) && run_once("P", 12));
    CHECK(SendPurge("C1") == 0);
    n = report_values("C1", v, 16);
    CHECK(n == 0);
    usleep(150000); /* P flushes its CSV log within 50 ms once idle */
    char *log = h_read_logs("P_");
    CHECK(log && strstr(log, ",P,data_posted,C2,0,8,to_port=0"));
    free(log);
    h_teardown();
}

void test_event_oneshot_continuous(void)
{
    REQUIRE(h_setup("events") == 0);
    RequestMessage *m = h_msg();
    REQUIRE(h_spawn_module("P", "P") > 0);
    REQUIRE(h_spawn_module("C1", "C1") > 0);
    REQUIRE(h_spawn_module("C2", "C2") > 0);
    CHECK(set_param("P", 1, 0));
    CHECK(SendSubscribeEvent("P", 0, "C1", 0, EVENT_CONTINUOUS) == 0 && h_wait_ack("P", 800, ACK_FINISHED, 2000, NULL));
    CHECK(SendSubscribeEvent("P", 0, "C2", 0, EVENT_ONESHOT) == 0 && h_wait_ack("P", 800, ACK_FINISHED, 2000, NULL));
    CHECK(run_once("P", 1) && run_once("P", 2) && run_once("P", 3));
    int from_c1 = 0, from_c2 = 0;
    long sum_c1 = 0;
    RTIME deadline = GetTime() + 700000000LL;
    while (WaitForRequestUntil(m, deadline) == 1) {
        if (m->Type != REQ_EVENT || m->Param.Event.targetPort != 2) continue;
        long v;
        memcpy(&v, m->Data, sizeof v);
        if (!strcmp(m->Sender, "C1")) { from_c1++; sum_c1 += v; }
        if (!strcmp(m->Sender, "C2")) { from_c2++; CHECK(v == 1); }
    }
    CHECK_MSG(from_c1 == 3 && sum_c1 == 6, "continuous subscriber got %d events", from_c1);
    CHECK_MSG(from_c2 == 1, "one-shot subscriber got %d events", from_c2);
    /* unsubscribe the continuous one */
    CHECK(SendUnsubscribeEvent("P", 0, "C1", 0) == 0);
    CHECK(run_once("P", 4));
    CHECK(!h_wait_event("C1", 2, 300, m));
    h_teardown();
}

void test_setparam_sizes(void)
{
    REQUIRE(h_setup("param") == 0);
    RequestMessage *m = h_msg();
    REQUIRE(h_spawn_module("C1", "C1") > 0);
    TestParam p;
    memset(&p, 0, sizeof p);
    p.x[0] = 1.5; p.x[1] = -2; p.x[2] = 1e-9; p.flags = 0; p.run_ms = 7;
    snprintf(p.label, sizeof p.label, "hello, struct");
    CHECK(SendSetParam("C1", 0, &p, sizeof p, ACK_NOTHING, -1) == 0);
    CHECK(h_wait_event("C1", 3, 2000, m) && m->DataSize == sizeof p && memcmp(m->Data, &p, sizeof p) == 0);
    CHECK(SendSetParam("C1", 0, &p, sizeof p - 8, ACK_NOTHING, -1) == 0);
    CHECK(h_wait_event("C1", 4, 2000, m));
    CHECK(SendSetParam("C1", 1, &p, sizeof p, ACK_NOTHING, -1) == 0); /* unknown port */
    CHECK(h_wait_event("C1", 4, 2000, m));
    static unsigned char big[CONTRACT_REQUEST_DATA_MAX + 1];
    CHECK(SendSetParam("C1", 0, big, sizeof big, ACK_NOTHING, -1) == CONTRACT_ETOOBIG);
    CHECK(SetModuleParam("C1", 0, big, sizeof big) == -1);
    CHECK(SendEvent("C1", 0, 0, big, sizeof big) == CONTRACT_ETOOBIG);
    CHECK(SendSetParam("C1", 0, big, CONTRACT_REQUEST_DATA_MAX, ACK_NOTHING, -1) == 0); /* fits, wrong size */
    CHECK(h_wait_event("C1", 4, 2000, m));
    h_teardown();
}

static int send_raw(const char *file, const void *a, size_t na, const void *b, size_t nb)
{
    struct sockaddr_un sa;
    memset(&sa, 0, sizeof sa);
    sa.sun_family = AF_UNIX;
    if (snprintf(sa.sun_path, sizeof sa.sun_path, "%s/%s", h_run_dir, file) >= (int)sizeof sa.sun_path) return 0;
    int fd = socket(AF_UNIX, SOCK_DGRAM, 0);
    unsigned char buf[40000];
    memcpy(buf, a, na);
    if (nb) memcpy(buf + na, b, nb);
    ssize_t r = sendto(fd, buf, na + nb, 0, (struct sockaddr *)&sa, sizeof sa);
    close(fd);
    return r == (ssize_t)(na + nb);
}

void test_malformed_datagrams(void)
{
    REQUIRE(h_setup("malformed") == 0);
    RequestMessage *m = h_msg();
    REQUIRE(h_spawn_module("C1", "C1") > 0);
    CHECK(set_param("C1", 4, 0));
    static unsigned char junk[20000];
    memset(junk, 0x41, sizeof junk);
    CHECK(send_raw("C1.mbx", junk, sizeof junk, NULL, 0));      /* garbage in the mailbox */
    WirePrefix pre = { WIRE_MAGIC, WIRE_REQUEST };
    RequestMessage *lie = h_msg();
    lie->Type = REQ_SETPARAM;
    lie->DataSize = 10; /* header says 10, datagram carries 100 */
    CHECK(send_raw("C1.mbx", &pre, sizeof pre, lie, REQUEST_HEADER_SIZE + 100));
    WirePrefix dpre = { WIRE_MAGIC, WIRE_DATA };
    struct { DataHeader h; long v[4]; } d;
    memset(&d, 0, sizeof d);
    snprintf(d.h.producer, sizeof d.h.producer, "X");
    d.h.size = sizeof d.v;
    CHECK(send_raw("C1.0.in", &dpre, sizeof dpre, &d, sizeof d));  /* 32 bytes for an 8-byte port */
    char status[512];
    CHECK(QueryStatus("C1", status, sizeof status, GetTime() + 2000000000LL) == 0);
    CHECK(strstr(status, "module=C1") != NULL);
    long v[4];
    CHECK(report_values("C1", v, 4) == 0);
    /* two well-formed values from two different producers: used, the change is reported */
    struct { DataHeader h; long v; } ok;
    memset(&ok, 0, sizeof ok);
    ok.h.size = sizeof ok.v;
    snprintf(ok.h.producer, sizeof ok.h.producer, "X");
    ok.v = 41;
    CHECK(send_raw("C1.0.in", &dpre, sizeof dpre, &ok, sizeof ok));
    snprintf(ok.h.producer, sizeof ok.h.producer, "Y");
    ok.v = 42;
    CHECK(send_raw("C1.0.in", &dpre, sizeof dpre, &ok, sizeof ok));
    CHECK(report_values("C1", v, 4) == 2 && v[0] == 41 && v[1] == 42);
    CHECK(SendKill("C1", ACK_KILLED, 1) == 0 && h_wait_ack("C1", 1, ACK_KILLED, 2000, m));
    usleep(100000);
    char *log = h_read_logs("C1_");
    CHECK(log && strstr(log, "dropped a malformed datagram of 20000 bytes"));
    CHECK(log && strstr(log, "does not match its header"));
    CHECK(log && strstr(log, "input data port 0: refused 32 bytes from X"));
    CHECK(log && strstr(log, ",C1,producer_changed,Y,0,8,was X: a new producer (a schema switch)"));
    free(log);
    h_teardown();
}

/* One value of `producer` into C1's input data port 0. */
static int feed_c1(const char *producer, long value)
{
    WirePrefix dpre = { WIRE_MAGIC, WIRE_DATA };
    struct { DataHeader h; long v; } ok;
    memset(&ok, 0, sizeof ok);
    ok.h.size = sizeof ok.v;
    snprintf(ok.h.producer, sizeof ok.h.producer, "%s", producer);
    ok.v = value;
    return send_raw("C1.0.in", &dpre, sizeof dpre, &ok, sizeof ok);
}

void test_producer_change_and_interleave(void)
{
    REQUIRE(h_setup("producers") == 0);
    RequestMessage *m = h_msg();
    REQUIRE(h_spawn_module("C1", "C1") > 0);
    CHECK(set_param("C1", 4, 0));
    long v[8];
    /* a schema switch (X's flow replaced by Y's) and one back at once: runs of values, facts, no warning */
    CHECK(feed_c1("X", 1) && feed_c1("X", 2) && feed_c1("Y", 3) && feed_c1("Y", 4) && feed_c1("X", 5) && feed_c1("X", 6));
    CHECK(report_values("C1", v, 8) == 6 && v[5] == 6);
    char out[1024];
    snprintf(out, sizeof out, "%s/C1.out", h_work_dir);
    char *said = h_read_file(out);
    CHECK(!said || !strstr(said, "warning: input data port"));
    free(said);
    /* X and Y feeding the port at once: single values between the other's, twice within a second: warned once */
    CHECK(feed_c1("Y", 7) && feed_c1("X", 8) && feed_c1("Y", 9) && feed_c1("X", 10));
    CHECK(report_values("C1", v, 8) == 4 && v[3] == 10);
    CHECK(SendKill("C1", ACK_KILLED, 1) == 0 && h_wait_ack("C1", 1, ACK_KILLED, 2000, m));
    usleep(100000);
    char *log = h_read_logs("C1_");
    CHECK(log && strstr(log, ",C1,producer_changed,Y,0,8,was X: a new producer (a schema switch)"));
    CHECK(log && strstr(log, ",C1,producer_changed,X,0,8,was Y: a new producer (a schema switch)"));
    CHECK(log && strstr(log, ",C1,producer_changed,Y,0,8,was X: interleaved: X and Y both feed this port"));
    CHECK(log && strstr(log, ",C1,producer_changed,X,0,8,was Y: interleaved: Y and X both feed this port"));
    said = h_read_file(out);
    CHECK(said && strstr(said, "C1: warning: input data port 0 is fed by X and Y at once"));
    CHECK(said && !strstr(strstr(said, "is fed by") + 1, "is fed by"));
    free(said);
    free(log);
    h_teardown();
}

void test_unknown_and_stale(void)
{
    REQUIRE(h_setup("stale") == 0);
    CHECK(ModuleState("NOPE") == CONTRACT_EUNKNOWN);
    CHECK(SendStart("NOPE", ACK_NOTHING, 0) == CONTRACT_EUNKNOWN);
    CHECK(SendStart("bad/name", ACK_NOTHING, 0) == CONTRACT_EINVAL);
    /* a mailbox whose process is gone */
    struct sockaddr_un sa;
    memset(&sa, 0, sizeof sa);
    sa.sun_family = AF_UNIX;
    REQUIRE(snprintf(sa.sun_path, sizeof sa.sun_path, "%s/GHOST.mbx", h_run_dir) < (int)sizeof sa.sun_path);
    int fd = socket(AF_UNIX, SOCK_DGRAM, 0);
    CHECK(bind(fd, (struct sockaddr *)&sa, sizeof sa) == 0);
    close(fd);
    CHECK(ModuleState("GHOST") == CONTRACT_ENOTRUNNING);
    CHECK(SendKill("GHOST", ACK_NOTHING, 0) == CONTRACT_ENOTRUNNING);
    unlink(sa.sun_path);
    /* the same module twice in one run directory: the second one refuses to start */
    pid_t p1 = h_spawn_module("P", "P");
    CHECK(p1 > 0);
    char *argv[] = { "P", NULL };
    char out[600];
    snprintf(out, sizeof out, "%s/second.out", h_work_dir);
    CHECK(h_run(argv, out, 3000) == 2);
    char *text = h_read_file(out);
    CHECK(text && strstr(text, "already exists and is in use"));
    free(text);
    CHECK(ModuleState("P") == CONTRACT_OK); /* the first one is untouched */
    h_teardown();
}

/* Module code that closed its stdout (close(1)): the socket libmodule opens next must not take
 * fd 1, or the code's next printf goes into a peer's mailbox as a malformed datagram. */
void test_sockets_above_stdio(void)
{
    REQUIRE(h_setup("stdio") == 0);
    pid_t p = h_spawn_module("P", "P");
    REQUIRE(p > 0);
    fflush(stdout);
    int saved = dup(1);
    REQUIRE(saved >= 0);
    close(1);
    int rc = SendStart("P", ACK_NOTHING, 0); /* the first request to P: a new socket to its mailbox */
    int fd1_open = fcntl(1, F_GETFD) != -1;
    dup2(saved, 1);
    close(saved);
    CHECK(rc == CONTRACT_OK);
    CHECK(!fd1_open);
    h_teardown();
}

void test_long_run_dir(void)
{
    REQUIRE(h_setup("longdir") == 0);
    ContractShutdown();
    char deep[600];
    memset(deep, 'd', 120);
    deep[120] = '\0';
    REQUIRE(snprintf(h_run_dir, sizeof h_run_dir, "%s/%s/run", h_work_dir, deep) < (int)sizeof h_run_dir);
    REQUIRE(strlen(h_run_dir) > 108); /* longer than sun_path */
    setenv("CONTRACT_RUN_DIR", h_run_dir, 1);
    REQUIRE(ContractClientInit("tester") == 0);
    RequestMessage *m = h_msg();
    pid_t pid = h_spawn_module("MSC", "MSC");
    REQUIRE(pid > 0);
    CHECK(SendStart("MSC", ACK_FINISHED, 1) == 0 && h_wait_ack("MSC", 1, ACK_FINISHED, 2000, m));
    CHECK(SendKill("MSC", ACK_KILLED, 2) == 0 && h_wait_ack("MSC", 2, ACK_KILLED, 2000, m));
    CHECK(h_wait_exit(pid, 2000) == 0);
    h_teardown();
}

/* While the launcher stops the run (CONTRACT_RUN_STOPPING_FILE), an event a module posts to a
 * subscriber that has already gone is logged but prints no error line; before and after, it is
 * an error on the module's stderr. */
void test_request_to_gone_while_stopping(void)
{
    REQUIRE(h_setup("stopping") == 0);
    pid_t pid = h_spawn_module("P", "P");
    REQUIRE(pid > 0);
    CHECK(set_param("P", 1, 0)); /* P posts an event at every run */
    CHECK(SendSubscribeEvent("P", 0, "GONE", 0, EVENT_CONTINUOUS) == 0 && h_wait_ack("P", 800, ACK_FINISHED, 2000, NULL));
    char mark[700];
    snprintf(mark, sizeof mark, "%s/%s", h_run_dir, CONTRACT_RUN_STOPPING_FILE);
    CHECK(run_once("P", 1));
    int fd = open(mark, O_WRONLY | O_CREAT, 0644);
    CHECK(fd >= 0);
    if (fd >= 0) close(fd);
    CHECK(run_once("P", 2) && run_once("P", 3));
    unlink(mark);
    CHECK(run_once("P", 4));
    CHECK(SendKill("P", ACK_NOTHING, -1) == 0 && h_wait_exit(pid, 2000) == 0);
    char out_path[700];
    snprintf(out_path, sizeof out_path, "%s/P.out", h_work_dir);
    char *out = h_read_file(out_path);
    int lines = 0;
    for (const char *at = out; at && (at = strstr(at, "P: error: EVENT request to GONE: unknown module")) != NULL; at++) lines++;
    /* the same line twice within 1 s: printed once, then counted (said at P's end) */
    CHECK_MSG(lines == 1 && strstr(out, "P: error: (the same error 1 more time in "),
              "%d error lines on stderr, expected 1 (run 1), then the count of run 4's: %s", lines, out ? out : "(none)");
    free(out);
    char *log = h_read_logs("P_");
    int records = 0, stopping = 0;
    for (const char *at = log; at && (at = strstr(at, ",P,error,,,0,EVENT request to GONE: unknown module")) != NULL; at++) {
        records++;
        const char *eol = strchr(at, '\n');
        const char *quiet = strstr(at, "; the run is stopping)");
        if (quiet && (!eol || quiet < eol)) stopping++;
    }
    CHECK_MSG(records == 4 && stopping == 2, "%d error records (%d while stopping), expected 4 (2)", records, stopping);
    free(log);
    h_teardown();
}

/* What ORD asks before it prints an error line for a request that failed (ContractPeerGoneAtStop): a
 * peer gone (no mailbox) is quiet only while the launcher stops the run; any other failure, or
 * the same outside the stop, is not. At a run's stop ORD may tick once more after LOC has gone:
 * without the check it prints `ORD: cannot release LOC (goTo): unknown module` under `all modules
 * stopped cleanly`. */
void test_peer_gone_at_stop(void)
{
    REQUIRE(h_setup("gone-at-stop") == 0);
    char mark[700];
    snprintf(mark, sizeof mark, "%s/%s", h_run_dir, CONTRACT_RUN_STOPPING_FILE);
    int before = SendStart("GONE", ACK_NOTHING, 0);
    CHECK_MSG(before == CONTRACT_EUNKNOWN, "a release to a module with no mailbox: %d, expected CONTRACT_EUNKNOWN", before);
    CHECK(!ContractRunStopping() && !ContractPeerGoneAtStop(before));
    int fd = open(mark, O_WRONLY | O_CREAT, 0644);
    CHECK(fd >= 0);
    if (fd >= 0) close(fd);
    int during = SendStart("GONE", ACK_NOTHING, 0);
    CHECK(ContractRunStopping() && during == CONTRACT_EUNKNOWN && ContractPeerGoneAtStop(during));
    CHECK(ContractPeerGoneAtStop(CONTRACT_ENOTRUNNING));
    CHECK(!ContractPeerGoneAtStop(CONTRACT_OK) && !ContractPeerGoneAtStop(CONTRACT_EBUSY) && !ContractPeerGoneAtStop(CONTRACT_ETOOBIG));
    unlink(mark);
    CHECK(!ContractRunStopping() && !ContractPeerGoneAtStop(CONTRACT_EUNKNOWN));
    h_teardown();
}

/* ContractSetNonBlockingSends (ORD sets it at start): a request to a mailbox that is full (its
 * module stuck, not reading it) fails at once with CONTRACT_EBUSY, said on stderr; without it
 * (every module's default) the sender waits for room, here made by a reader 300 ms later. */
void test_nonblocking_sends(void)
{
    REQUIRE(h_setup("nonblocking") == 0);
    struct sockaddr_un sa;
    socklen_t len;
    REQUIRE(rt_module_addr("FULL", ".mbx", &sa, &len) == 0);
    int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0); /* a mailbox nobody reads */
    REQUIRE(fd >= 0);
    REQUIRE(bind(fd, (struct sockaddr *)&sa, len) == 0);
    char err_path[700];
    int saved = h_stderr_to_file(err_path, sizeof err_path);
    REQUIRE(saved >= 0);
    int before = ContractSetNonBlockingSends(1);
    int sent = 0, rc = CONTRACT_OK;
    RTIME t0 = GetTime();
    while (sent < 1000 && (rc = SendStart("FULL", ACK_NOTHING, 0)) == CONTRACT_OK) sent++;
    RTIME took = GetTime() - t0;
    h_stderr_back(saved);
    CHECK_MSG(before == 0, "non-blocking sends were on (%d) before the call: every process starts waiting", before);
    CHECK_MSG(rc == CONTRACT_EBUSY && sent > 0 && sent < 1000, "%d requests taken, then %d (expected CONTRACT_EBUSY)", sent, rc);
    CHECK_MSG(took < 500000000LL, "filling the mailbox and the refused request took %lld ms (a full mailbox is not waited for)",
              (long long)(took / 1000000));
    char *err = h_read_file(err_path);
    CHECK_MSG(err && strstr(err, "tester: error: START request to FULL: mailbox full") &&
                  strstr(err, "; tester does not wait for a full mailbox)"), "stderr: %s", err ? err : "(none)");
    free(err);
    CHECK(ContractSetNonBlockingSends(0) == 1);
    pid_t reader = fork();
    REQUIRE(reader >= 0);
    if (reader == 0) {
        struct timespec later = { 0, 300000000L };
        nanosleep(&later, NULL);
        char byte;
        _exit(recv(fd, &byte, 1, 0) >= 0 ? 0 : 1); /* one request read: room for one more */
    }
    t0 = GetTime();
    rc = SendStart("FULL", ACK_NOTHING, 0);
    took = GetTime() - t0;
    CHECK_MSG(rc == CONTRACT_OK && took >= 250000000LL && took < 2000000000LL,
              "by default the request waited %lld ms for room and returned %d (expected ~300 ms, CONTRACT_OK)",
              (long long)(took / 1000000), rc);
    CHECK(h_wait_exit(reader, 2000) == 0);
    close(fd);
    unlink(sa.sun_path);
    h_teardown();
}

/* Requests sent without waiting until the mailbox takes no more (AckID 0). */
static void fill_mailbox(const char *name)
{
    int queued = ContractSetQueuedSends(0), nowait = ContractSetNonBlockingSends(1);
    for (int i = 0; i < 1000 && SendStart(name, ACK_NOTHING, 0) == CONTRACT_OK; i++) continue;
    ContractSetNonBlockingSends(nowait);
    ContractSetQueuedSends(queued);
}

/* A mailbox nobody reads, filled to the brim. */
static int full_mailbox(const char *name, struct sockaddr_un *sa)
{
    socklen_t len;
    if (rt_module_addr(name, ".mbx", sa, &len) != 0) return -1;
    int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (fd < 0 || bind(fd, (struct sockaddr *)sa, len) != 0) return -1;
    fill_mailbox(name);
    return fd;
}

/* Takes every datagram out of a mailbox; the AckIDs of the START requests among them, in order,
 * into ids (at most cap). Returns the number of datagrams. */
static int drain_starts(int fd, int *ids, int cap, int *n_ids)
{
    static struct { WirePrefix pre; RequestMessage m; } d;
    int n = 0;
    *n_ids = 0;
    while (recv(fd, &d, sizeof d, MSG_DONTWAIT) > 0) {
        n++;
        if (d.m.Type == REQ_START && *n_ids < cap) ids[(*n_ids)++] = d.m.Param.Start.AckID;
    }
    return n;
}

static int failed_calls, failed_type, failed_code;
static char failed_module[CONTRACT_NAME_MAX];
static void on_kept_failed(const char *module, const RequestMessage *request, int code)
{
    failed_calls++;
    failed_type = request->Type;
    failed_code = code;
    snprintf(failed_module, sizeof failed_module, "%s", module);
}

/* The requests_kept / requests_kept_end records of log, from their event column on, joined by
 * " | ", kept_ns cut to whole seconds (kept_s). */
static void kept_records(const char *log, char *out, size_t cap)
{
    out[0] = '\0';
    for (const char *line = log; line && *line;) {
        const char *end = strchr(line, '\n');
        size_t n = end ? (size_t)(end - line) : strlen(line);
        const char *ev = strstr(line, ",requests_kept");
        if (ev && ev < line + n) {
            /* mono,wall,module,EVENT,PEER,PORT,SIZE,DETAIL: from the event on, kept_ns's value cut */
            char one[160];
            snprintf(one, sizeof one, "%.*s", (int)(line + n - ev - 1), ev + 1);
            char *ns = strstr(one, " kept_ns=");
            if (ns) {
                long long v = atoll(ns + 9);
                snprintf(ns, sizeof one - (size_t)(ns - one), " kept_s=%lld", v / 1000000000LL);
            }
            size_t len = strlen(out);
            snprintf(out + len, cap - len, "%s%s", len ? " | " : "", one);
        }
        line = end ? end + 1 : NULL;
    }
}

/* Queued sends (the supervisors): a request to a full mailbox is kept and returns at once; it is
 * sent, in order, while the process waits for requests, once the mailbox has room; requests to
 * others go at once; a status question to it is not kept (busy at once); one still not sent after
 * 2 s fails with the usual error; at exit the process waits for what it kept. */
void test_queued_sends(void)
{
    REQUIRE(h_setup("queued") == 0);
    REQUIRE(rt_log_open() == 0); /* the tester's own log: the kept requests' records */
    struct sockaddr_un full_sa, other_sa;
    char err_path[700];
    int saved = h_stderr_to_file(err_path, sizeof err_path);
    REQUIRE(saved >= 0);
    int fd = full_mailbox("FULL", &full_sa);
    socklen_t other_len;
    int other = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    int other_ok = rt_module_addr("OTHER", ".mbx", &other_sa, &other_len) == 0 &&
                   bind(other, (struct sockaddr *)&other_sa, other_len) == 0;
    int before = ContractSetQueuedSends(1);
    RTIME t0 = GetTime();
    int rc1 = SendStart("FULL", ACK_NOTHING, 11), rc2 = SendStart("FULL", ACK_NOTHING, 12),
        rc3 = SendStart("FULL", ACK_NOTHING, 13), rc_other = SendStart("OTHER", ACK_NOTHING, 21);
    RTIME took = GetTime() - t0;
    int kept = ContractQueuedSends();
    char status[256];
    t0 = GetTime();
    int rc_status = QueryStatus("FULL", status, sizeof status, GetTime() + 1000000000LL);
    RTIME status_took = GetTime() - t0;
    static struct { WirePrefix pre; RequestMessage m; } d;
    int other_got = recv(other, &d, sizeof d, MSG_DONTWAIT) > 0 && d.m.Param.Start.AckID == 21;
    int ids[8], n_ids;
    int filled = drain_starts(fd, ids, 8, &n_ids); /* room now: the kept ones go at the next wait */
    RequestMessage *m = h_msg();
    t0 = GetTime();
    while (ContractQueuedSends() > 0 && GetTime() - t0 < 1000000000LL) WaitForRequestUntil(m, GetTime() + 20000000LL);
    RTIME sent_after = GetTime() - t0;
    int left = ContractQueuedSends();
    drain_starts(fd, ids, 8, &n_ids);

    /* a mailbox that stays full: the kept request fails after 2 s, the one behind it too; the
       handler hears of each */
    fill_mailbox("FULL");
    ContractSetKeptSendFailed(on_kept_failed);
    failed_calls = 0;
    RTIME q0 = GetTime();
    int rc_late = SendStart("FULL", ACK_NOTHING, 31);
    SendStart("FULL", ACK_NOTHING, 32);
    RTIME first_failed = 0;
    while (ContractQueuedSends() > 0 && GetTime() - q0 < 3000000000LL) {
        WaitForRequestUntil(m, GetTime() + 10000000LL);
        if (!first_failed && ContractQueuedSends() < 2) first_failed = GetTime() - q0;
    }
    int left_late = ContractQueuedSends();
    int calls_late = failed_calls;

    /* at exit: the process waits for a request it kept until the mailbox has room */
    int late_ids[8], n_late;
    drain_starts(fd, late_ids, 8, &n_late);
    fill_mailbox("FULL");
    SendStart("FULL", ACK_NOTHING, 41);
    pid_t reader = fork();
    REQUIRE(reader >= 0);
    if (reader == 0) {
        struct timespec later = { 0, 300000000L };
        nanosleep(&later, NULL);
        int got41 = 0, k, n;
        for (int t = 0; t < 200 && !got41; t++) { /* 2 s */
            drain_starts(fd, late_ids, 8, &n);
            for (k = 0; k < n; k++) got41 |= late_ids[k] == 41;
            nanosleep(&(struct timespec){ 0, 10000000L }, NULL);
        }
        _exit(got41 ? 0 : 1);
    }
    t0 = GetTime();
    ContractShutdown();
    RTIME exit_took = GetTime() - t0;
    int reader_rc = h_wait_exit(reader, 3000);
    ContractSetQueuedSends(before);
    ContractSetKeptSendFailed(NULL);
    h_stderr_back(saved);

    CHECK_MSG(calls_late == 2 && failed_calls == 2 && failed_type == REQ_START && failed_code == CONTRACT_EBUSY &&
                  !strcmp(failed_module, "FULL"),
              "the handler heard of %d failures (%d with the exit; expected the 2 that failed after 2 s, not the exit's): "
              "last %s type %d code %d", calls_late, failed_calls, failed_module, failed_type, failed_code);
    CHECK_MSG(before == 0, "queued sends were on (%d) before the call: every process starts without", before);
    CHECK(fd >= 0 && other_ok);
    CHECK_MSG(rc1 == CONTRACT_OK && rc2 == CONTRACT_OK && rc3 == CONTRACT_OK && rc_other == CONTRACT_OK,
              "sends to a full mailbox returned %d %d %d, to another %d (expected CONTRACT_OK: kept)", rc1, rc2, rc3, rc_other);
    CHECK_MSG(took < 100000000LL, "keeping 3 requests and sending 1 took %lld ms (nothing waits)", (long long)(took / 1000000));
    CHECK_MSG(kept == 3, "%d requests kept (expected the 3 to the full mailbox)", kept);
    CHECK_MSG(other_got, "the request to a mailbox with room did not go at once");
    CHECK_MSG(rc_status == CONTRACT_EBUSY && status_took < 100000000LL,
              "a status question to a full mailbox returned %d after %lld ms (expected CONTRACT_EBUSY at once)", rc_status,
              (long long)(status_took / 1000000));
    CHECK_MSG(filled > 0, "the mailbox was not full");
    CHECK_MSG(left == 0 && sent_after < 200000000LL, "%d requests still kept %lld ms after the mailbox had room", left,
              (long long)(sent_after / 1000000));
    CHECK_MSG(n_ids == 3 && ids[0] == 11 && ids[1] == 12 && ids[2] == 13, "the kept requests arrived as %d: %d %d %d (expected 11 12 13)",
              n_ids, n_ids > 0 ? ids[0] : -1, n_ids > 1 ? ids[1] : -1, n_ids > 2 ? ids[2] : -1);
    CHECK(rc_late == CONTRACT_OK);
    CHECK_MSG(left_late == 0 && first_failed >= 2000000000LL && first_failed < 2300000000LL,
              "a request kept for a mailbox that stays full failed after %lld ms (expected 2 s), %d still kept",
              (long long)(first_failed / 1000000), left_late);
    for (int k = 0; k < n_late; k++) CHECK_MSG(late_ids[k] == 0, "a failed request was sent after all: %d", late_ids[k]);
    CHECK_MSG(exit_took >= 250000000LL && exit_took < 2000000000LL && reader_rc == 0,
              "at exit the kept request waited %lld ms (expected ~300 ms) and reached the mailbox: %s",
              (long long)(exit_took / 1000000), reader_rc == 0 ? "yes" : "no");
    char *err = h_read_file(err_path);
    const char *fail = "tester: error: START request to FULL: mailbox full: the module did not read its requests in time "
                       "(Resource temporarily unavailable; its mailbox "
                       "stayed full for 2 s; tester kept the request meanwhile)";
    const char *first = err ? strstr(err, fail) : NULL; /* the second, 1 ms later, is counted (rt_error) */
    CHECK_MSG(first && strstr(first, "tester: error: (the same error ") && !strstr(err, "STATUS request"), "stderr: %s",
              err ? err : "(none)");
    free(err);
    /* each receiver's streak of kept requests is bracketed in the log, with what came of them
       (the exit's too, before the log closes) */
    char *log = h_read_logs("tester_"), recs[1024];
    kept_records(log, recs, sizeof recs);
    const char *begin = "requests_kept,FULL,,0,request=START | requests_kept_end,FULL,,0,";
    char want[1024];
    snprintf(want, sizeof want, "%ssent=3 failed=0 replaced=0 kept_s=0 | %ssent=0 failed=2 replaced=0 kept_s=2 | %ssent=1 failed=0 replaced=0 kept_s=0",
             begin, begin, begin);
    CHECK_MSG(!strcmp(recs, want), "the kept requests' records:\n  %s\nexpected\n  %s", recs, want);
    free(log);
    close(fd);
    close(other);
    unlink(full_sa.sun_path);
    unlink(other_sa.sun_path);
    h_teardown();
}

/* Queued sends: room for 64 kept requests per receiver (one more fails at once; another
 * receiver still has its room), and a new value for a parameter port replaces the one kept for it
 * (sent once, the last value, behind the other kept requests). */
void test_queued_sends_room(void)
{
    REQUIRE(h_setup("queuedroom") == 0);
    REQUIRE(rt_log_open() == 0); /* the tester's own log: the kept requests' records */
    char err_path[700];
    int saved = h_stderr_to_file(err_path, sizeof err_path);
    REQUIRE(saved >= 0);
    struct sockaddr_un a_sa, b_sa;
    int a = full_mailbox("ROOMA", &a_sa), b = full_mailbox("ROOMB", &b_sa);
    int before = ContractSetQueuedSends(1);
    int taken = 0, rc = CONTRACT_OK;
    while (taken < 100 && (rc = SendStart("ROOMA", ACK_NOTHING, 100 + taken)) == CONTRACT_OK) taken++;
    int for_a = ContractQueuedFor("ROOMA");
    int rc_b = SendStart("ROOMB", ACK_NOTHING, 7), for_b = ContractQueuedFor("ROOMB");
    long v1 = 1, v2 = 2, v3 = 3;
    int p1 = SendSetParam("ROOMB", 0, &v1, sizeof v1, ACK_NOTHING, 0), p2 = SendSetParam("ROOMB", 1, &v2, sizeof v2, ACK_NOTHING, 0);
    int p3 = SendSetParam("ROOMB", 0, &v3, sizeof v3, ACK_NOTHING, 0), p4 = SendStart("ROOMB", ACK_NOTHING, 8);
    int for_b_params = ContractQueuedFor("ROOMB");
    /* room again in ROOMB: its kept requests go, in order */
    int ids[8], n_ids;
    drain_starts(b, ids, 8, &n_ids);
    RequestMessage *m = h_msg();
    for (int t = 0; t < 50 && ContractQueuedFor("ROOMB") > 0; t++) WaitForRequestUntil(m, GetTime() + 10000000LL);
    static struct { WirePrefix pre; RequestMessage m; } d;
    char order[64] = "";
    while (recv(b, &d, sizeof d, MSG_DONTWAIT) > 0 && strlen(order) < 50) {
        char one[16];
        if (d.m.Type == REQ_START) snprintf(one, sizeof one, "S%d ", d.m.Param.Start.AckID);
        else if (d.m.Type == REQ_SETPARAM) snprintf(one, sizeof one, "P%d=%ld ", d.m.Param.SetParam.Port, *(long *)(void *)d.m.Data);
        else snprintf(one, sizeof one, "?%d ", (int)d.m.Type);
        strcat(order, one);
    }
    ContractSetQueuedSends(0);
    RTIME t0 = GetTime();
    ContractShutdown(); /* ROOMA's 64 fail at the exit, 0.5 s later */
    RTIME exit_took = GetTime() - t0;
    ContractSetQueuedSends(before);
    h_stderr_back(saved);
    CHECK(a >= 0 && b >= 0);
    CHECK_MSG(taken == 64 && rc == CONTRACT_EBUSY && for_a == 64, "%d requests kept for ROOMA (%d counted), then %d (expected 64, then CONTRACT_EBUSY)",
              taken, for_a, rc);
    CHECK_MSG(rc_b == CONTRACT_OK && for_b == 1, "another full mailbox's request: %d, %d kept (its own room)", rc_b, for_b);
    CHECK_MSG(p1 == CONTRACT_OK && p2 == CONTRACT_OK && p3 == CONTRACT_OK && p4 == CONTRACT_OK && for_b_params == 4,
              "ROOMB keeps %d requests after 2 values for port 0, 1 for port 1 and a start (expected 4: the second value replaced the first)",
              for_b_params);
    CHECK_MSG(!strcmp(order, "S7 P1=2 P0=3 S8 "), "ROOMB got, in order: %s (expected S7 P1=2 P0=3 S8)", order);
    CHECK_MSG(exit_took >= 450000000LL && exit_took < 1500000000LL, "the exit waited %lld ms for the kept requests (expected 0.5 s)",
              (long long)(exit_took / 1000000));
    char *err = h_read_file(err_path);
    CHECK_MSG(err && strstr(err, "tester: error: START request to ROOMA: mailbox full: the module did not read its requests in time "
                                 "(Resource temporarily unavailable; 64 requests to ROOMA already wait for its full mailbox)") &&
                  strstr(err, "(Resource temporarily unavailable; tester ended before its mailbox had room)"),
              "stderr: %.2000s", err ? err : "(none)");
    free(err);
    /* ROOMB's streak: its 4 kept requests sent, one value replaced; ROOMA's: the 65th refused at
       once and the 64 failed at the exit */
    char *log = h_read_logs("tester_"), recs[1024];
    kept_records(log, recs, sizeof recs);
    CHECK_MSG(strstr(recs, "requests_kept,ROOMA,,0,request=START") && strstr(recs, "requests_kept,ROOMB,,0,request=START") &&
                  strstr(recs, "requests_kept_end,ROOMB,,0,sent=4 failed=0 replaced=1 kept_s=0") &&
                  strstr(recs, "requests_kept_end,ROOMA,,0,sent=0 failed=65 replaced=0 kept_s=0"),
              "the kept requests' records: %s", recs);
    free(log);
    close(a);
    close(b);
    unlink(a_sa.sun_path);
    unlink(b_sa.sun_path);
    h_teardown();
}

/* The same error line again within 1 s is counted, not printed: said with its next print or at the
 * end; another error line is printed at once (after the count). */
void test_error_repeats(void)
{
    REQUIRE(h_setup("repeats") == 0);
    char err_path[700];
    int saved = h_stderr_to_file(err_path, sizeof err_path);
    REQUIRE(saved >= 0);
    for (int i = 0; i < 50; i++) SendStart("GONE", ACK_NOTHING, 0);
    SendStop("GONE", ACK_NOTHING, 0); /* another line: printed, after the count */
    for (int i = 0; i < 3; i++) SendStop("GONE", ACK_NOTHING, 0);
    ContractShutdown(); /* the count of the last one */
    h_stderr_back(saved);
    char *err = h_read_file(err_path);
    const char *start = "tester: error: START request to GONE: unknown module";
    const char *stop = "tester: error: STOP request to GONE: unknown module";
    const char *first = err ? strstr(err, start) : NULL, *count1 = err ? strstr(err, "tester: error: (the same error 49 more times in ") : NULL;
    const char *stop1 = err ? strstr(err, stop) : NULL, *count2 = err ? strstr(err, "tester: error: (the same error 3 more times in ") : NULL;
    CHECK_MSG(first && !strstr(first + 1, start) && count1 > first && stop1 > count1 && !strstr(stop1 + 1, stop) && count2 > stop1,
              "stderr: %.3000s", err ? err : "(none)");
    free(err);
    h_teardown();
}

void test_maa_events_params(void)
{
    REQUIRE(h_setup("maa") == 0);
    RequestMessage *m = h_msg();
    pid_t pid = h_spawn_module("MAA", "MAA");
    REQUIRE(pid > 0);
    char text[256];
    memset(text, 0, sizeof text);
    snprintf(text, sizeof text, "connect");
    CHECK(SendEvent("MAA", 0, 7, text, sizeof text) == CONTRACT_OK);
    CHECK(SendEvent("MAA", 0, 7, text, 10) == CONTRACT_OK);     /* wrong size: refused by GetEventId */
    TypeA p = { 1.0, 2.0, 3.0 };
    CHECK(SendSetParam("MAA", 0, &p, sizeof p, ACK_NOTHING, -1) == CONTRACT_OK);
    CHECK(SendSubscribeEvent("MAA", 2, "tester", 4, EVENT_ONESHOT) == CONTRACT_OK);
    char status[512];
    CHECK(QueryStatus("MAA", status, sizeof status, GetTime() + 2000000000LL) == 0);
    CHECK(strstr(status, "test asynchronous module A") != NULL);
    CHECK(SendKill("MAA", ACK_KILLED, 3) == 0 && h_wait_ack("MAA", 3, ACK_KILLED, 2000, m));
    CHECK(h_wait_exit(pid, 2000) == 0);
    char *log = h_read_logs("MAA_");
    CHECK(log && strstr(log, ",MAA,event_received,tester,0,256,from_port=7"));
    /* the handler's end: written when MAA reads its mailbox again, after the reception */
    const char *got = log ? strstr(log, ",MAA,event_received,tester,0,256,from_port=7") : NULL;
    const char *handled = log ? strstr(log, ",MAA,event_handled,tester,0,0,from_port=7 handling_ns=") : NULL;
    CHECK_MSG(got && handled > got, "log: %.3000s", log ? log : "(none)");
    CHECK(log && strstr(log, "event from tester:7 refused: 10 bytes for input event port 0 of 256 bytes"));
    CHECK(log && strstr(log, ",MAA,setparam,tester,0,24,"));
    CHECK(log && strstr(log, ",MAA,event_subscribed,tester,2,0,to_port=4 oneshot"));
    free(log);
    char *out = h_read_file(strcat(strcpy(status, h_work_dir), "/MAA.out"));
    CHECK(out && strstr(out, "initialization of MAA") && strstr(out, "termination of MAA"));
    free(out);
    h_teardown();
}

/* The undo of a one-shot subscription that already fired (supervisor rule deactivated after
 * the event): the producer accepts the REQ_UNSUB_EVENT quietly, and a later subscription of the
 * same consumer works again. */
void test_unsub_spent_oneshot(void)
{
    REQUIRE(h_setup("spent") == 0);
    RequestMessage *m = h_msg();
    REQUIRE(h_spawn_module("P", "P") > 0);
    REQUIRE(h_spawn_module("C2", "C2") > 0);
    CHECK(set_param("P", 1, 0));
    CHECK(SendSubscribeEvent("P", 0, "C2", 0, EVENT_ONESHOT) == 0 && h_wait_ack("P", 800, ACK_FINISHED, 2000, NULL));
    CHECK(run_once("P", 1));
    CHECK(h_wait_event("C2", 2, 2000, m));
    CHECK(SendUnsubscribeEvent("P", 0, "C2", 0) == 0);      /* the one-shot is spent */
    CHECK(SendUnsubscribeEvent("P", 0, "C2", 0) == 0);      /* and now not subscribed at all */
    CHECK(run_once("P", 2));
    CHECK(!h_wait_event("C2", 2, 300, m));
    CHECK(SendSubscribeEvent("P", 0, "C2", 0, EVENT_ONESHOT) == 0 && h_wait_ack("P", 800, ACK_FINISHED, 2000, NULL));
    CHECK(run_once("P", 3));
    CHECK(h_wait_event("C2", 2, 2000, m));
    long v = 0;
    memcpy(&v, m->Data, sizeof v);
    CHECK(v == 3);
    CHECK(SendKill("P", ACK_KILLED, 7) == 0 && h_wait_ack("P", 7, ACK_KILLED, 2000, NULL));
    char out[700];
    snprintf(out, sizeof out, "%s/P.out", h_work_dir);
    for (int t = 0; t < 100 && ModuleState("P") == CONTRACT_OK; t++) usleep(10000);
    char *text = h_read_file(out);
    CHECK_MSG(text && !strstr(text, "error") && !strstr(text, "warning"), "P said: %s", text ? text : "(nothing)");
    free(text);
    char *log = h_read_logs("P_");
    CHECK(log && strstr(log, "one-shot already spent") && strstr(log, "was not subscribed"));
    free(log);
    h_teardown();
}

/* "Is this module running?" (supervisors ask before starting a module of an event schema):
 * QueryStatus says running=yes from a START until the run ends or a STOP arrives, even when
 * nobody wants the STOP's ack. */
void test_status_running(void)
{
    REQUIRE(h_setup("status") == 0);
    REQUIRE(h_spawn_module("C1", "C1") > 0);
    char text[1024];
    RTIME soon = GetTime() + 2000000000LL;
    CHECK(QueryStatus("C1", text, sizeof text, soon) == CONTRACT_OK && strstr(text, " running=no"));
    CHECK(set_param("C1", 0, 5000));                 /* runs last 5 s unless stopped */
    CHECK(SendStart("C1", ACK_NOTHING, 0) == 0);
    CHECK(QueryStatus("C1", text, sizeof text, GetTime() + 2000000000LL) == CONTRACT_OK && strstr(text, " running=yes"));
    CHECK(SendStop("C1", ACK_NOTHING, 0) == 0);
    CHECK(QueryStatus("C1", text, sizeof text, GetTime() + 2000000000LL) == CONTRACT_OK && strstr(text, " running=no"));
    CHECK(set_param("C1", 0, 0));                    /* a run that finishes by itself */
    CHECK(run_once("C1", 5));
    CHECK(QueryStatus("C1", text, sizeof text, GetTime() + 2000000000LL) == CONTRACT_OK && strstr(text, " running=no"));
    CHECK(QueryStatus("NOPE", text, sizeof text, GetTime() + 100000000LL) == CONTRACT_EUNKNOWN);
    /* a loop that never goes back to WaitForRequest nor acks (WaitForRequestUntil / polling,
     * like an asynchronous module): here the tester itself, asking its own mailbox */
    RequestMessage *m = h_msg();
    CHECK(SendStart("tester", ACK_NOTHING, 0) == 0 && LookForRequest(m) && m->Type == REQ_START);
    CHECK(QueryStatus("tester", text, sizeof text, GetTime() + 2000000000LL) == CONTRACT_OK && strstr(text, " running=yes"));
    CHECK(SendStop("tester", ACK_NOTHING, 0) == 0 && LookForRequest(m) && m->Type == REQ_STOP);
    CHECK(QueryStatus("tester", text, sizeof text, GetTime() + 2000000000LL) == CONTRACT_OK && strstr(text, " running=no"));
    h_teardown();
}

static void on_alarm(int sig) { (void)sig; }

/* A child that sends SIGCONT to `pid` after `ms` milliseconds. */
static pid_t continue_later(pid_t pid, int ms)
{
    pid_t c = fork();
    if (c == 0) {
        usleep((useconds_t)ms * 1000);
        kill(pid, SIGCONT);
        _exit(0);
    }
    return c;
}

/* The supervisors' "is it running?" and "set its priority" answers stay true when the asker
 * gets signals and when an answer comes after its deadline (found under a stalled host: a
 * supervisor started a module another one held). While the asker takes a SIGALRM every
 * millisecond (no SA_RESTART), a query of a stopped module waits until the module answers;
 * and a late answer to an earlier query is never read as the answer to the next one. */
void test_status_through_signals(void)
{
    REQUIRE(h_setup("statussig") == 0);
    pid_t pid = h_spawn_module("C1", "C1");
    REQUIRE(pid > 0);
    CHECK(set_param("C1", 0, 5000)); /* runs last 5 s unless stopped */
    char text[1024];
    /* a query that times out: C1 is stopped, the query waits in its mailbox */
    REQUIRE(kill(pid, SIGSTOP) == 0);
    CHECK(QueryStatus("C1", text, sizeof text, GetTime() + 30000000LL) == CONTRACT_EBUSY);
    CHECK(SendStart("C1", ACK_NOTHING, 0) == 0); /* queued behind it */
    /* C1 goes on in 80 ms: it answers the old query (running=no), then starts its run */
    pid_t helper = continue_later(pid, 80);
    struct sigaction sa, old;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_alarm; /* no SA_RESTART: every blocking call sees EINTR */
    sigemptyset(&sa.sa_mask);
    sigaction(SIGALRM, &sa, &old);
    struct itimerval every_ms = { { 0, 1000 }, { 0, 1000 } }, off = { { 0, 0 }, { 0, 0 } };
    setitimer(ITIMER_REAL, &every_ms, NULL);
    int rc = QueryStatus("C1", text, sizeof text, GetTime() + 2000000000LL);
    setitimer(ITIMER_REAL, &off, NULL);
    CHECK_MSG(rc == CONTRACT_OK, "QueryStatus through signals: %s", ContractStrError(rc));
    CHECK_MSG(rc == CONTRACT_OK && strstr(text, " running=yes"), "the late answer was taken: '%s'", text);
    waitpid(helper, NULL, 0);
    /* the same for priorities: a late reply says the priority before an earlier request */
    int prev = -1;
    REQUIRE(kill(pid, SIGSTOP) == 0);
    CHECK(ContractSetModulePriority("C1", 20, &prev) == CONTRACT_EBUSY); /* 1 s without answer */
    helper = continue_later(pid, 80);
    setitimer(ITIMER_REAL, &every_ms, NULL);
    rc = ContractSetModulePriority("C1", 10, &prev);
    setitimer(ITIMER_REAL, &off, NULL);
    sigaction(SIGALRM, &old, NULL);
    CHECK_MSG(rc == 0 || rc == 1, "ContractSetModulePriority through signals: %s", ContractStrError(rc));
    CHECK_MSG(prev == 20, "previous priority %d: the late answer to the request for 20 was taken", prev);
    waitpid(helper, NULL, 0);
    CHECK(SendStop("C1", ACK_NOTHING, 0) == 0);
    h_teardown();
}

/* ContractAskModulePriority (the supervisor engine's priority changes): sent without waiting;
 * a synchronous wait of the same process meanwhile (a status query) keeps its answer instead of
 * dropping it as stale; ContractWaitModulePriority then gives it (the kept one first), and the
 * next answer comes through WaitForRequest as a REQ_PRIORITY_REPLY. */
void test_ask_module_priority(void)
{
    REQUIRE(h_setup("askprio") == 0);
    pid_t pid = h_spawn_module("C1", "C1");
    REQUIRE(pid > 0);
    RequestMessage *m = h_msg();
    unsigned s1 = 0, s2 = 0;
    REQUIRE(kill(pid, SIGSTOP) == 0); /* C1 busy: it answers when it goes on */
    CHECK(ContractAskModulePriority("C1", 20, &s1) == CONTRACT_OK);
    CHECK(ContractAskModulePriority("C1", 10, &s2) == CONTRACT_OK);
    CHECK(s1 != s2 && (s1 & 0x80000000u) && (s2 & 0x80000000u));
    CHECK(ContractAskModulePriority("C1", 0, &s1) == CONTRACT_EINVAL);
    CHECK(ContractAskModulePriority("NOPE", 10, NULL) == CONTRACT_EUNKNOWN);
    REQUIRE(kill(pid, SIGCONT) == 0);
    char text[1024];
    /* both answers come before the status answer: this wait keeps them */
    CHECK(QueryStatus("C1", text, sizeof text, GetTime() + 2000000000LL) == CONTRACT_OK);
    CHECK(ContractWaitModulePriority(GetTime() + 2000000000LL, m) == 1);
    CHECK(m->Type == REQ_PRIORITY_REPLY && m->Param.Priority.Seq == s1 && m->Param.Priority.Priority == 30 &&
          m->Param.Priority.Result == 0);
    int got = WaitForRequestUntil(m, GetTime() + 2000000000LL);
    CHECK(got == 1 && m->Type == REQ_PRIORITY_REPLY && m->Param.Priority.Seq == s2 && m->Param.Priority.Priority == 20);
    CHECK(ContractWaitModulePriority(GetTime() + 50000000LL, m) == 0); /* none left */
    CHECK(getpriority(PRIO_PROCESS, (id_t)pid) == (99 - 10) * 19 / 98);
    CHECK(SendKill("C1", ACK_NOTHING, 0) == 0);
    CHECK(h_wait_exit(pid, 2000) == 0);
    char *log = h_read_logs("tester_");
    CHECK(!log || !strstr(log, "PRIORITY_REPLY")); /* the answers are not request_received records */
    free(log);
    h_teardown();
}

/* A module busy in its run reads its mailbox once per state (100 ms here): a status query
   behind six parameter requests is answered at the next read, not after six more states (the
   engines' "is it running?" waited up to 0.5 s for it), and the requests ahead of it are all
   handled, in their order. A START read ahead with the request that ends the run is handed over
   once the run has ended: the module says it runs again (a run_started record, status). */
void test_status_behind_requests(void)
{
    REQUIRE(h_setup("statusahead") == 0);
    RequestMessage *m = h_msg();
    REQUIRE(h_spawn_module("C1", "C1") > 0);
    REQUIRE(set_param("C1", 16, 5000));
    CHECK(SendStart("C1", ACK_START | ACK_FINISHED, 1) == CONTRACT_OK);
    CHECK(h_wait_ack("C1", 1, ACK_START, 2000, m));
    usleep(150000); /* in its states */
    TestParam p;
    memset(&p, 0, sizeof p);
    p.flags = 16;
    p.run_ms = 5000;
    for (int i = 0; i < 6; i++) {
        snprintf(p.label, sizeof p.label, "request %d", i);
        CHECK(SendSetParam("C1", 0, &p, sizeof p, ACK_NOTHING, -1) == CONTRACT_OK);
    }
    char text[1024] = "";
    RTIME t0 = GetTime();
    CHECK(QueryStatus("C1", text, sizeof text, t0 + 2000000000LL) == CONTRACT_OK);
    double waited_ms = (double)(GetTime() - t0) / 1e6;
    CHECK_MSG(waited_ms < 350, "the status answer took %.0f ms (one state is 100 ms; six requests ahead of it)", waited_ms);
    CHECK_MSG(strstr(text, " running=yes") != NULL, "status '%s'", text);
    /* each parameter request handled, in order (the module reports each on port 3) */
    for (int i = 0; i < 6; i++) {
        CHECK(h_wait_event("C1", 3, 2000, m));
        char want[32];
        snprintf(want, sizeof want, "request %d", i);
        CHECK_MSG(strcmp(((TestParam *)m->Data)->label, want) == 0, "parameter %d: '%s'", i, ((TestParam *)m->Data)->label);
    }
    /* run_ms 0: the state after this request ends the run; the START behind it is read with it */
    p.run_ms = 0;
    snprintf(p.label, sizeof p.label, "end");
    CHECK(SendSetParam("C1", 0, &p, sizeof p, ACK_NOTHING, -1) == CONTRACT_OK);
    CHECK(SendStart("C1", ACK_START | ACK_FINISHED, 2) == CONTRACT_OK);
    CHECK(h_wait_event("C1", 3, 2000, m));
    CHECK(h_wait_ack("C1", 1, ACK_FINISHED, 2000, m)); /* run 1 ends */
    CHECK(h_wait_ack("C1", 2, ACK_START, 2000, m));    /* run 2 begins */
    CHECK(h_wait_ack("C1", 2, ACK_FINISHED, 2000, m));
    CHECK(QueryStatus("C1", text, sizeof text, GetTime() + 2000000000LL) == CONTRACT_OK);
    CHECK_MSG(strstr(text, " running=no") && strstr(text, " activations=2"), "status after run 2: '%s'", text);
    CHECK(SendKill("C1", ACK_KILLED, 3) == CONTRACT_OK);
    CHECK(h_wait_ack("C1", 3, ACK_KILLED, 2000, m));
    usleep(100000);
    char *log = h_read_logs("C1_");
    REQUIRE(log);
    int started = 0, finished = 0;
    for (const char *at = log; (at = strstr(at, ",C1,run_started,")) != NULL; at++) started++;
    for (const char *at = log; (at = strstr(at, ",C1,run_finished,")) != NULL; at++) finished++;
    CHECK_MSG(started == 2 && finished == 2, "%d run_started and %d run_finished records", started, finished);
    free(log);
    h_teardown();
}

/* A module whose log reaches CONTRACT_LOG_MAX_BYTES keeps its whole records up to the bound, then
   a `log-capped` record, and at exit a last one saying how many records were not written: the
   file stays a readable CSV, never larger than the bound (docs/runtime-api.md "CSV log"). */
void test_csv_log_cap(void)
{
    REQUIRE(h_setup("logcap") == 0);
    setenv("CONTRACT_LOG_MAX_BYTES", "8192", 1);
    RequestMessage *m = h_msg();
    pid_t pid = h_spawn_module("MSC", "MSC");
    unsetenv("CONTRACT_LOG_MAX_BYTES");
    REQUIRE(pid > 0);
    for (int i = 0; i < 150; i++) {
        CHECK(SendStart("MSC", ACK_FINISHED, 100 + i) == CONTRACT_OK);
        CHECK(h_wait_ack("MSC", 100 + i, ACK_FINISHED, 2000, m));
    }
    CHECK(SendKill("MSC", ACK_KILLED, 13) == CONTRACT_OK);
    CHECK(h_wait_ack("MSC", 13, ACK_KILLED, 2000, m));
    CHECK(h_wait_exit(pid, 2000) == 0);
    char *log = h_read_logs("MSC_");
    REQUIRE(log);
    size_t len = strlen(log);
    CHECK_MSG(len <= 8192, "the log holds %zu bytes, above its 8192-byte bound", len);
    CHECK(strncmp(log, "mono_ns,wall_time,module,event,peer,port,size,detail\n", 52) == 0);
    CHECK(strstr(log, ",MSC,run_started,tester,,0,activation=1\n") && strstr(log, ",MSC,ack_sent,tester,,0,ACK_FINISHED id=100\n"));
    CHECK(len > 0 && log[len - 1] == '\n');
    int caps = 0, lines = 0;
    const char *last = log;
    for (char *line = log, *nl; (nl = strchr(line, '\n')) != NULL; line = nl + 1) {
        *nl = '\0';
        int commas = 0;
        for (const char *c = line; *c; c++) commas += *c == ',';
        CHECK_MSG(commas >= 7, "line %d is not a whole record: '%s'", lines, line);
        if (strstr(line, ",MSC,log-capped,,,8192,")) caps++;
        last = line;
        lines++;
    }
    CHECK_MSG(caps == 2, "%d log-capped records, expected 2", caps);
    CHECK_MSG(strstr(last, ",MSC,log-capped,") && strstr(last, " records not written after the log reached its 8192-byte bound"),
              "last record: '%s'", last);
    free(log);
    h_teardown();
}

/* The largest mono_ns of a log's records (0 when none). */
static unsigned long long max_mono(const char *log)
{
    unsigned long long max = 0;
    for (const char *line = log; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
        unsigned long long v = strtoull(line, NULL, 10);
        if (v > max) max = v;
    }
    return max;
}

/* With CONTRACT_LOG_MARK=1 a module keeps <log>.mark: its first word is 0 when the file holds every
   record logged, else the mono_ns of the oldest record not written yet (never a record of the file,
   never in the future), and that record reaches the file; the mark is removed at exit
   (docs/build-service-api.md "Trace channel"). */
void test_csv_log_mark(void)
{
    REQUIRE(h_setup("logmark") == 0);
    setenv("CONTRACT_LOG_MARK", "1", 1);
    RequestMessage *m = h_msg();
    pid_t pid = h_spawn_module("MSC", "MSC");
    unsetenv("CONTRACT_LOG_MARK");
    REQUIRE(pid > 0);
    char csv[1024], mark[1024];
    REQUIRE(h_find_log_file("MSC_", ".csv", csv, sizeof csv));
    REQUIRE(h_find_log_file("MSC_", ".csv.mark", mark, sizeof mark));
    int fd = open(mark, O_RDONLY | O_CLOEXEC);
    REQUIRE(fd >= 0);
    unsigned long long dirty = 0;
    for (int i = 0; i < 50 && !dirty; i++) {
        CHECK(SendStart("MSC", ACK_FINISHED, 200 + i) == CONTRACT_OK);
        CHECK(h_wait_ack("MSC", 200 + i, ACK_FINISHED, 2000, m));
        char *before = h_read_file(csv);
        unsigned long long word = 0;
        CHECK(pread(fd, &word, sizeof word, 0) == (ssize_t)sizeof word);
        if (word >= 2) {
            dirty = word;
            CHECK_MSG(word <= (unsigned long long)GetTime(), "mark %llu is in the future", word);
            CHECK_MSG(max_mono(before) < word, "the file already held a record at %llu >= the mark %llu", max_mono(before), word);
        } else {
            CHECK_MSG(word == 0 || word == 1, "mark word %llu", word);
        }
        free(before);
    }
    CHECK_MSG(dirty != 0, "the mark never showed a record waiting to be written");
    /* the module waits: its records are written within LOG_FLUSH_NS and the mark says so */
    unsigned long long word = 1;
    for (int i = 0; i < 200 && word != 0; i++) {
        usleep(10000);
        CHECK(pread(fd, &word, sizeof word, 0) == (ssize_t)sizeof word);
    }
    CHECK_MSG(word == 0, "the mark still says %llu after 2 s of waiting", word);
    char *log = h_read_file(csv);
    REQUIRE(log);
    char want[32];
    snprintf(want, sizeof want, "\n%llu,", dirty);
    CHECK_MSG(strstr(log, want) != NULL, "no record at the mark's time %llu in the log", dirty);
    free(log);
    CHECK(SendKill("MSC", ACK_KILLED, 14) == CONTRACT_OK);
    CHECK(h_wait_ack("MSC", 14, ACK_KILLED, 2000, m));
    CHECK(h_wait_exit(pid, 2000) == 0);
    CHECK_MSG(access(mark, F_OK) != 0, "%s left after exit", mark);
    close(fd);
    h_teardown();
}

/* The flush mark's second word is the reader's: a flush delay of 1 ms..50 ms the module then uses
   instead of LOG_FLUSH_NS (anything else: LOG_FLUSH_NS); in process, on the tester's own log. */
void test_csv_log_mark_delay(void)
{
    REQUIRE(h_setup("logmarkdelay") == 0);
    CHECK(ContractLogFlushDelay() == LOG_FLUSH_NS); /* no log, no mark */
    setenv("CONTRACT_LOG_MARK", "1", 1);
    REQUIRE(rt_log_open() == 0);
    unsetenv("CONTRACT_LOG_MARK");
    char mark[1024];
    REQUIRE(h_find_log_file("tester_", ".csv.mark", mark, sizeof mark));
    int fd = open(mark, O_RDWR | O_CLOEXEC);
    REQUIRE(fd >= 0);
    unsigned long long asked, word = 7;
    CHECK(ContractLogFlushDelay() == LOG_FLUSH_NS);
    asked = 10000000ULL;
    CHECK(pwrite(fd, &asked, sizeof asked, 8) == (ssize_t)sizeof asked);
    CHECK(ContractLogFlushDelay() == 10000000LL);
    asked = 500000ULL; /* below 1 ms: not believed */
    CHECK(pwrite(fd, &asked, sizeof asked, 8) == (ssize_t)sizeof asked);
    CHECK(ContractLogFlushDelay() == LOG_FLUSH_NS);
    asked = 100000000000ULL; /* 100 s: not longer than LOG_FLUSH_NS */
    CHECK(pwrite(fd, &asked, sizeof asked, 8) == (ssize_t)sizeof asked);
    CHECK(ContractLogFlushDelay() == LOG_FLUSH_NS);
    /* the first word: the oldest record not written, then 0 once written */
    RTIME before = GetTime();
    ContractLog("test_record", "", -1, 0, "x");
    CHECK(pread(fd, &word, sizeof word, 0) == (ssize_t)sizeof word);
    CHECK_MSG(word >= (unsigned long long)before && word <= (unsigned long long)GetTime(), "mark %llu, logged after %lld", word, (long long)before);
    ContractLogFlush();
    CHECK(pread(fd, &word, sizeof word, 0) == (ssize_t)sizeof word);
    CHECK(word == 0);
    rt_log_close();
    CHECK_MSG(access(mark, F_OK) != 0, "%s left after close", mark);
    CHECK(ContractLogFlushDelay() == LOG_FLUSH_NS);
    close(fd);
    h_teardown();
}

/* Flush boundaries: buffered records are due at the first multiple of the flush delay on
   CLOCK_MONOTONIC after the oldest of them (every module of a run writes at the same instants),
   written at that instant and not before; in process, on the tester's own log. */
void test_csv_log_flush_boundary(void)
{
    REQUIRE(h_setup("logboundary") == 0);
    REQUIRE(rt_log_open() == 0);
    const RTIME delay = 10000000LL;
    CHECK(ContractLogFlushDue(delay) == 0); /* nothing buffered */
    ContractLog("test_record", "", -1, 0, "x");
    RTIME since = ContractLogPendingSince();
    REQUIRE(since > 0);
    RTIME due = ContractLogFlushDue(delay);
    CHECK_MSG(due % delay == 0, "due %lld is not on a %lld ns boundary", (long long)due, (long long)delay);
    CHECK_MSG(due > since && due - since <= delay, "due %lld for a record of %lld", (long long)due, (long long)since);
    ContractLogFlushIfDue(due - 1, delay);
    CHECK_MSG(ContractLogPendingSince() == since, "written before its boundary");
    ContractLog("test_record", "", -1, 0, "y"); /* a younger record rides with the oldest */
    CHECK(ContractLogFlushDue(delay) == due);
    ContractLogFlushIfDue(due, delay);
    CHECK_MSG(ContractLogPendingSince() == 0, "not written at its boundary");
    CHECK(ContractLogFlushDue(delay) == 0);
    ContractLogFlush(); /* the writer thread's write ends (a busy writer: test_log_writer.c) */
    /* the library's own wait uses the same boundaries with its delay */
    ContractLog("test_record", "", -1, 0, "z");
    RTIME lib_due = ContractLogFlushDue(ContractLogFlushDelay());
    CHECK_MSG(lib_due % ContractLogFlushDelay() == 0, "library due %lld off its boundary", (long long)lib_due);
    rt_log_maybe_flush(lib_due - 1);
    CHECK_MSG(ContractLogPendingSince() != 0, "the library wrote before its boundary");
    rt_log_maybe_flush(lib_due);
    CHECK_MSG(ContractLogPendingSince() == 0, "the library did not write at its boundary");
    rt_log_close();
    h_teardown();
}

/* Removes what a module that died outside contract-launch left in the run directory (the launcher
   removes it otherwise). */
static void remove_files_of(const char *name)
{
    DIR *d = opendir(h_run_dir);
    if (!d) return;
    size_t n = strlen(name);
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strncmp(e->d_name, name, n) == 0 && e->d_name[n] == '.') unlinkat(dirfd(d), e->d_name, 0);
    closedir(d);
}

/* Lines (records) of a log after its header. */
static int record_lines(const char *log)
{
    int n = 0;
    for (const char *c = log; *c; c++) n += *c == '\n';
    return n - 1;
}

/* The last line of a log (a static copy). */
static const char *last_line(const char *log)
{
    static char line[1024];
    size_t len = strlen(log);
    if (len && log[len - 1] == '\n') len--;
    size_t from = len;
    while (from > 0 && log[from - 1] != '\n') from--;
    snprintf(line, sizeof line, "%.*s", (int)(len - from), log + from);
    return line;
}

/* Starts P with $TMOD_CRASH_LOG=P:how, sends it a START (at which it logs its crash_test records
   and crashes) and returns its log once it died (NULL: no log); *status: as h_wait_exit. */
static char *crash_run(const char *how, int *status)
{
    char env[64];
    snprintf(env, sizeof env, "P:%s", how);
    setenv("TMOD_CRASH_LOG", env, 1);
    pid_t pid = h_spawn_module("P", "P");
    unsetenv("TMOD_CRASH_LOG");
    *status = -1;
    if (pid <= 0) return NULL;
    if (SendStart("P", ACK_NOTHING, 1) != CONTRACT_OK) return NULL;
    *status = h_wait_exit(pid, 5000);
    remove_files_of("P");
    char csv[1024];
    return h_find_log_file("P_", ".csv", csv, sizeof csv) ? h_read_file(csv) : NULL; /* (not its .mark) */
}

/* `before crash 1`..`n` each once, in order, from `from` on; returns the end of the last one (NULL: not so). */
static const char *crash_records_in_order(const char *from, int n)
{
    const char *at = from;
    for (int i = 1; i <= n && at; i++) {
        char want[64];
        snprintf(want, sizeof want, ",P,crash_test,,,0,before crash %d\n", i);
        const char *found = strstr(at, want);
        CHECK_MSG(found != NULL, "record 'before crash %d' missing or out of order", i);
        if (!found) return NULL;
        CHECK_MSG(strstr(found + 1, want) == NULL, "record 'before crash %d' written twice", i);
        at = found + strlen(want);
    }
    return at;
}

/* The function addr2line names for offset `off` of the test's module P (a static copy; "" when none). */
static const char *function_at(const char *off)
{
    static char fn[256];
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "addr2line -f -i -e '%s/P' %s 2>/dev/null", h_bin_dir, off);
    fn[0] = '\0';
    FILE *f = popen(cmd, "r");
    if (!f) return fn;
    if (!fgets(fn, sizeof fn, f)) fn[0] = '\0';
    pclose(f);
    fn[strcspn(fn, "\n")] = '\0';
    return fn;
}

/* A crash writes one crash report on stderr (crash_report.c): the module, the signal, then the
   frames, the first the instruction that faulted, each an offset in its object that addr2line maps
   to the function it is in; a stack overflow too (the handler's stack is its own); the process
   still dies by its signal. */
void test_crash_report(void)
{
    setenv("TEST_BIN_DIR", h_bin_dir, 1);
    static const struct { const char *how; int sig; const char *name; const char *fn; int first; } cases[] = {
        { "segv", SIGSEGV, "SIGSEGV", "null_store", 1 }, { "fpe", SIGFPE, "SIGFPE", "divide_by_zero", 1 },
        { "stack", SIGSEGV, "SIGSEGV", "deep", 1 }, { "abort", SIGABRT, "SIGABRT", "exec_state", 0 },
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        REQUIRE(h_setup("crashreport") == 0);
        int status;
        free(crash_run(cases[c].how, &status));
        CHECK_MSG(status == h_crash_status(cases[c].sig), "%s: the module ended with %d, not as signal %d's crash", cases[c].how, status, cases[c].sig);
        char out[1024];
        snprintf(out, sizeof out, "%s/P.out", h_work_dir);
        char *text = h_read_file(out);
        REQUIRE(text);
        if (h_asan_reports(cases[c].sig)) { /* ASan's report, not the crash report */
            CHECK_MSG(strstr(text, "ERROR: AddressSanitizer: ") != NULL, "%s: no ASan report in: %s", cases[c].how, text);
            CHECK_MSG(strstr(text, "==contract-crash==") == NULL, "%s: a crash report under ASan: %s", cases[c].how, text);
            free(text);
            h_teardown();
            continue;
        }
        char head[128];
        /* a null store's address is 0; abort() is sent, no fault: no address either */
        snprintf(head, sizeof head, "==contract-crash== module P signal %d %s addr 0x%s", cases[c].sig, cases[c].name,
                 strcmp(cases[c].how, "segv") == 0 || strcmp(cases[c].how, "abort") == 0 ? "0\n" : "");
        const char *at = strstr(text, head);
        CHECK_MSG(at != NULL, "%s: no crash report head '%s' in: %s", cases[c].how, head, text);
        CHECK_MSG(!at || !strstr(at + 1, "==contract-crash== module "), "%s: two crash reports", cases[c].how);
        /* the line after the head: the executable's build-id, as readelf says it */
        char want_id[200] = "", id_line[240];
        FILE *re = popen("readelf -n \"$TEST_BIN_DIR/P\" 2>/dev/null | sed -n 's/^ *Build ID: *//p'", "r");
        if (re) { if (!fgets(want_id, sizeof want_id, re)) want_id[0] = '\0'; pclose(re); }
        want_id[strcspn(want_id, "\n")] = '\0';
        snprintf(id_line, sizeof id_line, "\n==contract-crash== build-id %s\n==contract-crash== frame 0 ", want_id);
        CHECK_MSG(want_id[0] && at && strstr(at, id_line) == strchr(at, '\n'), "%s: no build-id line '%s' after the head: %s", cases[c].how, want_id, at ? at : text);
        int frames = 0, found = 0, told = -1;
        for (const char *line = at; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
            int i;
            char object[64], off[32];
            if (sscanf(line, "==contract-crash== frame %d %63s %31s", &i, object, off) == 3) {
                CHECK_MSG(i == frames, "%s: frame %d numbered %d", cases[c].how, frames, i);
                frames++;
                /* a caller's frame is a return address: its call is the instruction before */
                char call[32];
                snprintf(call, sizeof call, "0x%llx", strtoull(off, NULL, 16) - (i > 0));
                if (strcmp(object, "exe") == 0 && (!cases[c].first || i == 0) && strcmp(function_at(call), cases[c].fn) == 0) found = 1;
            } else if (sscanf(line, "==contract-crash== end %d frames", &told) == 1) {
                break;
            }
        }
        CHECK_MSG(frames > 0 && frames <= 48 && told == frames, "%s: %d frames, the end line says %d", cases[c].how, frames, told);
        CHECK_MSG(found, "%s: no frame (%s) in %s: %s", cases[c].how, cases[c].first ? "the first" : "any", cases[c].fn, at ? at : text);
        free(text);
        h_teardown();
    }
}

/* A module whose code crashes loses none of its records: the records it logged just before the
   crash (well inside the flush delay, still in its buffer) are written, in order, after those the
   writer thread wrote, then a `module_crashed` record; the process still dies by its signal
   (docs/runtime-api.md "CSV log"). */
void test_csv_log_crash(void)
{
    static const struct { const char *how; int sig; const char *name; } cases[] = {
        { "segv", SIGSEGV, "SIGSEGV" }, { "abort", SIGABRT, "SIGABRT" }, { "fpe", SIGFPE, "SIGFPE" },
        { "stack", SIGSEGV, "SIGSEGV" }, { "inlog", SIGSEGV, "SIGSEGV" }, { "many", SIGSEGV, "SIGSEGV" },
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        REQUIRE(h_setup("logcrash") == 0);
        if (c == 0) setenv("CONTRACT_LOG_MARK", "1", 1);
        int status;
        char *log = crash_run(cases[c].how, &status);
        unsetenv("CONTRACT_LOG_MARK");
        CHECK_MSG(status == h_crash_status(cases[c].sig), "%s: the module ended with %d, not as signal %d's crash", cases[c].how, status, cases[c].sig);
        CHECK_MSG(log != NULL, "%s: no log", cases[c].how);
        if (!log) { h_teardown(); continue; }
        CHECK(strncmp(log, "mono_ns,wall_time,module,event,peer,port,size,detail\n", 52) == 0);
        const char *start = strstr(log, ",P,request_received,tester,,0,START\n"); /* the release that led to it */
        CHECK_MSG(start != NULL, "%s: the START is not in the log", cases[c].how);
        const char *end = crash_records_in_order(start ? start : log, strcmp(cases[c].how, "many") == 0 ? 3000 : 5);
        char want[128];
        snprintf(want, sizeof want, ",P,module_crashed,,,0,signal %d (%s) records=%d", cases[c].sig, cases[c].name, record_lines(log));
        const char *last = last_line(log);
        CHECK_MSG(strstr(last, want) != NULL, "%s: last record '%s', expected '...%s'", cases[c].how, last, want);
        /* the crash record is the line after the last record logged (inlog: the record being logged is not written) */
        const char *nl = end ? strchr(end, '\n') : NULL;
        const char *crashed = end ? strstr(end, ",P,module_crashed,") : NULL;
        CHECK_MSG(nl && nl[1] == '\0' && crashed && crashed < nl, "%s: not one crash record right after the last crash_test record", cases[c].how);
        if (c == 0) { /* the mark says the log is whole */
            char mark[1024];
            unsigned long long word = 7;
            if (h_find_log_file("P_", ".csv.mark", mark, sizeof mark)) {
                int fd = open(mark, O_RDONLY | O_CLOEXEC);
                CHECK(fd >= 0 && pread(fd, &word, sizeof word, 0) == (ssize_t)sizeof word);
                if (fd >= 0) close(fd);
            }
            CHECK_MSG(word == 0, "the mark word after the crash: %llu", word);
        }
        free(log);
        h_teardown();
    }

    /* a module blocked in its own code and terminated (the launcher's SIGTERM at the stop): the
     * records it logged before, still in its buffer, are written; no record of its own */
    REQUIRE(h_setup("logterm") == 0);
    setenv("TMOD_CRASH_LOG", "P:block", 1);
    pid_t pid = h_spawn_module("P", "P");
    unsetenv("TMOD_CRASH_LOG");
    REQUIRE(pid > 0);
    CHECK(SendStart("P", ACK_NOTHING, 1) == CONTRACT_OK);
    usleep(300000); /* far past the log's flush delay: nothing writes a blocked module's buffer */
    kill(pid, SIGTERM);
    CHECK(h_wait_exit(pid, 5000) == 128 + SIGTERM);
    remove_files_of("P");
    char csv[1024];
    char *termlog = h_find_log_file("P_", ".csv", csv, sizeof csv) ? h_read_file(csv) : NULL;
    REQUIRE(termlog);
    const char *tstart = strstr(termlog, ",P,request_received,tester,,0,START\n");
    CHECK_MSG(tstart != NULL, "the START is not in the terminated module's log");
    const char *tend = crash_records_in_order(tstart ? tstart : termlog, 5);
    CHECK_MSG(tend && *tend == '\0', "the terminated module's log does not end with its 5 records: '%s'", last_line(termlog));
    CHECK(!strstr(termlog, "module_crashed") && !strstr(termlog, "module_exit"));
    free(termlog);
    h_teardown();

    /* within the log's bound: whole records, log-capped, the last log-capped record; never larger */
    REQUIRE(h_setup("logcrashcap") == 0);
    setenv("CONTRACT_LOG_MAX_BYTES", "8192", 1);
    int status;
    char *log = crash_run("many", &status);
    unsetenv("CONTRACT_LOG_MAX_BYTES");
    CHECK_MSG(status == h_crash_status(SIGSEGV), "the capped module ended with %d", status);
    REQUIRE(log);
    size_t len = strlen(log);
    CHECK_MSG(len <= 8192, "the log holds %zu bytes, above its 8192-byte bound", len);
    CHECK(strstr(log, ",P,log-capped,,,8192,log reached its 8192-byte bound (CONTRACT_LOG_MAX_BYTES): later records are not written\n"));
    CHECK_MSG(strstr(last_line(log), ",P,log-capped,,,8192,") && strstr(last_line(log), " records not written after the log reached its 8192-byte bound"),
              "last record: '%s'", last_line(log));
    CHECK(len > 0 && log[len - 1] == '\n');
    free(log);
    h_teardown();
}
