/*
 * sup_main.c — binds the supervisor core (sup_core.c) to libmodule: requests in the mailbox
 * become core inputs, the core's SupIo calls become requests to ORD, modules and other
 * supervisors. Timers: engine_wait() (timerfd on the core's next absolute CLOCK_MONOTONIC
 * deadline, polled together with the mailbox); no sleep loop.
 *
 * Wire conventions between engines (see docs/engines.md):
 *  - start a supervision function: REQ_START, Param.Start.Function = name ("" = the first
 *    function), Data = text arguments "p={1.0,2.0,3.0},q=3" (control tools) or
 *    CONTRACT_BINARY_ARGS_MAGIC followed by the parameter block (engines);
 *  - `activate supervisor`: the same REQ_START with AckID = the caller's activation id and
 *    ACK_START | ACK_NOTDONE wanted: the callee answers whether it started the function
 *    (sup_core_function_answer); its undo is REQ_STOP with Data = the function name and the
 *    same AckID, which stops the function only if it runs that activation of that sender;
 *  - stop one: REQ_STOP with Data = the function name (empty: every running function), AckID
 *    0 = whichever activation runs (control tools);
 *  - periodic schemas: REQ_START to ORD with Function = schema name, Data = parameter block,
 *    AckID = activation id; deactivation: REQ_STOP to ORD with Data = schema name, same AckID;
 *  - ORD events arrive as REQ_EVENT from module "ORD", source port 0/1, Data = schema name.
 */
#define _GNU_SOURCE
#include <sched.h>
#include <errno.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <unistd.h>

#include "contract/vocabulary.h"
#include "engine_values.h"
#include "engine_wait.h"
#include "engine_wire.h"
#include "libmodule/libmodule.h"
#include "log_engine.h"
#include "module_holds.h"
#include "prio_requests.h"
#include "sup_core.h"

/* subscribers of the supervisor's out event ports (kept here: the generated module.c of a
   supervisor has no IDETECT table, the vocabulary describes the ports) */
typedef struct Subscriber {
    char module[CONTRACT_NAME_MAX];
    int target_port, source_port, mode;
} Subscriber;

typedef struct SupBinding {
    const ContractSupervisorVocabulary *v;
    Subscriber subs[64];
    int nsubs;
} SupBinding;

/* the core's deadlines, for engine_next_request */
/* the core's deadlines, and those of the priority answers it does not wait for */
static int sup_next_deadline(const void *core, int64_t *deadline) {
    int rc = sup_core_next_deadline(core, deadline);
    int64_t answers = prio_requests_next_deadline();
    if (answers < *deadline) *deadline = answers;
    return rc;
}
static void sup_advance(void *core, int64_t t) {
    prio_requests_expire(t);
    sup_core_advance(core, t);
}

static void add_subscriber(SupBinding *b, const char *module, int target_port, int source_port, int mode) {
    int known = 0;
    for (int i = 0; i < b->v->nout_ports; i++)
        if (b->v->out_ports[i].port == source_port) known = 1;
    if (!known) {
        fprintf(stderr, "%s: subscription of %s:%d refused: no out event port :%d\n", b->v->name, module,
                target_port, source_port);
        return;
    }
    for (int i = 0; i < b->nsubs; i++)
        if (strcmp(b->subs[i].module, module) == 0 && b->subs[i].target_port == target_port &&
            b->subs[i].source_port == source_port) {
            b->subs[i].mode = mode;
            return;
        }
    if (b->nsubs == 64) {
        fprintf(stderr, "%s: too many event subscribers (64)\n", b->v->name);
        return;
    }
    Subscriber *s = &b->subs[b->nsubs++];
    snprintf(s->module, sizeof s->module, "%s", module);
    s->target_port = target_port;
    s->source_port = source_port;
    s->mode = mode;
    ContractLog("event_subscribed", module, source_port, 0, mode == EVENT_ONESHOT ? "oneshot" : "continuous");
}

