/*
 * sup_core.h — the supervisor rule engine's deterministic core (docs/semantics.md "Event schemas: ...", "Supervisors: ...").
 *
 * No I/O and no clock of its own: the caller passes the time of every input (virtual clock in
 * tests, CLOCK_MONOTONIC in sup_main.c) and the core acts on the world only through SupIo.
 * Timed events (`elapsed`, `duration`) are timers the caller fires by calling
 * sup_core_advance(); sup_core_next_deadline() says when the next one is due.
 *
 * Every input (module event, ORD event, start/stop of a function, timer) is processed to
 * completion, including the `started`/`endof` events it produces (queued behind it), before
 * the call returns. Calls must pass non-decreasing times.
 */
#ifndef CONTRACT_SUP_CORE_H
#define CONTRACT_SUP_CORE_H

#include <stddef.h>
#include <stdint.h>

#include "contract/vocabulary.h"

/** What the core asks of the world. Every callback may be NULL (then the action is a no-op). */
typedef struct SupIo {
    void *ctx;
    /* periodic schemas: requests to ORD; `activation_id` identifies this activation (the
       matching deactivation carries the same id) */
    void (*ord_activate)(void *ctx, const ContractSchema *s, const void *params, size_t size,
                         uint32_t activation_id);
    void (*ord_deactivate)(void *ctx, const ContractSchema *s, uint32_t activation_id);
    /* modules (event schemas, activate resttime/critical module, parameterize) */
    int (*module_running)(void *ctx, const char *module);               /* 1 running, 0 not  */
    void (*start_module)(void *ctx, const char *module, int priority);
    void (*stop_module)(void *ctx, const char *module);   /* only modules it started itself */
    /* priority of a running module (`activate resttime|critical module`): claim `id` sets it
       (0 applied, -1 not: nothing to release); its release restores the priority before it
       only if no later claim on that module, of any supervisor, still stands (sup_claims.h) */
    int (*claim_priority)(void *ctx, const char *module, uint32_t id, int priority);
    void (*release_priority)(void *ctx, const char *module, uint32_t id);
    /* port_name: the parameter port's name (ContractParamSetting.name), NULL when the tables have none */
    void (*set_param)(void *ctx, const char *module, int port, const char *port_name, const void *value,
                      size_t size, const ContractType *type);
    void (*connect_events)(void *ctx, const ContractEventFlow *flow);
    void (*disconnect_events)(void *ctx, const ContractEventFlow *flow);
    /* the supervisor's own event ports */
    /* id: the supervisor's number for this subscription (one counter with its activations),
       named again by its unsubscribe */
    void (*subscribe)(void *ctx, const char *module, int src_port, int in_port,
                      ContractEventMode mode, uint32_t id);
    void (*unsubscribe)(void *ctx, const char *module, int src_port, int in_port, uint32_t id);
    void (*notify)(void *ctx, int out_port, const ContractType *type, const void *value,
                   size_t size);
    /* other supervisors' functions (own functions are handled inside the core).
       `activation_id` (> 0, unique in this supervisor) names this activation: the callee
       answers it (sup_core_function_answer) and the undo's stop carries it, so that the callee
       stops the function only if it runs this very activation, never one that another caller
       started (docs/engines.md §4). start returns 0 when sent, -1 when it could not be sent
       (taken as refused: its undo stops nothing) */
    int (*start_function)(void *ctx, const ContractFunctionSignature *callee,
                          const void *params, size_t size, uint32_t activation_id);
    void (*stop_function)(void *ctx, const char *supervisor, const char *function,
                          uint32_t activation_id);
    /* one line per rule transition, function start/stop, refusal, ignored input */
    void (*trace)(void *ctx, int64_t t, const char *line);
    /* an event schema of this supervisor uses (`hold` 1) or stops using (0) a module that was
       already running when it was activated (started by someone else): lets the binding keep
       it running until its last user across supervisors is done
       (docs/semantics.md "Event schemas: undo and shared modules") */
    void (*share_module)(void *ctx, const char *module, int hold);
    /* makes each decide-and-act sequence on a module atomic across supervisors: `lock` 1
       before "is it running? then share it, else start it" and before "stop it / stop sharing
       it", 0 right after (the binding: a flock, module_holds.h) */
    void (*lock_module)(void *ctx, const char *module, int lock);
    /* a rule became active (1) or inactive (0) at t, with the event that caused it, in the
       grammar of docs/runtime-api.md "Trace records": `MAA:2 value="disconnected"`,
       `ORD:1 value="S"`, `started(L)`, `endof(L)`, `duration(L)=Nns`, `elapsed=Nns`, `stop`
       (the function stopped). NULL: none; the readable line stays in trace */
    void (*rule)(void *ctx, int64_t t, const char *function, const char *rule, int active,
                 const char *cause);
    /* an action or undo that no call above carries, for the binding to log with the others
       (docs/runtime-api.md "Trace records", `supervisor`): `activate schema S() (event schema)` (its values in the parentheses),
       `undo: deactivate schema S (event schema)` (before the holds and flows they take or drop),
       `compute f` (after the call). NULL: none */
    void (*action)(void *ctx, int64_t t, const char *line);
    /* a module this supervisor started and still holds, needed by one more of its rules or
       schemas: 1 when the run it started has ended by the module's own code since (an
       asynchronous module's exec region set `*stateindex = -1`: it no longer runs, its START
       taken), 0 when it still runs or that is not known; on 1 the core starts it again, as it
       starts a module not running (docs/engines.md). NULL: never asked (a held module is taken
       for running) */
    int (*module_run_ended)(void *ctx, const char *module);
    /* the time of the last trace line written (the binding's clock, read as it writes the line):
       a function's clock starts at its `function F(...) started` line's time, so that
       `elapsed=t` counts from the time the trace shows, not from the reading of the START before
       it (a supervisor preempted between the two showed an `elapsed=2ms` rule active 1.78 ms after
       that line). NULL: the core's time (the simulator's virtual time) */
    int64_t (*last_trace_time)(void *ctx);
} SupIo;

