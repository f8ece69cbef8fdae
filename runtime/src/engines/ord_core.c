/* ord_core.c — see ord_core.h. Semantics: docs/semantics.md "Scheduler: ...", decisions in docs/engines.md. */
#define _POSIX_C_SOURCE 200809L
#include "ord_core.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "engine_trace.h"
#include "engine_values.h"

typedef struct SchemaState {
    const ContractSchema *s;
    int active;
    uint32_t act_id;
    char requester[64];
    unsigned char *params;
    int64_t next_tick;
    int64_t act_t;         /* tick 0 of this activation: cycle k ticks at act_t + k * period */
    /* the current cycle */
    int running;
    int64_t cycle_tick;
    int reported;          /* ORD:0 already emitted for this cycle */
    int64_t released_late; /* real time: how late after its tick ORD released this cycle's heads,
                              when at or past its CRITICAL_DELAY (its modules had no time); 0 otherwise */
    int pending;           /* modules released or waiting, not finished */
    int *npreds;           /* per module: number of predecessors (static) */
    int *waiting;          /* per module: predecessors not yet finished this cycle */
    char *released, *finished;
    uint32_t *cycle_rel;   /* per module: id of its release in the current cycle (0: none)   */
    uint32_t *outstanding; /* per module: id of a release not acked yet, whatever the cycle or
                              activation (kept across deactivation: the module may still run it) */
    int64_t *outstanding_t; /* per module: when that release was sent */
    int held;              /* cycle started, releases wait until no module of it is outstanding */
    long cycle_overruns;   /* ticks skipped by the current cycle (the first traced, the count at its end) */
    long cycle_missed;     /* ticks missed (ORD late) while the current cycle ran (idem)     */
    char *stuck;           /* per module: its outstanding release was reported stuck */
    uint32_t *looked;      /* per module: the release seen half way to its stuck report (0: none) */
    int64_t *looked_t;     /* per module: when (the core's time) */
    OrdModuleActivity *look; /* per module: what module_activity said then */
    OrdSchemaStats stats;
} SchemaState;

struct OrdCore {
    const ContractOrdVocabulary *v;
    OrdIo io;
    int64_t now;
    int skip_late;         /* real time: ticks overtaken by a later due tick are missed */
    uint32_t next_release_id;
    SchemaState *st;
};

ENGINE_DEFINE_TRACE(OrdCore)

/* one typed trace fact of ss's current cycle (docs/runtime-api.md "Trace records") */
static void fact(OrdCore *c, const SchemaState *ss, OrdFactKind kind, int m, uint32_t id) {
    if (!c->io.fact) return;
    OrdFact f = {kind, ss->s->name, m >= 0 ? ss->s->modules[m].module : NULL,
                 (long)((ss->cycle_tick - ss->act_t) / ss->s->period_ns), ss->cycle_tick, id,
                 c->now - ss->cycle_tick, ss->s->critical_delay_ns};
    c->io.fact(c->io.ctx, c->now, &f);
}

const char *ord_fact_record(const OrdFact *f, int64_t t, char *detail, size_t n) {
    switch (f->kind) {
    case ORD_FACT_RELEASE:
        snprintf(detail, n, "schema=%s cycle=%ld tick_ns=%lld release_ns=%lld release=%u", f->schema,
                 f->cycle, (long long)f->tick, (long long)t, f->release_id);
        return "ord_release";
    case ORD_FACT_FINISHED:
        snprintf(detail, n, "schema=%s cycle=%ld release=%u response_ns=%lld", f->schema, f->cycle,
                 f->release_id, (long long)f->response_ns);
        return "ord_finished";
    case ORD_FACT_COMPLETE:
        snprintf(detail, n, "schema=%s cycle=%ld tick_ns=%lld response_ns=%lld", f->schema, f->cycle,
                 (long long)f->tick, (long long)f->response_ns);
        return "ord_complete";
    case ORD_FACT_DEADLINE_MISS:
        break;
    }
    /* the deadline it missed, so that a reader tells a cycle ORD released past it from a module late */
    snprintf(detail, n, "schema=%s cycle=%ld tick_ns=%lld critical_delay_ns=%lld", f->schema, f->cycle,
             (long long)f->tick, (long long)f->critical_delay_ns);
    return "ord_deadline_miss";
}