static void remove_subscriber(SupBinding *b, const char *module, int target_port, int source_port) {
    for (int i = 0; i < b->nsubs; i++)
        if (strcmp(b->subs[i].module, module) == 0 && b->subs[i].target_port == target_port &&
            b->subs[i].source_port == source_port) {
            b->subs[i] = b->subs[--b->nsubs];
            return;
        }
}

/* Each action the supervisor sends and each undo, as a `supervisor` record of its CSV log (not on
   stdout: a rule that fires at every event would flood the console), in the simulator's words
   (runtime/sim/sim_world.c), undos prefixed `undo: `; peer = the module, supervisor or ORD it
   goes to (a flow's: its source module). A module started or stopped, an event-schema flow
   connected or disconnected and a priority claimed or released are logged so too (`start module
   M (priority P)`, `undo: stop module M`, `connect A:p =* B:i`, `undo: disconnect A:p =* B:i`,
   `set priority of M to P (claim #N)`, `undo: release priority claim #N on M`), and what came of
   them has its own records (module_hold, flow_hold, module_priority). An action is logged *before* its request is sent, so that its
   record comes before what the receiver does with it (the receiver may log within microseconds);
   a request that could not be sent is followed by `error: not sent: <the action>: <reason>`
   (not_sent). */
static char last_action[400]; /* the engine's thread only */
static void log_action(const char *peer, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void log_action(const char *peer, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_action, sizeof last_action, fmt, ap);
    va_end(ap);
    ContractLog("supervisor", peer, -1, 0, last_action);
}

/* A request the supervisor could not send is said on stderr (`SUP: cannot set parameter 0 of CTL:
   mailbox full`) beside libmodule's own error line, and counted as libmodule counts its own
   (ContractSay: a rule parameterizing a crashed module at 100 Hz), the count said at the end. */
static ContractSaidLines cannot_lines = {"cannot ", "", "failure", "", 0, 0};

