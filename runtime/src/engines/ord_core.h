/*
 * ord_core.h — the scheduler's deterministic core (docs/semantics.md "Scheduler: ...").
 *
 * Like sup_core, it has no I/O and no clock: the caller passes times (virtual in tests,
 * CLOCK_MONOTONIC in ord_main.c), reports module completions, and fires the core's deadlines
 * with ord_core_advance(); ord_core_next_deadline() says when the next tick or critical-delay
 * check is due. Releases happen at absolute times tick_k = tick_0 + k * PERIOD (no drift), tick_0
 * being when the activation is set up (OrdIo.setup_done_at).
 */
#ifndef CONTRACT_ORD_CORE_H
#define CONTRACT_ORD_CORE_H

#include <stddef.h>
#include <stdint.h>

#include "contract/vocabulary.h"
#include "ord_stuck_cause.h"

/** A fact of the periodic timeline, for the run-time trace (docs/runtime-api.md "Trace
 *  records"): times are the core's clock, `cycle` is k of tick_k = activation + k * PERIOD. */
typedef enum OrdFactKind {
    ORD_FACT_RELEASE = 1,   /* a module of the cycle released (module, release_id)             */
    ORD_FACT_FINISHED,      /* a released module acked its release (module, response_ns)       */
    ORD_FACT_COMPLETE,      /* every module of the cycle finished (response_ns)                 */
    ORD_FACT_DEADLINE_MISS  /* the cycle was not finished at tick + CRITICAL_DELAY (ORD:0)      */
} OrdFactKind;

typedef struct OrdFact {
    OrdFactKind kind;
    const char *schema;
    const char *module;     /* RELEASE / FINISHED; NULL otherwise                              */
    long cycle;
    int64_t tick;           /* the cycle's tick                                                */
    uint32_t release_id;    /* RELEASE / FINISHED                                              */
    int64_t response_ns;    /* FINISHED / COMPLETE: time since the tick                        */
    int64_t critical_delay_ns; /* the schema's CRITICAL_DELAY (DEADLINE_MISS writes it)           */
} OrdFact;

/** The record a fact is in a run's CSV log (docs/runtime-api.md "Trace records"): returns its
 *  event name (`ord_release`, `ord_finished`, `ord_complete`, `ord_deadline_miss`) and writes its
 *  detail into `detail`; the record's peer is f->module (empty when NULL). One format for the
 *  real ORD's log and the simulator's trace. */
const char *ord_fact_record(const OrdFact *f, int64_t t, char *detail, size_t n);

typedef struct OrdIo {
    void *ctx;
    /* port_name: the parameter port's name (ContractParamSetting.name), NULL when the tables have none */
    void (*set_param)(void *ctx, const char *module, int port, const char *port_name, const void *value,
                      size_t size, const ContractType *type);
    void (*connect_data)(void *ctx, const ContractDataFlow *flow);
    void (*disconnect_data)(void *ctx, const ContractDataFlow *flow);
    /* start one activation (one cycle) of a synchronous module; release_id (never 0) names
       this release: the caller sends it as the AckID and reports the module's ack with
       ord_core_release_finished(..., release_id) */
    void (*release)(void *ctx, const char *module, const char *schema, int64_t tick,
                    uint32_t release_id);
    /* ORD:0 / ORD:1 with the schema name, to every supervisor of the tables */
    void (*emit)(void *ctx, int port, const char *schema);
    /* answer to an activation / deactivation request: ok = 1 done, 0 refused */
    void (*ack)(void *ctx, const char *requester, uint32_t activation_id, int ok);
    void (*trace)(void *ctx, int64_t t, const char *line);
    /* a released module has not finished its release `release_id` after `periods` periods of
       its schema (ORD_STUCK_PERIODS, at least ORD_STUCK_MIN_NS): called once per release, with
       the sentence to show, the `stuck: ` trace line's ("MSC has not finished release #2 after
       10 periods: does its exec region set *stateindex = -1?", "...: it is no longer running
       (it crashed or was killed)" when module_gone says so, or the cause module_activity shows:
       ord_stuck_cause.h). Optional (NULL: the trace line only). */
    void (*stuck)(void *ctx, const char *module, const char *schema, uint32_t release_id,
                  long periods, const char *message);
    /* typed facts of the timeline at time t (NULL: none); the readable lines stay in trace */
    void (*fact)(void *ctx, int64_t t, const OrdFact *f);
    /* 1 when `module` is no longer running (it crashed or was killed), else 0: asked when one of
       its releases is reported stuck, whose sentence then says so instead of the advice about
       its exec region, which fits only a module that runs on. Optional (NULL: never asked). */
    int (*module_gone)(void *ctx, const char *module);
    /* a look at a running module's main thread (ord_stuck_cause.h): its state and CPU time, 0
       when read. Asked for a release not finished half way to its stuck report, and at the
       report, whose sentence then says whether the module was running, waiting or starved
       instead of the bare advice. Optional (NULL: never asked; the advice). */
    int (*module_activity)(void *ctx, const char *module, OrdModuleActivity *out);
    /* the time now, read once an activation's set-up (its parameters and connections, sent by
       set_param and connect_data) is done: the schema's tick 0 is then, not at the request, so
       that ORD's own set-up, slow on a loaded machine, is not counted against cycle 0's
       CRITICAL_DELAY (docs/semantics.md "Scheduler: ticks at absolute time"). Optional (NULL: the
       set-up takes no time, tick 0 is the activation's t: a virtual clock). */
    int64_t (*setup_done_at)(void *ctx);
} OrdIo;

