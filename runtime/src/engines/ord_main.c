/*
 * ord_main.c — binds the scheduler core (ord_core.c) to libmodule.
 *
 * Requests ORD understands (see docs/engines.md):
 *  - REQ_START, Function = schema name, Data = CONTRACT_BINARY_ARGS_MAGIC + parameter block
 *    (or nothing: defaults), AckID = activation id -> activate (ack ACK_START / ACK_NOTDONE);
 *  - REQ_STOP, Data = schema name (empty: every active schema), AckID = the activation id
 *    (0: any) -> deactivate (ack ACK_STOPPED / ACK_NOTDONE);
 *  - REQ_ACK from a released module (ACK_FINISHED, or ACK_STOPPED/ACK_NOTDONE: the module
 *    did not run), AckID = the release id the core gave that release -> the module finished
 *    that activation (an ack of an earlier cycle's or activation's release never completes
 *    the current cycle: ord_core_release_finished);
 *  - REQ_KILL -> ORD ends.
 * Releases are REQ_START requests to the modules with ACK_FINISHED wanted, sent at absolute
 * CLOCK_MONOTONIC ticks (engine_wait: timerfd, TFD_TIMER_ABSTIME). ORD:0 / ORD:1 go to every
 * supervisor of the tables as REQ_EVENT from source port 0 / 1 (target port -1), Data = the
 * schema name as a Cactal string (char[256]).
 *
 * CONTRACT_ORD_STATS=<file>: at exit, ORD writes there a JSON object with its release
 * lateness figures (used by the benchmark).
 */
#define _POSIX_C_SOURCE 200809L
#include <ctype.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <limits.h>
#include <unistd.h>

#include "contract/vocabulary.h"
#include "engine_values.h"
#include "engine_wait.h"
#include "engine_wire.h"
#include "libmodule/libmodule.h"
#include "log_engine.h"
#include "ord_core.h"

typedef struct OrdBinding {
    const ContractOrdVocabulary *v;
    /* reply address of the request being handled (acks) */
    const char *reply_to;
    int reply_wanted;
    /* release lateness samples (first release of each cycle), for CONTRACT_ORD_STATS */
    int record;
    int64_t *late;
    size_t nlate, caplate;
    const char *last_schema[64];
    int64_t last_tick[64];
} OrdBinding;

/* the core's deadlines, for engine_next_request */
static int ord_next_deadline(const void *core, int64_t *deadline) { return ord_core_next_deadline(core, deadline); }
static void ord_advance(void *core, int64_t t) { ord_core_advance(core, t); }

/* What ORD does at a schema's activation and deactivation, in the simulator's words
   (runtime/sim/sim_world.c oio_*), as `scheduler` records of its CSV log only (peer = the module):
   `parameterize M:p NAME (N bytes) = V`, `connect A:p -> B:i * k`, `disconnect A:p -> B:i`; logged
   before the request, as a supervisor's actions are. */
static void b_set_param(void *ctx, const char *m, int port, const char *name, const void *v, size_t size,
                        const ContractType *t) {
    (void)ctx;
    char line[ACTION_LINE_MAX];
    engine_format_parameterize(line, sizeof line, m, port, name, v, size, t);
    ContractLog("scheduler", m, -1, 0, line);
    int rc = SendSetParam(m, port, v, size, ACK_NOTHING, 0);
    if (rc != CONTRACT_OK && !ContractPeerGoneAtStop(rc))
        fprintf(stderr, "ORD: cannot set parameter %d of %s: %s\n", port, m, ContractStrError(rc));
}