static void say_cannot(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void say_cannot(const char *fmt, ...) {
    char text[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    ContractSay(&cannot_lines, text);
}

/* rc of the request of the action logged last: a failure gets its own record */
static int not_sent(const char *peer, int rc) {
    if (rc == CONTRACT_OK) return 0;
    char line[512];
    snprintf(line, sizeof line, "error: not sent: %.380s: %s", last_action, ContractStrError(rc));
    ContractLog("supervisor", peer, -1, 0, line);
    return 1;
}

/* undo requests go to modules that may already have ended (architecture stopping): skip those */
static int alive(const char *module) { return ModuleState(module) == CONTRACT_OK; }

/* An undo whose receiver has already ended (the launcher stops the supervisors first at a run's
   end, one after the other; a crash; a kill): the undo is logged all the same, then why no request went,
   as an `error` record (the log says every undo its rule's end made, none is left out silently);
   stderr stays quiet, as for a peer gone at the run's stop (rt_send_failed). At the stop, when it
   ended is not known here (the launcher's stop of it, or a kill or crash before the stop): "it had
   already ended" says only what is known; `contract trace` tells a receiver whose records stopped
   mid-run. */
static void undo_skipped(const char *peer) {
    char line[256];
    snprintf(line, sizeof line, "STOP request to %.64s: not sent, it has ended (%s)", peer,
             ContractRunStopping() ? "it had already ended; the run is stopping" : "it crashed or was stopped");
    ContractLog("error", "", -1, 0, line);
}

static void b_ord_activate(void *ctx, const ContractSchema *s, const void *params, size_t size,
                           uint32_t id) {
    (void)ctx;
    char args[ACTION_VALUE_MAX];
    engine_format_params(args, sizeof args, s->params, size == s->params_size ? s->nparams : -1, params);
    log_action("ORD", "activate schema %s%s (activation #%u, to ORD)", s->name, args, id);
    int rc = engine_send_start("ORD", s->name, params, size, (int)id, ACK_NOTHING);
    if (not_sent("ORD", rc))
        say_cannot("ask ORD to activate %s: %s", s->name,
                ContractStrError(rc));
}

static void b_ord_deactivate(void *ctx, const ContractSchema *s, uint32_t id) {
    (void)ctx;
    log_action("ORD", "undo: deactivate schema %s (activation #%u, to ORD)", s->name, id);
    if (!alive("ORD")) {
        undo_skipped("ORD");
        return;
    }
    int rc = engine_send_stop("ORD", s->name, (int)id);
    if (not_sent("ORD", rc))
        say_cannot("ask ORD to deactivate %s: %s", s->name,
                ContractStrError(rc));
}

/* Priorities of other modules: the module applies them to itself when it next reads its
   mailbox (SCHED_FIFO where permitted, else a nice level, which an unprivileged module may lower
   but not raise); the supervisor does not wait for the answer (prio_requests.h). */

/* What this supervisor knows of the modules' runs, for b_module_run_ended: the `activations=N` of
   each module's last status, and the count its status shows once the START this supervisor last
   sent it was taken (that status's plus one; -1: not known). A run may end by the module's own
   code; a START still in its mailbox must not be taken for such an end. */
#define RUNS_KNOWN 64
static struct {
    char module[CONTRACT_NAME_MAX];
    long seen, after_start;
} runs_known[RUNS_KNOWN];

static int run_slot(const char *m) {
    int free_slot = -1;
    for (int i = 0; i < RUNS_KNOWN; i++) {
        if (runs_known[i].module[0] == '\0') {
            if (free_slot < 0) free_slot = i;
        } else if (strcmp(runs_known[i].module, m) == 0) {
            return i;
        }
    }
    if (free_slot >= 0) {
        snprintf(runs_known[free_slot].module, sizeof runs_known[free_slot].module, "%s", m);
        runs_known[free_slot].seen = runs_known[free_slot].after_start = -1;
    }
    return free_slot; /* -1: more modules than the table holds (then never taken for ended) */
}

/* A module's status (mailbox.c: `... running=yes|no activations=N ...`): running, and its activations noted */
static int status_running(const char *m, const char *status) {
    static const char key[] = " activations=";
    const char *a = strstr(status, key);
    int i = run_slot(m);
    if (a && i >= 0) runs_known[i].seen = strtol(a + sizeof key - 1, NULL, 10);
    return strstr(status, " running=yes") != NULL;
}

/* Is module `m` running (a run started and not finished or stopped)? Asked to the module
   itself, so that a module started by another supervisor is not started twice. No answer
   within 0.5 s: it is busy in its own code, hence running -- unless the last engine decision
   on m was to stop it (holds_stopped): then m is paused or starved with that STOP still in its
   mailbox, and a START sent now comes after it. (The core asks this under m's lock.) */
static int b_module_running(void *ctx, const char *m) {
    (void)ctx;
    char status[1024] = "";
    int rc = QueryStatus(m, status, sizeof status, GetTime() + 500000000LL);
    if (rc == CONTRACT_EBUSY) return !holds_stopped(m, 0);
    int running = rc == CONTRACT_OK && status_running(m, status);
    if (running) holds_stopped(m, 1); /* it says it runs: someone started it since the engines' STOP */
    return running;
}

/* Has the run this supervisor started of `m` (which it still holds) ended by the module's own
   code? Asked to the module: not running, and its activations past the START sent (so that START
   was taken). A module busy in its own code, answering nothing within 50 ms, runs; no answer
   at all (gone, crashed) is no run to start again. */
static int b_module_run_ended(void *ctx, const char *m) {
    (void)ctx;
    int i = run_slot(m);
    if (i < 0 || runs_known[i].after_start < 0) return 0;
    char status[1024] = "";
    if (QueryStatus(m, status, sizeof status, GetTime() + 50000000LL) != CONTRACT_OK) return 0;
    return !status_running(m, status) && runs_known[i].seen >= runs_known[i].after_start;
}

/* A request kept for a full mailbox (ContractSetQueuedSends) that failed after all, 2 s later:
   its `error` record is written (libmodule); this says which of the supervisor's requests it was
   (`error: not sent: STOP request to ASY (kept 2 s for its full mailbox): mailbox full`), and a
   STOP that did not reach its module leaves it running: the engines' "stopped it" mark goes, as
   for a STOP that fails at once (no lock taken: this runs inside any wait, maybe under one). */
static void kept_send_failed(const char *module, const RequestMessage *request, int code) {
    char line[256];
    snprintf(line, sizeof line, "error: not sent: %s request to %s (kept 2 s for its full mailbox): %s",
             ContractRequestName(request->Type), module, ContractStrError(code));
    ContractLog("supervisor", module, -1, 0, line);
    if (request->Type == REQ_STOP && holds_stopped(module, 1))
        ContractLog("module_hold", module, -1, 0, "stop failed: it had been kept for its full mailbox (it still runs)");
}

/* `start module M (priority P)`, then the hold it takes (module_hold `hold taken (started it)`);
   a start it cannot send (M not there, its mailbox full) is `error: not sent: ...`, no hold */
static void b_start_module(void *ctx, const char *m, int prio) {
    (void)ctx;
    log_action(m, ACTION_START_MODULE, m, prio);
    int rc = ModuleState(m);
    if (rc == CONTRACT_OK) {
        prio_request_start(m, prio); /* read before the start: its run begins at that priority */
        rc = SendStart(m, ACK_NOTHING, 0);
    }
    if (not_sent(m, rc)) {
        say_cannot("start %s: %s", m, ContractStrError(rc));
        return;
    }
    int i = run_slot(m);
    if (i >= 0) runs_known[i].after_start = runs_known[i].seen >= 0 ? runs_known[i].seen + 1 : -1;
    holds_take(m, 1);
}

/* the last holder across supervisors stops a module that a supervisor started (the core calls
   this under b_lock_module: no other supervisor decides on m meanwhile) */
static void stop_if_last(const char *m, int started_here) {
    int others = holds_drop(m);
    if (others > 0) {
        char detail[96];
        snprintf(detail, sizeof detail, "hold dropped (kept running: still used by %d other supervisor(s))", others);
        ContractLog("module_hold", m, -1, 0, detail);
        return;
    }
    int started = holds_started(m, 1);
    if (!started && !started_here) { /* started by the user or the launcher: leave it */
        ContractLog("module_hold", m, -1, 0, "last hold dropped (left running: not started by an engine)");
        return;
    }
    if (!alive(m)) {
        ContractLog("module_hold", m, -1, 0, "last hold dropped (it had ended)");
        return;
    }
    int rc = SendStop(m, ACK_NOTHING, 0);
    if (rc == CONTRACT_OK) holds_mark_stopped(m);
    ContractLog("module_hold", m, -1, 0, rc != CONTRACT_OK       ? "last hold dropped (stop failed)"
                                         : ContractQueuedFor(m) ? "last hold dropped (stop kept: its mailbox is full)"
                                                                : "last hold dropped (stopped)");
    if (rc != CONTRACT_OK)
        say_cannot("stop %s: %s", m, ContractStrError(rc));
}

/* "is it running? share it or start it" and "drop, count, stop" on one module: one
   supervisor at a time (module_holds.h) */
static void b_lock_module(void *ctx, const char *m, int lock) {
    (void)ctx;
    if (lock) holds_lock(m);
    else holds_unlock(m);
}

/* `undo: stop module M` (the undo of its start), then what its hold decided: `last hold dropped
   (stopped)`, or kept running for another supervisor, or it had ended (module_hold) */
static void b_stop_module(void *ctx, const char *m) {
    (void)ctx;
    log_action(m, "undo: " ACTION_STOP_MODULE, m);
    stop_if_last(m, 1);
}

static void b_share_module(void *ctx, const char *m, int hold) {
    (void)ctx;
    if (hold) holds_take(m, 0);
    else stop_if_last(m, 0);
}

/* `activate resttime|critical module` on a running module: a claim shared with the other
   supervisors of the run (prio_claims.h),
   recorded when the module answers (prio_requests.h); `set priority of M to P (claim #N)` and
   `undo: release priority claim #N on M` name the claim by the supervisor's activation number
   (a request that cannot be sent is a module_priority record `priority P not applied: ...`) */
static int b_claim_priority(void *ctx, const char *m, uint32_t id, int prio) {
    (void)ctx;
    log_action(m, ACTION_CLAIM_PRIORITY, m, prio, id);
    return prio_request_claim(m, id, prio);
}

static void b_release_priority(void *ctx, const char *m, uint32_t id) {
    (void)ctx;
    log_action(m, "undo: " ACTION_RELEASE_PRIORITY, id, m);
    prio_request_release(m, id);
}

static void b_set_param(void *ctx, const char *m, int port, const char *name, const void *v, size_t size,
                        const ContractType *t) {
    (void)ctx;
    char line[ACTION_LINE_MAX];
    engine_format_parameterize(line, sizeof line, m, port, name, v, size, t);
    log_action(m, "%s", line);
    int rc = SendSetParam(m, port, v, size, ACK_NOTHING, 0);
    if (not_sent(m, rc))
        say_cannot("set parameter %d of %s: %s", port, m,
                ContractStrError(rc));
}

static int mode_of(ContractEventMode m) { return m == CONTRACT_ONESHOT ? EVENT_ONESHOT : EVENT_CONTINUOUS; }

/* Event flows of event schemas. The core connects a flow at each activation and disconnects
   it when its last active schema *in this supervisor* ends; across supervisors the flow is one
   subscription at its producer, so this supervisor holds it (module_holds.h) and unsubscribes
   only when no other supervisor holds it, under the flow's lock. Each is logged first, peer =
   the flow's source: `connect A:p =* B:i` (`=>` one shot), `undo: disconnect A:p =* B:i`. */
static void b_connect(void *ctx, const ContractEventFlow *f) {
    (void)ctx;
    char name[CONTRACT_NAME_MAX], flow[ACTION_LINE_MAX];
    engine_flow_hold_name(name, sizeof name, f->src_module, f->src_port, f->dst_module, f->dst_port);
    engine_format_event_flow(flow, sizeof flow, f);
    log_action(f->src_module, "connect %s", flow);
    holds_lock(name);
    holds_take_flow(name);
    not_sent(f->src_module, SendSubscribeEvent(f->src_module, f->src_port, f->dst_module, f->dst_port, mode_of(f->mode)));
    holds_unlock(name);
}

static void b_disconnect(void *ctx, const ContractEventFlow *f) {
    (void)ctx;
    char name[CONTRACT_NAME_MAX], flow[ACTION_LINE_MAX];
    engine_flow_hold_name(name, sizeof name, f->src_module, f->src_port, f->dst_module, f->dst_port);
    engine_format_event_flow(flow, sizeof flow, f);
    log_action(f->src_module, "undo: disconnect %s", flow);
    holds_lock(name);
    int others = holds_drop(name);
    if (others > 0) {
        char detail[96];
        snprintf(detail, sizeof detail, "hold dropped (kept connected: used by %d other supervisor(s))", others);
        ContractLog("flow_hold", name, -1, 0, detail);
    } else {
        ContractLog("flow_hold", name, -1, 0, "last hold dropped (disconnected)");
        if (alive(f->src_module))
            not_sent(f->src_module, SendUnsubscribeEvent(f->src_module, f->src_port, f->dst_module, f->dst_port));
    }
    holds_unlock(name);
}

static void b_subscribe(void *ctx, const char *m, int sp, int ip, ContractEventMode mode, uint32_t id) {
    (void)ctx;
    log_action(m, "subscribe %s:%d %s :%d (activation #%u)", m, sp, mode == CONTRACT_ONESHOT ? "=>" : "=*", ip, id);
    not_sent(m, SendSubscribeEvent(m, sp, ContractSelfName(), ip, mode_of(mode)));
}

static void b_unsubscribe(void *ctx, const char *m, int sp, int ip, uint32_t id) {
    (void)ctx;
    if (!alive(m)) return;
    log_action(m, "undo: unsubscribe %s:%d :%d (activation #%u)", m, sp, ip, id);
    not_sent(m, SendUnsubscribeEvent(m, sp, ContractSelfName(), ip));
}

static void b_notify(void *ctx, int port, const ContractType *t, const void *v, size_t size) {
    SupBinding *b = ctx;
    char value[ACTION_VALUE_MAX];
    engine_format_value(value, sizeof value, v, t);
    log_action("", "notify :%d (%s) = %s", port, t && t->name ? t->name : "?", value);
    for (int i = 0; i < b->nsubs;) {
        Subscriber *s = &b->subs[i];
        if (s->source_port != port) {
            i++;
            continue;
        }
        int rc = SendEvent(s->module, s->target_port, port, v, size);
        ContractLog("event_posted", s->module, port, size, rc == CONTRACT_OK ? "" : "failed");
        if (rc == CONTRACT_OK && s->mode == EVENT_ONESHOT) b->subs[i] = b->subs[--b->nsubs];
        else i++;
    }
}

static int b_start_function(void *ctx, const ContractFunctionSignature *callee, const void *p,
                            size_t size, uint32_t id) {
    (void)ctx;
    const char *sup = callee->supervisor, *fn = callee->function;
    char args[ACTION_VALUE_MAX];
    engine_format_params(args, sizeof args, callee->params, size == callee->params_size ? callee->nparams : -1, p);
    log_action(sup, "activate supervisor %s.%s%s (activation #%u)", sup, fn, args, id);
    int rc = engine_send_start(sup, fn, p, size, (int)id, ACK_START | ACK_NOTDONE);
    if (not_sent(sup, rc)) {
        say_cannot("start %s.%s: %s", sup, fn, ContractStrError(rc));
        return -1;
    }
    return 0;
}

static void b_stop_function(void *ctx, const char *sup, const char *fn, uint32_t id) {
    (void)ctx;
    log_action(sup, "undo: stop %s.%s (activation #%u)", sup, fn, id);
    if (!alive(sup)) {
        undo_skipped(sup);
        return;
    }
    not_sent(sup, engine_send_stop(sup, fn, (int)id));
}

static int64_t last_trace_time; /* read just before the last trace line's record (b_last_trace_time) */

static void b_trace(void *ctx, int64_t t, const char *line) {
    (void)ctx;
    (void)t;
    last_trace_time = GetTime(); /* the record's own time, to a few ns: taken right after this */
    ContractLog("supervisor", "", -1, 0, line);
    printf("%s\n", line); /* after the record: a slow stdout does not separate the two times */
}

static int64_t b_last_trace_time(void *ctx) {
    (void)ctx;
    return last_trace_time;
}

/* an action the core has no other call for (event schemas, compute): CSV only, as the others */
static void b_action(void *ctx, int64_t t, const char *line) {
    (void)ctx;
    (void)t;
    ContractLog("supervisor", "", -1, 0, line);
}

/* a rule change with its cause (docs/runtime-api.md "Trace records"): CSV only, the readable
   `rule F.R active` line is b_trace's */
static void b_rule(void *ctx, int64_t t, const char *function, const char *rule, int active,
                   const char *cause) {
    (void)ctx;
    (void)t;
    char detail[400];
    snprintf(detail, sizeof detail, "%s.%s %s cause=%s", function, rule, active ? "active" : "inactive", cause);
    ContractLog("sup_rule", "", -1, 0, detail);
}

static void stop_all(SupCore *c, const ContractSupervisorVocabulary *v, int64_t t) {
    for (int f = 0; f < v->nfunctions; f++)
        if (sup_core_function_running(c, v->functions[f].name))
            sup_core_stop_function(c, t, v->functions[f].name);
}

static void handle_start(SupCore *c, const ContractSupervisorVocabulary *v, RequestMessage *m, int64_t t) {
    const char *fn = m->Param.Start.Function[0] ? m->Param.Start.Function
                                                : (v->nfunctions ? v->functions[0].name : "");
    char err[256] = "";
    int rc;
    const unsigned char *block;
    size_t size;
    if (engine_binary_args(m, &block, &size)) { /* `activate supervisor` of another supervisor */
        rc = sup_core_start_function_for(c, t, fn, block, size, m->Sender, (uint32_t)m->Param.Start.AckID);
        /* the precise reason, in the words of the core's `refused: ...` record */
        if (rc != 0)
            fprintf(stderr, "%s: start refused: activation #%d of %s.%s from %s: %s %s%s\n", v->name,
                    m->Param.Start.AckID, v->name, fn, m->Sender, rc == -1 ? "no function" : "function", fn,
                    rc == -1 ? "" : " already running");
    } else {
        char args[CONTRACT_REQUEST_DATA_MAX + 1];
        size_t n = m->DataSize < CONTRACT_REQUEST_DATA_MAX ? m->DataSize : CONTRACT_REQUEST_DATA_MAX;
        memcpy(args, m->Data, n);
        args[n] = '\0';
        rc = sup_core_start_function_text(c, t, fn, args, err, sizeof err);
        /* a start request (contract-launch's, a control tool's) that names no function or
           parameter, or a value the type cannot read (-1: the core did not trace it): said on
           stderr (the build service makes it a run issue, start-refused) and in the CSV log, so
           that the story tells it; -2, already running, is the core's own `refused: ...` line */
        if (rc == -1) {
            fprintf(stderr, "%s: start request from %s refused: %s\n", v->name, m->Sender, err);
            char line[400];
            snprintf(line, sizeof line, "refused: start request from %s: %.300s", m->Sender, err);
            ContractLog("supervisor", m->Sender, -1, 0, line);
        } else if (rc != 0) {
            fprintf(stderr, "%s: start refused: %s\n", v->name, err);
        }
    }
    SendAck(m->Param.Start.ModAck[0] ? m->Param.Start.ModAck : m->Sender, m->Param.Start.WantedAck,
            rc == 0 ? ACK_START : ACK_NOTDONE, m->Param.Start.AckID);
}

int contract_supervisor_main(const ContractSupervisorVocabulary *v, int argc, const char *argv[]) {
    rt_log_engine(RT_ENGINE_SUPERVISOR); /* its own record kinds are logged by it only (csvlog.c) */
    (void)argc;
    (void)argv;
    SupBinding b;
    memset(&b, 0, sizeof b);
    b.v = v;
    SupIo io = {&b, b_ord_activate, b_ord_deactivate, b_module_running, b_start_module, b_stop_module,
                b_claim_priority, b_release_priority, b_set_param, b_connect, b_disconnect, b_subscribe, b_unsubscribe,
                b_notify, b_start_function, b_stop_function, b_trace, b_share_module, b_lock_module,
                b_rule, b_action, b_module_run_ended, b_last_trace_time};
    char err[512] = "";
    /* A request to a module whose mailbox is full is kept and sent as soon as it has room
       (ContractSetQueuedSends), for up to 2 s, while the supervisor goes on: its requests are
       one-off transitions (start or stop a module, activate or undo a schema, parameterize,
       connect), each lost one leaving the architecture in a state its rules never chose (an undo
       lost keeps a module running, a deactivation lost keeps a schema), and nothing repeats
       them, as ORD's next cycle repeats a release (ORD drops instead: ord_main.c); and waiting
       for room, as libmodule does by default, would stop the supervisor reading anything for up
       to 2 s per request: its rules' events, its timers, the other modules' requests (one module
       stuck in its exec region, its mailbox full, held the supervisor, whose own mailbox then
       filled, so that every module posting events to it waited too). Requests to one module
       keep their order; a request still not sent after 2 s fails (`error: ... mailbox full`). */
    ContractSetQueuedSends(1);
    ContractSetKeptSendFailed(kept_send_failed);
    holds_before_block(prio_requests_settle);
    SupCore *c = sup_core_create(v, &io, err, sizeof err);
    if (!c) {
        fprintf(stderr, "%s: %s\n", v && v->name ? v->name : "supervisor", err);
        return 2;
    }
    RequestMessage *m = malloc(sizeof *m);
    if (!m) {
        sup_core_destroy(c);
        return 2;
    }
    int rc = 0;
    const EngineClock clock = {c, sup_next_deadline, sup_advance};
    int64_t now = 0;
    for (;;) {
        if (engine_next_request(m, &clock, &now) < 0) {
            rc = 1;
            break;
        }
        switch (m->Type) {
        case REQ_START: handle_start(c, v, m, now); break;
        case REQ_STOP: {
            char fn[CONTRACT_FUNCTION_MAX] = "";
            engine_data_string(m, fn, sizeof fn);
            int ok = 1;
            if (fn[0]) ok = sup_core_stop_function_for(c, now, fn, m->Sender, (uint32_t)m->Param.Stop.AckID) == 0;
            else stop_all(c, v, now);
            SendAck(m->Param.Stop.ModAck[0] ? m->Param.Stop.ModAck : m->Sender, m->Param.Stop.WantedAck,
                    ok ? ACK_STOPPED : ACK_NOTDONE, m->Param.Stop.AckID);
            break;
        }
        case REQ_KILL:
            stop_all(c, v, now);
            SendAck(m->Param.Kil.ModAck[0] ? m->Param.Kil.ModAck : m->Sender, m->Param.Kil.WantedAck,
                    ACK_KILLED, m->Param.Kil.AckID);
            goto out;
        case REQ_EVENT:
            if (strcmp(m->Param.Event.sourceModule, "ORD") == 0) {
                char name[CONTRACT_STRING_SIZE] = "";
                engine_data_string(m, name, sizeof name);
                sup_core_ord_event(c, now, m->Param.Event.sourcePort, name);
            } else {
                /* the delivery, as a module's GetEventId records it (the trace's event flows), written
                   once the rules have seen it, with its value and what it changed: `rules=0` is an
                   event no rule waited for (a rule's `status == "lost"` and a "lsot" sent), and
                   taken_ns: when the engine took it, before the rule changes it made */
                const RTIME taken = GetTime();
                int changed = sup_core_module_event(c, now, m->Param.Event.sourceModule, m->Param.Event.sourcePort,
                                                    m->Param.Event.targetPort, m->Data, m->DataSize);
                char value[ACTION_VALUE_MAX];
                sup_core_format_event_value(c, m->Param.Event.targetPort, m->Data, m->DataSize, value, sizeof value);
                char detail[ACTION_VALUE_MAX + 96];
                snprintf(detail, sizeof detail, "from_port=%d latency_ns=%lld taken_ns=%lld rules=%d value=%s",
                         m->Param.Event.sourcePort, (long long)(m->ReceptionTime - m->ProductionTime), (long long)taken,
                         changed, value);
                ContractLog("event_received", m->Param.Event.sourceModule, m->Param.Event.targetPort, m->DataSize, detail);
            }
            break;
        case REQ_SUB_EVENT:
            add_subscriber(&b, m->Param.SubscribeEvent.targetModule, m->Param.SubscribeEvent.targetPort,
                           m->Param.SubscribeEvent.sourcePort, m->Param.SubscribeEvent.mode);
            break;
        case REQ_UNSUB_EVENT:
            remove_subscriber(&b, m->Param.UnsubscribeEvent.targetModule,
                              m->Param.UnsubscribeEvent.targetPort, m->Param.UnsubscribeEvent.sourcePort);
            break;
        case REQ_PRIORITY_REPLY: /* a module's answer to a priority change of ours */
            prio_request_answered(m);
            break;
        case REQ_ACK: /* another supervisor's answer to an `activate supervisor` of ours */
            if (m->Param.Ack.AckID > 0 && (m->Param.Ack.Ack & (ACK_START | ACK_NOTDONE)))
                sup_core_function_answer(c, now, m->Param.Ack.Module, (uint32_t)m->Param.Ack.AckID,
                                         m->Param.Ack.Ack == ACK_START);
            break;
        default: /* data requests: nothing to do */
            break;
        }
    }
out:
    /* a supervisor stopped alone (not the run) still records the claims it made and restores
       what its undos asked for; at the end of a run the modules are being stopped too */
    if (!ContractRunStopping()) prio_requests_settle();
    free(m);
    sup_core_destroy(c);
    ContractSayRepeats(&cannot_lines);
    return rc;
}