static int schema_index(const OrdCore *c, const char *name) {
    for (int i = 0; i < c->v->nschemas; i++)
        if (strcmp(c->v->schemas[i]->name, name) == 0) return i;
    return -1;
}

static int shares_module(const ContractSchema *a, const ContractSchema *b) {
    for (int i = 0; i < a->nmodules; i++)
        for (int j = 0; j < b->nmodules; j++)
            if (strcmp(a->modules[i].module, b->modules[j].module) == 0) return 1;
    return 0;
}

/* " (activation #N from SUP)": which activation an activate/deactivate line serves, as the
   requester's own `activate schema S (activation #N, to ORD)` line numbers it; "" for none (0) */
static const char *activation_text(char *buf, size_t n, uint32_t id, const char *requester) {
    if (id == 0) snprintf(buf, n, "%s", "");
    else if (requester && *requester) snprintf(buf, n, " (activation #%u from %s)", id, requester);
    else snprintf(buf, n, " (activation #%u)", id);
    return buf;
}

static void release(OrdCore *c, SchemaState *ss, int m) {
    uint32_t id = ++c->next_release_id;
    if (id == 0) id = ++c->next_release_id; /* 0 never names a release */
    ss->released[m] = 1;
    ss->cycle_rel[m] = id;
    ss->outstanding[m] = id;
    ss->outstanding_t[m] = c->now;
    ss->stuck[m] = 0;
    trace(c, "release %s (%s)", ss->s->modules[m].module, ss->s->name);
    fact(c, ss, ORD_FACT_RELEASE, m, id);
    if (c->io.release)
        c->io.release(c->io.ctx, ss->s->modules[m].module, ss->s->name, ss->cycle_tick, id);
}

/* The name of a module of ss that still runs a release not acked yet (of any schema, any
   activation), or NULL. Releasing it again now would run it twice in this cycle. */
static const char *busy_module(const OrdCore *c, const SchemaState *ss) {
    for (int m = 0; m < ss->s->nmodules; m++)
        for (int i = 0; i < c->v->nschemas; i++) {
            const SchemaState *o = &c->st[i];
            for (int k = 0; k < o->s->nmodules; k++)
                if (o->outstanding[k] && strcmp(o->s->modules[k].module, ss->s->modules[m].module) == 0)
                    return ss->s->modules[m].module;
        }
    return NULL;
}

static void release_heads(OrdCore *c, SchemaState *ss) {
    for (int m = 0; m < ss->s->nmodules && ss->running; m++)
        if (ss->waiting[m] == 0 && !ss->released[m]) release(c, ss, m);
}

/* a module was freed: held cycles whose modules are all free release their heads */
static void resume_held(OrdCore *c) {
    for (int i = 0; i < c->v->nschemas; i++) {
        SchemaState *ss = &c->st[i];
        if (!ss->active || !ss->running || !ss->held || busy_module(c, ss)) continue;
        ss->held = 0;
        trace(c, "cycle of %s resumed", ss->s->name);
        release_heads(c, ss);
    }
}

/* the current cycle ends (finished, restarted, deactivated, or ORD stops): a cycle that skipped
   more than one release says how many, and one during which ORD missed more than one tick too,
   so that a reader of the trace counts them as ORD does (ORD traces only the first of each,
   "cycle still running", "missed tick of S") */
static void end_cycle_counts(OrdCore *c, SchemaState *ss) {
    if (ss->cycle_overruns > 1)
        trace(c, "overrun: %s cycle ended after %ld skipped releases", ss->s->name, ss->cycle_overruns);
    if (ss->cycle_missed > 1)
        trace(c, "missed ticks: %s cycle ended after %ld missed ticks", ss->s->name, ss->cycle_missed);
    ss->cycle_overruns = 0;
    ss->cycle_missed = 0;
}

static void finish_cycle(OrdCore *c, SchemaState *ss) {
    ss->running = 0;
    ss->stats.completed++;
    end_cycle_counts(c, ss);
    fact(c, ss, ORD_FACT_COMPLETE, -1, 0);
    int64_t rt = c->now - ss->cycle_tick;
    if (rt > ss->stats.max_response_ns) ss->stats.max_response_ns = rt;
}

