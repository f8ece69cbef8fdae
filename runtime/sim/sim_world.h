/*
 * sim_world.h — the simulator's world (docs/simulation.md §2): every supervisor core and the ORD
 * core of a project, driven on one virtual clock, with virtual modules and the messages between
 * engines. The semantics are entirely the cores' (sup_core.c, ord_core.c); this file only
 * delivers their requests to each other, in order, at the virtual instant they were sent.
 *
 * Deterministic: the same calls in the same order give the same records, byte for byte.
 */
#ifndef CONTRACT_SIM_WORLD_H
#define CONTRACT_SIM_WORLD_H

#include <stddef.h>
#include <stdint.h>

#include "contract/vocabulary.h"
#include "ord_core.h"

typedef struct SimWorld SimWorld;

/** What the world reports while it runs (any callback may be NULL). Times are virtual ns. */
typedef struct SimSink {
    void *ctx;
    /* a rule of a supervisor became active / inactive, with its cause (the `sup_rule` record) */
    void (*rule)(void *ctx, int64_t t, const char *sup, const char *function, const char *rule,
                 int active, const char *cause);
    /* an action an engine took on the world, in words: "SUP: activate schema schemaCommande1" */
    void (*action)(void *ctx, int64_t t, const char *who, const char *what);
    /* a readable trace line of a core ("SUP", "ORD") */
    void (*log)(void *ctx, int64_t t, const char *who, const char *line);
    /* a typed trace record, as a real run's CSV log of `module` holds it (docs/runtime-api.md
       "Trace records"; port -1: none): ORD's ord_release / ord_finished / ord_complete /
       ord_deadline_miss, a virtual module's run_started / run_finished for each release, a
       supervisor's event_received for each event delivered to it (once its rules have seen it,
       with taken_ns, rules and value as sup_main.c writes them) */
    void (*record)(void *ctx, int64_t t, const char *module, const char *event, const char *peer,
                   int port, const char *detail);
} SimSink;

/** Creates the world for `nsups` supervisor tables and ORD's (NULL: no scheduler). NULL and a
 *  message in err when a table is invalid or memory runs out. */
SimWorld *sim_world_create(const ContractSupervisorVocabulary *const *sups, int nsups,
                           const ContractOrdVocabulary *ord, const SimSink *sink, char *err,
                           size_t errlen);
void sim_world_destroy(SimWorld *w);

/** Runs every timer, tick, deadline and module completion due at or before t, in time order
 *  (completions, then ORD, then supervisors at one instant), with the messages they cause. */
void sim_world_advance(SimWorld *w, int64_t t);
/** The virtual time reached. */
int64_t sim_world_now(const SimWorld *w);

/* ---- scripted inputs, at the current time (call sim_world_advance(w, t) first) ---- */

/** A control tool starts SUP.fn with parameters in text form (`p={1.0,2.0,3.0},q=3`). -1 and a
 *  message when refused or unparsable. */
int sim_world_start(SimWorld *w, const char *sup, const char *fn, const char *args, char *err,
                    size_t errlen);
int sim_world_stop(SimWorld *w, const char *sup, const char *fn, char *err, size_t errlen);
/** Module (or supervisor, or "ORD") `module` emits on out event port `port` the value written
 *  in `value_text` (Cactal value syntax; empty: the type's default). Returns the number of
 *  supervisors and asynchronous modules (through a connected event flow) it was delivered to, or
 *  -1 and a message (unparsable value, crashed module). */
int sim_world_event(SimWorld *w, const char *module, int port, const char *value_text, char *err,
                    size_t errlen);
/** The module crashes: not running, never acks a release again (also one not started yet). -1 and
 *  a message when it has crashed already. */
int sim_world_crash(SimWorld *w, const char *module, char *err, size_t errlen);
/** The asynchronous module's code returns: its run ends (run_finished), it no longer runs; its
 *  holders keep their holds (the last one's STOP finds no run), and a supervisor that needs it later starts it again. -1 and a
 *  message when it is not running. */
int sim_world_finish(SimWorld *w, const char *module, char *err, size_t errlen);
/** Each run of the asynchronous module started from now on (once: the next one only) ends
 *  run_ns after its start, by its own code as sim_world_finish ends it (unless stopped first). */
void sim_world_set_run_time(SimWorld *w, const char *module, int64_t run_ns, int once);
/** Execution time of a synchronous module's releases from now on (once: the next one only). */
void sim_world_set_exec(SimWorld *w, const char *module, int64_t exec_ns, int once);

/* ---- state ---- */
/** 1 active, 0 inactive, -1 unknown supervisor/function/rule. */
int sim_world_rule_active(const SimWorld *w, const char *sup, const char *fn, const char *rule);
/** 1 running, 0 not, -1 unknown. */
int sim_world_function_running(const SimWorld *w, const char *sup, const char *fn);
/** 1 active (periodic: in ORD; event: an active rule of a running function activated it). */
int sim_world_schema_active(const SimWorld *w, const char *schema);
int sim_world_module_running(const SimWorld *w, const char *module);
/** ORD's figures of periodic schema `schema` since the simulation started (ord_core_stats):
 *  0, or -1 when ORD has no such schema. */
int sim_world_schema_stats(const SimWorld *w, const char *schema, OrdSchemaStats *out);
/** The local `name` of running SUP.fn with its type, or NULL. */
const void *sim_world_local(const SimWorld *w, const char *sup, const char *fn, const char *name,
                            const ContractType **type);

/** Calls fn for each active schema, in table order (periodic ones of ORD first). */
void sim_world_each_active_schema(const SimWorld *w, void (*fn)(void *ctx, const char *schema),
                                  void *ctx);
/** Calls fn for each local of each running function. */
void sim_world_each_local(const SimWorld *w,
                          void (*fn)(void *ctx, const char *sup, const char *function,
                                     const char *local, const ContractType *type, const void *v),
                          void *ctx);

/** Events processed by every core since creation (the benchmark's count). */
uint64_t sim_world_events_processed(const SimWorld *w);

#endif
