/* fake_world.c — see fake_world.h. */
#define _POSIX_C_SOURCE 200809L
#include "fake_world.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report_types.h"

/* ---- formatting ------------------------------------------------------------------------- */

void fake_format(char *out, size_t n, const ContractType *t, const void *v) {
    switch (t->kind) {
    case CONTRACT_KIND_LONG: snprintf(out, n, "%ld", *(const long *)v); return;
    case CONTRACT_KIND_DOUBLE: snprintf(out, n, "%g", *(const double *)v); return;
    case CONTRACT_KIND_STRING: snprintf(out, n, "%.*s", 255, (const char *)v); return;
    case CONTRACT_KIND_STRUCT: break;
    default: contract_value_format(out, n, t, v); return; /* bool, enums, arrays */
    }
    if (strcmp(t->name, "TypeA") == 0) {
        const TypeA *a = v;
        snprintf(out, n, "{%g,%g,%g}", a->i, a->j, a->k);
    } else if (strcmp(t->name, "TypeD") == 0) {
        const TypeD *d = v;
        snprintf(out, n, "{%s,%ld}", d->dataname, d->datavalue);
    } else if (strcmp(t->name, "TypeC") == 0) {
        const TypeC *c = v;
        snprintf(out, n, "{%s,%ld,{%g,%g,%g}}", c->message, c->messagetype, c->value.i, c->value.j,
                 c->value.k);
    } else {
        snprintf(out, n, "<%s>", t->name);
    }
}

static void wlog(FakeWorld *w, const char *line) {
    if (w->name) log_add(w->log, "%s: %s", w->name, line);
    else log_add(w->log, "%s", line);
}

#define WLOG(w, ...)                                  \
    do {                                              \
        char line_[1024];                         \
        snprintf(line_, sizeof line_, __VA_ARGS__);   \
        wlog((w), line_);                             \
    } while (0)

static void scopy(char *dst, size_t n, const char *src) {
    size_t l = strlen(src);
    if (l >= n) l = n - 1;
    memmove(dst, src, l);
    dst[l] = '\0';
}

static int find_running(const FakeWorld *w, const char *m) {
    for (int i = 0; i < w->nrunning; i++)
        if (strcmp(w->running[i], m) == 0) return i;
    return -1;
}

void fake_set_running(FakeWorld *w, const char *module, int priority) {
    int i = find_running(w, module);
    if (i < 0 && w->nrunning < FW_MAX) {
        i = w->nrunning++;
        snprintf(w->running[i], sizeof w->running[i], "%s", module);
    }
    if (i >= 0) w->prio[i] = priority;
}

int fake_is_running(const FakeWorld *w, const char *module) { return find_running(w, module) >= 0; }

static int find_ended(const FakeWorld *w, const char *m) {
    for (int i = 0; i < w->nended; i++)
        if (strcmp(w->ended[i], m) == 0) return i;
    return -1;
}

/* Takes `module` out of the running ones (its slot gets the last one), if it runs. */
static void stop_running(FakeWorld *w, const char *module) {
    int i = find_running(w, module);
    if (i < 0) return;
    w->nrunning--;
    memmove(w->running[i], w->running[w->nrunning], sizeof w->running[i]);
    w->prio[i] = w->prio[w->nrunning];
}

void fake_end_own_run(FakeWorld *w, const char *module) {
    stop_running(w, module);
    if (find_ended(w, module) < 0 && w->nended < FW_MAX) snprintf(w->ended[w->nended++], sizeof w->ended[0], "%s", module);
}

static void format_block(char *out, size_t n, const ContractVar *vars, int nvars, const void *block) {
    size_t used = 0;
    out[0] = '\0';
    for (int i = 0; i < nvars && used < n; i++) {
        char v[300];
        fake_format(v, sizeof v, vars[i].type, (const unsigned char *)block + vars[i].offset);
        used += (size_t)snprintf(out + used, n - used, "%s%s=%s", i ? " " : "", vars[i].name, v);
    }
}

/* ---- bus ------------------------------------------------------------------------------- */

typedef struct BusMsg {
    int kind;               /* 0 start function, 1 stop function, 2 event, 3 answer to a start */
    char to[16], function[64], from[16];
    uint32_t act_id;        /* start/stop/answer: the caller's activation id */
    int accepted;           /* answer */
    int src_port, in_port;
    unsigned char data[1024];
    size_t size;
} BusMsg;

typedef struct BusSub {
    int active;
    char producer[16], consumer[16];
    int src_port, in_port, mode;
} BusSub;

