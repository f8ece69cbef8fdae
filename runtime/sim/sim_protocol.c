/* sim_protocol.c — see sim_protocol.h. */
#define _POSIX_C_SOURCE 200809L
#include "sim_protocol.h"
#include "engine_values.h"

#include <errno.h>
#include <inttypes.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

/* Bounds of one step's lists: a step that sets off more than this is cut (counted). 100,000
   typed records is 10 s of a 1 ms schema of 2 modules, about 12 MB of JSON. */
#define SIM_MAX_RECORDS_PER_STEP 100000
#define SIM_MAX_OUTPUT_BYTES 8192
#define SIM_MAX_ARGS 8

typedef struct Buf {
    char *p;
    size_t n, cap;
    int items;
} Buf;

struct SimSession {
    SimWorld *w;
    FILE *out;
    int capture_fd;
    off_t captured;      /* bytes of the capture file already read                       */
    int quiet;
    int failures;
    Buf rules, actions, log, records;
    long dropped;
    long seq;            /* order of the rules, actions, log lines and records over the session:
                            within one virtual time, a cause comes before its effects */
    int64_t started_ns;  /* CLOCK_MONOTONIC at creation: the end record's wallNs       */
};

/* ---- JSON buffer -------------------------------------------------------------------------- */

static void bput(Buf *b, const char *s, size_t n) {
    if (b->n + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 1024;
        while (cap < b->n + n + 1) cap *= 2;
        char *q = realloc(b->p, cap);
        if (!q) return;
        b->p = q;
        b->cap = cap;
    }
    memcpy(b->p + b->n, s, n);
    b->n += n;
    b->p[b->n] = '\0';
}
static void bstr(Buf *b, const char *s) { bput(b, s, strlen(s)); }
static void bfmt(Buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void bfmt(Buf *b, const char *fmt, ...) {
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n > 0) bput(b, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
}
/** A JSON string literal of at most `max` bytes of s. */
static void bjson(Buf *b, const char *s, size_t max) {
    bput(b, "\"", 1);
    for (size_t i = 0; s && s[i] && i < max; i++) {
        unsigned char c = (unsigned char)s[i];
        if (c == '"' || c == '\\') { char e[2] = {'\\', (char)c}; bput(b, e, 2); }
        else if (c == '\n') bput(b, "\\n", 2);
        else if (c == '\t') bput(b, "\\t", 2);
        else if (c < 0x20 || c == 0x7f) bfmt(b, "\\u%04x", c);
        else bput(b, (const char *)&c, 1);
    }
    bput(b, "\"", 1);
}
static void item_sep(Buf *b) {
    if (b->items++) bput(b, ",", 1);
}

/* ---- sinks -------------------------------------------------------------------------------- */

static int room(SimSession *s, Buf *b) {
    if (b->items < SIM_MAX_RECORDS_PER_STEP) return 1;
    s->dropped++;
    return 0;
}

static void on_rule(void *ctx, int64_t t, const char *sup, const char *fn, const char *rule,
                    int active, const char *cause) {
    SimSession *s = ctx;
    if (s->quiet || !room(s, &s->rules)) return;
    item_sep(&s->rules);
    bfmt(&s->rules, "{\"timeNs\":%" PRId64 ",\"seq\":%ld,\"supervisor\":", t, s->seq++);
    bjson(&s->rules, sup, 256);
    bstr(&s->rules, ",\"function\":");
    bjson(&s->rules, fn, 256);
    bstr(&s->rules, ",\"rule\":");
    bjson(&s->rules, rule, 256);
    bfmt(&s->rules, ",\"active\":%s,\"cause\":", active ? "true" : "false");
    bjson(&s->rules, cause, 1024);
    bstr(&s->rules, "}");
}
static void on_action(void *ctx, int64_t t, const char *who, const char *what) {
    SimSession *s = ctx;
    if (s->quiet || !room(s, &s->actions)) return;
    item_sep(&s->actions);
    bfmt(&s->actions, "{\"timeNs\":%" PRId64 ",\"seq\":%ld,\"who\":", t, s->seq++);
    bjson(&s->actions, who, 256);
    bstr(&s->actions, ",\"what\":");
    bjson(&s->actions, what, 1024);
    bstr(&s->actions, "}");
}
static void on_log(void *ctx, int64_t t, const char *who, const char *line) {
    SimSession *s = ctx;
    if (s->quiet || !room(s, &s->log)) return;
    item_sep(&s->log);
    bfmt(&s->log, "{\"timeNs\":%" PRId64 ",\"seq\":%ld,\"who\":", t, s->seq++);
    bjson(&s->log, who, 256);
    bstr(&s->log, ",\"line\":");
    bjson(&s->log, line, 1024);
    bstr(&s->log, "}");
}

static void on_record(void *ctx, int64_t t, const char *module, const char *event, const char *peer,
                      int port, const char *detail) {
    SimSession *s = ctx;
    if (s->quiet || !room(s, &s->records)) return;
    item_sep(&s->records);
    bfmt(&s->records, "{\"timeNs\":%" PRId64 ",\"seq\":%ld,\"module\":", t, s->seq++);
    bjson(&s->records, module, 256);
    bstr(&s->records, ",\"kind\":");
    bjson(&s->records, event, 64);
    bstr(&s->records, ",\"peer\":");
    bjson(&s->records, peer, 256);
    if (port >= 0) bfmt(&s->records, ",\"port\":%d", port);
    bstr(&s->records, ",\"detail\":");
    bjson(&s->records, detail, 1024);
    bstr(&s->records, "}");
}

/* ---- captured output ---------------------------------------------------------------------- */

/** What the process printed on stdout since the last call (at most max bytes kept). */
static void read_capture(SimSession *s, Buf *into, size_t max) {
    if (s->capture_fd < 0) return;
    fflush(stdout);
    off_t end = lseek(s->capture_fd, 0, SEEK_END);
    if (end <= s->captured) return;
    char chunk[4096];
    off_t at = s->captured;
    while (at < end) {
        size_t want = (size_t)(end - at) < sizeof chunk ? (size_t)(end - at) : sizeof chunk;
        ssize_t got = pread(s->capture_fd, chunk, want, at);
        if (got <= 0) break;
        if (into && into->n < max) bput(into, chunk, (size_t)got < max - into->n ? (size_t)got : max - into->n);
        at += got;
    }
    s->captured = end;
}

/** The value in words: numbers and strings directly, structures by their type's own print_. */
static void format_value(SimSession *s, Buf *b, const ContractType *type, const void *v) {
    switch (type->kind) {
    case CONTRACT_KIND_LONG: bfmt(b, "%ld", *(const long *)v); return;
    case CONTRACT_KIND_STRING: {
        char tmp[CONTRACT_STRING_SIZE];
        memcpy(tmp, v, sizeof tmp);
        tmp[sizeof tmp - 1] = '\0';
        bput(b, "\"", 1); bstr(b, tmp); bput(b, "\"", 1);
        return;
    }
    case CONTRACT_KIND_STRUCT: break;
    default: { /* floats, bools, enums, arrays: their readable form (docs/runtime-api.md): a float as
                  Cactal writes it (0.8, not the 0.80000000000000004 of all 17 digits) */
        char tmp[4096];
        contract_value_format(tmp, sizeof tmp, type, v);
        bstr(b, tmp);
        return;
    }
    }
    if (s->capture_fd < 0 || !type->print) { bfmt(b, "<%s>", type->name); return; }
    read_capture(s, NULL, 0); /* what was printed before is not part of the value */
    type->print((void *)v);
    read_capture(s, b, 4096);
}

/* ---- records ------------------------------------------------------------------------------ */

typedef struct StepResult {
    int ok;
    int delivered;          /* -2: not an event                                            */
    char error[512];
    Buf expected, actual;
} StepResult;

static void each_schema(void *ctx, const char *name) {
    Buf *b = ctx;
    item_sep(b);
    bjson(b, name, 256);
}

typedef struct LocalsCtx { SimSession *s; Buf *b; } LocalsCtx;
static void each_local(void *ctx, const char *sup, const char *fn, const char *name,
                       const ContractType *type, const void *v) {
    LocalsCtx *lc = ctx;
    Buf val = {0};
    format_value(lc->s, &val, type, v);
    item_sep(lc->b);
    bstr(lc->b, "{\"supervisor\":"); bjson(lc->b, sup, 256);
    bstr(lc->b, ",\"function\":"); bjson(lc->b, fn, 256);
    bstr(lc->b, ",\"name\":"); bjson(lc->b, name, 256);
    bstr(lc->b, ",\"type\":"); bjson(lc->b, type->name, 256);
    bstr(lc->b, ",\"value\":"); bjson(lc->b, val.p ? val.p : "", 4096);
    bstr(lc->b, "}");
    free(val.p);
}

static void emit(SimSession *s, long line, int64_t t, const char *verb, StepResult *r, int end) {
    if (!r->ok) s->failures++;
    if (s->quiet && r->ok && !end) return; /* its output is read with the next record shown */
    Buf output = {0};
    read_capture(s, &output, SIM_MAX_OUTPUT_BYTES);
    Buf o = {0};
    bfmt(&o, "{\"line\":%ld,\"timeNs\":%" PRId64 ",\"verb\":", line, t);
    bjson(&o, verb, 64);
    bfmt(&o, ",\"ok\":%s", r->ok ? "true" : "false");
    if (r->delivered >= 0) bfmt(&o, ",\"delivered\":%d", r->delivered);
    if (r->error[0]) { bstr(&o, ",\"error\":"); bjson(&o, r->error, sizeof r->error); }
    if (r->expected.p) { bstr(&o, ",\"expected\":"); bjson(&o, r->expected.p, 8192); }
    if (r->actual.p) { bstr(&o, ",\"actual\":"); bjson(&o, r->actual.p, 8192); }
    bstr(&o, ",\"rules\":["); if (s->rules.p) bput(&o, s->rules.p, s->rules.n); bstr(&o, "]");
    bstr(&o, ",\"actions\":["); if (s->actions.p) bput(&o, s->actions.p, s->actions.n); bstr(&o, "]");
    bstr(&o, ",\"log\":["); if (s->log.p) bput(&o, s->log.p, s->log.n); bstr(&o, "]");
    bstr(&o, ",\"records\":["); if (s->records.p) bput(&o, s->records.p, s->records.n); bstr(&o, "]");
    if (!s->quiet) {
        Buf schemas = {0};
        sim_world_each_active_schema(s->w, each_schema, &schemas);
        bstr(&o, ",\"schemas\":["); if (schemas.p) bput(&o, schemas.p, schemas.n); bstr(&o, "]");
        free(schemas.p);
        Buf locals = {0};
        LocalsCtx lc = {s, &locals};
        sim_world_each_local(s->w, each_local, &lc);
        bstr(&o, ",\"locals\":["); if (locals.p) bput(&o, locals.p, locals.n); bstr(&o, "]");
        free(locals.p);
    }
    if (output.p) { bstr(&o, ",\"output\":"); bjson(&o, output.p, SIM_MAX_OUTPUT_BYTES); }
    if (s->dropped) bfmt(&o, ",\"dropped\":%ld", s->dropped);
    if (end) {
        struct timespec ts;
        clock_gettime(CLOCK_MONOTONIC, &ts);
        int64_t wall = (int64_t)ts.tv_sec * 1000000000LL + ts.tv_nsec - s->started_ns;
        bfmt(&o, ",\"end\":true,\"eventsProcessed\":%" PRIu64 ",\"wallNs\":%" PRId64,
             sim_world_events_processed(s->w), wall);
    }
    bstr(&o, "}\n");
    if (o.p) fwrite(o.p, 1, o.n, s->out);
    fflush(s->out);
    free(o.p);
    free(output.p);
    s->rules.n = s->actions.n = s->log.n = s->records.n = 0;
    s->rules.items = s->actions.items = s->log.items = s->records.items = 0;
    if (s->rules.p) s->rules.p[0] = '\0';
    if (s->actions.p) s->actions.p[0] = '\0';
    if (s->log.p) s->log.p[0] = '\0';
    if (s->records.p) s->records.p[0] = '\0';
    s->dropped = 0;
}

/* ---- lifecycle ---------------------------------------------------------------------------- */

SimSession *sim_session_create(const ContractSupervisorVocabulary *const *sups, int nsups,
                               const ContractOrdVocabulary *ord, FILE *out, int capture_fd,
                               char *err, size_t errlen) {
    SimSession *s = calloc(1, sizeof *s);
    if (!s) { snprintf(err, errlen, "out of memory"); return NULL; }
    s->out = out;
    s->capture_fd = capture_fd;
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    s->started_ns = (int64_t)ts.tv_sec * 1000000000LL + ts.tv_nsec;
    SimSink sink = {s, on_rule, on_action, on_log, on_record};
    s->w = sim_world_create(sups, nsups, ord, &sink, err, errlen);
    if (!s->w) { free(s); return NULL; }
    return s;
}

void sim_session_destroy(SimSession *s) {
    if (!s) return;
    sim_world_destroy(s->w);
    free(s->rules.p);
    free(s->actions.p);
    free(s->log.p);
    free(s->records.p);
    free(s);
}

int sim_session_failures(const SimSession *s) { return s->failures; }

int64_t sim_session_now(const SimSession *s) { return sim_world_now(s->w); }

/* ---- one line ----------------------------------------------------------------------------- */

static int parse_i64(const char *text, int64_t *out) {
    if (!text || !*text) return -1;
    char *end;
    errno = 0;
    long long v = strtoll(text, &end, 10);
    if (errno || *end || v < 0) return -1;
    *out = v;
    return 0;
}

static int flag01(const char *text) {
    return text && strcmp(text, "1") == 0 ? 1 : text && strcmp(text, "0") == 0 ? 0 : -1;
}

static void say(Buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void say(Buf *b, const char *fmt, ...) {
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    bstr(b, tmp);
}

static void expect_local(SimSession *s, char **a, StepResult *r) {
    const ContractType *type = NULL;
    const void *v = sim_world_local(s->w, a[0], a[1], a[2], &type);
    say(&r->expected, "%s.%s.%s == %s", a[0], a[1], a[2], a[3]);
    if (!v || !type) {
        r->ok = 0;
        say(&r->actual, "%s.%s is not running (no local %s)", a[0], a[1], a[2]);
        return;
    }
    unsigned char *want = calloc(1, type->size ? type->size : 1);
    char *copy = strdup(a[3]);
    if (!want || !copy) { r->ok = 0; snprintf(r->error, sizeof r->error, "out of memory"); free(want); free(copy); return; }
    /* the generic reader and comparison: a type's own get/eq when it has them, else the
       extension types' (an enumeration `Mode.AUTO` or `AUTO`, an array, a datatype's fields) */
    engine_default_value(want, type, NULL);
    int used = contract_value_get(type, want, copy);
    if (used < 0) {
        r->ok = 0;
        snprintf(r->error, sizeof r->error, "'%s' is not a value of type %s", a[3], type->name);
    } else if (!contract_value_compare(CONTRACT_TEST_EQ, type, want, v)) {
        r->ok = 0;
    }
    /* the actual value as a rule's cause writes it (`{what="late",speed=0.2,mode=SLOW}`), the
       notation of the expectation beside it; a datatype without a field table as it prints */
    if (type->kind == CONTRACT_KIND_STRUCT && type->nfields > 0 && type->fields) {
        char tmp[4096];
        contract_value_format(tmp, sizeof tmp, type, v);
        bstr(&r->actual, tmp);
    } else {
        format_value(s, &r->actual, type, v);
    }
    free(want);
    free(copy);
}

int sim_session_line(SimSession *s, char *line) {
    char *f[3 + SIM_MAX_ARGS + 1] = {0};
    int nf = 0;
    for (char *p = line; nf < (int)(sizeof f / sizeof f[0]);) {
        f[nf++] = p;
        char *tab = strchr(p, '\t');
        if (!tab) break;
        *tab = '\0';
        p = tab + 1;
    }
    StepResult r = {.ok = 1, .delivered = -2};
    int64_t t = 0, lineno = 0;
    const char *verb = nf >= 3 ? f[2] : "";
    char **a = f + 3;
    int na = nf - 3;
    int end = 0;
    if (nf < 3 || parse_i64(f[0], &t) || parse_i64(f[1], &lineno)) {
        r.ok = 0;
        snprintf(r.error, sizeof r.error, "expected TIME_NS<TAB>LINE<TAB>VERB...");
        emit(s, 0, sim_world_now(s->w), "?", &r, 0);
        return 0;
    }
    if (t < sim_world_now(s->w)) {
        r.ok = 0;
        snprintf(r.error, sizeof r.error, "time %" PRId64 " is before the simulation's %" PRId64, t, sim_world_now(s->w));
        emit(s, (long)lineno, sim_world_now(s->w), verb, &r, 0);
        return 0;
    }
    sim_world_advance(s->w, t);
#define NEED(n) if (na < (n)) { r.ok = 0; snprintf(r.error, sizeof r.error, "%s takes %d arguments", verb, (n)); break; }
    do {
        if (strcmp(verb, "quiet") == 0) { s->quiet = 1; return 0; }
        if (strcmp(verb, "end") == 0) { end = 1; break; }
        if (strcmp(verb, "start") == 0) {
            NEED(2);
            if (sim_world_start(s->w, a[0], a[1], na > 2 ? a[2] : "", r.error, sizeof r.error)) r.ok = 0;
        } else if (strcmp(verb, "stop") == 0) {
            NEED(2);
            if (sim_world_stop(s->w, a[0], a[1], r.error, sizeof r.error)) r.ok = 0;
        } else if (strcmp(verb, "event") == 0) {
            NEED(2);
            int64_t port;
            if (parse_i64(a[1], &port) || port > 65535) { r.ok = 0; snprintf(r.error, sizeof r.error, "bad port '%s'", a[1]); break; }
            r.delivered = sim_world_event(s->w, a[0], (int)port, na > 2 ? a[2] : "", r.error, sizeof r.error);
            if (r.delivered < 0) { r.ok = 0; r.delivered = 0; }
        } else if (strcmp(verb, "crash") == 0) {
            NEED(1);
            if (sim_world_crash(s->w, a[0], r.error, sizeof r.error)) r.ok = 0;
        } else if (strcmp(verb, "finish") == 0) {
            NEED(1);
            if (sim_world_finish(s->w, a[0], r.error, sizeof r.error)) r.ok = 0;
        } else if (strcmp(verb, "finish-after") == 0) {
            NEED(3);
            int64_t ns;
            if (parse_i64(a[1], &ns) || ns < 0) { r.ok = 0; snprintf(r.error, sizeof r.error, "bad time '%s'", a[1]); break; }
            sim_world_set_run_time(s->w, a[0], ns, strcmp(a[2], "once") == 0);
        } else if (strcmp(verb, "exec") == 0) {
            NEED(3);
            int64_t ns;
            if (parse_i64(a[1], &ns)) { r.ok = 0; snprintf(r.error, sizeof r.error, "bad time '%s'", a[1]); break; }
            sim_world_set_exec(s->w, a[0], ns, strcmp(a[2], "once") == 0);
        } else if (strcmp(verb, "expect-rule") == 0) {
            NEED(4);
            int want = flag01(a[3]), got = sim_world_rule_active(s->w, a[0], a[1], a[2]);
            say(&r.expected, "rule %s.%s.%s %s", a[0], a[1], a[2], want ? "active" : "inactive");
            say(&r.actual, got < 0 ? "no such rule" : got ? "active" : "inactive");
            r.ok = got == want;
        } else if (strcmp(verb, "expect-function") == 0) {
            NEED(3);
            int want = flag01(a[2]), got = sim_world_function_running(s->w, a[0], a[1]);
            say(&r.expected, "function %s.%s %s", a[0], a[1], want ? "running" : "stopped");
            say(&r.actual, got < 0 ? "no such function" : got ? "running" : "stopped");
            r.ok = got == want;
        } else if (strcmp(verb, "expect-schema") == 0) {
            NEED(2);
            int want = flag01(a[1]), got = sim_world_schema_active(s->w, a[0]);
            say(&r.expected, "schema %s %s", a[0], want ? "active" : "inactive");
            say(&r.actual, got ? "active" : "inactive");
            r.ok = got == want;
        } else if (strcmp(verb, "expect-module") == 0) {
            NEED(2);
            int want = flag01(a[1]), got = sim_world_module_running(s->w, a[0]);
            say(&r.expected, "module %s %s", a[0], want ? "running" : "stopped");
            say(&r.actual, got ? "running" : "stopped");
            r.ok = got == want;
        } else if (strcmp(verb, "expect-count") == 0) {
            NEED(3);
            int overruns = strcmp(a[1], "overruns") == 0;
            if (!overruns && strcmp(a[1], "deadline-misses") != 0) { r.ok = 0; snprintf(r.error, sizeof r.error, "bad count kind '%s'", a[1]); break; }
            const char *what = overruns ? "overruns" : "deadline misses";
            int64_t want;
            if (parse_i64(a[2], &want) || want < 0) { r.ok = 0; snprintf(r.error, sizeof r.error, "bad count '%s'", a[2]); break; }
            OrdSchemaStats st;
            say(&r.expected, "%s %s == %" PRId64, what, a[0], want);
            if (sim_world_schema_stats(s->w, a[0], &st) != 0) {
                say(&r.actual, "no periodic schema %s", a[0]);
                r.ok = 0;
                break;
            }
            long got = overruns ? st.overruns : st.deadline_misses;
            say(&r.actual, "%ld", got);
            r.ok = got == want;
        } else if (strcmp(verb, "expect-local") == 0) {
            NEED(4);
            expect_local(s, a, &r);
        } else {
            r.ok = 0;
            snprintf(r.error, sizeof r.error, "unknown verb '%s'", verb);
        }
    } while (0);
#undef NEED
    emit(s, (long)lineno, sim_world_now(s->w), verb, &r, end);
    free(r.expected.p);
    free(r.actual.p);
    return end;
}
