/* The request mailbox: receiving requests (WaitForRequest, LookForRequest, deadlines, acks),
 * sending requests and acks to other modules. Two AF_UNIX datagram sockets per process, bound
 * to <run dir>/<NAME>.mbx (the mailbox) and <NAME>.ctl (its control channel); one datagram = one
 * request (prefix + header + payload).
 *
 * The control channel carries what the processes that never wait for a full mailbox send:
 * the supervisors (queued sends), ORD and the launcher (non-blocking sends): START, STOP,
 * PRIORITY, SETPARAM (parameterize), subscriptions, status queries, KILL. Everything else — the
 * modules' events, values, acks and requests, which wait for room (PostEvent) — goes to the
 * mailbox. A receiver reads its control channel first. Why: a producer whose PostEvent waits for
 * room in a flooded consumer's mailbox is woken by the kernel the moment the consumer reads one
 * request, and takes that slot at once; a supervisor's request that found the mailbox full
 * (kept, tried again every 5 ms: outbox.c) found it full again at nearly every try, and a STOP or
 * PRIORITY change waited behind the flood up to 2 s, then failed. Waiting for writability
 * (poll POLLOUT) instead does not help: the supervisor is woken with the producer, and the
 * producer, still in its sendmsg, wins the slot most of the time (a quick test with a 2 ms
 * consumer: 24 to 370 ms for one request, no bound). On its own channel, which only these
 * senders fill, a control request has room unless the receiver reads nothing at all, and it is
 * read before the events waiting. Each sender's requests stay in their order (a sender uses one
 * channel); a control request can overtake events sent before it. A receiver without a control
 * channel (a process of an older library) gets them in its mailbox. */
#define _GNU_SOURCE
#include <errno.h>
#include <time.h>
#include <fcntl.h>
#include <poll.h>
#include <stdlib.h>
#include <string.h>
#include <sys/epoll.h>
#include <sys/stat.h>
#include <sys/uio.h>
#include <unistd.h>
#include "internal.h"