struct FakeBus {
    int npeers;
    const char *names[8];
    SupCore *cores[8];
    BusMsg msgs[64];
    int nmsgs;
    BusSub subs[32];
    int nsubs;
};

FakeBus *fake_bus_create(void) { return calloc(1, sizeof(FakeBus)); }
void fake_bus_destroy(FakeBus *b) { free(b); }
void fake_bus_attach(FakeBus *b, const char *name, SupCore *core) {
    b->names[b->npeers] = name;
    b->cores[b->npeers++] = core;
}

static BusMsg *bus_push(FakeBus *b) {
    if (b->nmsgs >= 64) return NULL;
    BusMsg *m = &b->msgs[b->nmsgs++];
    memset(m, 0, sizeof *m);
    return m;
}

int fake_bus_deliver(FakeBus *b, int64_t t) {
    int n = 0;
    while (b->nmsgs > 0) {
        BusMsg m = b->msgs[0];
        memmove(&b->msgs[0], &b->msgs[1], (size_t)(b->nmsgs - 1) * sizeof m);
        b->nmsgs--;
        SupCore *dst = NULL;
        for (int i = 0; i < b->npeers; i++)
            if (strcmp(b->names[i], m.to) == 0) dst = b->cores[i];
        if (!dst) continue;
        n++;
        if (m.kind == 0) { /* the callee answers, as sup_main.c does with ACK_START/ACK_NOTDONE */
            int rc = sup_core_start_function_for(dst, t, m.function, m.data, m.size, m.from, m.act_id);
            BusMsg *a = bus_push(b);
            if (a) {
                a->kind = 3;
                scopy(a->to, sizeof a->to, m.from);
                scopy(a->from, sizeof a->from, m.to);
                a->act_id = m.act_id;
                a->accepted = rc == 0;
            }
        } else if (m.kind == 1) {
            sup_core_stop_function_for(dst, t, m.function, m.from, m.act_id);
        } else if (m.kind == 3) {
            sup_core_function_answer(dst, t, m.from, m.act_id, m.accepted);
        } else {
            sup_core_module_event(dst, t, m.from, m.src_port, m.in_port, m.data, m.size);
        }
    }
    return n;
}

/* ---- SupIo ------------------------------------------------------------------------------ */