/* `at`: when ORD releases the cycle (real time: the time it runs at, which a loaded machine leaves
   behind the tick; virtual: the tick) */
static void start_cycle(OrdCore *c, SchemaState *ss, int64_t tick, int64_t at) {
    const ContractSchema *s = ss->s;
    ss->running = 1;
    ss->cycle_tick = tick;
    ss->reported = 0;
    ss->released_late = 0;
    ss->cycle_overruns = 0;
    ss->cycle_missed = 0;
    ss->pending = s->nmodules;
    ss->stats.cycles++;
    for (int m = 0; m < s->nmodules; m++) {
        ss->waiting[m] = ss->npreds[m];
        ss->released[m] = 0;
        ss->finished[m] = 0;
        ss->cycle_rel[m] = 0;
    }
    if (s->nmodules == 0) {
        finish_cycle(c, ss);
        return;
    }
    const char *busy = busy_module(c, ss);
    ss->held = busy != NULL;
    if (busy) {
        ss->stats.held_cycles++;
        trace(c, "cycle of %s held: %s still runs a release of an earlier activation", s->name, busy);
        return;
    }
    /* ORD itself released the cycle at or past its critical delay: a miss of ORD, not of the
       schema's modules (do_check); a cycle released on its tick never is */
    if (at > tick && at - tick >= s->critical_delay_ns) ss->released_late = at - tick;
    release_heads(c, ss);
}

/* A held cycle waits at most ORD_HOLD_LIMIT_NS (or one period if longer): a module stopped by
   someone else (its STOP is answered to that requester, never to ORD) or crashed would
   otherwise hold the schema for ever. Not shorter: under load a module may sit for tens of ms
   before reading the START it still has to run, and forgetting that release early would make
   it run twice in the new cycle. The releases it waits for are forgotten (their acks, if any
   come, are then ignored). */
#define ORD_HOLD_LIMIT_NS 1000000000LL

static void give_up_waiting(OrdCore *c, SchemaState *ss) {
    for (int m = 0; m < ss->s->nmodules; m++)
        for (int i = 0; i < c->v->nschemas; i++) {
            SchemaState *o = &c->st[i];
            for (int k = 0; k < o->s->nmodules; k++)
                if (o->outstanding[k] && strcmp(o->s->modules[k].module, ss->s->modules[m].module) == 0) {
                    trace(c, "gave up waiting for %s release #%u (no ack within 1 s, %s)",
                          o->s->modules[k].module, o->outstanding[k], ss->s->name);
                    o->outstanding[k] = 0;
                }
        }
}

static int64_t stuck_limit(const SchemaState *ss) {
    int64_t limit = ORD_STUCK_PERIODS * ss->s->period_ns;
    return limit < ORD_STUCK_MIN_NS ? ORD_STUCK_MIN_NS : limit;
}

/* Half way to a stuck report of module m's outstanding release: one look at the module
   (OrdIo.module_activity), which the report compares with its own (ord_stuck_cause.h). */
static void look_at(OrdCore *c, SchemaState *ss, int m) {
    if (!c->io.module_activity || ss->looked[m] == ss->outstanding[m]) return;
    ss->looked[m] = ss->outstanding[m];
    ss->looked_t[m] = c->now;
    if (c->io.module_activity(c->io.ctx, ss->s->modules[m].module, &ss->look[m]) != 0)
        ss->look[m].state = 0; /* unreadable: not asked again for this release */
}

/* Reports module m's outstanding release stuck, once (`periods` periods of ss after it): with the
   likely cause, as the looks at the module show it (running, waiting or starved:
   ord_stuck_cause.h), else the question whether its exec region sets *stateindex = -1, unless
   the module is no longer running (crashed, killed: OrdIo.module_gone), which the trace line and
   the stuck call then say. */