/* The calling thread's CPU time in ns (CLOCK_THREAD_CPUTIME_ID), -1 when the clock cannot be read. */
static long long thread_cpu_ns(void)
{
    struct timespec ts;
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return -1;
    return (long long)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

/* run_started: note the thread's CPU time; run_finished: the CPU time the run took since (cpu_ns=N), -1 if unknown. */
static void run_cpu_start(void) { g_rt.run_cpu0_ns = thread_cpu_ns(); }
static long long run_cpu_used(void)
{
    long long now = thread_cpu_ns();
    return now < 0 || g_rt.run_cpu0_ns < 0 ? -1 : now - g_rt.run_cpu0_ns;
}

extern const char ContractModuleDescription[] __attribute__((weak));

static RequestMessage rx_buffer; /* every datagram lands here first: user messages stay intact */

/* ---------------------------------------------------------------- sending */

/* Connected sockets to the mailboxes and control channels we talk to (a send then skips the path
 * lookup). `ctl`: the channel asked for (the socket is the mailbox's when the receiver has no
 * control channel). */
typedef struct { char module[CONTRACT_NAME_MAX]; int ctl; int fd; } Peer;
#define MAX_PEERS 32
static Peer peers[MAX_PEERS];
static int next_victim;

void rt_close_peers(void)
{
    for (int i = 0; i < MAX_PEERS; i++) {
        if (peers[i].module[0] && peers[i].fd >= 0) close(peers[i].fd);
        peers[i].module[0] = '\0';
        peers[i].fd = -1;
    }
}

static int connect_to(const char *module, const char *suffix)
{
    struct sockaddr_un sa;
    socklen_t len;
    if (rt_module_addr(module, suffix, &sa, &len) != 0) return -1;
    return rt_connect_peer(&sa, len, 0);
}

static Peer *peer_for(const char *module, int ctl, int reconnect)
{
    Peer *p = NULL;
    for (int i = 0; i < MAX_PEERS && !p; i++)
        if (peers[i].module[0] && peers[i].ctl == ctl && strcmp(peers[i].module, module) == 0) p = &peers[i];
    if (p && !reconnect) return p;
    if (!p) {
        for (int i = 0; i < MAX_PEERS && !p; i++) if (!peers[i].module[0]) p = &peers[i];
        if (!p) { p = &peers[next_victim]; next_victim = (next_victim + 1) % MAX_PEERS; }
    }
    if (p->module[0] && p->fd >= 0) close(p->fd);
    p->module[0] = '\0';
    p->fd = ctl ? connect_to(module, ".ctl") : -1;
    if (p->fd < 0) p->fd = connect_to(module, ".mbx"); /* no control channel: its mailbox */
    if (p->fd < 0) return NULL;
    snprintf(p->module, sizeof p->module, "%s", module);
    p->ctl = ctl;
    return p;
}

int rt_send_datagram(const char *module, const void *request, size_t len, int dontwait)
{
    WirePrefix pre = { WIRE_MAGIC, WIRE_REQUEST };
    struct iovec iov[2] = { { &pre, sizeof pre }, { (void *)request, len } };
    struct msghdr mh;
    memset(&mh, 0, sizeof mh);
    mh.msg_iov = iov;
    mh.msg_iovlen = 2;
    ssize_t n = -1;
    int flags = MSG_NOSIGNAL | (dontwait ? MSG_DONTWAIT : 0);
    int ctl = g_rt.send_queued || g_rt.send_nowait; /* the control channel: this file's header */
    for (int attempt = 0; attempt < 2; attempt++) {
        Peer *p = peer_for(module, ctl, attempt > 0);
        if (!p) break;
        do n = sendmsg(p->fd, &mh, flags); while (n < 0 && errno == EINTR);
        if (n >= 0) break;
        /* the peer restarted or died since we connected: reconnect once */
        if (errno != ECONNREFUSED && errno != ENOTCONN && errno != ECONNRESET) break;
    }
    return n < 0 ? (errno ? errno : EIO) : 0;
}

void rt_log_sent(const char *module, const RequestMessage *request, int sent, const char *detail)
{
    if (request->Type == REQ_SETPARAM && sent) {
        ContractLog("setparam_sent", module, request->Param.SetParam.Port, request->DataSize, detail ? detail : "");
    } else if (request->Type == REQ_ACK) {
        char ack[64];
        snprintf(ack, sizeof ack, "%s id=%d", rt_ack_name(request->Param.Ack.Ack), request->Param.Ack.AckID);
        ContractLog(sent ? "ack_sent" : "ack_failed", module, -1, 0, ack);
    }
}

int rt_send_failed(const char *module, int type, int err, const char *why_more)
{
    int code = rt_errno_to_code(err);
    /* while the launcher stops every module, a peer that has already gone is expected: the
     * record stays in the log, stderr stays quiet */
    int gone_at_stop = ContractPeerGoneAtStop(code);
    char text[512], why[288] = "";
    if (gone_at_stop) snprintf(why, sizeof why, "; the run is stopping");
    else if (why_more) snprintf(why, sizeof why, "; %s", why_more);
    snprintf(text, sizeof text, "%s request to %s: %s (%s%s)", rt_request_name(type), module, ContractStrError(code),
             strerror(err), why);
    if (gone_at_stop) ContractLog("error", "", -1, 0, text);
    else rt_error("%s", text);
    return code;
}

/* How a request meets a full mailbox: it waits up to SEND_TIMEOUT_MS (the sockets' SO_SNDTIMEO),
 * fails at once (ContractSetNonBlockingSends: ORD), or is kept and sent later
 * (ContractSetQueuedSends: supervisors; outbox.c) */
typedef enum { FULL_WAIT, FULL_FAIL, FULL_KEEP } OnFull;

static OnFull on_full(void)
{
    return g_rt.send_queued ? FULL_KEEP : g_rt.send_nowait ? FULL_FAIL : FULL_WAIT;
}

#define KEPT 1 /* try_send: the request is kept for its receiver's full mailbox (outbox.c) */

/* A request that waits for room (FULL_WAIT): tried without waiting first, so that a wait is known
 * and measured (g_rt.send_waited_ns: PostEvent's `event_waited` records, eventflow.c); the
 * mailbox had room: one sendmsg, as before. */
static int send_waiting(const char *module, const RequestMessage *msg, size_t len)
{
    g_rt.send_waited_ns = 0;
    int err = rt_send_datagram(module, msg, len, 1);
    if (err != EAGAIN && err != EWOULDBLOCK) return err;
    RTIME t0 = GetTime();
    err = rt_send_datagram(module, msg, len, 0);
    RTIME waited = GetTime() - t0;
    g_rt.send_waited_ns = waited > 0 ? waited : 1;
    return err;
}

/* Sends msg: CONTRACT_OK, KEPT, or the CONTRACT_E* code of a failure (already said: rt_error). */
static int try_send(const char *module, RequestMessage *msg, OnFull full)
{
    if (!rt_valid_name(module)) {
        rt_error("invalid module name '%s'", module ? module : "(null)");
        return CONTRACT_EINVAL;
    }
    if (msg->DataSize > CONTRACT_REQUEST_DATA_MAX) {
        rt_error("%s request to %s: payload of %zu bytes exceeds the limit of %d bytes (not sent)",
                 rt_request_name(msg->Type), module, msg->DataSize, CONTRACT_REQUEST_DATA_MAX);
        return CONTRACT_ETOOBIG;
    }
    if (g_rt.run_dir_fd < 0 && rt_init_run_dir() != 0) return CONTRACT_ESYS;
    memcpy(msg->Sender, g_rt.name, sizeof msg->Sender);
    msg->ProductionTime = GetTime();
    msg->ReceptionTime = 0;
    size_t len = REQUEST_HEADER_SIZE + msg->DataSize;
    /* a receiver with requests kept gets this one after them (in order): kept too */
    int err = full == FULL_KEEP && rt_outbox_holds(module) ? EAGAIN
            : full == FULL_WAIT ? send_waiting(module, msg, len) : rt_send_datagram(module, msg, len, 1);
    if (err == 0) return CONTRACT_OK;
    if (full == FULL_KEEP && (err == EAGAIN || err == EWOULDBLOCK)) {
        int rc = rt_outbox_add(module, msg, len);
        return rc == CONTRACT_OK ? KEPT : rc;
    }
    const char *why = NULL;
    char text[CONTRACT_NAME_MAX + 48];
    if (rt_errno_to_code(err) == CONTRACT_EBUSY && full == FULL_FAIL) {
        snprintf(text, sizeof text, "%s does not wait for a full mailbox", g_rt.name);
        why = text;
    }
    return rt_send_failed(module, msg->Type, err, why);
}

/* A request sent or failed has its record (rt_log_sent); a kept one has it when it goes or fails. */
static int send_request(const char *module, RequestMessage *msg, OnFull full)
{
    int rc = try_send(module, msg, full);
    if (rc == KEPT) return CONTRACT_OK;
    rt_log_sent(module, msg, rc == CONTRACT_OK, NULL);
    return rc;
}

int rt_send_request_to(const char *module, RequestMessage *msg) { return send_request(module, msg, on_full()); }

/* QueryStatus and the priority query wait for an answer: with queued sends their question is
 * never kept for later (its answer would come after the wait). A receiver whose mailbox is full,
 * or that has requests kept for it, is busy: CONTRACT_EBUSY at once, as no answer in time. */
static int send_query(const char *module, RequestMessage *q)
{
    if (on_full() != FULL_KEEP) return rt_send_request_to(module, q);
    if (rt_outbox_holds(module)) return CONTRACT_EBUSY;
    return send_request(module, q, FULL_FAIL);
}

int SendRequest(const char *module, RequestMessage *msg) { return rt_send_request_to(module, msg); }

int ContractSetNonBlockingSends(int on)
{
    int before = g_rt.send_nowait;
    g_rt.send_nowait = on != 0;
    return before;
}

/* Small requests are built in this header-only buffer (Data never read beyond DataSize). */
static RequestMessage *blank(RequestType type)
{
    static RequestMessage m;
    memset(&m, 0, REQUEST_HEADER_SIZE);
    m.Type = type;
    return &m;
}

static void set_ack(char *modAck, int *wanted, int *id, int wantedAck, int ackId)
{
    snprintf(modAck, CONTRACT_NAME_MAX, "%s", g_rt.name);
    *wanted = wantedAck;
    *id = ackId;
}

int SendStart(const char *module, int wantedAck, int ackId)
{
    return SendStartFunction(module, NULL, NULL, wantedAck, ackId);
}

int SendStartFunction(const char *module, const char *function, const char *args, int wantedAck, int ackId)
{
    RequestMessage *m = blank(REQ_START);
    set_ack(m->Param.Start.ModAck, &m->Param.Start.WantedAck, &m->Param.Start.AckID, wantedAck, ackId);
    if (function) {
        if (strlen(function) >= CONTRACT_FUNCTION_MAX) {
            rt_error("function name '%s' too long (max %d)", function, CONTRACT_FUNCTION_MAX - 1);
            return CONTRACT_EINVAL;
        }
        snprintf(m->Param.Start.Function, CONTRACT_FUNCTION_MAX, "%s", function);
    }
    if (args && *args) {
        size_t n = strlen(args) + 1;
        if (n > CONTRACT_REQUEST_DATA_MAX) {
            rt_error("start arguments of %zu bytes exceed the limit of %d bytes", n, CONTRACT_REQUEST_DATA_MAX);
            return CONTRACT_ETOOBIG;
        }
        memcpy(m->Data, args, n);
        m->DataSize = n;
    }
    return rt_send_request_to(module, m);
}

int SendStop(const char *module, int wantedAck, int ackId)
{
    RequestMessage *m = blank(REQ_STOP);
    set_ack(m->Param.Stop.ModAck, &m->Param.Stop.WantedAck, &m->Param.Stop.AckID, wantedAck, ackId);
    return rt_send_request_to(module, m);
}

int SendKill(const char *module, int wantedAck, int ackId)
{
    RequestMessage *m = blank(REQ_KILL);
    set_ack(m->Param.Kil.ModAck, &m->Param.Kil.WantedAck, &m->Param.Kil.AckID, wantedAck, ackId);
    return rt_send_request_to(module, m);
}

int SendKillWhy(const char *module, const char *why)
{
    RequestMessage *m = blank(REQ_KILL);
    set_ack(m->Param.Kil.ModAck, &m->Param.Kil.WantedAck, &m->Param.Kil.AckID, ACK_NOTHING, -1);
    if (why && *why) {
        size_t n = strnlen(why, CONTRACT_KILL_WHY_MAX);
        memcpy(m->Data, why, n);
        m->Data[n] = '\0';
        m->DataSize = n + 1;
    }
    return rt_send_request_to(module, m);
}

int SendSetParam(const char *module, int port, const void *value, size_t size, int wantedAck, int ackId)
{
    if (size > CONTRACT_REQUEST_DATA_MAX) {
        rt_error("setparam %s:%d: value of %zu bytes exceeds the limit of %d bytes (not sent)", module, port, size,
                 CONTRACT_REQUEST_DATA_MAX);
        return CONTRACT_ETOOBIG;
    }
    RequestMessage *m = blank(REQ_SETPARAM);
    m->Param.SetParam.Port = port;
    set_ack(m->Param.SetParam.ModAck, &m->Param.SetParam.WantedAck, &m->Param.SetParam.AckID, wantedAck, ackId);
    if (size) memcpy(m->Data, value, size);
    m->DataSize = size;
    return rt_send_request_to(module, m); /* setparam_sent once it is sent (rt_log_sent) */
}

int SendSubscribe(const char *producer, int sourcePort, const char *consumer, int targetPort, int periodicity,
                  int isContextual)
{
    RequestMessage *m = blank(REQ_SUBSCRIBE);
    m->Param.Subscribe.SourcePort = sourcePort;
    snprintf(m->Param.Subscribe.TargetModule, CONTRACT_NAME_MAX, "%s", consumer);
    m->Param.Subscribe.TargetPort = targetPort;
    m->Param.Subscribe.Periodicity = periodicity;
    m->Param.Subscribe.isContextual = isContextual;
    return rt_send_request_to(producer, m);
}

int SendUnsubscribe(const char *producer, int sourcePort, const char *consumer, int targetPort)
{
    RequestMessage *m = blank(REQ_UNSUBSCRIBE);
    m->Param.Unsubscribe.SourcePort = sourcePort;
    snprintf(m->Param.Unsubscribe.TargetModule, CONTRACT_NAME_MAX, "%s", consumer);
    m->Param.Unsubscribe.TargetPort = targetPort;
    return rt_send_request_to(producer, m);
}

int SendSubscribeEvent(const char *producer, int sourcePort, const char *consumer, int targetPort, int mode)
{
    RequestMessage *m = blank(REQ_SUB_EVENT);
    snprintf(m->Param.SubscribeEvent.targetModule, CONTRACT_NAME_MAX, "%s", consumer);
    m->Param.SubscribeEvent.targetPort = targetPort;
    m->Param.SubscribeEvent.sourcePort = sourcePort;
    m->Param.SubscribeEvent.mode = mode;
    return rt_send_request_to(producer, m);
}

int SendUnsubscribeEvent(const char *producer, int sourcePort, const char *consumer, int targetPort)
{
    RequestMessage *m = blank(REQ_UNSUB_EVENT);
    snprintf(m->Param.UnsubscribeEvent.targetModule, CONTRACT_NAME_MAX, "%s", consumer);
    m->Param.UnsubscribeEvent.targetPort = targetPort;
    m->Param.UnsubscribeEvent.sourcePort = sourcePort;
    return rt_send_request_to(producer, m);
}

int SendPurge(const char *module) { return rt_send_request_to(module, blank(REQ_PURGE_MBX)); }

int SendEvent(const char *module, int targetPort, int sourcePort, const void *data, size_t size)
{
    if (size > CONTRACT_REQUEST_DATA_MAX) {
        rt_error("event %s:%d -> %s:%d: %zu bytes exceed the limit of %d bytes (not sent)", g_rt.name, sourcePort,
                 module, targetPort, size, CONTRACT_REQUEST_DATA_MAX);
        return CONTRACT_ETOOBIG;
    }
    RequestMessage *m = blank(REQ_EVENT);
    m->Param.Event.sourcePort = sourcePort;
    snprintf(m->Param.Event.sourceModule, CONTRACT_NAME_MAX, "%s", g_rt.name);
    m->Param.Event.targetPort = targetPort;
    if (size) memcpy(m->Data, data, size);
    m->DataSize = size;
    return rt_send_request_to(module, m);
}

int SetModuleParam(const char *moduleName, unsigned char port, void *data, unsigned long size)
{
    return SendSetParam(moduleName, port, data, size, ACK_NOTHING, -1) == CONTRACT_OK ? 0 : -1;
}

int SendAck(const char *module, int wantedAck, int ack, int ackId)
{
    if ((wantedAck & ACK_NOTHING) != 0 || module == NULL || module[0] == '\0') return 0;
    RequestMessage *m = blank(REQ_ACK);
    snprintf(m->Param.Ack.Module, CONTRACT_NAME_MAX, "%s", g_rt.name);
    m->Param.Ack.Ack = ack;
    m->Param.Ack.AckID = ackId;
    if ((ack == ACK_FINISHED || ack == ACK_STOPPED) && g_rt.running) {
        g_rt.running = 0;
        char d[96];
        snprintf(d, sizeof d, "activation=%ld cpu_ns=%lld %s", g_rt.activations, run_cpu_used(), rt_ack_name(ack));
        ContractLog("run_finished", "", -1, 0, d);
    }
    int rc = rt_send_request_to(module, m); /* ack_sent or ack_failed once sent or not (rt_log_sent) */
    return rc == CONTRACT_OK ? 0 : -1;
}

/* ---------------------------------------------------------------- receiving */

/* The Seq of the last status or priority query this process sent (StatusParam). */
static unsigned query_seq;
/* Seq of the priority requests whose answer is read later (ContractAskModulePriority): the high
 * bit set, so that a synchronous wait keeps them for their reader instead of dropping them as
 * answers to an older query of its own. */
#define ASYNC_SEQ_BIT 0x80000000u
static unsigned async_seq;
static unsigned next_query_seq(void)
{
    query_seq = (query_seq + 1) & ~ASYNC_SEQ_BIT;
    if (query_seq == 0) query_seq = 1;
    return query_seq;
}

static void reply_status(const RequestMessage *req)
{
    RequestMessage *m = blank(REQ_STATUS_REPLY);
    m->Param.Status.Seq = req->Param.Status.Seq;
    int n = snprintf((char *)m->Data, 1024,
                     "module=%s pid=%ld running=%s activations=%ld requests=%ld run_dir=%s description=\"%s\"",
                     g_rt.name, (long)getpid(), g_rt.running ? "yes" : "no", g_rt.activations, g_rt.requests,
                     g_rt.run_dir, ContractModuleDescription ? ContractModuleDescription : "");
    m->DataSize = (size_t)(n < 1024 ? n : 1023) + 1;
    rt_send_request_to(req->Sender, m);
}

/* REQ_PRIORITY: the module applies the priority to itself and answers with the outcome. */
static void reply_priority(const RequestMessage *req)
{
    int before = g_rt.priority;
    int result = rt_apply_priority(req->Param.Priority.Priority, req->Sender);
    int err = result == CONTRACT_EPERM ? errno : 0;
    RequestMessage *m = blank(REQ_PRIORITY_REPLY);
    m->Param.Priority.Priority = before;
    m->Param.Priority.Result = result;
    m->Param.Priority.Errno = err;
    m->Param.Priority.Seq = req->Param.Priority.Seq;
    rt_send_request_to(req->Sender, m);
}

/* Bookkeeping at reception. Returns 0 if the request was handled inside the library. */
static int accept_request(RequestMessage *m)
{
    char detail[160];
    int port = -1;
    if (m->Type == REQ_PRIORITY) { reply_priority(m); return 0; }
    if (m->Type == REQ_PRIORITY_REPLY) return 1; /* its reader logs what it says (module_priority) */
    if (!rt_log_enabled()) { /* bookkeeping only */
        if (m->Type == REQ_STATUS) { reply_status(m); return 0; }
        if (m->Type == REQ_ACK) return 1;
        if (m->Type == REQ_START) { g_rt.activations++; g_rt.running = 1; }
        if (m->Type == REQ_STOP || m->Type == REQ_KILL) g_rt.running = 0; /* the run ends on it */
        g_rt.requests++;
        return 1;
    }
    switch (m->Type) {
    case REQ_STATUS:
        reply_status(m);
        return 0;
    case REQ_ACK:
        snprintf(detail, sizeof detail, "%s id=%d", rt_ack_name(m->Param.Ack.Ack), m->Param.Ack.AckID);
        ContractLog("ack_received", m->Sender, -1, 0, detail);
        return 1;
    case REQ_START:
        g_rt.activations++;
        snprintf(detail, sizeof detail, "START%s%s", m->Param.Start.Function[0] ? " " : "", m->Param.Start.Function);
        break;
    case REQ_EVENT:
        port = m->Param.Event.targetPort;
        snprintf(detail, sizeof detail, "EVENT from_port=%d", m->Param.Event.sourcePort);
        break;
    case REQ_SETPARAM: port = m->Param.SetParam.Port; snprintf(detail, sizeof detail, "SETPARAM"); break;
    case REQ_SUBSCRIBE:
        port = m->Param.Subscribe.SourcePort;
        snprintf(detail, sizeof detail, "SUBSCRIBE %s:%d *%d", m->Param.Subscribe.TargetModule,
                 m->Param.Subscribe.TargetPort, m->Param.Subscribe.Periodicity);
        break;
    case REQ_SUB_EVENT:
        port = m->Param.SubscribeEvent.sourcePort;
        snprintf(detail, sizeof detail, "SUB_EVENT %s:%d %s", m->Param.SubscribeEvent.targetModule,
                 m->Param.SubscribeEvent.targetPort, m->Param.SubscribeEvent.mode == EVENT_ONESHOT ? "oneshot" : "continuous");
        break;
    case REQ_KILL:
        /* why the run stops, when the sender said (SendKillWhy): printable characters only, bounded */
        if (m->DataSize > 1 && m->DataSize <= CONTRACT_KILL_WHY_MAX + 1) {
            char why[CONTRACT_KILL_WHY_MAX + 1];
            size_t n = 0;
            for (; n < m->DataSize - 1 && m->Data[n]; n++) why[n] = (m->Data[n] >= 0x20 && m->Data[n] < 0x7f) ? (char)m->Data[n] : '?';
            why[n] = '\0';
            snprintf(detail, sizeof detail, "KILL (%s)", why);
        } else {
            snprintf(detail, sizeof detail, "KILL");
        }
        break;
    default: snprintf(detail, sizeof detail, "%s", rt_request_name(m->Type)); break;
    }
    g_rt.requests++;
    ContractLog("request_received", m->Sender, port, m->DataSize, detail);
    if (m->Type == REQ_START && !g_rt.running) {
        g_rt.running = 1;
        run_cpu_start();
        snprintf(detail, sizeof detail, "activation=%ld", g_rt.activations);
        ContractLog("run_started", m->Sender, -1, 0, detail);
    } else if ((m->Type == REQ_STOP || m->Type == REQ_KILL) && g_rt.running) {
        /* a stopped module is not running any more, whether or not it acknowledges the stop
         * (status queries: "is it running?" across supervisors) */
        g_rt.running = 0;
        snprintf(detail, sizeof detail, "activation=%ld cpu_ns=%lld %s", g_rt.activations, run_cpu_used(), rt_request_name(m->Type));
        ContractLog("run_finished", m->Sender, -1, 0, detail);
    }
    return 1;
}

/* One datagram from fd (the mailbox or the control channel) into rx_buffer. Returns RX_GOT (a request for the caller),
 * RX_NONE (EAGAIN, or the receive timed out), RX_TAKEN (one the library answered itself, or an
 * invalid datagram that was reported and dropped: read on), -1 (error, errno set). */
#define RX_NONE 0
#define RX_GOT 1
#define RX_TAKEN 2
static int receive_from(int fd, int flags)
{
    WirePrefix pre;
    struct iovec iov[2] = { { &pre, sizeof pre }, { &rx_buffer, sizeof rx_buffer } };
    struct msghdr mh;
    memset(&mh, 0, sizeof mh);
    mh.msg_iov = iov;
    mh.msg_iovlen = 2;
    ssize_t n = recvmsg(fd, &mh, flags | MSG_TRUNC);
    if (n < 0) {
        if (errno == EAGAIN || errno == EWOULDBLOCK) return 0;
        return -1;
    }
    RTIME now = GetTime();
    if ((size_t)n < sizeof pre + REQUEST_HEADER_SIZE || pre.magic != WIRE_MAGIC || pre.kind != WIRE_REQUEST) {
        rt_error("dropped a malformed datagram of %zd bytes in the mailbox", n);
        return RX_TAKEN;
    }
    if ((mh.msg_flags & MSG_TRUNC) || (size_t)n != sizeof pre + REQUEST_HEADER_SIZE + rx_buffer.DataSize) {
        rt_error("dropped a %s request from %.63s: size %zd does not match its header (payload %zu, max %d)",
                 rt_request_name(rx_buffer.Type), rx_buffer.Sender, n, rx_buffer.DataSize, CONTRACT_REQUEST_DATA_MAX);
        return RX_TAKEN;
    }
    rx_buffer.Sender[CONTRACT_NAME_MAX - 1] = '\0';
    rx_buffer.ReceptionTime = now;
    return accept_request(&rx_buffer) ? RX_GOT : RX_TAKEN;
}

static int rx_ctl; /* the request in rx_buffer came by the control channel */

/* The control channel first (never waited on), then the mailbox (flags). */
static int receive_one(int flags)
{
    if (g_rt.ctl_fd >= 0) {
        int r = receive_from(g_rt.ctl_fd, MSG_DONTWAIT);
        if (r != RX_NONE) {
            rx_ctl = 1;
            return r;
        }
    }
    rx_ctl = 0;
    return receive_from(g_rt.mbx_fd, flags);
}

/* At most this many datagrams a non-blocking read goes through (answered queries, dropped
 * datagrams) before it says "none": a flood of them cannot hold the module in the read. */
#define RX_TAKEN_MAX 64
/* At most this many requests read ahead are kept (read_ahead): beyond, they wait in the socket,
 * whose bound tells senders that the module is behind (CONTRACT_EBUSY). 16 KiB each at most. */
#define READ_AHEAD_MAX 64

static void deliver(RequestMessage *out, const RequestMessage *in)
{
    if (out != in) memcpy(out, in, REQUEST_HEADER_SIZE + in->DataSize);
    if (out->Type == REQ_EVENT) rt_remember_event(out);
    if (out->Type == REQ_START && !g_rt.running) {
        /* a START read ahead while the run before went on, handed over once that run ended
         * (WaitForRequest): the module runs again from now (status queries) */
        g_rt.running = 1;
        run_cpu_start();
        if (rt_log_enabled()) {
            char d[48];
            snprintf(d, sizeof d, "activation=%ld", g_rt.activations);
            ContractLog("run_started", out->Sender, -1, 0, d);
        }
    }
}

static int pop_pending(RequestMessage *out)
{
    Pending *p = g_rt.pending_head;
    if (!p) return 0;
    g_rt.pending_head = p->next;
    if (!g_rt.pending_head) g_rt.pending_tail = NULL;
    g_rt.pending_count--;
    deliver(out, &p->msg);
    free(p);
    return 1;
}

/* Kept for later, in order, those of the control channel before those of the mailbox (a STOP read
 * behind the events read ahead is handed over before them, as it would have been read). */
static void push_pending(const RequestMessage *m, int ctl)
{
    Pending *p = malloc(sizeof *p);
    if (!p) { rt_error("out of memory: dropped a %s request", rt_request_name(m->Type)); return; }
    memcpy(&p->msg, m, REQUEST_HEADER_SIZE + m->DataSize);
    p->ctl = ctl;
    Pending **at = &g_rt.pending_head;
    while (*at && (!ctl || (*at)->ctl)) at = &(*at)->next;
    p->next = *at;
    *at = p;
    if (!p->next) g_rt.pending_tail = p;
    g_rt.pending_count++;
}

static int check_mailbox(void)
{
    if (g_rt.mbx_fd >= 0) return 0;
    fprintf(stderr, "%s: error: no mailbox (call ContractClientInit first, or run as a module)\n",
            g_rt.name[0] ? g_rt.name : "libmodule");
    errno = EBADF;
    return -1;
}

/* Receive the next accepted request into rx_buffer until `deadline`. 1 / 0 timeout / -1 error.
 * System calls per request: ppoll on the mailbox and the control channel (bounded by the
 * deadline, the log flush delay, and the next try of requests kept for full mailboxes: outbox.c)
 * + one recvmsg of the socket it found readable, the control channel first. */
static int receive_until(RTIME deadline)
{
    if (check_mailbox() != 0) return -1;
    for (;;) {
        RTIME retry = ContractRetryQueuedSends(); /* 0: no request kept for a full mailbox */
        RTIME now = GetTime();
        rt_log_maybe_flush(now);
        if (deadline <= now) {
            for (int taken = 0; taken < RX_TAKEN_MAX; taken++) {
                int r = receive_one(MSG_DONTWAIT);
                if (r != RX_TAKEN) return r;
            }
            return RX_NONE;
        }
        RTIME wait = deadline == INT64_MAX ? -1 : deadline - now;
        RTIME due = ContractLogFlushDue(rt_log_flush_ns());
        if (due) {
            RTIME flush_in = due - now;
            if (flush_in < 0) flush_in = 0;
            if (wait < 0 || flush_in < wait) wait = flush_in;
        }
        if (retry) {
            RTIME retry_in = retry > now ? retry - now : 0;
            if (wait < 0 || retry_in < wait) wait = retry_in;
        }
        struct pollfd pfd[2] = { { g_rt.mbx_fd, POLLIN, 0 }, { g_rt.ctl_fd, POLLIN, 0 } };
        struct timespec ts = { (time_t)(wait / 1000000000LL), (long)(wait % 1000000000LL) };
        int pr = ppoll(pfd, g_rt.ctl_fd >= 0 ? 2 : 1, wait < 0 ? NULL : &ts, NULL);
        if (pr < 0) return -1;
        if (pr <= 0) continue;
        /* Read the socket ppoll found readable (the control channel first): one recvmsg. */
        int from_ctl = g_rt.ctl_fd >= 0 && pfd[1].revents != 0;
        int r = receive_from(from_ctl ? g_rt.ctl_fd : g_rt.mbx_fd, MSG_DONTWAIT);
        rx_ctl = from_ctl;
        if (r == RX_GOT || r < 0) return r;
    }
}

/* The module reads its mailbox again after handling an event (its request loop's next wait or
 * poll): the handler has ended. One record per event handled, the end of the bar the IDE's
 * Timeline draws from its event_received. */
static void end_event_handling(void)
{
    if (!g_rt.handling.on) return;
    g_rt.handling.on = 0;
    char d[64];
    snprintf(d, sizeof d, "from_port=%d handling_ns=%lld", g_rt.handling.from_port,
             (long long)(GetTime() - g_rt.handling.since));
    ContractLog("event_handled", g_rt.handling.from, g_rt.handling.port, 0, d);
}

int WaitForRequestUntil(RequestMessage *msg, RTIME deadline)
{
    rt_mark_ready(); /* the first time: its init is done (the launcher then sends the start) */
    end_event_handling();
    if (pop_pending(msg)) return 1;
    int r = receive_until(deadline);
    if (r == 1) deliver(msg, &rx_buffer);
    return r;
}

RequestMessage *WaitForRequest(RequestMessage *msg)
{
    if (g_rt.running) { /* the skeleton waits only once a run is over */
        g_rt.running = 0;
        char d[80];
        snprintf(d, sizeof d, "activation=%ld cpu_ns=%lld", g_rt.activations, run_cpu_used());
        ContractLog("run_finished", "", -1, 0, d);
    }
    for (;;) {
        int r = WaitForRequestUntil(msg, INT64_MAX);
        if (r == 1) return msg;
        if (r < 0 && errno != EINTR) {
            rt_error("waiting for a request: %s", strerror(errno));
            return NULL;
        }
    }
}

/* The requests already waiting in the mailbox, read into the pending list in their order: a
 * status or priority query among them is answered at once (the library answers those at
 * reception) instead of after one module state per request ahead of it. */
static void read_ahead(void)
{
    for (int taken = 0; g_rt.pending_count < READ_AHEAD_MAX && taken < RX_TAKEN_MAX;) {
        int r = receive_one(MSG_DONTWAIT);
        if (r == RX_GOT) push_pending(&rx_buffer, rx_ctl);
        else if (r == RX_TAKEN) taken++;
        else break; /* none left, or an error the next read meets again */
    }
}

RequestMessage *LookForRequest(RequestMessage *msg)
{
    if (WaitForRequestUntil(msg, 0) != 1) return NULL;
    read_ahead(); /* the module is busy in its run: what waits behind this request */
    return msg;
}

/* One fd for the caller's poll, readable when a request waits in the mailbox or the control
 * channel: an epoll instance holding both (made at the first call). */
int MailboxFd(void)
{
    if (g_rt.wait_fd >= 0 || g_rt.mbx_fd < 0 || g_rt.ctl_fd < 0) return g_rt.wait_fd >= 0 ? g_rt.wait_fd : g_rt.mbx_fd;
    int ep = epoll_create1(EPOLL_CLOEXEC);
    if (ep < 0) return g_rt.mbx_fd;
    struct epoll_event ev = { .events = EPOLLIN };
    ev.data.fd = g_rt.mbx_fd;
    int ok = epoll_ctl(ep, EPOLL_CTL_ADD, g_rt.mbx_fd, &ev) == 0;
    ev.data.fd = g_rt.ctl_fd;
    ok = ok && epoll_ctl(ep, EPOLL_CTL_ADD, g_rt.ctl_fd, &ev) == 0;
    if (!ok) { close(ep); return g_rt.mbx_fd; }
    g_rt.wait_fd = ep;
    return ep;
}
int PendingRequests(void) { return g_rt.pending_count; }

typedef int (*Matcher)(const RequestMessage *m, const void *ctx);

/* Waits until `deadline` for the request `match` accepts (1); the others are kept for the
 * module's own reads (0), except answers to an earlier query of this process, come too late
 * (MATCH_STALE): dropped. A signal (EINTR) does not end the wait: the status, priority and ack
 * waits of the engines must not read "no answer" into a handler run or a stopped process. */
#define MATCH_STALE (-1)
static int wait_for_match(Matcher match, const void *ctx, RTIME deadline, RequestMessage *out)
{
    for (;;) {
        errno = 0; /* a failure that sets no errno is not taken for EINTR */
        int r = receive_until(deadline);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) return r;
        int m = match(&rx_buffer, ctx);
        if (m == 1) {
            if (out) deliver(out, &rx_buffer);
            return 1;
        }
        if (m != MATCH_STALE) push_pending(&rx_buffer, rx_ctl);
    }
}

