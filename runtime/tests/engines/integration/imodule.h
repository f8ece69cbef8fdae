/*
 * imodule.h — what the integration test's modules (imod.c, amod.c) share: their trace file
 * and the connection requests every module answers the same way. Header-only (each module
 * is one source file).
 */
#ifndef ITEST_IMODULE_H
#define ITEST_IMODULE_H

#include <libmodule/libmodule.h>
#include <stdio.h>
#include <stdlib.h>

#include "../engine_executable.h" /* under ASan, SCHED_OTHER before the leak check at exit */

/** $ITEST_OUT/<name>.trace opened for writing, line-buffered; NULL without ITEST_OUT. */
static inline FILE *imodule_open_trace(const char *name) {
    const char *dir = getenv("ITEST_OUT");
    if (!dir || !*dir) return NULL;
    char path[512];
    snprintf(path, sizeof path, "%s/%s.trace", dir, name);
    FILE *f = fopen(path, "w");
    if (f) setvbuf(f, NULL, _IOLBF, 0);
    return f;
}

/** Applies a data or event (un)subscription request. Returns 1 if m was one, else 0. */
static inline int imodule_connect(const RequestMessage *m) {
    switch (m->Type) {
    case REQ_SUBSCRIBE:
        SubscribeUser(m->Param.Subscribe.SourcePort, m->Param.Subscribe.TargetModule, m->Param.Subscribe.TargetPort,
                      m->Param.Subscribe.Periodicity, m->Param.Subscribe.isContextual);
        return 1;
    case REQ_UNSUBSCRIBE:
        UnsubscribeUser(m->Param.Unsubscribe.SourcePort, m->Param.Unsubscribe.TargetModule,
                        m->Param.Unsubscribe.TargetPort);
        return 1;
    case REQ_SUB_EVENT:
        SubscribeUserToEvent(m->Param.SubscribeEvent.targetModule, m->Param.SubscribeEvent.targetPort,
                             m->Param.SubscribeEvent.sourcePort, m->Param.SubscribeEvent.mode);
        return 1;
    case REQ_UNSUB_EVENT:
        UnsubscribeUserToEvent(m->Param.UnsubscribeEvent.targetModule, m->Param.UnsubscribeEvent.targetPort,
                               m->Param.UnsubscribeEvent.sourcePort);
        return 1;
    default:
        return 0;
    }
}

#endif