static void report_stuck(OrdCore *c, SchemaState *ss, int m, long periods, const char *whose) {
    ss->stuck[m] = 1;
    ss->stats.stuck_releases++;
    const char *module = ss->s->modules[m].module;
    int gone = c->io.module_gone && c->io.module_gone(c->io.ctx, module);
    char cause[200];
    if (gone) {
        snprintf(cause, sizeof cause, "%s", "it is no longer running (it crashed or was killed)");
    } else {
        OrdModuleActivity now;
        memset(&now, 0, sizeof now); /* a binding that does not read wchan leaves it "" */
        now.written_bytes = -1;
        int seen = c->io.module_activity && c->io.module_activity(c->io.ctx, module, &now) == 0;
        int looked = ss->looked[m] == ss->outstanding[m] && ss->look[m].state != 0;
        ord_stuck_cause(looked ? &ss->look[m] : NULL, ss->looked_t[m], seen ? &now : NULL, c->now, ss->s->period_ns, cause,
                        sizeof cause);
    }
    char msg[400];
    snprintf(msg, sizeof msg, "%s has not finished release #%u after %ld periods%s: %s", module, ss->outstanding[m],
             periods, whose, cause);
    trace(c, "stuck: %s (%s)", msg, ss->s->name);
    if (c->io.stuck)
        c->io.stuck(c->io.ctx, ss->s->modules[m].module, ss->s->name, ss->outstanding[m], periods, msg);
}

/* The cycle started at ss->cycle_tick still runs at `tick`: each module released and not
   finished for ORD_STUCK_PERIODS periods (at least ORD_STUCK_MIN_NS) is reported once, by name,
   with the likely cause (a synchronous module's exec region that never sets *stateindex = -1
   runs for ever: docs/engines.md §4), instead of an overrun at every tick. */
static void check_stuck(OrdCore *c, SchemaState *ss, int64_t tick) {
    int64_t period = ss->s->period_ns, elapsed = tick - ss->cycle_tick, limit = stuck_limit(ss);
    if (period <= 0 || elapsed < limit / 2) return;
    for (int m = 0; m < ss->s->nmodules; m++) {
        if (!ss->released[m] || ss->finished[m] || ss->stuck[m] || ss->outstanding[m] != ss->cycle_rel[m]) continue;
        if (elapsed >= limit) report_stuck(c, ss, m, (long)(elapsed / period), "");
        else look_at(c, ss, m);
    }
}

/* A release outside the running cycle of its schema: its activation was deactivated (the module
   may still run it), or the schema's new cycle is held for it. No tick of a running cycle
   checks it (check_stuck): it is checked at its own due time (stuck_due). */
static int orphan_release(const SchemaState *ss, int m) {
    return ss->outstanding[m] && !ss->stuck[m] && ss->s->period_ns > 0 &&
           !(ss->active && ss->running && !ss->held && ss->released[m] && ss->cycle_rel[m] == ss->outstanding[m]);
}

/* The earliest time an orphan release becomes stuck, its schema and module (INT64_MAX: none). */
static int64_t stuck_due(const OrdCore *c, int *schema, int *module) {
    int64_t due = INT64_MAX;
    for (int i = 0; i < c->v->nschemas; i++) {
        const SchemaState *ss = &c->st[i];
        for (int m = 0; m < ss->s->nmodules; m++) {
            if (!orphan_release(ss, m)) continue;
            int64_t t = ss->outstanding_t[m] + stuck_limit(ss);
            if (t < due) {
                due = t;
                if (schema) *schema = i;
                if (module) *module = m;
            }
        }
    }
    return due;
}

/* "CTL, EST": the modules of ss's current cycle released and not finished (the ones the overrun
   waits for: running their release, or not yet begun on it), cut with "..." past the buffer; for a
   held cycle (nothing released), the module whose earlier release holds it */
static const char *running_modules(const OrdCore *c, const SchemaState *ss, char *buf, size_t n) {
    size_t used = 0;
    buf[0] = '\0';
    for (int m = 0; m < ss->s->nmodules; m++) {
        if (!ss->released[m] || ss->finished[m]) continue;
        const char *name = ss->s->modules[m].module;
        if (used + strlen(name) + 8 > n) { snprintf(buf + used, n - used, "%s...", used ? ", " : ""); break; }
        used += (size_t)snprintf(buf + used, n - used, "%s%s", used ? ", " : "", name);
    }
    const char *holder = used == 0 && ss->held ? busy_module(c, ss) : NULL;
    if (holder) snprintf(buf, n, "%s", holder);
    return buf;
}

