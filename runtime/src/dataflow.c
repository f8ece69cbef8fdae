/* Data flows: one AF_UNIX datagram socket per input data port (<run dir>/<NAME>.<port>.in),
 * the producer keeps the list of consumers of each output port with their periodicity. */
#define _GNU_SOURCE
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/uio.h>
#include <unistd.h>
#include "internal.h"

static int find_use(const void *var)
{
    for (int i = 0; i < g_rt.n_iuse; i++) if (g_rt.iuse[i].Variable == var) return i;
    return -1;
}

static int find_produce_var(const void *var)
{
    for (int i = 0; i < g_rt.n_iproduce; i++) if (g_rt.iproduce[i].Variable == var) return i;
    return -1;
}

static int find_produce_port(int port)
{
    for (int i = 0; i < g_rt.n_iproduce; i++) if (g_rt.iproduce[i].Port == port) return i;
    return -1;
}

int rt_dataflow_setup(void)
{
    if (g_rt.n_iuse) {
        g_rt.in_fds = calloc((size_t)g_rt.n_iuse, sizeof(int));
        g_rt.in_producer = calloc((size_t)g_rt.n_iuse, sizeof *g_rt.in_producer);
        g_rt.scratch = malloc(CONTRACT_DATA_PORT_MAX + 1);
        if (!g_rt.in_fds || !g_rt.in_producer || !g_rt.scratch) { rt_error("out of memory"); return -1; }
    }
    for (int i = 0; i < g_rt.n_iuse; i++) g_rt.in_fds[i] = -1;
    for (int i = 0; i < g_rt.n_iuse; i++) {
        char file[CONTRACT_NAME_MAX + 24];
        snprintf(file, sizeof file, "%s.%d.in", g_rt.name, g_rt.iuse[i].Port);
        if (rt_bind_dgram(file, &g_rt.in_fds[i]) != 0) return -1;
    }
    if (g_rt.n_iproduce) {
        g_rt.data_subs = calloc((size_t)g_rt.n_iproduce, sizeof(Subscriber *));
        if (!g_rt.data_subs) { rt_error("out of memory"); return -1; }
    }
    return 0;
}

static void free_list(Subscriber *s)
{
    while (s) { Subscriber *n = s->next; if (s->fd >= 0) close(s->fd); free(s); s = n; }
}

void rt_dataflow_teardown(void)
{
    for (int i = 0; g_rt.in_fds && i < g_rt.n_iuse; i++) if (g_rt.in_fds[i] >= 0) close(g_rt.in_fds[i]);
    free(g_rt.in_fds);
    g_rt.in_fds = NULL;
    free(g_rt.in_producer);
    g_rt.in_producer = NULL;
    free(g_rt.scratch);
    g_rt.scratch = NULL;
    for (int i = 0; g_rt.data_subs && i < g_rt.n_iproduce; i++) free_list(g_rt.data_subs[i]);
    free(g_rt.data_subs);
    g_rt.data_subs = NULL;
}

/* A value from `producer` on input entry i: a producer change is recorded (`producer_changed`,
 * a fact: a new schema's data flow took over the port); it is a wiring fault, warned on stderr,
 * only when two producers interleave: a producer delivers a single value between two of the
 * other's (A A B A), twice within CONTRACT_INTERLEAVE_NS. A schema switch hands the port over for
 * at least a cycle of the new schema, and back only after the supervisor saw an event: its
 * producers deliver runs of values. */
static void note_producer(int i, const char *producer, size_t payload, RTIME now)
{
    InPortFeed *f = &g_rt.in_producer[i];
    if (strcmp(f->producer, producer) == 0) {
        f->values++;
        return;
    }
    if (f->producer[0]) {
        int single = strcmp(f->previous, producer) == 0 && f->values == 1;
        int interleaved = single && f->single_at && now - f->single_at < CONTRACT_INTERLEAVE_NS;
        if (single) f->single_at = now;
        char detail[3 * CONTRACT_NAME_MAX + 160];
        if (interleaved)
            snprintf(detail, sizeof detail,
                     "was %s: interleaved: %s and %s both feed this port (each gave a single value between two of the other's within 1 s): an input data port has one producer",
                     f->producer, f->producer, producer);
        else
            snprintf(detail, sizeof detail, "was %s: a new producer (a schema switch)", f->producer);
        if (interleaved && !f->interleave_said) {
            fprintf(stderr, "%s: warning: input data port %d is fed by %s and %s at once (each delivered single values between the other's: an input data port has one producer)\n",
                    g_rt.name, g_rt.iuse[i].Port, f->producer, producer);
            f->interleave_said = 1;
        }
        ContractLog("producer_changed", producer, g_rt.iuse[i].Port, payload, detail);
        memcpy(f->previous, f->producer, CONTRACT_NAME_MAX);
    }
    memcpy(f->producer, producer, CONTRACT_NAME_MAX);
    f->values = 1;
}