static void s_ord_activate(void *ctx, const ContractSchema *s, const void *params, size_t size,
                           uint32_t id) {
    (void)size;
    (void)id;
    char p[400];
    format_block(p, sizeof p, s->params, s->nparams, params);
    WLOG((FakeWorld *)ctx, "ORD activate %s %s", s->name, p);
}
static void s_ord_deactivate(void *ctx, const ContractSchema *s, uint32_t id) {
    (void)id;
    WLOG((FakeWorld *)ctx, "ORD deactivate %s", s->name);
}
static int s_module_running(void *ctx, const char *m) {
    const FakeWorld *w = ctx;
    return fake_is_running(w->modules ? w->modules : w, m);
}
static void require_locked(FakeWorld *w, const char *m) {
    if (strcmp(w->locked, m) != 0) w->unlocked_effects++;
}
static void s_lock_module(void *ctx, const char *m, int lock) {
    FakeWorld *w = ctx;
    if (lock) {
        if (w->locked[0]) w->unlocked_effects++; /* the core never nests two locks */
        snprintf(w->locked, sizeof w->locked, "%s", m);
        w->nlocks++;
    } else {
        if (strcmp(w->locked, m) != 0) w->unlocked_effects++;
        w->locked[0] = '\0';
    }
}
static void s_start_module(void *ctx, const char *m, int prio) {
    FakeWorld *w = ctx;
    require_locked(w, m);
    fake_set_running(w, m, prio);
    WLOG(w, "start %s prio %d", m, prio);
}
static int s_module_run_ended(void *ctx, const char *m) {
    FakeWorld *w = ctx;
    require_locked(w, m);
    return find_ended(w, m) >= 0 && find_running(w, m) < 0;
}
static void s_stop_module(void *ctx, const char *m) {
    FakeWorld *w = ctx;
    require_locked(w, m);
    stop_running(w, m);
    WLOG(w, "stop %s", m);
}
static int set_priority(FakeWorld *w, const char *m, int prio) {
    FakeWorld *mw = w->modules ? w->modules : w;
    int i = find_running(mw, m);
    int old = i >= 0 ? mw->prio[i] : -1;
    if (i >= 0) mw->prio[i] = prio;
    WLOG(w, "priority %s %d (was %d)", m, prio, old);
    return old;
}
static int s_claim_priority(void *ctx, const char *m, uint32_t id, int prio) {
    FakeWorld *w = ctx, *mw = w->modules ? w->modules : w;
    int before = set_priority(w, m, prio);
    if (before < 0) return -1;
    return sup_claims_push_priority(&mw->prio_claims, w->name ? w->name : "", m, id, prio, before);
}
static void s_release_priority(void *ctx, const char *m, uint32_t id) {
    FakeWorld *w = ctx, *mw = w->modules ? w->modules : w;
    int restore = -1, later = -1;
    int r = sup_claims_drop_priority(&mw->prio_claims, w->name ? w->name : "", m, id, &restore, &later);
    if (r == 1) set_priority(w, m, restore);
    else if (r == 0) WLOG(w, "kept: priority of %s (a later change by %s stands)", m,
                          mw->prio_claims.prio[later].owner[0] ? mw->prio_claims.prio[later].owner : "this supervisor");
    if (mw->prio_claims.nprio == 0) sup_claims_free(&mw->prio_claims); /* nothing left to free */
}
static void s_set_param(void *ctx, const char *m, int port, const char *name, const void *v, size_t size,
                        const ContractType *t) {
    (void)name;
    (void)t;
    char buf[300];
    if (size == sizeof(TypeA)) fake_format(buf, sizeof buf, &(ContractType){.name = "TypeA", .kind = CONTRACT_KIND_STRUCT}, v);
    else snprintf(buf, sizeof buf, "<%zu bytes>", size);
    WLOG((FakeWorld *)ctx, "setparam %s:%d %s", m, port, buf);
}
static void s_connect(void *ctx, const ContractEventFlow *f) {
    WLOG((FakeWorld *)ctx, "connect %s:%d %s %s:%d", f->src_module, f->src_port,
         f->mode == CONTRACT_ONESHOT ? "=>" : "=*", f->dst_module, f->dst_port);
}
static void s_disconnect(void *ctx, const ContractEventFlow *f) {
    WLOG((FakeWorld *)ctx, "disconnect %s:%d %s %s:%d", f->src_module, f->src_port,
         f->mode == CONTRACT_ONESHOT ? "=>" : "=*", f->dst_module, f->dst_port);
}
static void s_subscribe(void *ctx, const char *m, int sp, int ip, ContractEventMode mode, uint32_t id) {
    FakeWorld *w = ctx;
    (void)id; /* the lines of the supervisor tests name the port, not the number */
    WLOG(w, "subscribe %s:%d %s :%d", m, sp, mode == CONTRACT_ONESHOT ? "=>" : "=*", ip);
    if (w->bus && w->bus->nsubs < 32) {
        BusSub *s = &w->bus->subs[w->bus->nsubs++];
        s->active = 1;
        snprintf(s->producer, sizeof s->producer, "%s", m);
        snprintf(s->consumer, sizeof s->consumer, "%s", w->name ? w->name : "");
        s->src_port = sp;
        s->in_port = ip;
        s->mode = mode;
    }
}
static void s_unsubscribe(void *ctx, const char *m, int sp, int ip, uint32_t id) {
    FakeWorld *w = ctx;
    (void)id;
    WLOG(w, "unsubscribe %s:%d :%d", m, sp, ip);
    if (w->bus)
        for (int i = 0; i < w->bus->nsubs; i++) {
            BusSub *s = &w->bus->subs[i];
            if (s->active && strcmp(s->producer, m) == 0 && s->src_port == sp && s->in_port == ip &&
                strcmp(s->consumer, w->name ? w->name : "") == 0)
                s->active = 0;
        }
}
static void s_notify(void *ctx, int port, const ContractType *t, const void *v, size_t size) {
    FakeWorld *w = ctx;
    char buf[300];
    fake_format(buf, sizeof buf, t, v);
    WLOG(w, "notify :%d %s", port, buf);
    if (!w->bus) return;
    for (int i = 0; i < w->bus->nsubs; i++) {
        BusSub *s = &w->bus->subs[i];
        if (!s->active || s->src_port != port || strcmp(s->producer, w->name ? w->name : "") != 0)
            continue;
        BusMsg *m = bus_push(w->bus);
        if (!m) return;
        m->kind = 2;
        scopy(m->to, sizeof m->to, s->consumer);
        scopy(m->from, sizeof m->from, w->name);
        m->src_port = port;
        m->in_port = s->in_port;
        m->size = size < sizeof m->data ? size : sizeof m->data;
        memcpy(m->data, v, m->size);
        if (s->mode == CONTRACT_ONESHOT) s->active = 0;
    }
}
static int s_start_function(void *ctx, const ContractFunctionSignature *callee, const void *p,
                            size_t size, uint32_t id) {
    FakeWorld *w = ctx;
    const char *sup = callee->supervisor, *fn = callee->function;
    char buf[300] = "";
    if (size == sizeof(TypeA)) /* the report's parameter blocks; others are not shown */
        fake_format(buf, sizeof buf, &(ContractType){.name = "TypeA", .kind = CONTRACT_KIND_STRUCT}, p);
    WLOG(w, "start %s.%s %s", sup, fn, buf);
    if (w->bus) {
        BusMsg *m = bus_push(w->bus);
        if (m) {
            m->kind = 0;
            m->act_id = id;
            scopy(m->from, sizeof m->from, w->name ? w->name : "");
            snprintf(m->to, sizeof m->to, "%s", sup);
            snprintf(m->function, sizeof m->function, "%s", fn);
            m->size = size < sizeof m->data ? size : sizeof m->data;
            memcpy(m->data, p, m->size);
        }
    }
    return 0;
}
static void s_stop_function(void *ctx, const char *sup, const char *fn, uint32_t id) {
    FakeWorld *w = ctx;
    WLOG(w, "stop %s.%s", sup, fn);
    if (w->bus) {
        BusMsg *m = bus_push(w->bus);
        if (m) {
            m->kind = 1;
            m->act_id = id;
            scopy(m->from, sizeof m->from, w->name ? w->name : "");
            snprintf(m->to, sizeof m->to, "%s", sup);
            snprintf(m->function, sizeof m->function, "%s", fn);
        }
    }
}
static void s_trace(void *ctx, int64_t t, const char *line) {
    (void)t;
    wlog(ctx, line);
}
static void s_action(void *ctx, int64_t t, const char *line) {
    (void)t;
    if (((FakeWorld *)ctx)->log_actions) wlog(ctx, line);
}
static void s_share_module(void *ctx, const char *m, int hold) {
    require_locked(ctx, m);
    WLOG((FakeWorld *)ctx, "%s %s", hold ? "share" : "unshare", m);
}