static void do_tick(OrdCore *c, SchemaState *ss, int64_t until) {
    int64_t tick = ss->next_tick;
    ss->next_tick += ss->s->period_ns;
    if (c->skip_late && until >= ss->next_tick) { /* a later tick is already due: this one is obsolete */
        ss->stats.missed_ticks++;
        /* a module hogging the CPU makes ORD late at every tick: one line per cycle, and the
           stuck check still runs (it may never see an overrun) */
        if (!ss->running || ++ss->cycle_missed == 1)
            trace(c, "missed tick of %s (cycle %ld)", ss->s->name, (long)((tick - ss->act_t) / ss->s->period_ns));
        if (ss->running && !ss->held) check_stuck(c, ss, tick);
        return;
    }
    if (ss->running && ss->held &&
        tick - ss->cycle_tick >= (ss->s->period_ns > ORD_HOLD_LIMIT_NS ? ss->s->period_ns : ORD_HOLD_LIMIT_NS)) {
        /* the held cycle never ran: this tick starts afresh */
        end_cycle_counts(c, ss);
        ss->stats.overruns++;
        trace(c, "overrun: %s cycle still held, restarted", ss->s->name);
        give_up_waiting(c, ss);
        ss->running = 0;
        ss->held = 0;
    }
    if (ss->running) {
        ss->stats.overruns++;
        /* one line per cycle, not per tick: a module that never ends would flood the output */
        if (++ss->cycle_overruns == 1) {
            char running[160], named[164] = "";
            if (*running_modules(c, ss, running, sizeof running)) snprintf(named, sizeof named, " (%s)", running);
            trace(c, "overrun: %s cycle still running%s, release skipped", ss->s->name, named);
        }
        if (!ss->held) check_stuck(c, ss, tick);
        return;
    }
    start_cycle(c, ss, tick, c->skip_late && until > tick ? until : tick);
}

/* The cycle is not finished at tick + CRITICAL_DELAY: ORD:0 to every supervisor, unless ORD itself
   released the cycle that late (real time, a loaded machine): no module of it had any time, and
   ORD:0 would make a supervisor's rule take out a schema whose modules did nothing wrong. That
   miss is ORD's, told by its own line (docs/semantics.md "Scheduler: critical delay (ORD:0)"). */
static void do_check(OrdCore *c, SchemaState *ss) {
    ss->reported = 1;
    long k = (long)((ss->cycle_tick - ss->act_t) / ss->s->period_ns);
    if (ss->released_late) {
        ss->stats.late_releases++;
        trace(c, "late release: %s cycle %ld released %lld us after its tick, past CRITICAL_DELAY %lld us "
                 "(ORD late, no ORD:0)",
              ss->s->name, k, (long long)(ss->released_late / 1000), (long long)(ss->s->critical_delay_ns / 1000));
        return;
    }
    ss->stats.deadline_misses++;
    trace(c, "deadline miss: %s cycle %ld (ORD:0)", ss->s->name, k);
    fact(c, ss, ORD_FACT_DEADLINE_MISS, -1, 0);
    if (c->io.emit) c->io.emit(c->io.ctx, CONTRACT_ORD_EVENT_DEADLINE_MISS, ss->s->name);
}

/* fires ticks and checks due at or before `until` (strictly before when !inclusive) */
static void run_until(OrdCore *c, int64_t until, int inclusive) {
    for (;;) {
        int best = -1, best_is_check = 0;
        int64_t best_t = 0;
        for (int i = 0; i < c->v->nschemas; i++) {
            SchemaState *ss = &c->st[i];
            if (!ss->active) continue;
            if (ss->running && !ss->reported) {
                int64_t tc = ss->cycle_tick + ss->s->critical_delay_ns;
                if (best < 0 || tc < best_t || (tc == best_t && !best_is_check)) {
                    best = i;
                    best_t = tc;
                    best_is_check = 1;
                }
            }
            int64_t tt = ss->next_tick;
            if (best < 0 || tt < best_t) {
                best = i;
                best_t = tt;
                best_is_check = 0;
            }
        }
        int so = -1, sm = -1;
        int64_t st = stuck_due(c, &so, &sm);
        if (st != INT64_MAX && (best < 0 || st < best_t) && (st < until || (inclusive && st == until))) {
            if (st > c->now) c->now = st;
            SchemaState *ss = &c->st[so];
            report_stuck(c, ss, sm, (long)((c->now - ss->outstanding_t[sm]) / ss->s->period_ns),
                         ss->active && ss->running ? " (its schema's new cycle waits for it)"
                                                   : " (of a deactivated activation)");
            continue;
        }
        if (best < 0 || best_t > until || (!inclusive && best_t == until)) break;
        if (best_t > c->now) c->now = best_t;
        if (best_is_check) do_check(c, &c->st[best]);
        else do_tick(c, &c->st[best], until);
    }
    if (until > c->now && inclusive) c->now = until;
}

