/* Event flows: events travel as REQ_EVENT requests in the subscriber's mailbox; the producer
 * keeps the subscribers of each output event port (continuous or one-shot). A one-shot
 * subscriber stays listed as spent after its notification, so that the undo of its
 * subscription (REQ_UNSUB_EVENT) is recognised and accepted quietly. */
#define _GNU_SOURCE
#include <stdlib.h>
#include <string.h>
#include "internal.h"

#define EVENT_SPENT (-1) /* Subscriber.periodicity of a one-shot subscription already notified */

static int find_detect_var(const void *var)
{
    for (int i = 0; i < g_rt.n_idetect; i++) if (g_rt.idetect[i].Variable == var) return i;
    return -1;
}

static int find_detect_port(int port)
{
    for (int i = 0; i < g_rt.n_idetect; i++) if (g_rt.idetect[i].Port == port) return i;
    return -1;
}

int rt_eventflow_setup(void)
{
    if (g_rt.n_idetect) {
        g_rt.event_subs = calloc((size_t)g_rt.n_idetect, sizeof(Subscriber *));
        if (!g_rt.event_subs) { rt_error("out of memory"); return -1; }
    }
    return 0;
}

void rt_eventflow_teardown(void)
{
    for (int i = 0; g_rt.event_subs && i < g_rt.n_idetect; i++) {
        Subscriber *s = g_rt.event_subs[i];
        while (s) { Subscriber *n = s->next; free(s); s = n; }
    }
    free(g_rt.event_subs);
    g_rt.event_subs = NULL;
}

void rt_remember_event(const RequestMessage *msg)
{
    if (!g_rt.last_event) {
        g_rt.last_event = malloc(sizeof *g_rt.last_event);
        if (!g_rt.last_event) { rt_error("out of memory: event dropped"); return; }
    }
    memcpy(g_rt.last_event, msg, REQUEST_HEADER_SIZE + msg->DataSize);
}

/* PostEvent's sends that waited for room in a subscriber's full mailbox (its consumer reads its
 * events slower than they come) are told by `event_waited` records, one per streak, not one per
 * wait: a streak ends (its record written) at the first post to that subscriber 1 s or more after
 * the streak's first wait, at the unsubscription and at the module's exit. So at most one record a
 * second per subscriber, however fast the producer posts; no allocation, a few words per post. */
#define WAIT_STREAK_NS 1000000000LL

static void say_waits(Subscriber *s, const ModuleDetect *o, RTIME now)
{
    char detail[160];
    snprintf(detail, sizeof detail, "to_port=%d waits=%ld wait_ns=%lld max_wait_ns=%lld streak_ns=%lld", s->port, s->waits,
             (long long)s->wait_ns, (long long)s->wait_max_ns, (long long)(now - s->wait_since));
    ContractLog("event_waited", s->module, o->Port, o->Size, detail);
    s->waits = 0;
    s->wait_ns = s->wait_max_ns = s->wait_since = 0;
}

/* One post's send to s: counted in its streak when it waited (`waited` ns); the streak's record
 * when it has lasted WAIT_STREAK_NS */
static void count_wait(Subscriber *s, const ModuleDetect *o, RTIME waited)
{
    if (waited <= 0 && s->waits == 0) return;
    RTIME now = GetTime();
    if (waited > 0) {
        if (s->waits++ == 0) s->wait_since = now - waited;
        s->wait_ns += waited;
        if (waited > s->wait_max_ns) s->wait_max_ns = waited;
    }
    if (now - s->wait_since >= WAIT_STREAK_NS) say_waits(s, o, now);
}

void rt_eventflow_say_waits(void)
{
    for (int d = 0; g_rt.event_subs && d < g_rt.n_idetect; d++)
        for (Subscriber *s = g_rt.event_subs[d]; s; s = s->next)
            if (s->waits) say_waits(s, &g_rt.idetect[d], GetTime());
}