static void b_connect(void *ctx, const ContractDataFlow *f) {
    (void)ctx;
    char flow[ACTION_LINE_MAX], line[ACTION_LINE_MAX + 32];
    engine_format_data_flow(flow, sizeof flow, f);
    snprintf(line, sizeof line, "connect %s * %d", flow, f->periodicity);
    ContractLog("scheduler", f->src_module, -1, 0, line);
    int rc = SendSubscribe(f->src_module, f->src_port, f->dst_module, f->dst_port, f->periodicity, 1);
    if (rc != CONTRACT_OK && !ContractPeerGoneAtStop(rc))
        fprintf(stderr, "ORD: cannot connect %s:%d -> %s:%d: %s\n", f->src_module, f->src_port,
                f->dst_module, f->dst_port, ContractStrError(rc));
}

static void b_disconnect(void *ctx, const ContractDataFlow *f) {
    (void)ctx;
    char flow[ACTION_LINE_MAX], line[ACTION_LINE_MAX + 16];
    engine_format_data_flow(flow, sizeof flow, f);
    snprintf(line, sizeof line, "disconnect %s", flow);
    ContractLog("scheduler", f->src_module, -1, 0, line);
    SendUnsubscribe(f->src_module, f->src_port, f->dst_module, f->dst_port);
}

static void record_lateness(OrdBinding *b, const char *schema, int64_t tick) {
    int slot = -1;
    for (int i = 0; i < 64; i++) {
        if (b->last_schema[i] == schema) { slot = i; break; }
        if (!b->last_schema[i]) { b->last_schema[i] = schema; b->last_tick[i] = INT64_MIN; slot = i; break; }
    }
    if (slot < 0 || b->last_tick[slot] == tick) return; /* not the first release of this cycle */
    b->last_tick[slot] = tick;
    if (b->nlate == b->caplate) {
        size_t n = b->caplate ? b->caplate * 2 : 16384;
        int64_t *p = realloc(b->late, n * sizeof *p);
        if (!p) return;
        b->late = p;
        b->caplate = n;
    }
    b->late[b->nlate++] = GetTime() - tick;
}

/* the core names every release: that id is the AckID, so each ack is matched to its release */
static void b_release(void *ctx, const char *m, const char *schema, int64_t tick, uint32_t id) {
    OrdBinding *b = ctx;
    if (b->record) record_lateness(b, schema, tick);
    int rc = SendStart(m, ACK_FINISHED | ACK_STOPPED | ACK_NOTDONE, (int)id);
    /* at the run's stop, ORD (stopped with the modules) may tick once more after a module has
       gone: libmodule logs that release as an error record, quietly */
    if (rc != CONTRACT_OK && !ContractPeerGoneAtStop(rc))
        fprintf(stderr, "ORD: cannot release %s (%s): %s\n", m, schema, ContractStrError(rc));
}

static void b_emit(void *ctx, int port, const char *schema) {
    OrdBinding *b = ctx;
    char name[CONTRACT_STRING_SIZE];
    memset(name, 0, sizeof name);
    strncpy(name, schema, sizeof name - 1);
    for (int i = 0; i < b->v->nsupervisors; i++) {
        int rc = SendEvent(b->v->supervisors[i], -1, port, name, sizeof name);
        if (rc != CONTRACT_OK && rc != CONTRACT_EUNKNOWN && !ContractPeerGoneAtStop(rc))
            fprintf(stderr, "ORD: cannot notify ORD:%d to %s: %s\n", port, b->v->supervisors[i],
                    ContractStrError(rc));
    }
}

static void b_ack(void *ctx, const char *requester, uint32_t id, int ok) {
    OrdBinding *b = ctx;
    (void)requester;
    if (b->reply_to) SendAck(b->reply_to, b->reply_wanted, ok ? ACK_START : ACK_NOTDONE, (int)id);
}

/* ORD's lines on stdout, rate-limited as libmodule's error lines are (ContractSay), but by kind:
   a schema missing every deadline of a 1 ms period wrote some 700 lines a second (`deadline miss:
   S cycle 812 (ORD:0)`, `overrun: ...`), a line each of its own numbers, and a run's output is
   bounded (the build service and contract run fail a run past 1 MiB a stream). A line whose kind
   (the line with each number that is not part of a name read as N: `deadline miss: S cycle N
   (ORD:0)`) was printed less than 1 s ago is counted, not printed; the count is said with the
   kind's next print or at ORD's end: `(the same line 249 more times in 1.0 s, in the CSV log
   only: deadline miss: S cycle N (ORD:0))`. The CSV log keeps every line (b_trace). */