void ord_core_advance(OrdCore *c, int64_t t) { run_until(c, t, 1); }

int ord_core_next_deadline(const OrdCore *c, int64_t *deadline) {
    int64_t stuck = stuck_due(c, NULL, NULL);
    int found = stuck != INT64_MAX;
    if (found) *deadline = stuck;
    for (int i = 0; i < c->v->nschemas; i++) {
        const SchemaState *ss = &c->st[i];
        if (!ss->active) continue;
        int64_t t = ss->next_tick;
        if (ss->running && !ss->reported && ss->cycle_tick + ss->s->critical_delay_ns < t)
            t = ss->cycle_tick + ss->s->critical_delay_ns;
        if (!found || t < *deadline) *deadline = t;
        found = 1;
    }
    return found;
}

int ord_core_activate(OrdCore *c, int64_t t, const char *name, const void *params, size_t size,
                      const char *requester, uint32_t activation_id) {
    ord_core_advance(c, t);
    int i = schema_index(c, name);
    if (i < 0) {
        trace(c, "refused: unknown schema %s", name);
        if (c->io.ack) c->io.ack(c->io.ctx, requester, activation_id, 0);
        return -1;
    }
    SchemaState *ss = &c->st[i];
    for (int j = 0; j < c->v->nschemas; j++) {
        if (!c->st[j].active || !shares_module(ss->s, c->st[j].s)) continue;
        trace(c, "conflict: %s shares a module with active %s (ORD:1)", name, c->st[j].s->name);
        if (c->io.emit) c->io.emit(c->io.ctx, CONTRACT_ORD_EVENT_CONFLICT, name);
        if (c->io.ack) c->io.ack(c->io.ctx, requester, activation_id, 0);
        return -1;
    }
    const ContractSchema *s = ss->s;
    engine_init_block(ss->params, s->params, s->nparams);
    if (params && size != s->params_size)
        trace(c, "warning: %s activated with %zu parameter bytes, its tables say %zu (tables of ORD "
                 "and %s from different generations?)", name, size, s->params_size,
              requester ? requester : "the requester");
    if (params) memcpy(ss->params, params, size < s->params_size ? size : s->params_size);
    EngineScope scope;
    memset(&scope, 0, sizeof scope);
    scope.params = ss->params;
    scope.param_vars = s->params;
    scope.nparam_vars = s->nparams;
    scope.occ_port = -1;
    for (int m = 0; m < s->nmodules; m++)
        for (int k = 0; k < s->modules[m].nsettings; k++) {
            const ContractParamSetting *ps = &s->modules[m].settings[k];
            unsigned char *val = malloc(ps->type->size);
            if (val && engine_build_setting(&scope, ps, val) == 0 && c->io.set_param)
                c->io.set_param(c->io.ctx, s->modules[m].module, ps->port, ps->name, val, ps->type->size, ps->type);
            free(val);
        }
    for (int k = 0; k < s->ndata_flows; k++)
        if (c->io.connect_data) c->io.connect_data(c->io.ctx, &s->data_flows[k]);
    /* tick 0 is when the set-up is done: the other schemas' ticks due meanwhile come first */
    if (c->io.setup_done_at) ord_core_advance(c, c->io.setup_done_at(c->io.ctx));
    ss->active = 1;
    ss->act_id = activation_id;
    snprintf(ss->requester, sizeof ss->requester, "%s", requester ? requester : "");
    ss->running = 0;
    ss->next_tick = c->now;
    ss->act_t = c->now;
    char act[96];
    trace(c, "activate %s%s", name, activation_text(act, sizeof act, activation_id, requester));
    if (c->io.ack) c->io.ack(c->io.ctx, requester, activation_id, 1);
    ord_core_advance(c, c->now);
    return 0;
}