SupCore *fake_make_sup(FakeWorld *w, TestLog *log, const ContractSupervisorVocabulary *v, const char *name) {
    memset(w, 0, sizeof *w);
    w->log = log;
    w->name = name;
    SupIo io = fake_sup_io(w);
    char err[256] = "";
    SupCore *c = sup_core_create(v, &io, err, sizeof err);
    if (!c) fprintf(stderr, "  %s\n", err);
    return c;
}

SupIo fake_sup_io(FakeWorld *w) {
    SupIo io = {w, s_ord_activate, s_ord_deactivate, s_module_running, s_start_module,
                s_stop_module, s_claim_priority, s_release_priority, s_set_param, s_connect, s_disconnect, s_subscribe,
                s_unsubscribe, s_notify, s_start_function, s_stop_function, s_trace, s_share_module,
                s_lock_module, NULL, s_action, s_module_run_ended, NULL};
    return io;
}

/* ---- OrdIo ------------------------------------------------------------------------------ */

static void o_set_param(void *ctx, const char *m, int port, const char *name, const void *v, size_t size,
                        const ContractType *t) {
    ((FakeWorld *)ctx)->ord_clock += ((FakeWorld *)ctx)->ord_request_ns;
    s_set_param(ctx, m, port, name, v, size, t);
}
static void o_connect(void *ctx, const ContractDataFlow *f) {
    ((FakeWorld *)ctx)->ord_clock += ((FakeWorld *)ctx)->ord_request_ns;
    WLOG((FakeWorld *)ctx, "connect %s:%d -> %s:%d * %d", f->src_module, f->src_port, f->dst_module,
         f->dst_port, f->periodicity);
}
static void o_disconnect(void *ctx, const ContractDataFlow *f) {
    WLOG((FakeWorld *)ctx, "disconnect %s:%d -> %s:%d", f->src_module, f->src_port, f->dst_module,
         f->dst_port);
}
static void o_release(void *ctx, const char *m, const char *schema, int64_t tick, uint32_t id) {
    FakeWorld *w = ctx;
    if (w->nrel < (int)(sizeof w->rel_id / sizeof w->rel_id[0])) {
        snprintf(w->rel_module[w->nrel], sizeof w->rel_module[0], "%s", m);
        w->rel_id[w->nrel++] = id;
    }
    (void)schema;
    (void)tick;
    (void)ctx;
    (void)m;
}
static void o_emit(void *ctx, int port, const char *schema) {
    WLOG((FakeWorld *)ctx, "emit ORD:%d %s", port, schema);
}
static void o_ack(void *ctx, const char *req, uint32_t id, int ok) {
    WLOG((FakeWorld *)ctx, "ack %s #%u %s", req ? req : "", id, ok ? "done" : "refused");
}

