/* sup_core.c — see sup_core.h. Semantics: docs/semantics.md "Event schemas: ...", "Supervisors: ...", decisions in docs/engines.md. */
#define _POSIX_C_SOURCE 200809L
#include "sup_core.h"
#include "engine_array.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine_trace.h"
#include "engine_values.h"
#include "sup_claims.h"

/* ---- state -------------------------------------------------------------------------- */

typedef struct Occ {        /* the latest significant occurrence of one event descriptor */
    int valid;
    int64_t t;
    uint64_t seq;           /* number of the processed event that recorded it */
    unsigned char *data;    /* its data (module events), NULL otherwise */
} Occ;

typedef struct Slot {       /* one event descriptor of one condition clause */
    const ContractEvent *ev;
    size_t data_size;
} Slot;

typedef struct UndoRec {    /* what one action did, so that its undo does exactly the inverse */
    int done;
    uint32_t act_id;        /* this action's activation id: periodic schema, subscription,
                               priority claim, function activation (unique in the core) */
    int started_module;     /* resttime/critical: we took a hold (started it) */
    int changed_priority;   /* resttime/critical: a priority claim (SupIo.claim_priority) */
    int started_function;   /* activation sent and not refused: its undo stops it */
} UndoRec;

typedef struct RuleState {
    int active;
    int64_t since;
    uint32_t gen;           /* bumped at each activation: stale duration timers are dropped */
    UndoRec *undo;          /* one per action */
    int pre_first, post_first; /* index of the first slot of pre / post */
} RuleState;

typedef struct FnState {
    int running;
    uint32_t gen;
    uint64_t start_seq;     /* c->seq when started: it does not see the event that started it */
    int64_t started_at;
    unsigned char *params, *locals;
    RuleState *rules;
    Slot *slots;
    int nslots;
    Occ *occ;
    char *hit;              /* per slot: recorded by the event being processed */
    /* the activation it runs: `activate supervisor` of caller/owner_id; "" and 0 for a
       control tool. Only the undo of that activation stops it (docs/engines.md §4). */
    char owner[64];
    uint32_t owner_id;
} FnState;

typedef struct Sub {        /* active subscription of one in port */
    int active;
    const char *module;
    int src_port;
    ContractEventMode mode;
    uint32_t token;
} Sub;

typedef struct Hold {       /* modules this supervisor started */
    const char *module;
    int holders;
    int owned;
    int shared;             /* held while started by someone else (io.share_module told) */
} Hold;

typedef struct Timer {
    int64_t deadline;
    uint64_t order;
    int fn;
    uint32_t fn_gen;
    ContractEventKind kind; /* ELAPSED or DURATION */
    int rule;
    uint32_t rule_gen;
    int64_t time_ns;
} Timer;

typedef struct QEv {        /* a started/endof event waiting behind the current one */
    int fn;
    uint32_t fn_gen;
    ContractEventKind kind;
    int rule;
} QEv;

/* the event being processed */
typedef struct CurEv {
    ContractEventKind kind;
    const char *module;
    int port;
    int in_port;
    const unsigned char *data;
    size_t size;
    const char *ord_schema;
    int rule;
    int64_t time_ns;
} CurEv;

struct SupCore {
    const ContractSupervisorVocabulary *v;
    SupIo io;
    int64_t now;
    uint64_t seq;
    uint64_t processed;
    /* rule changes reported so far (report_rule): what a module event changed, for its record */
    uint64_t rule_changes;
    FnState *fns;
    unsigned char **in_vals;
    unsigned char **out_vals;
    Sub *subs;              /* per in port (table index) */
    Hold *holds;
    int nholds, capholds;
    Timer *timers;
    int ntimers, captimers;
    uint64_t timer_order;
    QEv *queue;
    int qhead, qlen, qcap;
    const CurEv *cur;       /* the event being processed (NULL: none): a rule change's cause */
    uint32_t next_token;
    SupClaims claims;       /* event-flow users of the active schemas */
    unsigned char *scratch;
    size_t scratch_used;
};

#define SCRATCH_SIZE (4 * CONTRACT_MAX_VALUE_SIZE)

/* ---- small helpers ------------------------------------------------------------------- */

ENGINE_DEFINE_TRACE(SupCore)