int ord_core_deactivate(OrdCore *c, int64_t t, const char *name, const char *requester,
                        uint32_t activation_id) {
    ord_core_advance(c, t);
    int i = schema_index(c, name);
    SchemaState *ss = i < 0 ? NULL : &c->st[i];
    /* ids are numbered by each supervisor on its own: an activation is its id *and* its
       requester (another supervisor's refused activation may carry the same number) */
    if (!ss || !ss->active ||
        (activation_id != 0 && (activation_id != ss->act_id ||
                                strcmp(requester ? requester : "", ss->requester) != 0))) {
        trace(c, "ignored: deactivate %s (not this activation)", name);
        if (c->io.ack) c->io.ack(c->io.ctx, requester, activation_id, 0);
        return -1;
    }
    if (ss->running) end_cycle_counts(c, ss);
    ss->active = 0;
    ss->running = 0;
    ss->held = 0; /* modules released and not acked stay outstanding: they may still run */
    for (int k = 0; k < ss->s->ndata_flows; k++)
        if (c->io.disconnect_data) c->io.disconnect_data(c->io.ctx, &ss->s->data_flows[k]);
    char act[96];
    trace(c, "deactivate %s%s", name, activation_text(act, sizeof act, ss->act_id, ss->requester));
    if (c->io.ack) c->io.ack(c->io.ctx, requester, activation_id, 1);
    return 0;
}

/* the outstanding release that `id` names (0: the release of `module` in its schema's current
   cycle); 1 when found */
static int find_release(OrdCore *c, const char *module, uint32_t id, SchemaState **out, int *mout) {
    for (int i = 0; i < c->v->nschemas; i++) {
        SchemaState *ss = &c->st[i];
        for (int m = 0; m < ss->s->nmodules; m++) {
            if (!ss->outstanding[m] || strcmp(ss->s->modules[m].module, module) != 0) continue;
            if (id ? ss->outstanding[m] != id
                   : !(ss->active && ss->running && ss->cycle_rel[m] == ss->outstanding[m]))
                continue;
            *out = ss;
            *mout = m;
            return 1;
        }
    }
    return 0;
}

static void complete_module(OrdCore *c, SchemaState *ss, int m) {
    const ContractSchema *s = ss->s;
    if (ss->stuck[m])
        trace(c, "%s finished release #%u at last (reported stuck, %s)", s->modules[m].module,
              ss->cycle_rel[m], s->name);
    ss->finished[m] = 1;
    ss->pending--;
    for (int e = 0; e < s->nprecedences; e++)
        if (s->precedences[e].before == m) {
            int n = s->precedences[e].after;
            if (--ss->waiting[n] == 0 && !ss->released[n]) release(c, ss, n);
        }
    if (ss->pending == 0) finish_cycle(c, ss);
}

void ord_core_release_finished(OrdCore *c, int64_t t, const char *module, uint32_t release_id) {
    run_until(c, t, 0); /* a check due exactly at t comes after this completion */
    if (t > c->now) c->now = t;
    SchemaState *ss = NULL;
    int m = -1;
    if (!find_release(c, module, release_id, &ss, &m)) {
        trace(c, "ignored: %s finished outside a cycle (release #%u is not outstanding)", module,
              release_id);
    } else {
        uint32_t id = ss->outstanding[m];
        ss->outstanding[m] = 0;
        if (ss->active && ss->running && !ss->held && ss->released[m] && !ss->finished[m] &&
            ss->cycle_rel[m] == id) {
            fact(c, ss, ORD_FACT_FINISHED, m, id);
            complete_module(c, ss, m);
        } else {
            ss->stats.late_acks++;
            trace(c, "late ack: %s finished release #%u of an earlier cycle of %s (not counted%s)",
                  module, id, ss->s->name, ss->stuck[m] ? ", reported stuck" : "");
        }
        resume_held(c);
    }
    run_until(c, t, 1);
}

void ord_core_module_finished(OrdCore *c, int64_t t, const char *module) {
    ord_core_release_finished(c, t, module, 0);
}

