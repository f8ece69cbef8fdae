/* sim_world.c — see sim_world.h. The requests an engine makes through its io are queued with the
 * virtual time and delivered after the input that caused them (as mailboxes would, without their
 * latency): a core is never re-entered from its own callback. */
#define _POSIX_C_SOURCE 200809L
#include "sim_world.h"
#include "engine_array.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ord_core.h"
#include "engine_values.h"
#include "sup_core.h"

/* A livelock guard: messages delivered at one virtual instant (two supervisors notifying each
   other forever would otherwise never let time advance). */
#define SIM_MAX_MESSAGES_PER_INSTANT 1000000L

typedef struct SimSub {
    char module[64];
    int src_port, in_port;
    ContractEventMode mode;
    int active;
} SimSub;

typedef struct SimSup {
    SimWorld *w;
    int index;
    const ContractSupervisorVocabulary *v;
    SupCore *core;
    SimSub *subs;
    int nsubs, capsubs;
    /* what it holds, by name, as module_holds.c's files: the modules it started or shares, and
       the event flows its event schemas use (engine_flow_hold_name) */
    char (*held)[ENGINE_HOLD_NAME_MAX];
    int nheld, capheld;
} SimSup;

typedef struct SimModule {
    char name[64];
    int started;        /* started by an engine (event schema, activate ... module)          */
    int start_marked;   /* an engine started it, not stopped since: module_holds.c's M.started */
    int crashed;
    int outstanding;    /* releases not acked yet                                            */
    int64_t exec_ns;    /* -1: its C (wcet) from ORD's table, else 0                          */
    int64_t exec_once;  /* -1: none                                                           */
    int64_t wcet_ns;
    long activations;   /* releases started: the `activation=N` of its run records            */
    int64_t run_ns;     /* asynchronous: each run ends this long after its start, -1: never   */
    int64_t run_once;   /* -1: none; else the next run only                                   */
    /* asynchronous: the events of connected event flows its handler has taken or will take (one
       at a time, as its request loop does), and when the last one's handling ends; exec_ns /
       exec_once are the time of each handling (a release's time for a synchronous module) */
    int handling;
    int64_t busy_until;
} SimModule;

typedef struct SimFinish {
    int64_t at;
    uint64_t seq;
    int module;
    uint32_t release_id;
    long activation;     /* the module's activation this release is                            */
    int own_end;         /* an asynchronous run its own code ends (finish M after T), not a release */
    int event;           /* an event of a connected flow: 1 its handler takes it (event_received),
                            2 its handler has ended (event_handled); 0: none of these           */
    char from[64];       /* the event's producer, its out port, the module's in port             */
    int from_port, port;
    int64_t taken;       /* event 2: when the handler took it                                    */
    int64_t exec;        /* a release: its simulated work time, said as its run_finished's cpu_ns */
} SimFinish;

/* An event flow an event schema connected (`A:o =* B:i`, `=>` one shot): B's handler takes what A
   emits on o, as libmodule's PostEvent delivers it to B's mailbox (mailbox.c). */
typedef struct SimEventFlow {
    char src[64], dst[64];
    int src_port, dst_port;
    int oneshot;
} SimEventFlow;

/* A data flow ORD connected (`A:o -> B:i * k`): B receives what A posts on every k-th activation
   of A since the connection, as libmodule's PostData counts (dataflow.c). */
typedef struct SimFlow {
    int src;             /* A: its index in mods (a release's end compares no names)              */
    char dst[64];
    int src_port, dst_port, periodicity;
    long base;           /* A's activations when connected                                      */
} SimFlow;

typedef enum SimMsgKind {
    MSG_ORD_ACTIVATE = 1, MSG_ORD_DEACTIVATE, MSG_ORD_EVENT, MSG_EVENT, MSG_START_FN, MSG_STOP_FN,
    MSG_ANSWER
} SimMsgKind;

typedef struct SimMsg {
    struct SimMsg *next;
    SimMsgKind kind;
    int from;            /* supervisor index, -1: ORD or scripted                                */
    char a[256];         /* schema / module / callee supervisor                                  */
    char b[256];         /* function                                                             */
    int port;
    uint32_t id;
    int ok;
    size_t size;
    unsigned char data[]; /* parameters / event data                                            */
} SimMsg;

struct SimWorld {
    SimSink sink;
    int64_t now;
    SimSup *sups;
    int nsups;
    const ContractOrdVocabulary *ordv;
    OrdCore *ord;
    SimModule *mods;
    int nmods, capmods;
    SimFinish *fin;
    int nfin, capfin;
    SimFlow *flows;
    int nflows, capflows;
    SimEventFlow *evflows;
    int nevflows, capevflows;
    uint64_t seq;
    SimMsg *head, *tail;
    uint64_t finished;
    int storm;           /* the livelock guard tripped (reported once)                        */
};

/* ---- small helpers ------------------------------------------------------------------------ */

static void scopy(char *dst, size_t n, const char *src) {
    size_t l = src ? strlen(src) : 0;
    if (l >= n) l = n - 1;
    if (l) memcpy(dst, src, l);
    dst[l] = '\0';
}