#define SAID_KINDS 32
#define SAID_AGAIN_NS 1000000000LL
typedef struct {
    char kind[ACTION_LINE_MAX];
    RTIME said;
    unsigned repeats;
} SaidKind;
static SaidKind said_kinds[SAID_KINDS];
static int n_said_kinds;

/* `line` with each run of digits not inside a name (after a letter, digit, `_` or `:`, as in
   `S1`, `ORD:0`) written `N` */
static void line_kind(const char *line, char *kind, size_t size) {
    size_t o = 0;
    for (const char *p = line; *p && o + 1 < size; p++) {
        int in_name = p > line && (isalnum((unsigned char)p[-1]) || p[-1] == '_' || p[-1] == ':');
        if (isdigit((unsigned char)*p) && !in_name) {
            kind[o++] = 'N';
            while (isdigit((unsigned char)p[1])) p++;
        } else {
            kind[o++] = *p;
        }
    }
    kind[o] = '\0';
}

static void say_repeats(SaidKind *k) {
    if (!k->repeats) return;
    printf("(the same line %u more time%s in %.1f s, in the CSV log only: %s)\n", k->repeats,
           k->repeats == 1 ? "" : "s", (double)(GetTime() - k->said) / 1e9, k->kind);
    k->repeats = 0;
}

static void say_line(const char *line) {
    char kind[ACTION_LINE_MAX];
    line_kind(line, kind, sizeof kind);
    RTIME now = GetTime();
    SaidKind *k = NULL;
    for (int i = 0; i < n_said_kinds && !k; i++)
        if (strcmp(said_kinds[i].kind, kind) == 0) k = &said_kinds[i];
    if (k && now - k->said < SAID_AGAIN_NS) {
        k->repeats++;
        return;
    }
    if (!k) { /* a new kind: a free slot, or the one said longest ago (its count said first) */
        if (n_said_kinds < SAID_KINDS) {
            k = &said_kinds[n_said_kinds++];
        } else {
            k = &said_kinds[0];
            for (int i = 1; i < SAID_KINDS; i++)
                if (said_kinds[i].said < k->said) k = &said_kinds[i];
        }
        say_repeats(k);
        snprintf(k->kind, sizeof k->kind, "%s", kind);
    }
    say_repeats(k);
    printf("%s\n", line);
    k->said = now;
}

static void say_all_repeats(void) {
    for (int i = 0; i < n_said_kinds; i++) say_repeats(&said_kinds[i]);
    fflush(stdout);
}

static void b_trace(void *ctx, int64_t t, const char *line) {
    (void)ctx;
    (void)t;
    /* releases are too frequent for stdout and b_fact records them in the CSV log;
       late completions of a deactivated schema (and the cycles they hold) are expected: CSV only */
    if (strncmp(line, "release ", 8) == 0) return;
    ContractLog("scheduler", "", -1, 0, line);
    if (!strstr(line, "finished outside a cycle") && strncmp(line, "late ack: ", 10) != 0 &&
        strncmp(line, "stuck: ", 7) != 0 && /* said once on stderr by b_stuck */
        !strstr(line, " held: ") && !strstr(line, " resumed"))
        say_line(line);
}

/* A module that never finishes its release (ord_core check_stuck): one line on stderr, prefixed
   `STUCK: ` so the launcher's caller (contract run, the build service) can tell the run did not
   go as designed (docs/engines.md §4, docs/ci.md). The sentence is the core's, the one of the CSV
   record `stuck: ...` too: for a module that is no longer running (b_module_gone) it says so
   instead of the advice about its exec region. */
