/* ECHO: a module whose ports have the extension types (tests/modules/ext_types.h). Every event
 * received on input event port k goes out again on output event port k (same type); a
 * parameter (port 0, XScan) is posted as data on output data port 0; a run reads input data
 * port 0 (XScan) and posts it as an event on output event port 4. So a driver subscribed to
 * its outputs sees every value after a trip through real mailboxes. */
#define _GNU_SOURCE
#include <libmodule/libmodule.h>
#include <stdio.h>
#include <string.h>
#include "ext_types.h"

MODULE_DESCRIPTION("extension types echo");
MODULE_AUTHOR("runtime tests");

static bool b_in, b_out;
static XMode mode_in, mode_out;
static double m_in[3][3], m_out[3][3];
static XCell cells_in[4], cells_out[4];
static XScan scan_in, scan_out, param, produced, used;

char MODULE_NAME[] = "ECHO";
int MODULE_PRIORITY = 30;
ModuleUse IUSE[] = { { &used, 0, sizeof used, "---", 0, 1 }, IUSE_TERM };
ModuleProduce IPRODUCE[] = { { &produced, 0, sizeof produced }, IPRODUCE_TERM };
ModuleReact IREACT[] = { { &b_in, 0, sizeof b_in, "---", 0, 0 }, { &mode_in, 1, sizeof mode_in, "---", 0, 0 },
                         { m_in, 2, sizeof m_in, "---", 0, 0 }, { cells_in, 3, sizeof cells_in, "---", 0, 0 },
                         { &scan_in, 4, sizeof scan_in, "---", 0, 0 }, IREACT_TERM };
ModuleDetect IDETECT[] = { { &b_out, 0, sizeof b_out }, { &mode_out, 1, sizeof mode_out }, { m_out, 2, sizeof m_out },
                           { cells_out, 3, sizeof cells_out }, { &scan_out, 4, sizeof scan_out }, IDETECT_TERM };
size_t PARAM_SIZE_IN[] = { sizeof(XScan), PARAM_SIZE_TERM };
size_t PARAM_SIZE_OUT[] = { PARAM_SIZE_TERM };

static void echo(int port)
{
    switch (port) {
    case 0: b_out = b_in; PostEvent(&b_out); break;
    case 1: mode_out = mode_in; PostEvent(&mode_out); break;
    case 2: memcpy(m_out, m_in, sizeof m_out); PostEvent(m_out); break;
    case 3: memcpy(cells_out, cells_in, sizeof cells_out); PostEvent(cells_out); break;
    case 4: scan_out = scan_in; PostEvent(&scan_out); break;
    default: break;
    }
}

int ModuleMain(int argc, const char *argv[])
{
    (void)argc; (void)argv;
    RequestMessage m;
    RTIME produced_at, received_at;
    for (;;) {
        if (!WaitForRequest(&m)) continue;
        switch (m.Type) {
        case REQ_EVENT: {
            int port = GetEventId(&produced_at, &received_at);
            if (port >= 0) echo(port);
            break;
        }
        case REQ_SETPARAM:
            if (m.Param.SetParam.Port == 0 &&
                GetDataFromSetParamRequest(&m, &param, sizeof param, &produced_at, &received_at) == 0) {
                produced = param;
                PostData(&produced);
            }
            break;
        case REQ_START:
            if (GetData(&used, &produced_at, &received_at) == 1) {
                scan_out = used;
                PostEvent(&scan_out);
            }
            if (m.Param.Start.WantedAck & ACK_FINISHED)
                SendAck(m.Param.Start.ModAck, m.Param.Start.WantedAck, ACK_FINISHED, m.Param.Start.AckID);
            break;
        case REQ_SUBSCRIBE:
            SubscribeUser(m.Param.Subscribe.SourcePort, m.Param.Subscribe.TargetModule, m.Param.Subscribe.TargetPort,
                          m.Param.Subscribe.Periodicity, m.Param.Subscribe.isContextual);
            SendAck(m.Sender, 0, ACK_FINISHED, 900 + m.Param.Subscribe.TargetPort);
            break;
        case REQ_SUB_EVENT:
            SubscribeUserToEvent(m.Param.SubscribeEvent.targetModule, m.Param.SubscribeEvent.targetPort,
                                 m.Param.SubscribeEvent.sourcePort, m.Param.SubscribeEvent.mode);
            SendAck(m.Sender, 0, ACK_FINISHED, 800 + m.Param.SubscribeEvent.targetPort);
            break;
        case REQ_KILL:
            if (m.Param.Kil.WantedAck & ACK_KILLED)
                SendAck(m.Param.Kil.ModAck, m.Param.Kil.WantedAck, ACK_KILLED, m.Param.Kil.AckID);
            return 0;
        default:
            break;
        }
    }
}