void ord_core_set_skip_late_ticks(OrdCore *c, int on) { c->skip_late = on; }

int ord_core_schema_active(const OrdCore *c, const char *name) {
    int i = schema_index(c, name);
    return i >= 0 && c->st[i].active;
}

int ord_core_stats(const OrdCore *c, const char *name, OrdSchemaStats *out) {
    int i = schema_index(c, name);
    if (i < 0) return -1;
    *out = c->st[i].stats;
    return 0;
}

OrdCore *ord_core_create(const ContractOrdVocabulary *v, const OrdIo *io, char *err, size_t errlen) {
    if (contract_check_ord_vocabulary(v, err, errlen) != 0) return NULL;
    OrdCore *c = calloc(1, sizeof *c);
    if (!c) goto oom;
    c->v = v;
    if (io) c->io = *io;
    c->now = INT64_MIN;
    c->st = calloc((size_t)v->nschemas + 1, sizeof *c->st);
    if (!c->st) goto oom;
    for (int i = 0; i < v->nschemas; i++) {
        SchemaState *ss = &c->st[i];
        const ContractSchema *s = v->schemas[i];
        ss->s = s;
        size_t n = (size_t)s->nmodules + 1;
        ss->params = calloc(1, s->params_size + 1);
        ss->npreds = calloc(n, sizeof(int));
        ss->waiting = calloc(n, sizeof(int));
        ss->released = calloc(n, 1);
        ss->finished = calloc(n, 1);
        ss->cycle_rel = calloc(n, sizeof(uint32_t));
        ss->outstanding = calloc(n, sizeof(uint32_t));
        ss->outstanding_t = calloc(n, sizeof(int64_t));
        ss->stuck = calloc(n, 1);
        ss->looked = calloc(n, sizeof(uint32_t));
        ss->looked_t = calloc(n, sizeof(int64_t));
        ss->look = calloc(n, sizeof(OrdModuleActivity));
        if (!ss->stuck || !ss->looked || !ss->looked_t || !ss->look || !ss->cycle_rel || !ss->outstanding || !ss->outstanding_t || !ss->params || !ss->npreds || !ss->waiting || !ss->released || !ss->finished) goto oom;
        for (int e = 0; e < s->nprecedences; e++) ss->npreds[s->precedences[e].after]++;
        /* the precedence graph must be acyclic: Kahn's algorithm */
        int *w = ss->waiting, done = 0;
        char *seen = ss->released;
        for (int m = 0; m < s->nmodules; m++) { w[m] = ss->npreds[m]; seen[m] = 0; }
        for (int progress = 1; progress;) {
            progress = 0;
            for (int m = 0; m < s->nmodules; m++)
                if (!seen[m] && w[m] == 0) {
                    seen[m] = 1;
                    done++;
                    progress = 1;
                    for (int e = 0; e < s->nprecedences; e++)
                        if (s->precedences[e].before == m) w[s->precedences[e].after]--;
                }
        }
        if (done != s->nmodules) {
            snprintf(err, errlen, "invalid tables: ORD schema %s: the scheduling graph has a cycle",
                     s->name);
            ord_core_destroy(c);
            return NULL;
        }
    }
    return c;
oom:
    snprintf(err, errlen, "out of memory creating ORD");
    ord_core_destroy(c);
    return NULL;
}

void ord_core_stop(OrdCore *c) {
    for (int i = 0; i < c->v->nschemas; i++)
        if (c->st[i].active && c->st[i].running) end_cycle_counts(c, &c->st[i]);
}

void ord_core_destroy(OrdCore *c) {
    if (!c) return;
    if (c->st)
        for (int i = 0; i < c->v->nschemas; i++) {
            free(c->st[i].params);
            free(c->st[i].npreds);
            free(c->st[i].waiting);
            free(c->st[i].released);
            free(c->st[i].finished);
            free(c->st[i].cycle_rel);
            free(c->st[i].outstanding);
            free(c->st[i].outstanding_t);
            free(c->st[i].stuck);
            free(c->st[i].looked);
            free(c->st[i].looked_t);
            free(c->st[i].look);
        }
    free(c->st);
    free(c);
}