typedef struct { const char *module; int ackId; int mask; } AckWanted;

static int match_ack(const RequestMessage *m, const void *ctx)
{
    const AckWanted *w = ctx;
    return m->Type == REQ_ACK && strcmp(m->Sender, w->module) == 0 && m->Param.Ack.AckID == w->ackId &&
           (m->Param.Ack.Ack & w->mask) != 0;
}

int WaitForAck(const char *module, int ackId, int ackMask, RTIME deadline, RequestMessage *ack)
{
    AckWanted w = { module, ackId, ackMask };
    return wait_for_match(match_ack, &w, deadline, ack);
}

/* The answer of type `type` from `module` to the query numbered `seq`. */
typedef struct { const char *module; RequestType type; unsigned seq; } ReplyWanted;

static int match_reply(const RequestMessage *m, const void *ctx)
{
    const ReplyWanted *w = ctx;
    if (m->Type != w->type) return 0;
    unsigned seq = m->Type == REQ_STATUS_REPLY ? m->Param.Status.Seq : m->Param.Priority.Seq;
    if (seq != w->seq) /* whoever sent it, it answers no query of now; unless it is read later */
        return m->Type == REQ_PRIORITY_REPLY && (seq & ASYNC_SEQ_BIT) ? 0 : MATCH_STALE;
    return strcmp(m->Sender, w->module) == 0;
}