/* Reads pending values of input entry i. latest: all of them (var gets the newest), else one.
 * purge: drop them without touching var. Returns values taken, -1 on error. */
static int read_port(int i, void *var, RTIME *prod, RTIME *recv, int latest, int purge)
{
    const ModuleUse *u = &g_rt.iuse[i];
    int got = 0;
    for (;;) {
        WirePrefix pre;
        DataHeader h;
        struct iovec iov[3] = { { &pre, sizeof pre }, { &h, sizeof h }, { g_rt.scratch, CONTRACT_DATA_PORT_MAX + 1 } };
        struct msghdr mh;
        memset(&mh, 0, sizeof mh);
        mh.msg_iov = iov;
        mh.msg_iovlen = 3;
        ssize_t n = recvmsg(g_rt.in_fds[i], &mh, MSG_DONTWAIT | MSG_TRUNC);
        if (n < 0) {
            if (errno == EAGAIN || errno == EWOULDBLOCK) break;
            if (errno == EINTR) continue;
            rt_error("reading input data port %d: %s", u->Port, strerror(errno));
            return -1;
        }
        RTIME now = GetTime();
        if ((size_t)n < sizeof pre + sizeof h || pre.magic != WIRE_MAGIC || pre.kind != WIRE_DATA) {
            rt_error("input data port %d: dropped a malformed datagram of %zd bytes", u->Port, n);
            continue;
        }
        h.producer[CONTRACT_NAME_MAX - 1] = '\0';
        size_t payload = (size_t)n - sizeof pre - sizeof h;
        if ((mh.msg_flags & MSG_TRUNC) || payload != u->Size || h.size != u->Size) {
            rt_error("input data port %d: refused %zu bytes from %s (the port holds %zu bytes)", u->Port, payload,
                     h.producer, u->Size);
            continue;
        }
        got++;
        note_producer(i, h.producer, payload, now);
        if (purge) { ContractLog("data_purged", h.producer, u->Port, payload, ""); continue; }
        memcpy(var, g_rt.scratch, u->Size);
        if (prod) *prod = h.production;
        if (recv) *recv = now;
        char detail[48];
        snprintf(detail, sizeof detail, "latency_ns=%lld", (long long)(now - h.production));
        ContractLog("data_received", h.producer, u->Port, payload, detail);
        if (!latest) break;
    }
    return got;
}

int GetData(void *var, RTIME *productionTime, RTIME *receptionTime)
{
    int i = find_use(var);
    if (i < 0) { rt_error("GetData: this address is not the variable of an input data port (IUSE)"); return -1; }
    return read_port(i, var, productionTime, receptionTime, 0, 0) > 0 ? 1 : 0;
}

int GetLatestData(void *var, RTIME *productionTime, RTIME *receptionTime)
{
    int i = find_use(var);
    if (i < 0) { rt_error("GetLatestData: this address is not the variable of an input data port (IUSE)"); return -1; }
    int r = read_port(i, var, productionTime, receptionTime, 1, 0);
    return r < 0 ? -1 : (r > 0);
}

int PurgeData(void *var)
{
    int total = 0;
    for (int i = 0; i < g_rt.n_iuse; i++) {
        if (var != NULL && g_rt.iuse[i].Variable != var) continue;
        int r = read_port(i, NULL, NULL, NULL, 1, 1);
        if (r > 0) total += r;
    }
    if (var != NULL && find_use(var) < 0) { rt_error("PurgeData: not the variable of an input data port"); return -1; }
    return total;
}

int PostData(void *var)
{
    int p = find_produce_var(var);
    if (p < 0) { rt_error("PostData: this address is not the variable of an output data port (IPRODUCE)"); return -1; }
    const ModuleProduce *o = &g_rt.iproduce[p];
    DataHeader h;
    memset(&h, 0, sizeof h);
    snprintf(h.producer, sizeof h.producer, "%s", g_rt.name);
    h.production = GetTime();
    h.port = o->Port;
    h.size = (unsigned int)o->Size;
    WirePrefix pre = { WIRE_MAGIC, WIRE_DATA };
    int reached = 0;
    for (Subscriber *s = g_rt.data_subs[p]; s; s = s->next) {
        long n = g_rt.activations - s->base;
        if (s->periodicity > 1 && (n <= 0 || n % s->periodicity != 0)) continue;
        struct iovec iov[3] = { { &pre, sizeof pre }, { &h, sizeof h }, { var, o->Size } };
        struct msghdr mh;
        memset(&mh, 0, sizeof mh);
        mh.msg_iov = iov;
        mh.msg_iovlen = 3;
        ssize_t r = -1;
        for (int attempt = 0; attempt < 2; attempt++) {
            if (s->fd < 0 && (s->fd = rt_connect_peer(&s->addr, s->addrlen, 1)) < 0) break;
            do r = sendmsg(s->fd, &mh, MSG_DONTWAIT | MSG_NOSIGNAL); while (r < 0 && errno == EINTR);
            if (r >= 0 || (errno != ECONNREFUSED && errno != ENOTCONN && errno != ECONNRESET)) break;
            close(s->fd); /* the consumer restarted or died: reconnect once */
            s->fd = -1;
        }
        char detail[96];
        if (r < 0) {
            snprintf(detail, sizeof detail, "to_port=%d %s", s->port,
                     errno == EAGAIN ? "queue full" : ContractStrError(rt_errno_to_code(errno)));
            ContractLog("data_dropped", s->module, o->Port, o->Size, detail);
            continue;
        }
        reached++;
        snprintf(detail, sizeof detail, "to_port=%d", s->port);
        ContractLog("data_posted", s->module, o->Port, o->Size, detail);
    }
    return reached;
}