static void b_stuck(void *ctx, const char *module, const char *schema, uint32_t id, long periods,
                    const char *message) {
    (void)ctx;
    (void)module;
    (void)schema;
    (void)id;
    (void)periods;
    fprintf(stderr, "STUCK: %s\n", message);
    fflush(stderr);
}

/* A module whose mailbox is stale (it crashed or was killed) or gone (the launcher removed it)
   is no longer running: a stuck release of it will never finish, whatever its exec region does. */
static int b_module_gone(void *ctx, const char *module) {
    (void)ctx;
    int state = ModuleState(module);
    return state == CONTRACT_ENOTRUNNING || state == CONTRACT_EUNKNOWN;
}

/* A look at a running module's main thread for a stuck report (ord_stuck_cause.h): its pid from
   <run dir>/<module>.pid (written by the module at start-up), then in /proc/<pid>/task/<pid>/:
   the state letter from `stat`, the CPU time and the time spent waiting for a CPU from
   `schedstat` (ns; without it, stat's utime + stime and an unknown wait), the kernel function it
   sleeps in from `wchan` (a write to a full pipe: ord_activity_writing_to_full_pipe), the bytes
   it wrote from `io` (wchar). Asked at most twice per
   stuck release. -1 when the pid or stat cannot be read (the report then keeps the question). */
static int b_module_activity(void *ctx, const char *module, OrdModuleActivity *out) {
    (void)ctx;
    char path[PATH_MAX];
    if (snprintf(path, sizeof path, "%s/%s.pid", ContractRunDir(), module) >= (int)sizeof path) return -1;
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    long pid = 0;
    int got = fscanf(f, "%ld", &pid);
    fclose(f);
    if (got != 1 || pid <= 0) return -1;
    snprintf(path, sizeof path, "/proc/%ld/task/%ld/stat", pid, pid);
    f = fopen(path, "r");
    if (!f) return -1;
    char line[1024];
    char *text = fgets(line, sizeof line, f);
    fclose(f);
    /* "pid (comm) S ppid ...": comm may hold spaces and ')', the state follows the last ')' */
    char *close = text ? strrchr(line, ')') : NULL;
    if (!close) return -1;
    char state = 0;
    unsigned long long utime = 0, stime = 0;
    /* fields 3 (state) to 15 (stime): state, ppid, pgrp, session, tty, tpgid, flags, minflt,
       cminflt, majflt, cmajflt, utime, stime */
    if (sscanf(close + 1, " %c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %llu %llu", &state, &utime, &stime) != 3)
        return -1;
    long hz = sysconf(_SC_CLK_TCK);
    if (hz <= 0) return -1;
    out->state = state;
    out->cpu_ns = (int64_t)((utime + stime) * (1000000000ULL / (unsigned long long)hz));
    out->wait_ns = -1;
    out->waiting_in[0] = '\0';
    out->written_bytes = -1;
    /* the bytes it wrote ("wchar: N"; hidden from another user's process) */
    snprintf(path, sizeof path, "/proc/%ld/task/%ld/io", pid, pid);
    f = fopen(path, "r");
    if (f) {
        char io_line[128];
        unsigned long long wchar = 0;
        while (fgets(io_line, sizeof io_line, f))
            if (sscanf(io_line, "wchar: %llu", &wchar) == 1) {
                out->written_bytes = (int64_t)wchar;
                break;
            }
        fclose(f);
    }
    /* the kernel function it sleeps in ("0" when running, or hidden from this process) */
    snprintf(path, sizeof path, "/proc/%ld/task/%ld/wchan", pid, pid);
    f = fopen(path, "r");
    if (f) {
        size_t got_chars = fread(out->waiting_in, 1, sizeof out->waiting_in - 1, f);
        out->waiting_in[got_chars] = '\0';
        out->waiting_in[strcspn(out->waiting_in, "\n")] = '\0';
        fclose(f);
    }
    snprintf(path, sizeof path, "/proc/%ld/task/%ld/schedstat", pid, pid);
    f = fopen(path, "r");
    if (f) {
        unsigned long long run = 0, wait = 0;
        if (fscanf(f, "%llu %llu", &run, &wait) == 2) {
            out->cpu_ns = (int64_t)run;
            out->wait_ns = (int64_t)wait;
        }
        fclose(f);
    }
    return 0;
}