int QueryStatus(const char *module, char *text, size_t textSize, RTIME deadline)
{
    RequestMessage *q = blank(REQ_STATUS);
    q->Param.Status.Seq = next_query_seq();
    ReplyWanted w = { module, REQ_STATUS_REPLY, query_seq };
    int rc = send_query(module, q);
    if (rc != CONTRACT_OK) return rc;
    RequestMessage *reply = malloc(sizeof *reply);
    if (!reply) return CONTRACT_ESYS;
    int r = wait_for_match(match_reply, &w, deadline, reply);
    if (r == 1 && textSize > 0) {
        size_t n = reply->DataSize < textSize ? reply->DataSize : textSize;
        memcpy(text, reply->Data, n);
        text[n ? n - 1 : 0] = '\0';
    }
    free(reply);
    return r == 1 ? CONTRACT_OK : (r == 0 ? CONTRACT_EBUSY : CONTRACT_ESYS);
}

int ContractSetModulePriority(const char *module, int priority, int *previous)
{
    if (priority < 1 || priority > 99) return CONTRACT_EINVAL;
    if (module && strcmp(module, g_rt.name) == 0) { /* myself */
        if (previous) *previous = g_rt.priority;
        return rt_apply_priority(priority, g_rt.name);
    }
    if (check_mailbox() != 0) return CONTRACT_EINVAL;
    RequestMessage *m = blank(REQ_PRIORITY);
    m->Param.Priority.Priority = priority;
    m->Param.Priority.Seq = next_query_seq();
    ReplyWanted w = { module, REQ_PRIORITY_REPLY, query_seq };
    int rc = send_query(module, m);
    if (rc != CONTRACT_OK) return rc;
    RequestMessage *reply = malloc(sizeof *reply);
    if (!reply) return CONTRACT_ESYS;
    int r = wait_for_match(match_reply, &w, GetTime() + 1000000000LL, reply);
    if (r == 1) {
        if (previous) *previous = reply->Param.Priority.Priority;
        rc = reply->Param.Priority.Result;
        if (rc == CONTRACT_EPERM) errno = reply->Param.Priority.Errno;
    } else {
        rc = r == 0 ? CONTRACT_EBUSY : CONTRACT_ESYS;
    }
    free(reply);
    return rc;
}