/* A release not finished after this many periods of its schema, and at least ORD_STUCK_MIN_NS
   (short periods: a loaded machine may stall a module for a few periods without it being
   stuck), is reported once as stuck (docs/engines.md §4). */
#define ORD_STUCK_PERIODS 10
#define ORD_STUCK_MIN_NS 1000000000LL

/** Figures of one schema since the core was created. */
typedef struct OrdSchemaStats {
    long cycles;            /* cycles released                                         */
    long completed;         /* cycles whose every module finished                      */
    long deadline_misses;   /* cycles not finished at tick + CRITICAL_DELAY (ORD:0)    */
    long late_releases;     /* cycles ORD itself released at or past tick + CRITICAL_DELAY
                               (real time only): not finished then, but no ORD:0, its
                               modules had no time (`late release: ...`)                 */
    long overruns;          /* ticks skipped because the previous cycle still ran      */
    long missed_ticks;      /* ticks that passed while ORD could not run at all         */
    int64_t max_response_ns;/* longest tick -> last module finished                    */
    long held_cycles;       /* cycles whose releases waited for a module still running a
                               release of an earlier activation                          */
    long late_acks;         /* acks of releases of earlier cycles/activations (ignored)  */
    long stuck_releases;    /* releases reported stuck (OrdIo.stuck)                      */
} OrdSchemaStats;

typedef struct OrdCore OrdCore;

OrdCore *ord_core_create(const ContractOrdVocabulary *v, const OrdIo *io, char *err, size_t errlen);
void ord_core_destroy(OrdCore *c);
/** ORD stops (the end of a run): a cycle still running that skipped more than one release says
 *  how many, as one that ends does, so that the trace gives ORD's count of overruns whole. */
void ord_core_stop(OrdCore *c);

/** Activates schema `name` at time t with its parameter block (NULL: defaults). Refused (and
 *  ORD:1 emitted) if it shares a module with an active schema, including itself. The first
 *  cycle (tick 0) is released once the set-up is done: at OrdIo.setup_done_at's time (t when
 *  NULL). Returns 0 when activated, -1 when refused or unknown. */
int ord_core_activate(OrdCore *c, int64_t t, const char *name, const void *params, size_t size,
                      const char *requester, uint32_t activation_id);
/** Deactivates it (no further release, flows disconnected). activation_id 0 matches any;
 *  otherwise requester and id must be those of the activation (a refused activation's undo
 *  does not deactivate someone else's, even one of another supervisor with the same id).
 *  Returns 0, or -1 if not active / not that activation. */
int ord_core_deactivate(OrdCore *c, int64_t t, const char *name, const char *requester,
                        uint32_t activation_id);
/** A released module finished the activation `release_id` (the AckID of its ack) at time t.
 *  Acks are matched to the release that asked for them: the ack of a release of an earlier
 *  cycle or of a deactivated activation never completes the current cycle (it only frees the
 *  module), and an ack that matches no outstanding release is ignored. */
void ord_core_release_finished(OrdCore *c, int64_t t, const char *module, uint32_t release_id);
/** Same for the release of `module` in its schema's current cycle (tests, simple callers). */
void ord_core_module_finished(OrdCore *c, int64_t t, const char *module);
/** Fires every tick and critical-delay check due at or before t, in time order. */
void ord_core_advance(OrdCore *c, int64_t t);
/** 1 and the next deadline, or 0 when nothing is active. */
int ord_core_next_deadline(const OrdCore *c, int64_t *deadline);

/** Real-time mode (ord_main.c): when ORD itself ran so late that a later tick is already due,
 *  the overtaken ticks are counted as missed instead of released back to back, and a cycle it
 *  releases at or past its tick + CRITICAL_DELAY (its modules had no time) misses that deadline
 *  without ORD:0 (`late release: ...`, OrdSchemaStats.late_releases). Off by default (virtual
 *  clock: every tick is processed at its time). */
void ord_core_set_skip_late_ticks(OrdCore *c, int on);

int ord_core_schema_active(const OrdCore *c, const char *name);
int ord_core_stats(const OrdCore *c, const char *name, OrdSchemaStats *out);

#endif
