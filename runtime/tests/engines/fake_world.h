/*
 * fake_world.h — a scripted world for the engines' cores: implements SupIo and OrdIo by
 * recording every effect as one line of a TestLog, keeps which modules run (and at which
 * priority), and a message bus between several supervisor cores (start/stop of functions,
 * notifications to subscribers) delivered only when the test says so, like separate
 * processes would.
 */
#ifndef ENGINES_TEST_FAKE_WORLD_H
#define ENGINES_TEST_FAKE_WORLD_H

#include "harness.h"
#include "ord_core.h"
#include "sup_claims.h"
#include "sup_core.h"

#define FW_MAX 32

typedef struct FakeBus FakeBus;

typedef struct FakeWorld {
    const char *name;        /* prefix of its log lines ("SUP: "), NULL for none */
    TestLog *log;
    FakeBus *bus;            /* NULL: no other supervisor */
    int nrunning;
    char running[FW_MAX][16];
    int prio[FW_MAX];
    /* ORD releases in order: module and release id (the AckID a real module answers with) */
    int nrel;
    char rel_module[256][16];
    uint32_t rel_id[256];
    /* SupIo.lock_module: the module locked now ("" none), locks taken, and starts, stops and
       shares of a module done while it was not locked (the binding needs them locked) */
    char locked[16];
    int nlocks, unlocked_effects;
    /* priority claims (SupIo.claim_priority), decided by sup_claims.c as the binding does;
       `modules` (NULL: itself) is the world whose modules and claims they act on, so that
       several supervisors can share them */
    struct FakeWorld *modules;
    SupClaims prio_claims;
    /* SupIo.action lines (event schemas, compute) go to the log too when set (off by default:
       most tests check the effects only) */
    int log_actions;
    /* OrdIo.module_gone: the modules no longer running (fake_set_gone), and the sentence of the
       last OrdIo.stuck call */
    int ngone;
    char gone[FW_MAX][16];
    char stuck_message[400];
    /* OrdIo.module_activity: the modules that can be looked at (fake_set_activity): each look
       answers `state`, a CPU time `cpu_step_ns` and a wait for a CPU `wait_step_ns` further than
       the last look's (a negative wait step: the wait is unknown) */
    int nact;
    char act_module[FW_MAX][16];
    char act_state[FW_MAX];
    char act_waiting_in[FW_MAX][32]; /* the wchan each look answers (fake_set_waiting_in), "" by default */
    int64_t act_written_step[FW_MAX], act_written[FW_MAX]; /* bytes written further at each look (-1: unknown, the default) */
    int64_t act_step[FW_MAX], act_cpu[FW_MAX], act_wait_step[FW_MAX], act_wait[FW_MAX];
    int act_looks[FW_MAX];
    /* SupIo.module_run_ended: the modules whose run ended by their own code (fake_end_own_run),
       until started again */
    int nended;
    char ended[FW_MAX][16];
    /* ORD's clock as its set-up sees it (fake_setup_done_at): each parameter and connection ORD
       sends moves it `ord_request_ns` further (a loaded machine) */
    int64_t ord_clock, ord_request_ns;
} FakeWorld;

SupIo fake_sup_io(FakeWorld *w);
/** A supervisor core on a cleared world that records into `log`; NULL (error on stderr) if refused. */
SupCore *fake_make_sup(FakeWorld *w, TestLog *log, const ContractSupervisorVocabulary *v, const char *name);
OrdIo fake_ord_io(FakeWorld *w);
/** OrdIo.setup_done_at over a FakeWorld (not set by fake_ord_io): its ord_clock, which each
 *  parameter and connection ORD sent moved `ord_request_ns` further. */
int64_t fake_setup_done_at(void *ctx);
/** Marks a module as already running (started by someone else) at a priority. */
void fake_set_running(FakeWorld *w, const char *module, int priority);
int fake_is_running(const FakeWorld *w, const char *module);
/** The run of a module ends by its own code: it no longer runs, and SupIo.module_run_ended
 *  says so until it is started again. */
void fake_end_own_run(FakeWorld *w, const char *module);
/** Marks a module as no longer running (crashed or killed): OrdIo.module_gone says so. */
void fake_set_gone(FakeWorld *w, const char *module);
/** Lets OrdIo.module_activity look at `module`: in scheduler state `state`, its CPU time going
 *  `cpu_step_ns` further at each look and its wait for a CPU `wait_step_ns` (< 0: unknown). */
void fake_set_activity(FakeWorld *w, const char *module, char state, int64_t cpu_step_ns, int64_t wait_step_ns);
/** The kernel function `module`'s looks say it sleeps in (its wchan: `anon_pipe_write`), after fake_set_activity. */
void fake_set_waiting_in(FakeWorld *w, const char *module, const char *wchan);
/** `module`'s looks say it wrote `written_step` bytes more than at the last look (-1: unknown), after fake_set_activity. */
void fake_set_written(FakeWorld *w, const char *module, int64_t written_step);
/** How many times OrdIo.module_activity looked at `module`. */
int fake_activity_looks(const FakeWorld *w, const char *module);
/** The id of the latest ORD release of `module` (0: never released). */
uint32_t fake_last_release(const FakeWorld *w, const char *module);
/** Formats a value for log lines: ints, floats (%g), strings, TypeA {i,j,k}, TypeD {name,v}. */
void fake_format(char *out, size_t n, const ContractType *t, const void *v);

/* ---- bus between supervisor cores ---- */
FakeBus *fake_bus_create(void);
void fake_bus_destroy(FakeBus *b);
void fake_bus_attach(FakeBus *b, const char *name, SupCore *core);
/** Delivers every pending message (and those their processing sends) at time t. Returns
 *  the number delivered. */
int fake_bus_deliver(FakeBus *b, int64_t t);

#endif