static int has_live_subscriber(int d)
{
    for (const Subscriber *s = g_rt.event_subs[d]; s; s = s->next)
        if (s->periodicity != EVENT_SPENT) return 1;
    return 0;
}

int PostEvent(void *var)
{
    int d = find_detect_var(var);
    if (d < 0) { rt_error("PostEvent: this address is not the variable of an output event port (IDETECT)"); return -1; }
    const ModuleDetect *o = &g_rt.idetect[d];
    int reached = 0;
    Subscriber **it = &g_rt.event_subs[d];
    while (*it) {
        Subscriber *s = *it;
        if (s->periodicity == EVENT_SPENT) { it = &s->next; continue; }
        g_rt.send_waited_ns = 0;
        int rc = SendEvent(s->module, s->port, o->Port, var, o->Size);
        char detail[64];
        snprintf(detail, sizeof detail, "to_port=%d%s%s", s->port, s->periodicity == EVENT_ONESHOT ? " oneshot" : "",
                 rc == CONTRACT_OK ? "" : " failed");
        ContractLog("event_posted", s->module, o->Port, o->Size, detail);
        count_wait(s, o, g_rt.send_waited_ns);
        if (rc == CONTRACT_OK) reached++;
        if (rc == CONTRACT_OK && s->periodicity == EVENT_ONESHOT) s->periodicity = EVENT_SPENT;
        it = &s->next;
    }
    if (reached == 0 && !has_live_subscriber(d)) ContractLog("event_posted", "", o->Port, o->Size, "no subscriber");
    return reached;
}

int GetEventId(RTIME *productionTime, RTIME *receptionTime)
{
    const RequestMessage *e = g_rt.last_event;
    if (!e || e->Type != REQ_EVENT) { rt_error("GetEventId: no event request received"); return -1; }
    int port = e->Param.Event.targetPort;
    if (productionTime) *productionTime = e->ProductionTime;
    if (receptionTime) *receptionTime = e->ReceptionTime;
    for (int i = 0; i < g_rt.n_ireact; i++) {
        const ModuleReact *r = &g_rt.ireact[i];
        if (r->Port != port) continue;
        if (e->DataSize != r->Size) {
            rt_error("event from %s:%d refused: %zu bytes for input event port %d of %zu bytes",
                     e->Param.Event.sourceModule, e->Param.Event.sourcePort, e->DataSize, port, r->Size);
            return -1;
        }
        memcpy(r->Variable, e->Data, r->Size);
        char detail[48];
        snprintf(detail, sizeof detail, "from_port=%d latency_ns=%lld", e->Param.Event.sourcePort,
                 (long long)(e->ReceptionTime - e->ProductionTime));
        ContractLog("event_received", e->Param.Event.sourceModule, port, e->DataSize, detail);
        /* its handler runs from now until the module reads its mailbox again (mailbox.c); an
         * engine's events are its rules', told by its own records */
        g_rt.handling.on = g_rt.is_module;
        g_rt.handling.port = port;
        g_rt.handling.from_port = e->Param.Event.sourcePort;
        g_rt.handling.since = GetTime();
        snprintf(g_rt.handling.from, sizeof g_rt.handling.from, "%s", e->Param.Event.sourceModule);
        return port;
    }
    if (g_rt.is_module) {
        rt_error("event from %s:%d for unknown input event port %d", e->Param.Event.sourceModule,
                 e->Param.Event.sourcePort, port);
        return -1;
    }
    return port;
}