/* an action no other io call carries (io.action) */
static void note_action(SupCore *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void note_action(SupCore *c, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    engine_vtrace(c->io.action, c->io.ctx, c->now, fmt, ap);
    va_end(ap);
}

static void *scratch_alloc(SupCore *c, size_t n) {
    size_t a = (c->scratch_used + 15u) & ~(size_t)15u;
    if (a + n > SCRATCH_SIZE) return NULL;
    c->scratch_used = a + n;
    return c->scratch + a;
}

static int in_port_index(const ContractSupervisorVocabulary *v, int port) {
    for (int i = 0; i < v->nin_ports; i++)
        if (v->in_ports[i].port == port) return i;
    return -1;
}

static int out_port_index(const ContractSupervisorVocabulary *v, int port) {
    for (int i = 0; i < v->nout_ports; i++)
        if (v->out_ports[i].port == port) return i;
    return -1;
}

static int function_index(const ContractSupervisorVocabulary *v, const char *name) {
    for (int i = 0; i < v->nfunctions; i++)
        if (strcmp(v->functions[i].name, name) == 0) return i;
    return -1;
}

static const unsigned char *port_value_cb(void *ctx, int port, const ContractType **type) {
    SupCore *c = ctx;
    int i = in_port_index(c->v, port);
    if (i < 0) return NULL;
    if (type) *type = c->v->in_ports[i].type;
    return c->in_vals[i];
}

static EngineScope fn_scope(SupCore *c, int f) {
    EngineScope s;
    memset(&s, 0, sizeof s);
    s.fn = &c->v->functions[f];
    s.locals = c->fns[f].locals;
    s.params = c->fns[f].params;
    s.param_vars = s.fn->params;
    s.nparam_vars = s.fn->nparams;
    s.port_value = port_value_cb;
    s.port_ctx = c;
    s.occ_port = -1;
    return s;
}

static int grow(void **p, int *cap, int need, size_t elem) { return engine_grow(p, cap, need, elem, 16); }

/* ---- timers and queue ----------------------------------------------------------------- */

static void add_timer(SupCore *c, int64_t deadline, int f, ContractEventKind kind, int rule,
                      int64_t time_ns) {
    if (grow((void **)&c->timers, &c->captimers, c->ntimers + 1, sizeof(Timer)) != 0) {
        trace(c, "error: out of memory arming a timer");
        return;
    }
    Timer *t = &c->timers[c->ntimers++];
    t->deadline = deadline;
    t->order = c->timer_order++;
    t->fn = f;
    t->fn_gen = c->fns[f].gen;
    t->kind = kind;
    t->rule = rule;
    t->rule_gen = rule >= 0 ? c->fns[f].rules[rule].gen : 0;
    t->time_ns = time_ns;
}

static int timer_valid(const SupCore *c, const Timer *t) {
    const FnState *fs = &c->fns[t->fn];
    if (!fs->running || fs->gen != t->fn_gen) return 0;
    if (t->kind == CONTRACT_EV_DURATION) {
        const RuleState *r = &fs->rules[t->rule];
        if (!r->active || r->gen != t->rule_gen) return 0;
    }
    return 1;
}

static void queue_push(SupCore *c, int f, ContractEventKind kind, int rule) {
    if (c->qlen == c->qcap) {
        int ncap = c->qcap ? c->qcap * 2 : 32;
        QEv *q = malloc((size_t)ncap * sizeof *q);
        if (!q) {
            trace(c, "error: out of memory queueing an event");
            return;
        }
        for (int i = 0; i < c->qlen; i++) q[i] = c->queue[(c->qhead + i) % c->qcap];
        free(c->queue);
        c->queue = q;
        c->qcap = ncap;
        c->qhead = 0;
    }
    QEv *e = &c->queue[(c->qhead + c->qlen) % c->qcap];
    e->fn = f;
    e->fn_gen = c->fns[f].gen;
    e->kind = kind;
    e->rule = rule;
    c->qlen++;
}

/* ---- module holds (modules this supervisor started) ---------------------------------- */

static Hold *find_hold(SupCore *c, const char *module, int create) {
    for (int i = 0; i < c->nholds; i++)
        if (strcmp(c->holds[i].module, module) == 0) return &c->holds[i];
    if (!create) return NULL;
    if (grow((void **)&c->holds, &c->capholds, c->nholds + 1, sizeof(Hold)) != 0) return NULL;
    Hold *h = &c->holds[c->nholds++];
    h->module = module;
    h->holders = 0;
    h->owned = 0;
    h->shared = 0;
    return h;
}

static void lock_module(SupCore *c, const char *module, int lock) {
    if (c->io.lock_module) c->io.lock_module(c->io.ctx, module, lock);
}

static int module_is_running(SupCore *c, const char *module) {
    Hold *h = find_hold(c, module, 0);
    if (h && h->owned) return 1;
    return c->io.module_running ? c->io.module_running(c->io.ctx, module) : 0;
}

/* takes a hold on a module, starting it at `priority` if it is not running */
static void hold_acquire(SupCore *c, const char *module, int priority) {
    Hold *h = find_hold(c, module, 1);
    if (!h) {
        trace(c, "error: out of memory holding module %s", module);
        return;
    }
    if (h->holders == 0 && !h->owned) {
        lock_module(c, module, 1);
        if (!module_is_running(c, module)) {
            if (c->io.start_module) c->io.start_module(c->io.ctx, module, priority);
            h->owned = 1;
        } else if (c->io.share_module) { /* running, started elsewhere: say we use it too */
            c->io.share_module(c->io.ctx, module, 1);
            h->shared = 1;
        }
        lock_module(c, module, 0);
    } else if (h->owned && c->io.module_run_ended) {
        /* held for another rule or schema of this supervisor: a run it started that the module's
           own code has ended since is started again, as a module not running is */
        lock_module(c, module, 1);
        if (c->io.module_run_ended(c->io.ctx, module) && c->io.start_module) c->io.start_module(c->io.ctx, module, priority);
        lock_module(c, module, 0);
    }
    h->holders++;
}

static void hold_release(SupCore *c, const char *module) {
    Hold *h = find_hold(c, module, 0);
    if (!h || h->holders == 0 || --h->holders > 0 || (!h->owned && !h->shared)) return;
    lock_module(c, module, 1);
    if (h->owned) {
        if (c->io.stop_module) c->io.stop_module(c->io.ctx, module);
    } else if (c->io.share_module) {
        c->io.share_module(c->io.ctx, module, 0);
    }
    h->owned = 0;
    h->shared = 0;
    lock_module(c, module, 0);
}

/* ---- actions -------------------------------------------------------------------------- */

static unsigned char *build_block(SupCore *c, int f, const ContractVar *vars, int nvars,
                                  size_t size, const ContractAssign *as, int nas) {
    unsigned char *b = calloc(1, size ? size : 1);
    if (!b) return NULL;
    engine_init_block(b, vars, nvars);
    EngineScope s = fn_scope(c, f);
    for (int i = 0; i < nas; i++)
        if (engine_apply_assign(&s, &as[i], b, vars) != 0)
            trace(c, "error: cannot read the value of assignment %d", i);
    return b;
}

static void activate_event_schema(SupCore *c, int f, const ContractSchema *sc,
                                  const unsigned char *params) {
    char args[ACTION_VALUE_MAX];
    engine_format_params(args, sizeof args, sc->params, sc->nparams, params);
    note_action(c, "activate schema %s%s (event schema)", sc->name, args);
    EngineScope s = fn_scope(c, f);
    s.params = params;
    s.param_vars = sc->params;
    s.nparam_vars = sc->nparams;
    for (int m = 0; m < sc->nmodules; m++) {
        const ContractSchemaModule *sm = &sc->modules[m];
        for (int k = 0; k < sm->nsettings; k++) {
            void *val = scratch_alloc(c, sm->settings[k].type->size);
            if (val && engine_build_setting(&s, &sm->settings[k], val) == 0 && c->io.set_param)
                c->io.set_param(c->io.ctx, sm->module, sm->settings[k].port, sm->settings[k].name, val,
                                sm->settings[k].type->size, sm->settings[k].type);
        }
    }
    /* Flows are connected at every activation (the same subscription again: a spent one-shot
       flow is armed again), disconnected by the last active schema using it. Consumers first: a
       module is started only once the consumers of its flows are started, and its flows are
       connected just before its start. Each mailbox reads in order, so a consumer's START is
       ahead of any event of the schema's flows (a producer posts only once subscribed), and a
       producer is subscribed before its START: its first events reach their consumers. (Connected
       before the starts, a producer posting a burst filled its consumer's mailbox ahead of the
       consumer's START, which waited ~1.5 s behind the events.) A cycle of flows is broken in the
       modules' order: the first module left is started after connecting its flows. */
    unsigned char *started = calloc((size_t)sc->nmodules + 1, 1);
    unsigned char *connected = calloc((size_t)sc->nevent_flows + 1, 1);
    if (!started || !connected) {
        trace(c, "error: out of memory activating schema %s", sc->name);
        free(started);
        free(connected);
        return;
    }
    for (int left = sc->nmodules + 1; left > 0; left--) { /* a module at least per pass, then the rest */
        int next = -1;
        for (int m = 0; m < sc->nmodules && next < 0; m++) {
            if (started[m]) continue;
            int ready = 1;
            for (int i = 0; i < sc->nevent_flows && ready; i++) {
                const ContractEventFlow *fl = &sc->event_flows[i];
                if (connected[i] || strcmp(fl->src_module, sc->modules[m].module) != 0) continue;
                for (int d = 0; d < sc->nmodules; d++)
                    if (!started[d] && d != m && strcmp(fl->dst_module, sc->modules[d].module) == 0) ready = 0;
            }
            if (ready) next = m;
        }
        for (int m = 0; m < sc->nmodules && next < 0; m++) /* a cycle: the first module left */
            if (!started[m]) next = m;
        /* the flows of `next` (all the others once every module is started: a producer outside) */
        for (int i = 0; i < sc->nevent_flows; i++) {
            const ContractEventFlow *fl = &sc->event_flows[i];
            if (connected[i] || (next >= 0 && strcmp(fl->src_module, sc->modules[next].module) != 0)) continue;
            connected[i] = 1;
            sup_claims_flow_use(&c->claims, fl, +1);
            if (c->io.connect_events) c->io.connect_events(c->io.ctx, fl);
        }
        if (next < 0) break;
        started[next] = 1;
        hold_acquire(c, sc->modules[next].module, c->v->priority_interaction);
    }
    free(started);
    free(connected);
}

static void deactivate_event_schema(SupCore *c, const ContractSchema *sc) {
    note_action(c, "undo: deactivate schema %s (event schema)", sc->name);
    for (int i = 0; i < sc->nevent_flows; i++) {
        const ContractEventFlow *fl = &sc->event_flows[i];
        int left = sup_claims_flow_use(&c->claims, fl, -1);
        if (left > 0)
            trace(c, "kept: event flow %s:%d -> %s:%d (used by %d other active schema(s))",
                  fl->src_module, fl->src_port, fl->dst_module, fl->dst_port, left);
        else if (c->io.disconnect_events)
            c->io.disconnect_events(c->io.ctx, fl);
    }
    for (int m = 0; m < sc->nmodules; m++) hold_release(c, sc->modules[m].module);
}

static int local_start(SupCore *c, int64_t t, int f, const void *params, size_t size,
                       const char *caller, uint32_t activation_id);
static void local_stop(SupCore *c, int f);
static int owned_stop(SupCore *c, int f, const char *caller, uint32_t activation_id);

static void do_action(SupCore *c, int f, const ContractAction *a, UndoRec *u) {
    memset(u, 0, sizeof *u);
    c->scratch_used = 0;
    EngineScope s = fn_scope(c, f);
    switch (a->kind) {
    case CONTRACT_ACT_SCHEMA: {
        const ContractSchema *sc = a->schema;
        unsigned char *p = build_block(c, f, sc->params, sc->nparams, sc->params_size,
                                       a->assigns, a->nassigns);
        if (!p) break;
        if (sc->kind == CONTRACT_SCHEMA_PERIODIC) {
            u->act_id = ++c->next_token;
            if (c->io.ord_activate)
                c->io.ord_activate(c->io.ctx, sc, p, sc->params_size, u->act_id);
        } else {
            activate_event_schema(c, f, sc, p);
        }
        free(p);
        u->done = 1;
        break;
    }
    case CONTRACT_ACT_PARAMETERIZE:
        for (int k = 0; k < a->nsettings; k++) {
            void *val = scratch_alloc(c, a->settings[k].type->size);
            if (!val || engine_build_setting(&s, &a->settings[k], val) != 0) {
                trace(c, "error: cannot build parameter %d of %s", a->settings[k].port, a->module);
                continue;
            }
            if (c->io.set_param)
                c->io.set_param(c->io.ctx, a->module, a->settings[k].port, a->settings[k].name, val,
                                a->settings[k].type->size, a->settings[k].type);
        }
        break;
    case CONTRACT_ACT_SUPERVISOR: {
        const ContractFunctionSignature *sig = a->callee;
        unsigned char *p = build_block(c, f, sig->params, sig->nparams, sig->params_size,
                                       a->assigns, a->nassigns);
        if (!p) break;
        int r;
        u->act_id = ++c->next_token;
        if (strcmp(sig->supervisor, c->v->name) == 0) {
            int g = function_index(c->v, sig->function);
            r = g < 0 ? -1
                      : local_start(c, c->now, g, p, sig->params_size, c->v->name, u->act_id);
        } else {
            r = c->io.start_function ? c->io.start_function(c->io.ctx, sig, p, sig->params_size,
                                                            u->act_id)
                                     : -1;
        }
        free(p);
        u->started_function = (r == 0);
        u->done = 1;
        break;
    }
    case CONTRACT_ACT_RESTTIME_MODULE:
    case CONTRACT_ACT_CRITICAL_MODULE: {
        int prio = a->kind == CONTRACT_ACT_RESTTIME_MODULE ? c->v->priority_resttime
                                                           : c->v->priority_critical;
        if (module_is_running(c, a->module)) {
            u->act_id = ++c->next_token;
            u->changed_priority =
                c->io.claim_priority &&
                c->io.claim_priority(c->io.ctx, a->module, u->act_id, prio) == 0;
        } else {
            hold_acquire(c, a->module, prio);
            u->started_module = 1;
        }
        u->done = 1;
        break;
    }
    case CONTRACT_ACT_COMPUTE: {
        void *args[64];
        int n = a->nargs < 64 ? a->nargs : 64;
        for (int i = 0; i < n; i++) {
            const ContractRef *r = &a->args[i];
            if (r->kind == CONTRACT_REF_LOCAL) {
                args[i] = (void *)(uintptr_t)engine_ref_ptr(&s, r);
            } else {
                const unsigned char *src = engine_ref_ptr(&s, r);
                const ContractType *at = a->fn->arg_types ? a->fn->arg_types[i] : r->type;
                args[i] = scratch_alloc(c, at->size);
                if (args[i] && src) engine_copy_value(args[i], at, src, r->type);
            }
            if (!args[i]) {
                trace(c, "error: cannot pass argument %d of %s", i, a->fn->name);
                return;
            }
        }
        a->fn->call(args);
        note_action(c, "compute %s", a->fn->name);
        break;
    }
    case CONTRACT_ACT_SUBSCRIBE: {
        int pi = in_port_index(c->v, a->in_port);
        if (pi < 0) break;
        Sub *sub = &c->subs[pi];
        if (sub->active) {
            trace(c, "refused: subscribe %s:%d to :%d, port :%d already subscribed to %s:%d",
                  a->module, a->src_port, a->in_port, a->in_port, sub->module, sub->src_port);
            break;
        }
        sub->active = 1;
        sub->module = a->module;
        sub->src_port = a->src_port;
        sub->mode = a->mode;
        sub->token = u->act_id = ++c->next_token;
        if (c->io.subscribe)
            c->io.subscribe(c->io.ctx, a->module, a->src_port, a->in_port, a->mode, u->act_id);
        u->done = 1;
        break;
    }
    case CONTRACT_ACT_NOTIFY: {
        int oi = out_port_index(c->v, a->out_port);
        if (oi < 0) break;
        for (int i = 0; i < a->nassigns; i++)
            if (engine_apply_assign(&s, &a->assigns[i], c->out_vals[oi], NULL) != 0)
                trace(c, "error: cannot read the value notified on :%d", a->out_port);
        if (c->io.notify)
            c->io.notify(c->io.ctx, a->out_port, c->v->out_ports[oi].type, c->out_vals[oi],
                         c->v->out_ports[oi].type->size);
        break;
    }
    }
}

static void undo_action(SupCore *c, const ContractAction *a, UndoRec *u) {
    if (!u->done) return;
    u->done = 0;
    switch (a->kind) {
    case CONTRACT_ACT_SCHEMA:
        if (a->schema->kind == CONTRACT_SCHEMA_PERIODIC) {
            if (c->io.ord_deactivate) c->io.ord_deactivate(c->io.ctx, a->schema, u->act_id);
        } else {
            deactivate_event_schema(c, a->schema);
        }
        break;
    case CONTRACT_ACT_SUPERVISOR:
        /* refused (answered or local): someone else's run of that function is not ours */
        if (!u->started_function) break;
        if (strcmp(a->callee->supervisor, c->v->name) == 0) {
            int g = function_index(c->v, a->callee->function);
            if (g >= 0) owned_stop(c, g, c->v->name, u->act_id);
        } else if (c->io.stop_function) {
            c->io.stop_function(c->io.ctx, a->callee->supervisor, a->callee->function, u->act_id);
        }
        break;
    case CONTRACT_ACT_RESTTIME_MODULE:
    case CONTRACT_ACT_CRITICAL_MODULE:
        if (u->started_module) {
            hold_release(c, a->module);
        } else if (u->changed_priority && c->io.release_priority) {
            c->io.release_priority(c->io.ctx, a->module, u->act_id);
        }
        break;
    case CONTRACT_ACT_SUBSCRIBE: {
        int pi = in_port_index(c->v, a->in_port);
        const Sub *sub = pi >= 0 ? &c->subs[pi] : NULL;
        if (sub && sub->active && sub->token == u->act_id) {
            c->subs[pi].active = 0;
        } else if (sub && sub->active && sub->src_port == a->src_port &&
                   strcmp(sub->module, a->module) == 0) {
            /* ours was a spent one-shot, and another rule subscribed the same producer port to
               this in port since: that is one subscription at the producer, now the other's */
            trace(c, "kept: subscription %s:%d to :%d (made again since by another rule)",
                  a->module, a->src_port, a->in_port);
            break;
        }
        if (c->io.unsubscribe)
            c->io.unsubscribe(c->io.ctx, a->module, a->src_port, a->in_port, u->act_id);
        break;
    }
    default: /* parameterize, compute, notify: no undo */
        break;
    }
}

/* ---- rules ---------------------------------------------------------------------------- */

static void run_extractions(SupCore *c, int f, const ContractClause *cl, int first_slot) {
    FnState *fs = &c->fns[f];
    for (int e = 0; e < cl->nevents; e++) {
        const ContractEvent *ev = &cl->events[e];
        if (ev->nextractions == 0) continue;
        const Occ *o = &fs->occ[first_slot + e];
        EngineScope s = fn_scope(c, f);
        if (ev->kind == CONTRACT_EV_MODULE && o->data) {
            if (strcmp(ev->module, "ORD") == 0) s.ord_schema = (const char *)o->data;
            else {
                s.occ_port = ev->in_port;
                s.occ_data = o->data;
            }
        }
        for (int i = 0; i < ev->nextractions; i++)
            if (engine_apply_assign(&s, &ev->extractions[i], fs->locals, s.fn->locals) != 0)
                trace(c, "error: extraction %d of an event has no value", i);
    }
}

/* The cause of a rule change, for io.rule (grammar in sup_core.h): the event being processed,
   or `stop` when there is none (the function stopped). */
static void format_cause(const SupCore *c, int f, char *buf, size_t len) {
    const CurEv *cur = c->cur;
    const ContractFunction *fn = &c->v->functions[f];
    if (!cur) {
        snprintf(buf, len, "stop");
        return;
    }
    const char *label = cur->rule >= 0 && cur->rule < fn->nrules ? fn->rules[cur->rule].label : "?";
    switch (cur->kind) {
    case CONTRACT_EV_MODULE: {
        char value[ACTION_VALUE_MAX]; /* with the module and port, fits the 400-byte CSV detail */
        const ContractType *type = NULL;
        int pi = cur->ord_schema ? -1 : in_port_index(c->v, cur->in_port);
        if (cur->ord_schema) type = &contract_type_string;
        else if (pi >= 0) type = c->v->in_ports[pi].type;
        engine_format_value(value, sizeof value, cur->data, type);
        snprintf(buf, len, "%s:%d value=%s", cur->module, cur->port, value);
        return;
    }
    case CONTRACT_EV_STARTED: snprintf(buf, len, "started(%s)", label); return;
    case CONTRACT_EV_ENDOF: snprintf(buf, len, "endof(%s)", label); return;
    case CONTRACT_EV_DURATION:
        snprintf(buf, len, "duration(%s)=%lldns", label, (long long)cur->time_ns);
        return;
    case CONTRACT_EV_ELAPSED: snprintf(buf, len, "elapsed=%lldns", (long long)cur->time_ns); return;
    }
    snprintf(buf, len, "?");
}

static void report_rule(SupCore *c, int f, int r, int active) {
    c->rule_changes++;
    if (!c->io.rule) return;
    char cause[300];
    format_cause(c, f, cause, sizeof cause);
    const ContractFunction *fn = &c->v->functions[f];
    c->io.rule(c->io.ctx, c->now, fn->name, fn->rules[r].label, active, cause);
}

static void activate_rule(SupCore *c, int f, int r, const ContractClause *cl, int first_slot) {
    FnState *fs = &c->fns[f];
    const ContractFunction *fn = &c->v->functions[f];
    const ContractRule *rule = &fn->rules[r];
    RuleState *rs = &fs->rules[r];
    if (cl) run_extractions(c, f, cl, first_slot);
    rs->active = 1;
    rs->since = c->now;
    rs->gen++;
    trace(c, "rule %s.%s active", fn->name, rule->label);
    report_rule(c, f, r, 1);
    uint32_t gen = fs->gen;
    for (int i = 0; i < rule->nactions; i++) {
        do_action(c, f, &rule->actions[i], &rs->undo[i]);
        if (!fs->running || fs->gen != gen) return; /* an action stopped this function */
    }
    queue_push(c, f, CONTRACT_EV_STARTED, r);
    /* duration(L)=t timers, one per distinct t */
    for (int i = 0; i < fs->nslots; i++) {
        const ContractEvent *ev = fs->slots[i].ev;
        if (ev->kind != CONTRACT_EV_DURATION || ev->rule != r) continue;
        int dup = 0;
        for (int j = 0; j < i; j++)
            if (fs->slots[j].ev->kind == CONTRACT_EV_DURATION && fs->slots[j].ev->rule == r &&
                fs->slots[j].ev->time_ns == ev->time_ns)
                dup = 1;
        if (!dup) add_timer(c, c->now + ev->time_ns, f, CONTRACT_EV_DURATION, r, ev->time_ns);
    }
}

static void deactivate_rule(SupCore *c, int f, int r, const ContractClause *cl, int first_slot,
                            int emit_endof) {
    FnState *fs = &c->fns[f];
    const ContractFunction *fn = &c->v->functions[f];
    const ContractRule *rule = &fn->rules[r];
    RuleState *rs = &fs->rules[r];
    if (cl) run_extractions(c, f, cl, first_slot);
    rs->active = 0;
    trace(c, "rule %s.%s inactive", fn->name, rule->label);
    report_rule(c, f, r, 0);
    for (int i = 0; i < rule->nactions; i++) undo_action(c, &rule->actions[i], &rs->undo[i]);
    if (emit_endof && fs->running) queue_push(c, f, CONTRACT_EV_ENDOF, r);
}

static int slot_present(const SupCore *c, const FnState *fs, int i) {
    const Occ *o = &fs->occ[i];
    if (!o->valid) return 0;
    if (o->seq == c->seq) return 1;
    const ContractEvent *ev = fs->slots[i].ev;
    switch (ev->persist) {
    case CONTRACT_PERSIST_INFINITE: return 1;
    case CONTRACT_PERSIST_TIME: return o->t <= c->now && c->now <= o->t + ev->persist_ns;
    default: return 0;
    }
}

/* first clause of `cond` (slots from first_slot) triggered by the current event and true */
static int true_clause(const SupCore *c, const FnState *fs, const ContractCondition *cond,
                       int first_slot, int *clause_first) {
    int s = first_slot;
    for (int k = 0; k < cond->nclauses; k++) {
        const ContractClause *cl = &cond->clauses[k];
        int triggered = 0, all = 1;
        for (int e = 0; e < cl->nevents; e++) {
            if (fs->hit[s + e]) triggered = 1;
            if (!slot_present(c, fs, s + e)) all = 0;
        }
        if (triggered && all) {
            *clause_first = s;
            return k;
        }
        s += cl->nevents;
    }
    return -1;
}

/* ---- events --------------------------------------------------------------------------- */

static int eval_test(SupCore *c, const EngineScope *s, const ContractTest *t) {
    if (t->op == CONTRACT_TEST_CALL) {
        void *args[64];
        size_t mark = c->scratch_used;
        int n = t->nargs < 64 ? t->nargs : 64;
        for (int i = 0; i < n; i++) {
            const ContractRef *r = &t->args[i];
            const unsigned char *src = engine_ref_ptr(s, r);
            const ContractType *at = t->fn->arg_types ? t->fn->arg_types[i] : r->type;
            args[i] = scratch_alloc(c, at->size);
            if (!src || !args[i]) {
                c->scratch_used = mark;
                return 0;
            }
            engine_copy_value(args[i], at, src, r->type);
        }
        int res = t->fn->call(args) ? 1 : 0;
        c->scratch_used = mark;
        return res;
    }
    const unsigned char *a = engine_ref_ptr(s, &t->lhs), *b = engine_ref_ptr(s, &t->rhs);
    if (!a || !b) return 0;
    return engine_compare(t->op, a, t->lhs.type, b, t->rhs.type);
}

static int tests_pass(SupCore *c, int f, const ContractEvent *ev, const CurEv *cur) {
    if (ev->ntest_clauses == 0) return 1;
    EngineScope s = fn_scope(c, f);
    s.occ_port = cur->in_port;
    s.occ_data = cur->data;
    s.ord_schema = cur->ord_schema;
    for (int k = 0; k < ev->ntest_clauses; k++) {
        const ContractTestClause *tc = &ev->test_clauses[k];
        int all = 1;
        for (int i = 0; i < tc->ntests && all; i++)
            if (!eval_test(c, &s, &tc->tests[i])) all = 0;
        if (all) return 1;
    }
    return 0;
}

static int event_matches(const ContractEvent *ev, const CurEv *cur) {
    if (ev->kind != cur->kind) return 0;
    switch (ev->kind) {
    case CONTRACT_EV_MODULE:
        if (ev->port != cur->port || strcmp(ev->module, cur->module) != 0) return 0;
        return ev->in_port < 0 || cur->in_port < 0 || ev->in_port == cur->in_port;
    case CONTRACT_EV_STARTED:
    case CONTRACT_EV_ENDOF: return ev->rule == cur->rule;
    case CONTRACT_EV_DURATION: return ev->rule == cur->rule && ev->time_ns == cur->time_ns;
    case CONTRACT_EV_ELAPSED: return ev->time_ns == cur->time_ns;
    }
    return 0;
}

/* one event against one function: record occurrences, then postconditions of the rules
   active before it, then preconditions of the rules inactive before it */
static void process_for_function(SupCore *c, int f, const CurEv *cur) {
    FnState *fs = &c->fns[f];
    const ContractFunction *fn = &c->v->functions[f];
    int any = 0;
    for (int i = 0; i < fs->nslots; i++) {
        const ContractEvent *ev = fs->slots[i].ev;
        fs->hit[i] = 0;
        if (!event_matches(ev, cur) || !tests_pass(c, f, ev, cur)) continue;
        Occ *o = &fs->occ[i];
        o->valid = 1;
        o->t = c->now;
        o->seq = c->seq;
        if (o->data && cur->data) {
            size_t n = cur->size < fs->slots[i].data_size ? cur->size : fs->slots[i].data_size;
            memcpy(o->data, cur->data, n);
            if (n < fs->slots[i].data_size) memset(o->data + n, 0, fs->slots[i].data_size - n);
        }
        fs->hit[i] = 1;
        any = 1;
    }
    if (!any) return;
    uint32_t gen = fs->gen;
    char stack_before[64];
    char *before = fn->nrules <= 64 ? stack_before : malloc((size_t)fn->nrules);
    if (!before) return;
    for (int r = 0; r < fn->nrules; r++) before[r] = (char)fs->rules[r].active;
    for (int r = 0; r < fn->nrules && fs->running && fs->gen == gen; r++) {
        if (!before[r] || !fs->rules[r].active) continue;
        int first;
        int k = true_clause(c, fs, &fn->rules[r].post, fs->rules[r].post_first, &first);
        if (k >= 0) deactivate_rule(c, f, r, &fn->rules[r].post.clauses[k], first, 1);
    }
    for (int r = 0; r < fn->nrules && fs->running && fs->gen == gen; r++) {
        if (before[r] || fs->rules[r].active) continue;
        int first;
        int k = true_clause(c, fs, &fn->rules[r].pre, fs->rules[r].pre_first, &first);
        if (k >= 0) activate_rule(c, f, r, &fn->rules[r].pre.clauses[k], first);
    }
    if (before != stack_before) free(before);
}

static void process(SupCore *c, int only_fn, const CurEv *cur) {
    c->seq++;
    c->processed++;
    const CurEv *outer = c->cur;
    c->cur = cur;
    for (int f = 0; f < c->v->nfunctions; f++) {
        if (only_fn >= 0 && f != only_fn) continue;
        if (c->fns[f].running && c->fns[f].start_seq != c->seq) process_for_function(c, f, cur);
    }
    c->cur = outer;
}

static void drain_queue(SupCore *c) {
    while (c->qlen > 0) {
        QEv e = c->queue[c->qhead];
        c->qhead = (c->qhead + 1) % c->qcap;
        c->qlen--;
        if (!c->fns[e.fn].running || c->fns[e.fn].gen != e.fn_gen) continue;
        CurEv cur;
        memset(&cur, 0, sizeof cur);
        cur.kind = e.kind;
        cur.rule = e.rule;
        cur.in_port = -1;
        process(c, e.fn, &cur);
    }
}

static void set_now(SupCore *c, int64_t t) {
    if (t > c->now) c->now = t;
}

void sup_core_advance(SupCore *c, int64_t t) {
    for (;;) {
        int best = -1;
        for (int i = 0; i < c->ntimers; i++) {
            if (!timer_valid(c, &c->timers[i])) {
                c->timers[i--] = c->timers[--c->ntimers];
                continue;
            }
            if (c->timers[i].deadline > t) continue;
            if (best < 0 || c->timers[i].deadline < c->timers[best].deadline ||
                (c->timers[i].deadline == c->timers[best].deadline &&
                 c->timers[i].order < c->timers[best].order))
                best = i;
        }
        if (best < 0) break;
        Timer tm = c->timers[best];
        c->timers[best] = c->timers[--c->ntimers];
        set_now(c, tm.deadline);
        CurEv cur;
        memset(&cur, 0, sizeof cur);
        cur.kind = tm.kind;
        cur.rule = tm.rule;
        cur.time_ns = tm.time_ns;
        cur.in_port = -1;
        process(c, tm.fn, &cur);
        drain_queue(c);
    }
    set_now(c, t);
}

int sup_core_next_deadline(const SupCore *c, int64_t *deadline) {
    int found = 0;
    for (int i = 0; i < c->ntimers; i++) {
        if (!timer_valid(c, &c->timers[i])) continue;
        if (!found || c->timers[i].deadline < *deadline) *deadline = c->timers[i].deadline;
        found = 1;
    }
    return found;
}

int sup_core_module_event(SupCore *c, int64_t t, const char *module, int src_port, int in_port,
                          const void *data, size_t size) {
    sup_core_advance(c, t);
    const uint64_t changes_before = c->rule_changes;
    int pi = -1;
    if (in_port >= 0) {
        pi = in_port_index(c->v, in_port);
    } else {
        for (int i = 0; i < c->v->nin_ports; i++)
            if (c->subs[i].active && c->subs[i].src_port == src_port &&
                strcmp(c->subs[i].module, module) == 0) {
                pi = i;
                break;
            }
    }
    if (pi < 0 || !c->subs[pi].active || c->subs[pi].src_port != src_port ||
        strcmp(c->subs[pi].module, module) != 0) {
        trace(c, "ignored: event %s:%d (no active subscription)", module, src_port);
        return 0;
    }
    if (c->subs[pi].mode == CONTRACT_ONESHOT) c->subs[pi].active = 0;
    const ContractType *pt = c->v->in_ports[pi].type;
    size_t n = size < pt->size ? size : pt->size;
    if (data) memcpy(c->in_vals[pi], data, n);
    CurEv cur;
    memset(&cur, 0, sizeof cur);
    cur.kind = CONTRACT_EV_MODULE;
    cur.module = module;
    cur.port = src_port;
    cur.in_port = c->v->in_ports[pi].port;
    cur.data = c->in_vals[pi];
    cur.size = pt->size;
    process(c, -1, &cur);
    drain_queue(c);
    return (int)(c->rule_changes - changes_before);
}

void sup_core_format_event_value(const SupCore *c, int in_port, const void *data, size_t size, char *buf,
                                 size_t len) {
    int pi = in_port_index(c->v, in_port);
    const ContractType *type = pi >= 0 ? c->v->in_ports[pi].type : NULL;
    if (type && data && size >= type->size) engine_format_value(buf, len, data, type);
    else if (len) snprintf(buf, len, "?");
}

void sup_core_ord_event(SupCore *c, int64_t t, int port, const char *schema) {
    sup_core_advance(c, t);
    char name[CONTRACT_STRING_SIZE];
    engine_set_string(name, schema ? schema : "");
    CurEv cur;
    memset(&cur, 0, sizeof cur);
    cur.kind = CONTRACT_EV_MODULE;
    cur.module = "ORD";
    cur.port = port;
    cur.in_port = -1;
    cur.data = (const unsigned char *)name;
    cur.size = sizeof name;
    cur.ord_schema = name;
    process(c, -1, &cur);
    drain_queue(c);
}

/* ---- functions ------------------------------------------------------------------------ */

static int local_start(SupCore *c, int64_t t, int f, const void *params, size_t size,
                       const char *caller, uint32_t activation_id) {
    FnState *fs = &c->fns[f];
    const ContractFunction *fn = &c->v->functions[f];
    if (fs->running) {
        trace(c, "refused: function %s already running", fn->name);
        return -1;
    }
    (void)t;
    snprintf(fs->owner, sizeof fs->owner, "%s", caller ? caller : "");
    fs->owner_id = activation_id;
    fs->gen++;
    engine_init_block(fs->params, fn->params, fn->nparams);
    if (params) {
        if (size != fn->params_size)
            trace(c, "warning: %s started with %zu parameter bytes, expected %zu", fn->name, size,
                  fn->params_size);
        memcpy(fs->params, params, size < fn->params_size ? size : fn->params_size);
    }
    engine_init_block(fs->locals, fn->locals, fn->nlocals);
    fs->running = 1;
    fs->start_seq = c->seq;
    EngineScope s = fn_scope(c, f);
    for (int i = 0; i < fn->nlocal_inits; i++)
        engine_apply_assign(&s, &fn->local_inits[i], fs->locals, fn->locals);
    for (int r = 0; r < fn->nrules; r++) fs->rules[r].active = 0;
    for (int i = 0; i < fs->nslots; i++) fs->occ[i].valid = 0;
    char args[ACTION_VALUE_MAX];
    engine_format_params(args, sizeof args, fn->params, fn->nparams, fs->params);
    trace(c, "function %s%s started", fn->name, args);
    /* its clock (its elapsed timers, its duration) starts at the time of that line */
    if (c->io.last_trace_time) set_now(c, c->io.last_trace_time(c->io.ctx));
    fs->started_at = c->now;
    for (int i = 0; i < fs->nslots; i++) {
        const ContractEvent *ev = fs->slots[i].ev;
        if (ev->kind != CONTRACT_EV_ELAPSED) continue;
        int dup = 0;
        for (int j = 0; j < i; j++)
            if (fs->slots[j].ev->kind == CONTRACT_EV_ELAPSED &&
                fs->slots[j].ev->time_ns == ev->time_ns)
                dup = 1;
        if (!dup) add_timer(c, c->now + ev->time_ns, f, CONTRACT_EV_ELAPSED, -1, ev->time_ns);
    }
    return 0;
}

static void local_stop(SupCore *c, int f) {
    FnState *fs = &c->fns[f];
    const ContractFunction *fn = &c->v->functions[f];
    if (!fs->running) return;
    uint32_t gen = fs->gen;
    const CurEv *outer = c->cur;
    c->cur = NULL; /* the rules end because the function stops, whatever event led to it */
    for (int r = 0; r < fn->nrules; r++)
        if (fs->rules[r].active) {
            deactivate_rule(c, f, r, NULL, 0, 0);
            if (fs->gen != gen) {
                c->cur = outer;
                return;
            }
        }
    c->cur = outer;
    fs->running = 0;
    fs->gen++;
    trace(c, "function %s stopped", fn->name);
}

/* the undo of one activation stops the function only if it runs that activation: a refused
   activation's undo must not end the run another caller started (docs/engines.md, "Undo and
   refusals": a function ends when *its* caller undoes its activation) */
static int owned_stop(SupCore *c, int f, const char *caller, uint32_t activation_id) {
    FnState *fs = &c->fns[f];
    const char *name = c->v->functions[f].name;
    if (!fs->running) return -1;
    if (activation_id != 0 &&
        (fs->owner_id != activation_id || strcmp(fs->owner, caller ? caller : "") != 0)) {
        if (fs->owner[0])
            trace(c, "ignored: stop of %s for activation #%u of %s (it runs activation #%u of %s)",
                  name, activation_id, caller ? caller : "?", fs->owner_id, fs->owner);
        else
            trace(c, "ignored: stop of %s for activation #%u of %s (started by a control tool)",
                  name, activation_id, caller ? caller : "?");
        return -1;
    }
    local_stop(c, f);
    return 0;
}

int sup_core_start_function(SupCore *c, int64_t t, const char *name, const void *params,
                            size_t size) {
    sup_core_advance(c, t);
    int f = function_index(c->v, name);
    if (f < 0) {
        trace(c, "refused: no function %s", name);
        return -1;
    }
    return local_start(c, t, f, params, size, NULL, 0);
}

int sup_core_start_function_for(SupCore *c, int64_t t, const char *name, const void *params,
                                size_t size, const char *caller, uint32_t activation_id) {
    sup_core_advance(c, t);
    int f = function_index(c->v, name);
    if (f < 0) {
        trace(c, "refused: no function %s", name);
        return -1;
    }
    int rc = local_start(c, t, f, params, size, caller, activation_id);
    drain_queue(c);
    return rc == 0 ? 0 : -2;
}

int sup_core_start_function_text(SupCore *c, int64_t t, const char *name, const char *args,
                                 char *err, size_t errlen) {
    int f = function_index(c->v, name);
    if (f < 0) {
        snprintf(err, errlen, "%s has no supervision function '%s'", c->v->name, name);
        return -1;
    }
    const ContractFunction *fn = &c->v->functions[f];
    unsigned char *block = calloc(1, fn->params_size ? fn->params_size : 1);
    char *copy = strdup(args ? args : "");
    if (!block || !copy) {
        free(block);
        free(copy);
        snprintf(err, errlen, "out of memory");
        return -1;
    }
    engine_init_block(block, fn->params, fn->nparams);
    char *p = copy;
    int rc = 0;
    while (*p) {
        while (*p == ' ' || *p == ',' || *p == '\t') p++;
        if (!*p) break;
        char *eq = strchr(p, '=');
        if (!eq) {
            snprintf(err, errlen, "expected name=value in '%s'", p);
            rc = -1;
            break;
        }
        *eq = '\0';
        char *pname = p;
        for (char *e = eq - 1; e >= pname && (*e == ' ' || *e == '\t'); e--) *e = '\0';
        int k = -1;
        for (int i = 0; i < fn->nparams; i++)
            if (strcmp(fn->params[i].name, pname) == 0) k = i;
        if (k < 0) {
            snprintf(err, errlen, "%s.%s has no parameter '%s'", c->v->name, name, pname);
            rc = -1;
            break;
        }
        const ContractType *ty = fn->params[k].type;
        int used = contract_value_get(ty, block + fn->params[k].offset, eq + 1);
        if (used < 0) {
            snprintf(err, errlen, "cannot read a %s for parameter '%s' from '%s'", ty->name,
                     pname, eq + 1);
            rc = -1;
            break;
        }
        p = eq + 1 + used;
        while (*p == '}' || *p == '"') p++; /* tolerate get_ functions stopping early */
    }
    if (rc == 0) {
        rc = sup_core_start_function(c, t, name, block, fn->params_size);
        if (rc != 0) { /* refused and traced by local_start: `refused: function F already running` */
            snprintf(err, errlen, "%s.%s is already running", c->v->name, name);
            rc = -2;
        }
    }
    free(block);
    free(copy);
    return rc;
}

int sup_core_stop_function(SupCore *c, int64_t t, const char *name) {
    sup_core_advance(c, t);
    int f = function_index(c->v, name);
    if (f < 0 || !c->fns[f].running) return -1;
    local_stop(c, f);
    drain_queue(c);
    return 0;
}

int sup_core_stop_function_for(SupCore *c, int64_t t, const char *name, const char *caller,
                               uint32_t activation_id) {
    sup_core_advance(c, t);
    int f = function_index(c->v, name);
    if (f < 0) return -1;
    int rc = owned_stop(c, f, caller, activation_id);
    drain_queue(c);
    return rc;
}

void sup_core_function_answer(SupCore *c, int64_t t, const char *supervisor,
                              uint32_t activation_id, int accepted) {
    sup_core_advance(c, t);
    if (accepted || activation_id == 0) return;
    for (int f = 0; f < c->v->nfunctions; f++) {
        const ContractFunction *fn = &c->v->functions[f];
        for (int r = 0; r < fn->nrules; r++)
            for (int i = 0; i < fn->rules[r].nactions; i++) {
                const ContractAction *a = &fn->rules[r].actions[i];
                UndoRec *u = &c->fns[f].rules[r].undo[i];
                if (a->kind != CONTRACT_ACT_SUPERVISOR || u->act_id != activation_id ||
                    !u->done || strcmp(a->callee->supervisor, supervisor) != 0)
                    continue;
                u->started_function = 0;
                trace(c, "activation #%u of %s.%s refused: its undo stops nothing", activation_id,
                      supervisor, a->callee->function);
                return;
            }
    }
}

int sup_core_function_running(const SupCore *c, const char *name) {
    int f = function_index(c->v, name);
    return f >= 0 && c->fns[f].running;
}

/* ---- introspection -------------------------------------------------------------------- */

int sup_core_rule_active(const SupCore *c, const char *function, const char *label) {
    int f = function_index(c->v, function);
    if (f < 0) return -1;
    const ContractFunction *fn = &c->v->functions[f];
    for (int r = 0; r < fn->nrules; r++)
        if (strcmp(fn->rules[r].label, label) == 0) return c->fns[f].rules[r].active;
    return -1;
}

const void *sup_core_local(const SupCore *c, const char *function, const char *local) {
    int f = function_index(c->v, function);
    if (f < 0) return NULL;
    const ContractFunction *fn = &c->v->functions[f];
    for (int i = 0; i < fn->nlocals; i++)
        if (strcmp(fn->locals[i].name, local) == 0) return c->fns[f].locals + fn->locals[i].offset;
    return NULL;
}

const void *sup_core_in_port_value(const SupCore *c, int port) {
    int i = in_port_index(c->v, port);
    return i < 0 ? NULL : c->in_vals[i];
}

uint64_t sup_core_events_processed(const SupCore *c) { return c->processed; }

/* ---- creation ------------------------------------------------------------------------- */

static int count_slots(const ContractCondition *cond) {
    int n = 0;
    for (int k = 0; k < cond->nclauses; k++) n += cond->clauses[k].nevents;
    return n;
}

static size_t slot_data_size(const ContractSupervisorVocabulary *v, const ContractEvent *ev) {
    if (ev->kind != CONTRACT_EV_MODULE) return 0;
    if (strcmp(ev->module, "ORD") == 0) return CONTRACT_STRING_SIZE;
    int i = in_port_index(v, ev->in_port);
    return i < 0 ? 0 : v->in_ports[i].type->size;
}

static void add_slots(FnState *fs, const ContractSupervisorVocabulary *v,
                      const ContractCondition *cond, int *n) {
    for (int k = 0; k < cond->nclauses; k++)
        for (int e = 0; e < cond->clauses[k].nevents; e++) {
            fs->slots[*n].ev = &cond->clauses[k].events[e];
            fs->slots[*n].data_size = slot_data_size(v, fs->slots[*n].ev);
            (*n)++;
        }
}

SupCore *sup_core_create(const ContractSupervisorVocabulary *v, const SupIo *io, char *err,
                         size_t errlen) {
    if (contract_check_supervisor_vocabulary(v, err, errlen) != 0) return NULL;
    SupCore *c = calloc(1, sizeof *c);
    if (!c) goto oom;
    c->v = v;
    if (io) c->io = *io;
    c->now = INT64_MIN;
    c->scratch = malloc(SCRATCH_SIZE);
    c->fns = calloc((size_t)v->nfunctions + 1, sizeof *c->fns);
    c->in_vals = calloc((size_t)v->nin_ports + 1, sizeof *c->in_vals);
    c->out_vals = calloc((size_t)v->nout_ports + 1, sizeof *c->out_vals);
    c->subs = calloc((size_t)v->nin_ports + 1, sizeof *c->subs);
    if (!c->scratch || !c->fns || !c->in_vals || !c->out_vals || !c->subs) goto oom;
    for (int i = 0; i < v->nin_ports; i++) {
        if (!(c->in_vals[i] = malloc(v->in_ports[i].type->size))) goto oom;
        engine_default_value(c->in_vals[i], v->in_ports[i].type, v->in_ports[i].initial_value);
    }
    for (int i = 0; i < v->nout_ports; i++) {
        if (!(c->out_vals[i] = malloc(v->out_ports[i].type->size))) goto oom;
        engine_default_value(c->out_vals[i], v->out_ports[i].type, v->out_ports[i].initial_value);
    }
    for (int f = 0; f < v->nfunctions; f++) {
        const ContractFunction *fn = &v->functions[f];
        FnState *fs = &c->fns[f];
        fs->params = calloc(1, fn->params_size + 1);
        fs->locals = calloc(1, fn->locals_size + 1);
        fs->rules = calloc((size_t)fn->nrules + 1, sizeof *fs->rules);
        if (!fs->params || !fs->locals || !fs->rules) goto oom;
        int n = 0;
        for (int r = 0; r < fn->nrules; r++)
            n += count_slots(&fn->rules[r].pre) + count_slots(&fn->rules[r].post);
        fs->slots = calloc((size_t)n + 1, sizeof *fs->slots);
        fs->occ = calloc((size_t)n + 1, sizeof *fs->occ);
        fs->hit = calloc((size_t)n + 1, 1);
        fs->nslots = n;
        if (!fs->slots || !fs->occ || !fs->hit) goto oom;
        int k = 0;
        for (int r = 0; r < fn->nrules; r++) {
            fs->rules[r].undo = calloc((size_t)fn->rules[r].nactions + 1, sizeof(UndoRec));
            if (!fs->rules[r].undo) goto oom;
            fs->rules[r].pre_first = k;
            add_slots(fs, v, &fn->rules[r].pre, &k);
            fs->rules[r].post_first = k;
            add_slots(fs, v, &fn->rules[r].post, &k);
        }
        for (int i = 0; i < n; i++)
            if (fs->slots[i].data_size && !(fs->occ[i].data = calloc(1, fs->slots[i].data_size)))
                goto oom;
    }
    return c;
oom:
    snprintf(err, errlen, "out of memory creating supervisor %s", v->name);
    sup_core_destroy(c);
    return NULL;
}

void sup_core_destroy(SupCore *c) {
    if (!c) return;
    const ContractSupervisorVocabulary *v = c->v;
    if (c->fns)
        for (int f = 0; f < v->nfunctions; f++) {
            FnState *fs = &c->fns[f];
            free(fs->params);
            free(fs->locals);
            if (fs->rules)
                for (int r = 0; r < v->functions[f].nrules; r++) free(fs->rules[r].undo);
            free(fs->rules);
            if (fs->occ)
                for (int i = 0; i < fs->nslots; i++) free(fs->occ[i].data);
            free(fs->occ);
            free(fs->slots);
            free(fs->hit);
        }
    free(c->fns);
    if (c->in_vals)
        for (int i = 0; i < v->nin_ports; i++) free(c->in_vals[i]);
    if (c->out_vals)
        for (int i = 0; i < v->nout_ports; i++) free(c->out_vals[i]);
    free(c->in_vals);
    free(c->out_vals);
    free(c->subs);
    free(c->holds);
    sup_claims_free(&c->claims);
    free(c->timers);
    free(c->queue);
    free(c->scratch);
    free(c);
}