typedef struct SupCore SupCore;

/** Creates a core for checked tables. Returns NULL (and a message in err) on invalid tables
 *  or out of memory. */
SupCore *sup_core_create(const ContractSupervisorVocabulary *v, const SupIo *io, char *err,
                         size_t errlen);
void sup_core_destroy(SupCore *c);

/** Starts function `name` at time t with a parameter block laid out as its params (NULL:
 *  defaults), for a control tool (any stop ends it). Returns 0, or -1 if unknown or already
 *  running (refused, traced). */
int sup_core_start_function(SupCore *c, int64_t t, const char *name, const void *params,
                            size_t size);
/** Same, for activation `activation_id` of supervisor `caller` (`activate supervisor`): the
 *  function then belongs to that activation, and only a stop naming it (or a stop with id 0)
 *  ends it. Returns 0, -1 when the supervisor has no such function (traced `refused: no
 *  function F`), -2 when it is already running (traced `refused: function F already running`). */
int sup_core_start_function_for(SupCore *c, int64_t t, const char *name, const void *params,
                                size_t size, const char *caller, uint32_t activation_id);
/** Same, with parameters in text form `p1={1.0,2.0,3.0} p2="x"` (control tools). -1 when the
 *  request names no function or parameter of it or a value cannot be read (not traced: the
 *  caller says it), -2 when the function is already running (traced `refused: function F already
 *  running`); a message in err either way. */
int sup_core_start_function_text(SupCore *c, int64_t t, const char *name, const char *args,
                                 char *err, size_t errlen);
/** Stops a running function: its active rules are deactivated (undos run). 0 or -1. */
int sup_core_stop_function(SupCore *c, int64_t t, const char *name);
/** The undo of activation `activation_id` of `caller`: stops `name` only if it runs that
 *  activation (id 0: whichever runs). 0, or -1 (not running, or another activation: traced
 *  `ignored: ...`, the function goes on). */
int sup_core_stop_function_for(SupCore *c, int64_t t, const char *name, const char *caller,
                               uint32_t activation_id);
/** The answer of `supervisor` to this core's activation `activation_id` (accepted 1 /
 *  refused 0). A refused activation's undo stops nothing. Unknown ids are ignored. */
void sup_core_function_answer(SupCore *c, int64_t t, const char *supervisor,
                              uint32_t activation_id, int accepted);
int sup_core_function_running(const SupCore *c, const char *name);

/** An event from `module`'s out port `src_port` with its data. in_port >= 0 names the
 *  supervisor in port it arrived on; -1: found from the active subscriptions. Events on no
 *  active subscription are ignored (traced). Returns the rule changes it made (rules turned
 *  active or inactive, those of the rules it ended included): 0 when it changed no rule. */
int sup_core_module_event(SupCore *c, int64_t t, const char *module, int src_port, int in_port,
                          const void *data, size_t size);
/** The value of an event that arrived on in port `in_port`, as a rule's cause writes it
 *  (engine_format_value with the port's type: `"lost"`, `12`, `{x=1.5,mode=AUTO}`); `?` for an
 *  unknown port or fewer bytes than its type holds. */
void sup_core_format_event_value(const SupCore *c, int in_port, const void *data, size_t size, char *buf,
                                 size_t len);
/** An ORD event (port 0: deadline miss, 1: conflict) carrying a schema name. */
void sup_core_ord_event(SupCore *c, int64_t t, int port, const char *schema);

/** Fires every timer due at or before t (in time order), then sets the clock to t. */
void sup_core_advance(SupCore *c, int64_t t);
/** 1 and the earliest timer deadline in *deadline, or 0 when no timer is armed. */
int sup_core_next_deadline(const SupCore *c, int64_t *deadline);

/** Introspection for tests and logs. */
int sup_core_rule_active(const SupCore *c, const char *function, const char *label);
const void *sup_core_local(const SupCore *c, const char *function, const char *local);
const void *sup_core_in_port_value(const SupCore *c, int port);
/** Number of events processed since creation (all kinds). */
uint64_t sup_core_events_processed(const SupCore *c);

#endif