/* An activation's set-up (its parameters and connections, one request each) is done: the schema's
   tick 0 is now. On a loaded machine at a nice level the set-up of a schema with many flows took
   6 ms, which counted against cycle 0's 5 ms CRITICAL_DELAY when tick 0 was the request's time. */
static int64_t b_setup_done_at(void *ctx) {
    (void)ctx;
    return (int64_t)GetTime();
}

/* the typed records of the periodic timeline (docs/runtime-api.md "Trace records"): CSV only */
static void b_fact(void *ctx, int64_t t, const OrdFact *f) {
    (void)ctx;
    char detail[384];
    /* a release's release_ns is when it was sent: the core's time is the tick it serves, which a
       late wake-up of ORD (a loaded machine) leaves behind; release_ns - tick_ns shows that */
    if (f->kind == ORD_FACT_RELEASE) {
        int64_t sent = (int64_t)GetTime();
        if (sent > t) t = sent;
    }
    const char *event = ord_fact_record(f, t, detail, sizeof detail);
    ContractLog(event, f->module ? f->module : "", -1, 0, detail);
}

static int cmp64(const void *a, const void *b) {
    int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

static void write_stats(OrdBinding *b, OrdCore *c, const char *path) {
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        return;
    }
    long cycles = 0, completed = 0, misses = 0, late_released = 0, overruns = 0, missed = 0, held = 0, late = 0, stuck = 0;
    int64_t max_response = 0;
    for (int i = 0; i < b->v->nschemas; i++) {
        OrdSchemaStats st;
        if (ord_core_stats(c, b->v->schemas[i]->name, &st) != 0) continue;
        cycles += st.cycles;
        completed += st.completed;
        misses += st.deadline_misses;
        late_released += st.late_releases;
        overruns += st.overruns;
        missed += st.missed_ticks;
        held += st.held_cycles;
        late += st.late_acks;
        stuck += st.stuck_releases;
        if (st.max_response_ns > max_response) max_response = st.max_response_ns;
    }
    double p50 = 0, p99 = 0, max = 0;
    if (b->nlate) {
        qsort(b->late, b->nlate, sizeof *b->late, cmp64);
        p50 = (double)b->late[b->nlate / 2] / 1000.0;
        p99 = (double)b->late[(size_t)((double)(b->nlate - 1) * 0.99)] / 1000.0;
        max = (double)b->late[b->nlate - 1] / 1000.0;
    }
    fprintf(f,
            "{\"cycles\": %ld, \"completed\": %ld, \"deadline_misses\": %ld, \"late_releases\": %ld, \"overruns\": %ld, "
            "\"missed_ticks\": %ld, \"held_cycles\": %ld, \"late_acks\": %ld, \"stuck_releases\": %ld, \"release_late_us_p50\": %.3f, \"release_late_us_p99\": %.3f, "
            "\"release_late_us_max\": %.3f, \"cycle_response_us_max\": %.3f, \"samples\": %zu}\n",
            cycles, completed, misses, late_released, overruns, missed, held, late, stuck, p50, p99, max, (double)max_response / 1000.0,
            b->nlate);
    fclose(f);
}

