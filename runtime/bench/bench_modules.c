/* Modules used by the runtime benchmark, built under several names:
 *   PONG  (-DBENCH_PONG): answers every START with ACK_START (request/ack round trip)
 *   SRC   (-DBENCH_SRC):  on START posts BENCH_MSGS values of 1 KiB on data port 0
 *   SINK  (-DBENCH_SINK): on START consumes BENCH_MSGS values of 1 KiB, then ACK_FINISHED */
#define _GNU_SOURCE
#include <libmodule/libmodule.h>
#include <sched.h>
#include <string.h>

#define BENCH_MSGS 100000L
typedef struct { long seq; unsigned char bytes[1024 - sizeof(long)]; } KiB;
KiB value;

#if defined(BENCH_PONG)
char MODULE_NAME[] = "PONG";
ModuleUse IUSE[] = { IUSE_TERM };
ModuleProduce IPRODUCE[] = { IPRODUCE_TERM };
#elif defined(BENCH_SRC)
char MODULE_NAME[] = "SRC";
ModuleUse IUSE[] = { IUSE_TERM };
ModuleProduce IPRODUCE[] = { { &value, 0, sizeof(KiB) }, IPRODUCE_TERM };
#else
char MODULE_NAME[] = "SINK";
ModuleUse IUSE[] = { { &value, 0, sizeof(KiB), "---", 0, 1 }, IUSE_TERM };
ModuleProduce IPRODUCE[] = { IPRODUCE_TERM };
#endif
int MODULE_PRIORITY = 99; /* nice 0 when SCHED_FIFO is not used: same footing as the raw ping-pong */
ModuleReact IREACT[] = { IREACT_TERM };
ModuleDetect IDETECT[] = { IDETECT_TERM };
size_t PARAM_SIZE_IN[] = { PARAM_SIZE_TERM };
size_t PARAM_SIZE_OUT[] = { PARAM_SIZE_TERM };

int ModuleMain(int argc, const char *argv[])
{
    (void)argc; (void)argv;
    RequestMessage m;
    while (WaitForRequest(&m) != NULL) {
        switch (m.Type) {
        case REQ_KILL: return 0;
        case REQ_SUBSCRIBE:
            SubscribeUser(m.Param.Subscribe.SourcePort, m.Param.Subscribe.TargetModule, m.Param.Subscribe.TargetPort,
                          m.Param.Subscribe.Periodicity, m.Param.Subscribe.isContextual);
            SendAck(m.Sender, 0, ACK_FINISHED, 77);
            break;
        case REQ_START:
            SendAck(m.Param.Start.ModAck, m.Param.Start.WantedAck, ACK_START, m.Param.Start.AckID);
#if defined(BENCH_SRC)
            for (long i = 0; i < BENCH_MSGS; i++) {
                value.seq = i;
                while (PostData(&value) < 1) sched_yield(); /* consumer queue full: retry */
            }
#elif defined(BENCH_SINK)
            for (long got = 0; got < BENCH_MSGS;) {
                if (GetData(&value, NULL, NULL) == 1) got++;
                else sched_yield();
            }
            SendAck(m.Param.Start.ModAck, m.Param.Start.WantedAck, ACK_FINISHED, m.Param.Start.AckID);
#endif
            break;
        default: break;
        }
    }
    return 0;
}