int SubscribeUserToEvent(const char *targetModule, int targetPort, int sourcePort, int mode)
{
    int d = find_detect_port(sourcePort);
    if (d < 0) { rt_error("event subscription: %s has no output event port %d", g_rt.name, sourcePort); return -1; }
    Subscriber *s = NULL;
    for (Subscriber *it = g_rt.event_subs[d]; it; it = it->next)
        if (strcmp(it->module, targetModule) == 0 && it->port == targetPort) s = it;
    if (!s) {
        if (!rt_valid_name(targetModule)) { rt_error("event subscription: invalid module name '%s'", targetModule); return -1; }
        s = calloc(1, sizeof *s);
        if (!s) { rt_error("out of memory"); return -1; }
        snprintf(s->module, sizeof s->module, "%s", targetModule);
        s->port = targetPort;
        Subscriber **tail = &g_rt.event_subs[d];
        while (*tail) tail = &(*tail)->next;
        *tail = s;
    }
    s->periodicity = mode == EVENT_ONESHOT ? EVENT_ONESHOT : EVENT_CONTINUOUS;
    char detail[48];
    snprintf(detail, sizeof detail, "to_port=%d %s", targetPort, s->periodicity == EVENT_ONESHOT ? "oneshot" : "continuous");
    ContractLog("event_subscribed", targetModule, sourcePort, 0, detail);
    return 0;
}

int UnsubscribeUserToEvent(const char *targetModule, int targetPort, int sourcePort)
{
    int d = find_detect_port(sourcePort);
    if (d < 0) { rt_error("event unsubscription: %s has no output event port %d", g_rt.name, sourcePort); return -1; }
    for (Subscriber **it = &g_rt.event_subs[d]; *it; it = &(*it)->next) {
        if (strcmp((*it)->module, targetModule) == 0 && (*it)->port == targetPort) {
            Subscriber *gone = *it;
            if (gone->waits) say_waits(gone, &g_rt.idetect[d], GetTime());
            *it = gone->next;
            ContractLog("event_unsubscribed", targetModule, sourcePort, 0,
                        gone->periodicity == EVENT_SPENT ? "one-shot already spent" : "");
            free(gone);
            return 0;
        }
    }
    /* not subscribed (never, or already removed): nothing to undo, not an error */
    ContractLog("event_unsubscribed", targetModule, sourcePort, 0, "was not subscribed");
    return 0;
}

static int named(const char *m) { return m && m[0] && strcmp(m, NO_MODULE) != 0; }

int SubscribeEvent(void)
{
    int failures = 0;
    for (int i = 0; i < g_rt.n_ireact; i++) {
        const ModuleReact *r = &g_rt.ireact[i];
        if (!named(r->SourceModule)) continue;
        if (SendSubscribeEvent(r->SourceModule, r->SourcePort, g_rt.name, r->Port,
                               r->OneShot ? EVENT_ONESHOT : EVENT_CONTINUOUS) != 0)
            failures++;
    }
    return failures ? -1 : 0;
}

int UnsubscribeEvent(void)
{
    int failures = 0;
    for (int i = 0; i < g_rt.n_ireact; i++) {
        const ModuleReact *r = &g_rt.ireact[i];
        if (!named(r->SourceModule)) continue;
        if (ModuleState(r->SourceModule) != CONTRACT_OK) continue;
        if (SendUnsubscribeEvent(r->SourceModule, r->SourcePort, g_rt.name, r->Port) != 0) failures++;
    }
    return failures ? -1 : 0;
}

int GetDataFromSetParamRequest(RequestMessage *msg, void *dst, size_t size, RTIME *productionTime, RTIME *receptionTime)
{
    if (!msg || msg->Type != REQ_SETPARAM) { rt_error("GetDataFromSetParamRequest: not a SETPARAM request"); return -1; }
    int port = msg->Param.SetParam.Port;
    size_t declared = 0;
    for (int i = 0; g_rt.param_in && g_rt.param_in[i] != PARAM_SIZE_TERM; i++)
        if (i == port) declared = g_rt.param_in[i];
    if (msg->DataSize != size || (declared && declared != size)) {
        rt_error("setparam from %s on port %d refused: %zu bytes received, the parameter holds %zu bytes", msg->Sender,
                 port, msg->DataSize, declared ? declared : size);
        return -1;
    }
    memcpy(dst, msg->Data, size);
    if (productionTime) *productionTime = msg->ProductionTime;
    if (receptionTime) *receptionTime = msg->ReceptionTime;
    ContractLog("setparam", msg->Sender, port, size, "");
    return 0;
}