int contract_ord_main(const ContractOrdVocabulary *v, int argc, const char *argv[]) {
    rt_log_engine(RT_ENGINE_ORD); /* its own record kinds are logged by it only (csvlog.c) */
    (void)argc;
    (void)argv;
    OrdBinding b;
    memset(&b, 0, sizeof b);
    b.v = v;
    const char *stats_path = getenv("CONTRACT_ORD_STATS");
    b.record = stats_path && *stats_path;
    OrdIo io = {&b, b_set_param, b_connect, b_disconnect, b_release, b_emit, b_ack, b_trace, b_stuck, b_fact, b_module_gone,
                b_module_activity, b_setup_done_at};
    char err[512] = "";
    OrdCore *c = ord_core_create(v, &io, err, sizeof err);
    if (!c) {
        fprintf(stderr, "ORD: %s\n", err);
        return 2;
    }
    ord_core_set_skip_late_ticks(c, 1);
    /* ORD never waits for a module: a request whose receiver's mailbox is full (a module stuck in
       its exec region no longer reads it) fails at once (CONTRACT_EBUSY: libmodule's `error`
       record, and the binding's own line as for any request it could not send), instead of
       blocking ORD up to 2 s per request while every other schema misses its ticks and ORD its
       KILL. What a failed request does is unchanged: a release not delivered stays outstanding
       (its cycle misses its deadline, overruns, and the module is reported stuck), a parameter,
       connection or ORD:0 not delivered is lost, as when its receiver has crashed. */
    ContractSetNonBlockingSends(1);
    int rc = 0;
    RequestMessage *m = malloc(sizeof *m);
    if (!m) {
        ord_core_destroy(c);
        return 2;
    }
    const EngineClock clock = {c, ord_next_deadline, ord_advance};
    int64_t now = 0;
    for (;;) {
        if (engine_next_request(m, &clock, &now) < 0) {
            rc = 1;
            break;
        }
        b.reply_to = NULL;
        switch (m->Type) {
        case REQ_START: {
            const unsigned char *block = NULL;
            size_t size = 0;
            engine_binary_args(m, &block, &size);
            b.reply_to = m->Param.Start.ModAck[0] ? m->Param.Start.ModAck : m->Sender;
            b.reply_wanted = m->Param.Start.WantedAck;
            ord_core_activate(c, now, m->Param.Start.Function, block, size, m->Sender,
                              (uint32_t)m->Param.Start.AckID);
            break;
        }
        case REQ_STOP: {
            char name[CONTRACT_STRING_SIZE] = "";
            engine_data_string(m, name, sizeof name);
            int ok = 1;
            if (name[0]) {
                ok = ord_core_deactivate(c, now, name, m->Sender, (uint32_t)m->Param.Stop.AckID) == 0;
            } else {
                for (int i = 0; i < v->nschemas; i++)
                    if (ord_core_schema_active(c, v->schemas[i]->name))
                        ord_core_deactivate(c, now, v->schemas[i]->name, m->Sender, 0);
            }
            SendAck(m->Param.Stop.ModAck[0] ? m->Param.Stop.ModAck : m->Sender, m->Param.Stop.WantedAck,
                    ok ? ACK_STOPPED : ACK_NOTDONE, m->Param.Stop.AckID);
            break;
        }
        case REQ_ACK: {
            /* AckID 0 never names a release (ord_core_release_finished would take it as "the
               current cycle's"): such an ack is not an answer to ORD */
            if ((m->Param.Ack.Ack & (ACK_FINISHED | ACK_STOPPED | ACK_NOTDONE)) && m->Param.Ack.AckID > 0)
                ord_core_release_finished(c, m->ReceptionTime ? m->ReceptionTime : now,
                                          m->Param.Ack.Module, (uint32_t)m->Param.Ack.AckID);
            break;
        }
        case REQ_KILL:
            SendAck(m->Param.Kil.ModAck[0] ? m->Param.Kil.ModAck : m->Sender, m->Param.Kil.WantedAck,
                    ACK_KILLED, m->Param.Kil.AckID);
            goto out;
        default:
            break;
        }
    }
out:
    ord_core_stop(c); /* a cycle still overrunning tells its count (the trace's overruns are ORD's) */
    say_all_repeats();
    if (b.record) write_stats(&b, c, stats_path);
    free(b.late);
    free(m);
    ord_core_destroy(c);
    return rc;
}