static void action(SimWorld *w, const char *who, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void action(SimWorld *w, const char *who, const char *fmt, ...) {
    if (!w->sink.action) return;
    char line[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    w->sink.action(w->sink.ctx, w->now, who, line);
}

static void record(SimWorld *w, const char *module, const char *event, const char *peer, int port,
                   const char *fmt, ...) __attribute__((format(printf, 6, 7)));
static void record(SimWorld *w, const char *module, const char *event, const char *peer, int port,
                   const char *fmt, ...) {
    if (!w->sink.record) return;
    char detail[384];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(detail, sizeof detail, fmt, ap);
    va_end(ap);
    w->sink.record(w->sink.ctx, w->now, module, event, peer, port, detail);
}

static int grow(void **p, int *cap, int need, size_t elem) { return engine_grow(p, cap, need, elem, 8); }

static int module_index(SimWorld *w, const char *name, int create) {
    for (int i = 0; i < w->nmods; i++)
        if (strcmp(w->mods[i].name, name) == 0) return i;
    if (!create || grow((void **)&w->mods, &w->capmods, w->nmods + 1, sizeof *w->mods)) return -1;
    SimModule *m = &w->mods[w->nmods];
    memset(m, 0, sizeof *m);
    scopy(m->name, sizeof m->name, name);
    m->exec_ns = -1;
    m->exec_once = -1;
    m->run_ns = -1;
    m->run_once = -1;
    if (w->ordv)
        for (int i = 0; i < w->ordv->nmodules; i++)
            if (strcmp(w->ordv->modules[i].name, name) == 0) m->wcet_ns = w->ordv->modules[i].wcet_ns;
    return w->nmods++;
}

static int sup_index(const SimWorld *w, const char *name) {
    for (int i = 0; i < w->nsups; i++)
        if (strcmp(w->sups[i].v->name, name) == 0) return i;
    return -1;
}

static SimMsg *msg_new(SimWorld *w, SimMsgKind kind, int from, const void *data, size_t size) {
    if (size > CONTRACT_MAX_VALUE_SIZE) size = CONTRACT_MAX_VALUE_SIZE;
    SimMsg *m = calloc(1, sizeof *m + size + 1);
    if (!m) return NULL;
    m->kind = kind;
    m->from = from;
    m->size = size;
    if (data && size) memcpy(m->data, data, size);
    if (w->tail) w->tail->next = m;
    else w->head = m;
    w->tail = m;
    return m;
}

/* ---- supervisor io: each callback queues or records, never calls a core ------------------- */

static void sio_ord_activate(void *ctx, const ContractSchema *s, const void *params, size_t size,
                             uint32_t id) {
    SimSup *p = ctx;
    SimMsg *m = msg_new(p->w, MSG_ORD_ACTIVATE, p->index, params, size);
    if (m) { scopy(m->a, sizeof m->a, s->name); m->id = id; }
    char args[ACTION_VALUE_MAX];
    engine_format_params(args, sizeof args, s->params, size == s->params_size ? s->nparams : -1, params);
    action(p->w, p->v->name, "activate schema %s%s (activation #%u, to ORD)", s->name, args, id);
}
static void sio_ord_deactivate(void *ctx, const ContractSchema *s, uint32_t id) {
    SimSup *p = ctx;
    SimMsg *m = msg_new(p->w, MSG_ORD_DEACTIVATE, p->index, NULL, 0);
    if (m) { scopy(m->a, sizeof m->a, s->name); m->id = id; }
    action(p->w, p->v->name, "deactivate schema %s (activation #%u, to ORD)", s->name, id);
}
static int sio_module_running(void *ctx, const char *module) {
    SimSup *p = ctx;
    return sim_world_module_running(p->w, module) == 1;
}
/* ---- holds: what module_holds.c and sup_main.c decide in a run, with the same module_hold and
   flow_hold records. A module or an event flow is held by name, per supervisor; the last holder
   lets it go. A module is stopped then only when an engine started it (one started otherwise,
   e.g. run by ORD, is left running). */

static int hold_index(const SimSup *p, const char *name) {
    for (int k = 0; k < p->nheld; k++)
        if (strcmp(p->held[k], name) == 0) return k;
    return -1;
}

/* 0 once p holds `name` (already, or now), -1 out of memory */
static int hold_take(SimSup *p, const char *name) {
    if (hold_index(p, name) >= 0) return 0;
    if (grow((void **)&p->held, &p->capheld, p->nheld + 1, sizeof *p->held) != 0) return -1;
    scopy(p->held[p->nheld++], sizeof *p->held, name);
    return 0;
}

/* drops p's hold on `name`; the number of other supervisors that still hold it (module_holds.c's holds_drop) */
static int hold_drop(SimSup *p, const char *name) {
    int k = hold_index(p, name);
    if (k >= 0 && k != --p->nheld) memcpy(p->held[k], p->held[p->nheld], sizeof *p->held);
    int others = 0;
    for (int s = 0; s < p->w->nsups; s++)
        if (&p->w->sups[s] != p && hold_index(&p->w->sups[s], name) >= 0) others++;
    return others;
}

static void hold_record(SimSup *p, const char *module, const char *detail) {
    record(p->w, p->v->name, "module_hold", module, -1, "%s", detail);
}

/* sup_main.c's stop_if_last: kept for the others, left running, it had ended, or stopped */
static void stop_if_last(SimSup *p, const char *module, int started_here) {
    int i = module_index(p->w, module, 1);
    if (i < 0) return;
    SimModule *m = &p->w->mods[i];
    int others = hold_drop(p, module);
    if (others > 0) {
        char detail[96];
        snprintf(detail, sizeof detail, "hold dropped (kept running: still used by %d other supervisor(s))", others);
        hold_record(p, module, detail);
        return;
    }
    int marked = m->start_marked;
    m->start_marked = 0;
    if (!marked && !started_here) {
        hold_record(p, module, "last hold dropped (left running: not started by an engine)");
        return;
    }
    if (m->crashed) { /* its process is gone (sup_main.c's alive()) */
        hold_record(p, module, "last hold dropped (it had ended)");
        return;
    }
    /* a module whose own code ended its run (finish) is still there: the STOP is sent and finds no
       run, as in a run (the module answers it, logs nothing) */
    int running = m->started;
    m->started = 0;
    hold_record(p, module, "last hold dropped (stopped)");
    /* a run it ends ends with the STOP, as libmodule logs it (mailbox.c) */
    if (running) record(p->w, module, "run_finished", p->v->name, -1, "activation=%ld cpu_ns=0 STOP", m->activations);
}

static void sio_start_module(void *ctx, const char *module, int priority) {
    SimSup *p = ctx;
    int i = module_index(p->w, module, 1);
    int crashed = i >= 0 && p->w->mods[i].crashed;
    action(p->w, p->v->name, ACTION_START_MODULE "%s", module, priority,
           crashed ? ": it has crashed, it does not start" : "");
    if (i < 0 || crashed) return; /* a run's start that cannot be sent takes no hold */
    SimModule *m = &p->w->mods[i];
    m->started = 1;
    m->start_marked = 1;
    if (hold_take(p, module) == 0) hold_record(p, module, "hold taken (started it)");
    /* the START begins a run of the (virtual, asynchronous) module, as libmodule logs it: the
       Monitor's running modules; it lasts until a STOP, a crash or a scenario's `finish` */
    record(p->w, module, "run_started", p->v->name, -1, "activation=%ld", ++m->activations);
    /* `finish M after T`: this run's own code ends it T later (unless a STOP or a crash comes first) */
    int64_t run = m->run_once >= 0 ? m->run_once : m->run_ns;
    m->run_once = -1;
    if (run >= 0 && grow((void **)&p->w->fin, &p->w->capfin, p->w->nfin + 1, sizeof *p->w->fin) == 0)
        p->w->fin[p->w->nfin++] = (SimFinish){.at = p->w->now + run, .seq = p->w->seq++, .module = i, .release_id = 0, .activation = m->activations, .own_end = 1};
}
/* `stop module M` (the undo of its start: steps-to-trace.ts adds `undo: `), then what its hold decided */
static void sio_stop_module(void *ctx, const char *module) {
    SimSup *p = ctx;
    action(p->w, p->v->name, ACTION_STOP_MODULE, module);
    stop_if_last(p, module, 1);
}
/* a module running when the supervisor needs it (started by another one, or by ORD): shared */
static void sio_share_module(void *ctx, const char *module, int hold) {
    SimSup *p = ctx;
    if (!hold) {
        stop_if_last(p, module, 0);
        return;
    }
    int i = module_index(p->w, module, 1);
    if (i >= 0 && hold_take(p, module) == 0) hold_record(p, module, "hold taken (it was running)");
}
/* sup_main.c's b_module_run_ended: the run a START began has ended by the module's own code
   (finish), so a supervisor that holds it and needs it again starts it again; a crashed module
   has no run to start */
static int sio_module_run_ended(void *ctx, const char *module) {
    SimSup *p = ctx;
    int i = module_index(p->w, module, 0);
    if (i < 0) return 0;
    const SimModule *m = &p->w->mods[i];
    return !m->crashed && !m->started && m->outstanding == 0 && m->activations > 0;
}
static int sio_claim_priority(void *ctx, const char *module, uint32_t id, int priority) {
    SimSup *p = ctx;
    action(p->w, p->v->name, ACTION_CLAIM_PRIORITY, module, priority, id);
    return 0;
}
static void sio_release_priority(void *ctx, const char *module, uint32_t id) {
    SimSup *p = ctx;
    action(p->w, p->v->name, ACTION_RELEASE_PRIORITY, id, module);
}
static void sio_set_param(void *ctx, const char *module, int port, const char *name, const void *value,
                          size_t size, const ContractType *type) {
    SimSup *p = ctx;
    char line[ACTION_LINE_MAX];
    engine_format_parameterize(line, sizeof line, module, port, name, value, size, type);
    action(p->w, p->v->name, "%s", line);
}
/* ---- event flows: sup_main.c's b_connect / b_disconnect, held as modules are (above). One flow
   is one subscription whichever supervisors ask for it: the last one lets it go. */

static void sio_connect(void *ctx, const ContractEventFlow *f) {
    SimSup *p = ctx;
    char flow[ACTION_LINE_MAX], name[ENGINE_HOLD_NAME_MAX];
    engine_format_event_flow(flow, sizeof flow, f);
    engine_flow_hold_name(name, sizeof name, f->src_module, f->src_port, f->dst_module, f->dst_port);
    action(p->w, p->v->name, "connect %s", flow);
    if (hold_take(p, name) == 0) record(p->w, p->v->name, "flow_hold", name, -1, "hold taken");
    SimWorld *w = p->w;
    for (int i = 0; i < w->nevflows; i++) /* one subscription, whichever supervisors ask for it */
        if (w->evflows[i].src_port == f->src_port && w->evflows[i].dst_port == f->dst_port &&
            strcmp(w->evflows[i].src, f->src_module) == 0 && strcmp(w->evflows[i].dst, f->dst_module) == 0)
            return;
    if (grow((void **)&w->evflows, &w->capevflows, w->nevflows + 1, sizeof *w->evflows) != 0) return;
    SimEventFlow *e = &w->evflows[w->nevflows++];
    scopy(e->src, sizeof e->src, f->src_module);
    scopy(e->dst, sizeof e->dst, f->dst_module);
    e->src_port = f->src_port;
    e->dst_port = f->dst_port;
    e->oneshot = f->mode == CONTRACT_ONESHOT;
}
/* the flow's subscription ends with its last hold */
static void drop_event_flow(SimWorld *w, const ContractEventFlow *f) {
    for (int i = 0; i < w->nevflows; i++)
        if (w->evflows[i].src_port == f->src_port && w->evflows[i].dst_port == f->dst_port &&
            strcmp(w->evflows[i].src, f->src_module) == 0 && strcmp(w->evflows[i].dst, f->dst_module) == 0) {
            w->evflows[i] = w->evflows[--w->nevflows];
            return;
        }
}
static void sio_disconnect(void *ctx, const ContractEventFlow *f) {
    SimSup *p = ctx;
    char flow[ACTION_LINE_MAX], name[ENGINE_HOLD_NAME_MAX];
    engine_format_event_flow(flow, sizeof flow, f);
    engine_flow_hold_name(name, sizeof name, f->src_module, f->src_port, f->dst_module, f->dst_port);
    action(p->w, p->v->name, "disconnect %s", flow);
    int others = hold_drop(p, name);
    if (others > 0)
        record(p->w, p->v->name, "flow_hold", name, -1,
               "hold dropped (kept connected: used by %d other supervisor(s))", others);
    else {
        record(p->w, p->v->name, "flow_hold", name, -1, "last hold dropped (disconnected)");
        drop_event_flow(p->w, f);
    }
}
static void sio_subscribe(void *ctx, const char *module, int src_port, int in_port,
                          ContractEventMode mode, uint32_t id) {
    SimSup *p = ctx;
    SimSub *s = NULL;
    for (int i = 0; i < p->nsubs; i++)
        if (p->subs[i].src_port == src_port && p->subs[i].in_port == in_port &&
            strcmp(p->subs[i].module, module) == 0)
            s = &p->subs[i];
    if (!s && !grow((void **)&p->subs, &p->capsubs, p->nsubs + 1, sizeof *p->subs)) {
        s = &p->subs[p->nsubs++];
        scopy(s->module, sizeof s->module, module);
        s->src_port = src_port;
        s->in_port = in_port;
    }
    if (s) { s->mode = mode; s->active = 1; }
    action(p->w, p->v->name, "subscribe %s:%d %s :%d (activation #%u)", module, src_port,
           mode == CONTRACT_ONESHOT ? "=>" : "=*", in_port, id);
}
static void sio_unsubscribe(void *ctx, const char *module, int src_port, int in_port, uint32_t id) {
    SimSup *p = ctx;
    for (int i = 0; i < p->nsubs; i++)
        if (p->subs[i].src_port == src_port && p->subs[i].in_port == in_port &&
            strcmp(p->subs[i].module, module) == 0)
            p->subs[i].active = 0;
    action(p->w, p->v->name, "unsubscribe %s:%d :%d (activation #%u)", module, src_port, in_port, id);
}
static void sio_notify(void *ctx, int out_port, const ContractType *type, const void *value,
                       size_t size) {
    SimSup *p = ctx;
    SimMsg *m = msg_new(p->w, MSG_EVENT, p->index, value, size);
    if (m) { scopy(m->a, sizeof m->a, p->v->name); m->port = out_port; }
    char v[ACTION_VALUE_MAX];
    engine_format_value(v, sizeof v, value, type);
    action(p->w, p->v->name, "notify :%d (%s) = %s", out_port, type ? type->name : "?", v);
}
static int sio_start_function(void *ctx, const ContractFunctionSignature *callee,
                              const void *params, size_t size, uint32_t id) {
    SimSup *p = ctx;
    const char *sup = callee->supervisor, *fn = callee->function;
    SimMsg *m = msg_new(p->w, MSG_START_FN, p->index, params, size);
    if (!m) return -1;
    scopy(m->a, sizeof m->a, sup);
    scopy(m->b, sizeof m->b, fn);
    m->id = id;
    char args[ACTION_VALUE_MAX];
    engine_format_params(args, sizeof args, callee->params, size == callee->params_size ? callee->nparams : -1, params);
    action(p->w, p->v->name, "activate supervisor %s.%s%s (activation #%u)", sup, fn, args, id);
    return 0;
}
static void sio_stop_function(void *ctx, const char *sup, const char *fn, uint32_t id) {
    SimSup *p = ctx;
    SimMsg *m = msg_new(p->w, MSG_STOP_FN, p->index, NULL, 0);
    if (m) { scopy(m->a, sizeof m->a, sup); scopy(m->b, sizeof m->b, fn); m->id = id; }
    action(p->w, p->v->name, "stop %s.%s (activation #%u)", sup, fn, id);
}
static void sio_trace(void *ctx, int64_t t, const char *line) {
    SimSup *p = ctx;
    if (p->w->sink.log) p->w->sink.log(p->w->sink.ctx, t, p->v->name, line);
}
static void sio_rule(void *ctx, int64_t t, const char *function, const char *rule, int active,
                     const char *cause) {
    SimSup *p = ctx;
    if (p->w->sink.rule) p->w->sink.rule(p->w->sink.ctx, t, p->v->name, function, rule, active, cause);
}
static void sio_action(void *ctx, int64_t t, const char *line) {
    SimSup *p = ctx;
    (void)t;
    action(p->w, p->v->name, "%s", line);
}

/* ---- ORD io ------------------------------------------------------------------------------- */

static void oio_set_param(void *ctx, const char *module, int port, const char *name, const void *value,
                          size_t size, const ContractType *type) {
    char line[ACTION_LINE_MAX];
    engine_format_parameterize(line, sizeof line, module, port, name, value, size, type);
    action(ctx, "ORD", "%s", line);
}
static int flow_index(const SimWorld *w, int src, const ContractDataFlow *f) {
    for (int i = 0; i < w->nflows; i++) {
        const SimFlow *g = &w->flows[i];
        if (g->src == src && g->src_port == f->src_port && g->dst_port == f->dst_port && strcmp(g->dst, f->dst_module) == 0)
            return i;
    }
    return -1;
}
static void oio_connect(void *ctx, const ContractDataFlow *f) {
    SimWorld *w = ctx;
    char flow[ACTION_LINE_MAX];
    engine_format_data_flow(flow, sizeof flow, f);
    action(w, "ORD", "connect %s * %d", flow, f->periodicity);
    int src = module_index(w, f->src_module, 1);
    if (src < 0) return;
    int i = flow_index(w, src, f);
    if (i < 0) {
        if (grow((void **)&w->flows, &w->capflows, w->nflows + 1, sizeof *w->flows)) return;
        i = w->nflows++;
    }
    SimFlow *g = &w->flows[i];
    g->src = src;
    scopy(g->dst, sizeof g->dst, f->dst_module);
    g->src_port = f->src_port;
    g->dst_port = f->dst_port;
    g->periodicity = f->periodicity < 1 ? 1 : f->periodicity;
    g->base = w->mods[src].activations;
}
static void oio_disconnect(void *ctx, const ContractDataFlow *f) {
    SimWorld *w = ctx;
    char flow[ACTION_LINE_MAX];
    engine_format_data_flow(flow, sizeof flow, f);
    action(w, "ORD", "disconnect %s", flow);
    int i = flow_index(w, module_index(w, f->src_module, 0), f);
    if (i >= 0) w->flows[i] = w->flows[--w->nflows];
}
/* A virtual module posts each of its connected output ports once per run (it runs no code: the
   value is not known), at the end of the run: the producer's data_posted records of a real run. */
static void post_data(SimWorld *w, int module, long activation) {
    const SimModule *m = &w->mods[module];
    for (int i = 0; i < w->nflows; i++) {
        const SimFlow *g = &w->flows[i];
        if (g->src != module) continue;
        long n = activation - g->base;
        if (n <= 0 || n % g->periodicity != 0) continue;
        record(w, m->name, "data_posted", g->dst, g->src_port, "to_port=%d", g->dst_port);
    }
}
static void oio_release(void *ctx, const char *module, const char *schema, int64_t tick,
                        uint32_t release_id) {
    SimWorld *w = ctx;
    (void)schema;
    (void)tick;
    int i = module_index(w, module, 1);
    if (i < 0) return;
    SimModule *m = &w->mods[i];
    if (m->crashed) return; /* never answers */
    int64_t exec = m->exec_once >= 0 ? m->exec_once : m->exec_ns >= 0 ? m->exec_ns : m->wcet_ns;
    m->exec_once = -1;
    if (grow((void **)&w->fin, &w->capfin, w->nfin + 1, sizeof *w->fin)) return;
    w->fin[w->nfin++] = (SimFinish){.at = w->now + exec, .seq = w->seq++, .module = i, .release_id = release_id, .activation = ++m->activations, .own_end = 0, .exec = exec};
    m->outstanding++;
    record(w, m->name, "run_started", "ORD", -1, "activation=%ld", m->activations);
}
static void oio_emit(void *ctx, int port, const char *schema) {
    SimWorld *w = ctx;
    SimMsg *m = msg_new(w, MSG_ORD_EVENT, -1, NULL, 0);
    if (m) { scopy(m->a, sizeof m->a, schema); m->port = port; }
    action(w, "ORD", "ORD:%d \"%s\" (%s) to every supervisor", port, schema,
           port == CONTRACT_ORD_EVENT_DEADLINE_MISS ? "deadline miss" : "conflict");
}
static void oio_ack(void *ctx, const char *requester, uint32_t id, int ok) {
    (void)ctx; (void)requester; (void)id; (void)ok; /* supervisors do not wait (engines.md §5.6) */
}
static void oio_trace(void *ctx, int64_t t, const char *line) {
    SimWorld *w = ctx;
    if (w->sink.log) w->sink.log(w->sink.ctx, t, "ORD", line);
}
static void oio_fact(void *ctx, int64_t t, const OrdFact *f) {
    SimWorld *w = ctx;
    if (!w->sink.record) return;
    char detail[384];
    const char *event = ord_fact_record(f, t, detail, sizeof detail);
    w->sink.record(w->sink.ctx, t, "ORD", event, f->module ? f->module : "", -1, detail);
}

/* ---- delivery ----------------------------------------------------------------------------- */

/** A handling of an event by module i's handler, at `at`: 1 it takes it, 2 it has ended. */
static void schedule_handling(SimWorld *w, int i, int what, int64_t at, int64_t taken,
                              const char *src, int src_port, int port) {
    if (grow((void **)&w->fin, &w->capfin, w->nfin + 1, sizeof *w->fin) != 0) return;
    SimFinish *f = &w->fin[w->nfin++];
    *f = (SimFinish){.at = at, .seq = w->seq++, .module = i, .release_id = 0, .activation = 0, .own_end = 0};
    f->event = what;
    f->taken = taken;
    f->from_port = src_port;
    f->port = port;
    scopy(f->from, sizeof f->from, src);
}

/** The asynchronous module `dst`'s handler gets an event of `src`:`src_port` on its in port
 *  `port`, as libmodule's request loop does: it takes it (GetEventId: event_received) when its
 *  handler of the previous one has ended, and its handler ends `exec` later (the module reads its
 *  mailbox again: event_handled). A crashed module takes nothing. */
static int module_event(SimWorld *w, const char *dst, const char *src, int src_port, int port) {
    int i = module_index(w, dst, 1);
    if (i < 0 || w->mods[i].crashed) return 0;
    SimModule *m = &w->mods[i];
    int64_t took = m->exec_once >= 0 ? m->exec_once : m->exec_ns >= 0 ? m->exec_ns : 0;
    m->exec_once = -1;
    int64_t start = m->handling > 0 && m->busy_until > w->now ? m->busy_until : w->now;
    if (m->handling > 0) schedule_handling(w, i, 1, start, start, src, src_port, port);
    else record(w, m->name, "event_received", src, port, "from_port=%d latency_ns=0", src_port);
    m->handling++;
    m->busy_until = start + took;
    schedule_handling(w, i, 2, m->busy_until, start, src, src_port, port);
    return 1;
}

/** Delivers an event of `src`:`port` to every supervisor subscribed to it, and to the
 *  asynchronous modules an event flow connects to it; returns how many received it. */
static int deliver_event(SimWorld *w, const char *src, int port, const void *data, size_t size) {
    int n = 0;
    for (int k = 0; k < w->nevflows;) {
        SimEventFlow e = w->evflows[k];
        if (e.src_port != port || strcmp(e.src, src) != 0) { k++; continue; }
        if (e.oneshot) w->evflows[k] = w->evflows[--w->nevflows]; /* spent by this event */
        else k++;
        n += module_event(w, e.dst, src, port, e.dst_port);
    }
    for (int s = 0; s < w->nsups; s++) {
        SimSup *p = &w->sups[s];
        for (int i = 0; i < p->nsubs; i++) {
            SimSub *sub = &p->subs[i];
            if (!sub->active || sub->src_port != port || strcmp(sub->module, src) != 0) continue;
            if (sub->mode == CONTRACT_ONESHOT) sub->active = 0; /* spent by this event */
            /* as sup_main.c writes it: once the rules have seen it, with the rule changes it made
               and its value as a rule's cause writes it (no latency: messages take no virtual time) */
            const int changed = sup_core_module_event(p->core, w->now, src, port, sub->in_port, data, size);
            char value[ACTION_VALUE_MAX];
            sup_core_format_event_value(p->core, sub->in_port, data, size, value, sizeof value);
            record(w, p->v->name, "event_received", src, sub->in_port,
                   "from_port=%d latency_ns=0 taken_ns=%lld rules=%d value=%s", port, (long long)w->now, changed, value);
            n++;
        }
    }
    return n;
}

static void dispatch(SimWorld *w, SimMsg *m) {
    const char *from = m->from >= 0 ? w->sups[m->from].v->name : "ORD";
    switch (m->kind) {
    case MSG_ORD_ACTIVATE:
        if (w->ord) ord_core_activate(w->ord, w->now, m->a, m->data, m->size, from, m->id);
        else action(w, "ORD", "no scheduler configuration: %s's activation of %s is lost", from, m->a);
        break;
    case MSG_ORD_DEACTIVATE:
        if (w->ord) ord_core_deactivate(w->ord, w->now, m->a, from, m->id);
        break;
    case MSG_ORD_EVENT:
        for (int s = 0; s < w->nsups; s++) sup_core_ord_event(w->sups[s].core, w->now, m->port, m->a);
        break;
    case MSG_EVENT:
        deliver_event(w, m->a, m->port, m->data, m->size);
        break;
    case MSG_START_FN: {
        int callee = sup_index(w, m->a);
        int ok = callee >= 0 && sup_core_start_function_for(w->sups[callee].core, w->now, m->b,
                                                            m->data, m->size, from, m->id) == 0;
        SimMsg *a = msg_new(w, MSG_ANSWER, callee, NULL, 0);
        if (a) { a->port = m->from; a->id = m->id; a->ok = ok; scopy(a->a, sizeof a->a, m->a); }
        break;
    }
    case MSG_STOP_FN: {
        int callee = sup_index(w, m->a);
        if (callee >= 0) sup_core_stop_function_for(w->sups[callee].core, w->now, m->b, from, m->id);
        break;
    }
    case MSG_ANSWER:
        if (m->port >= 0 && m->port < w->nsups)
            sup_core_function_answer(w->sups[m->port].core, w->now, m->a, m->id, m->ok);
        break;
    }
}

static void drain(SimWorld *w) {
    long n = 0;
    while (w->head) {
        SimMsg *m = w->head;
        w->head = m->next;
        if (!w->head) w->tail = NULL;
        if (++n > SIM_MAX_MESSAGES_PER_INSTANT) {
            if (!w->storm) action(w, "sim", "more than %ld messages at one instant: dropped (engines notifying each other forever?)", SIM_MAX_MESSAGES_PER_INSTANT);
            w->storm = 1;
            free(m);
            continue;
        }
        dispatch(w, m);
        free(m);
    }
}

/* ---- lifecycle ---------------------------------------------------------------------------- */

SimWorld *sim_world_create(const ContractSupervisorVocabulary *const *sups, int nsups,
                           const ContractOrdVocabulary *ord, const SimSink *sink, char *err,
                           size_t errlen) {
    SimWorld *w = calloc(1, sizeof *w);
    if (!w || nsups < 0 || (nsups && !(w->sups = calloc((size_t)nsups, sizeof *w->sups)))) {
        free(w);
        snprintf(err, errlen, "out of memory");
        return NULL;
    }
    if (sink) w->sink = *sink;
    w->nsups = nsups;
    for (int i = 0; i < nsups; i++) {
        SimSup *p = &w->sups[i];
        p->w = w;
        p->index = i;
        p->v = sups[i];
        SupIo io = {0};
        io.ctx = p;
        io.ord_activate = sio_ord_activate;
        io.ord_deactivate = sio_ord_deactivate;
        io.module_running = sio_module_running;
        io.start_module = sio_start_module;
        io.stop_module = sio_stop_module;
        io.share_module = sio_share_module;
        io.claim_priority = sio_claim_priority;
        io.release_priority = sio_release_priority;
        io.set_param = sio_set_param;
        io.connect_events = sio_connect;
        io.disconnect_events = sio_disconnect;
        io.subscribe = sio_subscribe;
        io.unsubscribe = sio_unsubscribe;
        io.notify = sio_notify;
        io.start_function = sio_start_function;
        io.stop_function = sio_stop_function;
        io.trace = sio_trace;
        io.rule = sio_rule;
        io.action = sio_action;
        io.module_run_ended = sio_module_run_ended;
        p->core = sup_core_create(sups[i], &io, err, errlen);
        if (!p->core) {
            sim_world_destroy(w);
            return NULL;
        }
    }
    if (ord) {
        w->ordv = ord;
        OrdIo io = {0};
        io.ctx = w;
        io.set_param = oio_set_param;
        io.connect_data = oio_connect;
        io.disconnect_data = oio_disconnect;
        io.release = oio_release;
        io.emit = oio_emit;
        io.ack = oio_ack;
        io.trace = oio_trace;
        io.fact = oio_fact;
        w->ord = ord_core_create(ord, &io, err, errlen);
        if (!w->ord) {
            sim_world_destroy(w);
            return NULL;
        }
        for (int i = 0; i < ord->nmodules; i++) module_index(w, ord->modules[i].name, 1);
    }
    return w;
}

void sim_world_destroy(SimWorld *w) {
    if (!w) return;
    while (w->head) {
        SimMsg *m = w->head;
        w->head = m->next;
        free(m);
    }
    for (int i = 0; i < w->nsups; i++) {
        if (w->sups[i].core) sup_core_destroy(w->sups[i].core);
        free(w->sups[i].subs);
        free(w->sups[i].held);
    }
    if (w->ord) ord_core_destroy(w->ord);
    free(w->sups);
    free(w->mods);
    free(w->fin);
    free(w->flows);
    free(w->evflows);
    free(w);
}

/* The asynchronous module's own code ends its run (finish): it no longer runs; its holders keep
   their holds (the last one's STOP finds no run: stop_if_last). Logged as libmodule logs a run
   whose code returned (mailbox.c: no STOP, no ack, no peer). */
static void end_own_run(SimWorld *w, SimModule *m) {
    m->started = 0;
    record(w, m->name, "run_finished", "", -1, "activation=%ld cpu_ns=0", m->activations);
    drain(w);
}

/* ---- the clock ---------------------------------------------------------------------------- */

static int next_due(const SimWorld *w, int64_t *at) {
    int any = 0;
    int64_t best = 0, d;
    for (int i = 0; i < w->nfin; i++)
        if (!any || w->fin[i].at < best) { best = w->fin[i].at; any = 1; }
    if (w->ord && ord_core_next_deadline(w->ord, &d) && (!any || d < best)) { best = d; any = 1; }
    for (int s = 0; s < w->nsups; s++)
        if (sup_core_next_deadline(w->sups[s].core, &d) && (!any || d < best)) { best = d; any = 1; }
    *at = best;
    return any;
}

/** Completes the earliest release due at t (lowest sequence first); 0 when none is due. */
static int finish_one(SimWorld *w, int64_t t) {
    int k = -1;
    for (int i = 0; i < w->nfin; i++)
        if (w->fin[i].at <= t && (k < 0 || w->fin[i].seq < w->fin[k].seq)) k = i;
    if (k < 0) return 0;
    SimFinish f = w->fin[k];
    w->fin[k] = w->fin[--w->nfin];
    SimModule *m = &w->mods[f.module];
    if (f.own_end) { /* that run, if it still goes on (not stopped, not started again since) */
        if (m->started && !m->crashed && m->activations == f.activation) end_own_run(w, m);
        return 1;
    }
    if (f.event == 1) { /* its handler takes the next event (GetEventId) */
        record(w, m->name, "event_received", f.from, f.port, "from_port=%d latency_ns=0", f.from_port);
        return 1;
    }
    if (f.event == 2) { /* its handler has ended: the module reads its mailbox again */
        if (m->handling > 0) m->handling--;
        record(w, m->name, "event_handled", f.from, f.port, "from_port=%d handling_ns=%lld", f.from_port,
               (long long)(w->now - f.taken));
        return 1;
    }
    if (m->outstanding > 0) m->outstanding--;
    w->finished++;
    post_data(w, f.module, f.activation);
    /* the release's CPU time: its simulated work time (a simulated module computes alone on its CPU:
       no preemption, no load), as libmodule measures the module's thread (mailbox.c) */
    record(w, m->name, "run_finished", "", -1, "activation=%ld cpu_ns=%lld ACK_FINISHED", f.activation, (long long)f.exec);
    if (w->ord) ord_core_release_finished(w->ord, w->now, m->name, f.release_id);
    drain(w);
    return 1;
}

void sim_world_advance(SimWorld *w, int64_t t) {
    int64_t at;
    while (next_due(w, &at) && at <= t) {
        if (at > w->now) w->now = at;
        while (finish_one(w, w->now)) {}
        if (w->ord) { ord_core_advance(w->ord, w->now); drain(w); }
        for (int s = 0; s < w->nsups; s++) { sup_core_advance(w->sups[s].core, w->now); drain(w); }
    }
    if (t > w->now) w->now = t;
    if (w->ord) ord_core_advance(w->ord, w->now);
    for (int s = 0; s < w->nsups; s++) sup_core_advance(w->sups[s].core, w->now);
    drain(w);
}

int64_t sim_world_now(const SimWorld *w) { return w->now; }

/* ---- scripted inputs ---------------------------------------------------------------------- */

int sim_world_start(SimWorld *w, const char *sup, const char *fn, const char *args, char *err,
                    size_t errlen) {
    int s = sup_index(w, sup);
    if (s < 0) { snprintf(err, errlen, "no supervisor %s", sup); return -1; }
    int rc = sup_core_start_function_text(w->sups[s].core, w->now, fn, args, err, errlen);
    if (rc != 0 && !err[0]) snprintf(err, errlen, "%s.%s refused to start (already running?)", sup, fn);
    drain(w);
    return rc;
}

int sim_world_stop(SimWorld *w, const char *sup, const char *fn, char *err, size_t errlen) {
    int s = sup_index(w, sup);
    if (s < 0) { snprintf(err, errlen, "no supervisor %s", sup); return -1; }
    int rc = sup_core_stop_function(w->sups[s].core, w->now, fn);
    if (rc != 0) snprintf(err, errlen, "%s.%s is not running", sup, fn);
    drain(w);
    return rc;
}

/** The type of what src:port carries: the in port of a supervisor subscribed to it (any one:
 *  the language checks they agree), the out port of a supervisor source, string for ORD. */
static const ContractType *event_type(const SimWorld *w, const char *src, int port) {
    if (strcmp(src, "ORD") == 0) return &contract_type_string;
    int s = sup_index(w, src);
    if (s >= 0)
        for (int i = 0; i < w->sups[s].v->nout_ports; i++)
            if (w->sups[s].v->out_ports[i].port == port) return w->sups[s].v->out_ports[i].type;
    for (int k = 0; k < w->nsups; k++) {
        const SimSup *p = &w->sups[k];
        for (int i = 0; i < p->nsubs; i++) {
            if (p->subs[i].src_port != port || strcmp(p->subs[i].module, src) != 0) continue;
            for (int j = 0; j < p->v->nin_ports; j++)
                if (p->v->in_ports[j].port == p->subs[i].in_port) return p->v->in_ports[j].type;
        }
    }
    return NULL;
}

/** Parses `text` (Cactal value syntax) as a value of `type` into buf (type->size bytes). */
static int parse_value(const ContractType *type, const char *text, unsigned char *buf, char *err,
                       size_t errlen) {
    engine_default_value(buf, type, NULL);
    while (*text == ' ' || *text == '\t') text++;
    if (!*text) return 0;
    char *copy = strdup(text);
    if (!copy) { snprintf(err, errlen, "out of memory"); return -1; }
    int used = contract_value_get(type, buf, copy);
    int ok = used >= 0;
    if (ok) for (const char *p = copy + used; *p; p++) if (*p != ' ' && *p != '\t') ok = 0;
    free(copy);
    if (!ok) snprintf(err, errlen, "'%s' is not a value of type %s", text, type->name);
    return ok ? 0 : -1;
}

int sim_world_event(SimWorld *w, const char *module, int port, const char *value_text, char *err,
                    size_t errlen) {
    int mi = module_index(w, module, 0);
    if (mi >= 0 && w->mods[mi].crashed) {
        snprintf(err, errlen, "%s has crashed: it emits nothing", module);
        return -1;
    }
    const ContractType *type = event_type(w, module, port);
    if (!type) return 0; /* nobody subscribed: nobody receives it */
    unsigned char *buf = calloc(1, type->size ? type->size : 1);
    if (!buf) { snprintf(err, errlen, "out of memory"); return -1; }
    int n = -1;
    if (parse_value(type, value_text ? value_text : "", buf, err, errlen) == 0) {
        if (strcmp(module, "ORD") == 0) {
            if (port != CONTRACT_ORD_EVENT_DEADLINE_MISS && port != CONTRACT_ORD_EVENT_CONFLICT) {
                snprintf(err, errlen, "ORD has event ports 0 (deadline miss) and 1 (conflict) only");
            } else {
                for (int s = 0; s < w->nsups; s++) sup_core_ord_event(w->sups[s].core, w->now, port, (const char *)buf);
                n = w->nsups;
            }
        } else {
            n = deliver_event(w, module, port, buf, type->size);
        }
    }
    free(buf);
    drain(w);
    return n;
}

int sim_world_crash(SimWorld *w, const char *module, char *err, size_t errlen) {
    int i = module_index(w, module, 1);
    if (i < 0) return 0;
    /* a module that is not running yet may crash (its process dies before it is started); one that
       has crashed has no process left to crash: a second crash was taken without a word */
    if (w->mods[i].crashed) {
        snprintf(err, errlen, "%s has already crashed: there is no process of it left to crash", module);
        return -1;
    }
    w->mods[i].crashed = 1;
    w->mods[i].started = 0;
    w->mods[i].handling = 0;
    for (int k = 0; k < w->nfin;) /* its releases and its handler never finish */
        if (w->fin[k].module == i) w->fin[k] = w->fin[--w->nfin];
        else k++;
    action(w, module, "crashed");
    return 0;
}

int sim_world_finish(SimWorld *w, const char *module, char *err, size_t errlen) {
    int i = module_index(w, module, 0);
    if (i < 0 || !w->mods[i].started || w->mods[i].crashed) {
        snprintf(err, errlen, "%s is not running: it has no run to finish%s", module,
                 i >= 0 && w->mods[i].crashed ? " (it has crashed)" : "");
        return -1;
    }
    end_own_run(w, &w->mods[i]);
    return 0;
}

void sim_world_set_run_time(SimWorld *w, const char *module, int64_t run_ns, int once) {
    int i = module_index(w, module, 1);
    if (i < 0) return;
    if (once) w->mods[i].run_once = run_ns;
    else w->mods[i].run_ns = run_ns;
}

void sim_world_set_exec(SimWorld *w, const char *module, int64_t exec_ns, int once) {
    int i = module_index(w, module, 1);
    if (i < 0) return;
    if (once) w->mods[i].exec_once = exec_ns;
    else w->mods[i].exec_ns = exec_ns;
}

/* ---- state -------------------------------------------------------------------------------- */

int sim_world_rule_active(const SimWorld *w, const char *sup, const char *fn, const char *rule) {
    int s = sup_index(w, sup);
    return s < 0 ? -1 : sup_core_rule_active(w->sups[s].core, fn, rule);
}

int sim_world_function_running(const SimWorld *w, const char *sup, const char *fn) {
    int s = sup_index(w, sup);
    if (s < 0) return -1;
    for (int f = 0; f < w->sups[s].v->nfunctions; f++)
        if (strcmp(w->sups[s].v->functions[f].name, fn) == 0)
            return sup_core_function_running(w->sups[s].core, fn);
    return -1;
}

/** 1 when an active rule of a running function activated the event schema `name`. */
static int event_schema_active(const SimWorld *w, const char *name) {
    for (int s = 0; s < w->nsups; s++) {
        const ContractSupervisorVocabulary *v = w->sups[s].v;
        for (int f = 0; f < v->nfunctions; f++) {
            const ContractFunction *fn = &v->functions[f];
            if (!sup_core_function_running(w->sups[s].core, fn->name)) continue;
            for (int r = 0; r < fn->nrules; r++) {
                const ContractRule *rule = &fn->rules[r];
                for (int a = 0; a < rule->nactions; a++) {
                    const ContractAction *act = &rule->actions[a];
                    if (act->kind == CONTRACT_ACT_SCHEMA && act->schema &&
                        act->schema->kind == CONTRACT_SCHEMA_EVENT &&
                        strcmp(act->schema->name, name) == 0 &&
                        sup_core_rule_active(w->sups[s].core, fn->name, rule->label) == 1)
                        return 1;
                }
            }
        }
    }
    return 0;
}

int sim_world_schema_active(const SimWorld *w, const char *schema) {
    if (w->ord && ord_core_schema_active(w->ord, schema)) return 1;
    return event_schema_active(w, schema);
}

int sim_world_schema_stats(const SimWorld *w, const char *schema, OrdSchemaStats *out) {
    return w->ord ? ord_core_stats(w->ord, schema, out) : -1;
}

int sim_world_module_running(const SimWorld *w, const char *module) {
    for (int i = 0; i < w->nmods; i++)
        if (strcmp(w->mods[i].name, module) == 0)
            return !w->mods[i].crashed && (w->mods[i].started || w->mods[i].outstanding > 0);
    return 0;
}

const void *sim_world_local(const SimWorld *w, const char *sup, const char *fn, const char *name,
                            const ContractType **type) {
    int s = sup_index(w, sup);
    if (s < 0 || !sup_core_function_running(w->sups[s].core, fn)) return NULL;
    const ContractSupervisorVocabulary *v = w->sups[s].v;
    for (int f = 0; f < v->nfunctions; f++) {
        if (strcmp(v->functions[f].name, fn) != 0) continue;
        for (int i = 0; i < v->functions[f].nlocals; i++)
            if (strcmp(v->functions[f].locals[i].name, name) == 0) {
                if (type) *type = v->functions[f].locals[i].type;
                return sup_core_local(w->sups[s].core, fn, name);
            }
    }
    return NULL;
}

void sim_world_each_active_schema(const SimWorld *w, void (*fn)(void *ctx, const char *schema),
                                  void *ctx) {
    if (w->ord)
        for (int i = 0; i < w->ordv->nschemas; i++)
            if (ord_core_schema_active(w->ord, w->ordv->schemas[i]->name)) fn(ctx, w->ordv->schemas[i]->name);
    /* event schemas, each name once, in the order of the supervisors' tables */
    const char *seen[256];
    int nseen = 0;
    for (int s = 0; s < w->nsups; s++) {
        const ContractSupervisorVocabulary *v = w->sups[s].v;
        for (int f = 0; f < v->nfunctions; f++)
            for (int r = 0; r < v->functions[f].nrules; r++)
                for (int a = 0; a < v->functions[f].rules[r].nactions; a++) {
                    const ContractAction *act = &v->functions[f].rules[r].actions[a];
                    if (act->kind != CONTRACT_ACT_SCHEMA || !act->schema || act->schema->kind != CONTRACT_SCHEMA_EVENT) continue;
                    int dup = 0;
                    for (int k = 0; k < nseen; k++) if (strcmp(seen[k], act->schema->name) == 0) dup = 1;
                    if (dup || nseen >= 256) continue;
                    seen[nseen++] = act->schema->name;
                    if (event_schema_active(w, act->schema->name)) fn(ctx, act->schema->name);
                }
    }
}

void sim_world_each_local(const SimWorld *w,
                          void (*fn)(void *ctx, const char *sup, const char *function,
                                     const char *local, const ContractType *type, const void *v),
                          void *ctx) {
    for (int s = 0; s < w->nsups; s++) {
        const ContractSupervisorVocabulary *v = w->sups[s].v;
        for (int f = 0; f < v->nfunctions; f++) {
            const ContractFunction *func = &v->functions[f];
            if (!sup_core_function_running(w->sups[s].core, func->name)) continue;
            for (int i = 0; i < func->nlocals; i++) {
                const void *val = sup_core_local(w->sups[s].core, func->name, func->locals[i].name);
                if (val) fn(ctx, v->name, func->name, func->locals[i].name, func->locals[i].type, val);
            }
        }
    }
}

uint64_t sim_world_events_processed(const SimWorld *w) {
    uint64_t n = w->finished;
    for (int s = 0; s < w->nsups; s++) n += sup_core_events_processed(w->sups[s].core);
    return n;
}