int ContractAskModulePriority(const char *module, int priority, unsigned *seq)
{
    if (priority < 1 || priority > 99 || !module || strcmp(module, g_rt.name) == 0) return CONTRACT_EINVAL;
    if (check_mailbox() != 0) return CONTRACT_EINVAL;
    RequestMessage *m = blank(REQ_PRIORITY);
    m->Param.Priority.Priority = priority;
    async_seq = (async_seq + 1) & ~ASYNC_SEQ_BIT;
    m->Param.Priority.Seq = ASYNC_SEQ_BIT | async_seq;
    int rc = rt_send_request_to(module, m);
    if (rc == CONTRACT_OK && seq) *seq = m->Param.Priority.Seq;
    return rc;
}

static int match_async_priority_reply(const RequestMessage *m, const void *ctx)
{
    (void)ctx;
    return m->Type == REQ_PRIORITY_REPLY && (m->Param.Priority.Seq & ASYNC_SEQ_BIT);
}

/* Takes the first kept request `match` accepts out of the pending list. 1 (in *out), 0 none. */
static int take_pending(Matcher match, const void *ctx, RequestMessage *out)
{
    for (Pending **at = &g_rt.pending_head, *prev = NULL; *at; prev = *at, at = &(*at)->next) {
        Pending *p = *at;
        if (match(&p->msg, ctx) != 1) continue;
        *at = p->next;
        if (g_rt.pending_tail == p) g_rt.pending_tail = prev;
        g_rt.pending_count--;
        deliver(out, &p->msg);
        free(p);
        return 1;
    }
    return 0;
}

int ContractWaitModulePriority(RTIME deadline, RequestMessage *reply)
{
    if (check_mailbox() != 0) return -1;
    if (take_pending(match_async_priority_reply, NULL, reply)) return 1;
    return wait_for_match(match_async_priority_reply, NULL, deadline, reply);
}

int ModuleState(const char *module)
{
    if (!rt_valid_name(module)) return CONTRACT_EINVAL;
    if (g_rt.run_dir_fd < 0 && rt_init_run_dir() != 0) return CONTRACT_ESYS;
    char file[CONTRACT_NAME_MAX + 8];
    snprintf(file, sizeof file, "%s.mbx", module);
    struct stat st;
    if (fstatat(g_rt.run_dir_fd, file, &st, 0) != 0) return CONTRACT_EUNKNOWN;
    struct sockaddr_un sa;
    socklen_t len;
    if (rt_addr(file, &sa, &len) != 0) return CONTRACT_EINVAL;
    int probe = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    if (probe < 0) return CONTRACT_ESYS;
    int rc = connect(probe, (struct sockaddr *)&sa, len) == 0 ? CONTRACT_OK : rt_errno_to_code(errno);
    close(probe);
    return rc;
}