static void o_trace(void *ctx, int64_t t, const char *line) {
    WLOG((FakeWorld *)ctx, "%lldus %s", (long long)(t / 1000), line);
}

static void o_stuck(void *ctx, const char *m, const char *schema, uint32_t id, long periods,
                    const char *message) {
    FakeWorld *w = ctx;
    snprintf(w->stuck_message, sizeof w->stuck_message, "%s", message);
    WLOG(w, "stuck %s #%u (%s) after %ld periods", m, id, schema, periods);
}

static int o_module_gone(void *ctx, const char *m) {
    const FakeWorld *w = ctx;
    for (int i = 0; i < w->ngone; i++)
        if (strcmp(w->gone[i], m) == 0) return 1;
    return 0;
}

void fake_set_gone(FakeWorld *w, const char *module) {
    if (w->ngone < FW_MAX) snprintf(w->gone[w->ngone++], sizeof w->gone[0], "%s", module);
}

static int activity_index(const FakeWorld *w, const char *module) {
    for (int i = 0; i < w->nact; i++)
        if (strcmp(w->act_module[i], module) == 0) return i;
    return -1;
}

static int o_module_activity(void *ctx, const char *m, OrdModuleActivity *out) {
    FakeWorld *w = ctx;
    int i = activity_index(w, m);
    if (i < 0) return -1;
    w->act_looks[i]++;
    w->act_cpu[i] += w->act_step[i];
    w->act_wait[i] += w->act_wait_step[i] < 0 ? 0 : w->act_wait_step[i];
    out->state = w->act_state[i];
    out->cpu_ns = w->act_cpu[i];
    out->wait_ns = w->act_wait_step[i] < 0 ? -1 : w->act_wait[i];
    snprintf(out->waiting_in, sizeof out->waiting_in, "%s", w->act_waiting_in[i]);
    w->act_written[i] += w->act_written_step[i] < 0 ? 0 : w->act_written_step[i];
    out->written_bytes = w->act_written_step[i] < 0 ? -1 : w->act_written[i];
    return 0;
}

void fake_set_written(FakeWorld *w, const char *module, int64_t written_step) {
    int i = activity_index(w, module);
    if (i >= 0) w->act_written_step[i] = written_step;
}

void fake_set_waiting_in(FakeWorld *w, const char *module, const char *wchan) {
    int i = activity_index(w, module);
    if (i >= 0) snprintf(w->act_waiting_in[i], sizeof w->act_waiting_in[0], "%s", wchan);
}

void fake_set_activity(FakeWorld *w, const char *module, char state, int64_t cpu_step_ns, int64_t wait_step_ns) {
    int i = activity_index(w, module);
    if (i < 0) {
        if (w->nact >= FW_MAX) return;
        i = w->nact++;
        snprintf(w->act_module[i], sizeof w->act_module[0], "%s", module);
    }
    w->act_state[i] = state;
    w->act_waiting_in[i][0] = '\0';
    w->act_written_step[i] = -1;
    w->act_written[i] = 0;
    w->act_step[i] = cpu_step_ns;
    w->act_wait_step[i] = wait_step_ns;
}

int fake_activity_looks(const FakeWorld *w, const char *module) {
    int i = activity_index(w, module);
    return i < 0 ? 0 : w->act_looks[i];
}

uint32_t fake_last_release(const FakeWorld *w, const char *module) {
    for (int i = w->nrel - 1; i >= 0; i--)
        if (strcmp(w->rel_module[i], module) == 0) return w->rel_id[i];
    return 0;
}

int64_t fake_setup_done_at(void *ctx) {
    return ((FakeWorld *)ctx)->ord_clock;
}

OrdIo fake_ord_io(FakeWorld *w) {
    OrdIo io = {w, o_set_param, o_connect, o_disconnect, o_release, o_emit, o_ack, o_trace, o_stuck, NULL, o_module_gone,
                o_module_activity, NULL};
    return io;
}