int SubscribeUser(int sourcePort, const char *targetModule, int targetPort, int periodicity, int isContextual)
{
    int p = find_produce_port(sourcePort);
    if (p < 0) { rt_error("subscribe: %s has no output data port %d", g_rt.name, sourcePort); return -1; }
    if (periodicity < 1) { rt_error("subscribe %s:%d: periodicity %d must be >= 1", targetModule, targetPort, periodicity); return -1; }
    char suffix[24];
    snprintf(suffix, sizeof suffix, ".%d.in", targetPort);
    Subscriber *s = NULL;
    for (Subscriber *it = g_rt.data_subs[p]; it; it = it->next)
        if (strcmp(it->module, targetModule) == 0 && it->port == targetPort) s = it;
    if (!s) {
        s = calloc(1, sizeof *s);
        if (!s) { rt_error("out of memory"); return -1; }
        s->fd = -1;
        if (rt_module_addr(targetModule, suffix, &s->addr, &s->addrlen) != 0) {
            rt_error("subscribe: invalid consumer name '%s'", targetModule);
            free(s);
            return -1;
        }
        snprintf(s->module, sizeof s->module, "%s", targetModule);
        s->port = targetPort;
        /* append: consumers are served in subscription order */
        Subscriber **tail = &g_rt.data_subs[p];
        while (*tail) tail = &(*tail)->next;
        *tail = s;
    }
    s->periodicity = periodicity;
    s->contextual = isContextual;
    s->base = g_rt.activations;
    char detail[64];
    snprintf(detail, sizeof detail, "to_port=%d periodicity=%d%s", targetPort, periodicity, isContextual ? " contextual" : "");
    ContractLog("subscribed", targetModule, sourcePort, g_rt.iproduce[p].Size, detail);
    return 0;
}

int UnsubscribeUser(int sourcePort, const char *targetModule, int targetPort)
{
    int p = find_produce_port(sourcePort);
    if (p < 0) { rt_error("unsubscribe: %s has no output data port %d", g_rt.name, sourcePort); return -1; }
    for (Subscriber **it = &g_rt.data_subs[p]; *it; it = &(*it)->next) {
        if (strcmp((*it)->module, targetModule) == 0 && (*it)->port == targetPort) {
            Subscriber *gone = *it;
            *it = gone->next;
            if (gone->fd >= 0) close(gone->fd);
            free(gone);
            char detail[32];
            snprintf(detail, sizeof detail, "to_port=%d", targetPort);
            ContractLog("unsubscribed", targetModule, sourcePort, 0, detail);
            return 0;
        }
    }
    return 0; /* not subscribed: nothing to do */
}

static int named(const char *m) { return m && m[0] && strcmp(m, NO_MODULE) != 0; }

int SubscribeVariables(void)
{
    int failures = 0;
    for (int i = 0; i < g_rt.n_iuse; i++) {
        const ModuleUse *u = &g_rt.iuse[i];
        if (!named(u->SourceModule)) continue;
        if (SendSubscribe(u->SourceModule, u->SourcePort, g_rt.name, u->Port, u->Periodicity < 1 ? 1 : u->Periodicity, 0) != 0)
            failures++;
    }
    return failures ? -1 : 0;
}

int UnsubscribeVariables(void)
{
    int failures = 0;
    for (int i = 0; i < g_rt.n_iuse; i++) {
        const ModuleUse *u = &g_rt.iuse[i];
        if (!named(u->SourceModule)) continue;
        /* the producer may already be gone at exit: that is not an error worth a message */
        if (ModuleState(u->SourceModule) != CONTRACT_OK) continue;
        if (SendUnsubscribe(u->SourceModule, u->SourcePort, g_rt.name, u->Port) != 0) failures++;
    }
    return failures ? -1 : 0;
}
