/*
 * engine_check.c — consistency checks of generated tables, so that a generator bug or a
 * hand-written table mistake gives a message naming the place instead of a crash.
 */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "contract/vocabulary.h"

/* a parameter block travels in one request (libmodule: 16384 bytes, minus the binary-args tag) */
#define CONTRACT_MAX_ARGS_SIZE (16384 - 5)

typedef struct Ctx {
    char *err;
    size_t errlen;
    char where[256];
} Ctx;

static int fail(Ctx *x, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int fail(Ctx *x, const char *fmt, ...) {
    char msg[256];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    if (x->err && x->errlen) snprintf(x->err, x->errlen, "invalid tables: %s: %s", x->where, msg);
    return -1;
}

static int check_type_at(Ctx *x, const ContractType *t, const char *what, int depth);

/* bool, enumerations, arrays and field tables (the extension parts of a descriptor). */
static int check_extension(Ctx *x, const ContractType *t, const char *what, int depth) {
    const char *name = t->name ? t->name : "?";
    switch (t->kind) {
    case CONTRACT_KIND_BOOL:
        if (t->size != 1) return fail(x, "%s: bool type %s of size %zu (C bool is 1 byte)", what, name, t->size);
        return 0;
    case CONTRACT_KIND_ENUM:
        if (t->size != 1 && t->size != 2 && t->size != 4 && t->size != 8)
            return fail(x, "%s: enum type %s of size %zu (1, 2, 4 or 8)", what, name, t->size);
        if (t->nmembers <= 0 || !t->members) return fail(x, "%s: enum type %s has no members", what, name);
        for (int i = 0; i < t->nmembers; i++)
            if (!t->members[i].name) return fail(x, "%s: enum type %s: member %d has no name", what, name, i);
        return 0;
    case CONTRACT_KIND_ARRAY:
        if (!t->element || t->count <= 0)
            return fail(x, "%s: array type %s needs an element type and a count >= 1", what, name);
        if (check_type_at(x, t->element, what, depth + 1)) return -1;
        if (t->size != (size_t)t->count * t->element->size)
            return fail(x, "%s: array type %s of size %zu is not %d x %zu bytes", what, name, t->size, t->count,
                        t->element->size);
        return 0;
    case CONTRACT_KIND_STRUCT:
        if (t->nfields < 0 || (t->nfields > 0 && !t->fields)) return fail(x, "%s: type %s: field table missing", what, name);
        for (int i = 0; i < t->nfields; i++) {
            const ContractField *f = &t->fields[i];
            if (!f->name) return fail(x, "%s: type %s: field %d has no name", what, name, i);
            if (check_type_at(x, f->type, what, depth + 1)) return -1;
            if (f->offset + f->type->size > t->size)
                return fail(x, "%s: type %s: field %s at %zu (+%zu) exceeds its %zu bytes", what, name, f->name, f->offset,
                            f->type->size, t->size);
        }
        return 0;
    default: return 0;
    }
}

static int check_type_at(Ctx *x, const ContractType *t, const char *what, int depth) {
    if (!t) return fail(x, "%s has no type", what);
    if (depth > 16) return fail(x, "%s: type %s nests more than 16 levels (a cycle?)", what, t->name ? t->name : "?");
    if (t->size == 0 || t->size > CONTRACT_MAX_VALUE_SIZE)
        return fail(x, "%s: type %s has size %zu", what, t->name ? t->name : "?", t->size);
    if (t->kind == CONTRACT_KIND_STRING && t->size != CONTRACT_STRING_SIZE)
        return fail(x, "%s: string type of size %zu", what, t->size);
    if (t->kind < CONTRACT_KIND_LONG || t->kind > CONTRACT_KIND_ARRAY)
        return fail(x, "%s: type %s of unknown kind %d", what, t->name ? t->name : "?", (int)t->kind);
    return check_extension(x, t, what, depth);
}

static int check_type(Ctx *x, const ContractType *t, const char *what) { return check_type_at(x, t, what, 0); }

static int check_vars(Ctx *x, const ContractVar *vars, int n, size_t size, const char *what) {
    if (n < 0 || (n > 0 && !vars)) return fail(x, "%s table missing", what);
    for (int i = 0; i < n; i++) {
        if (!vars[i].name) return fail(x, "%s %d has no name", what, i);
        if (check_type(x, vars[i].type, vars[i].name)) return -1;
        if (vars[i].offset + vars[i].type->size > size)
            return fail(x, "%s '%s' at offset %zu (+%zu) exceeds its block of %zu bytes", what,
                        vars[i].name, vars[i].offset, vars[i].type->size, size);
    }
    return 0;
}

/* limits of what a reference may designate in a context */
typedef struct RefLimits {
    int nlocals;
    int nparams;
    const ContractSupervisorVocabulary *sup; /* IN_PORT allowed when non-NULL */
    int allow_ord;
    const ContractVar *locals, *params;      /* their types bound field paths (NULL: not checked) */
} RefLimits;

/* A field path (an element `ranges[90]` included) must stay inside the variable it starts from. */
static int check_path(Ctx *x, const ContractRef *r, const ContractType *var, const char *what) {
    if (!var || r->offset + r->type->size <= var->size) return 0;
    return fail(x, "%s: field path at offset %zu (+%zu bytes) exceeds its %s of %zu bytes", what, r->offset,
                r->type->size, var->name ? var->name : "?", var->size);
}

static int check_ref(Ctx *x, const ContractRef *r, const RefLimits *l, const char *what) {
    if (check_type(x, r->type, what)) return -1;
    switch (r->kind) {
    case CONTRACT_REF_CONST:
        if (!r->constant) return fail(x, "%s: constant without a value", what);
        return 0;
    case CONTRACT_REF_LOCAL:
        if (r->index < 0 || r->index >= l->nlocals)
            return fail(x, "%s: local %d out of range (%d locals)", what, r->index, l->nlocals);
        return check_path(x, r, l->locals ? l->locals[r->index].type : NULL, what);
    case CONTRACT_REF_PARAM:
        if (r->index < 0 || r->index >= l->nparams)
            return fail(x, "%s: parameter %d out of range (%d parameters)", what, r->index,
                        l->nparams);
        return check_path(x, r, l->params ? l->params[r->index].type : NULL, what);
    case CONTRACT_REF_IN_PORT:
        if (l->sup) {
            for (int i = 0; i < l->sup->nin_ports; i++)
                if (l->sup->in_ports[i].port == r->index) return check_path(x, r, l->sup->in_ports[i].type, what);
        }
        return fail(x, "%s: no in event port :%d here", what, r->index);
    case CONTRACT_REF_ORD_SCHEMA:
        if (!l->allow_ord) return fail(x, "%s: ord_schema outside an ORD event", what);
        if (r->type->kind != CONTRACT_KIND_STRING) return fail(x, "%s: ord_schema is a string", what);
        return 0;
    }
    return fail(x, "%s: unknown reference kind %d", what, (int)r->kind);
}

static int numeric(const ContractType *t) {
    return t->kind == CONTRACT_KIND_LONG || t->kind == CONTRACT_KIND_DOUBLE;
}

/* the same type: structs and enums by name and size, arrays by count and element type */
static int same_type(const ContractType *a, const ContractType *b) {
    if (a == b) return 1;
    if (a->kind != b->kind || a->size != b->size) return 0;
    switch (a->kind) {
    case CONTRACT_KIND_STRUCT:
    case CONTRACT_KIND_ENUM: return a->name && b->name && strcmp(a->name, b->name) == 0;
    case CONTRACT_KIND_ARRAY: return a->count == b->count && a->element && b->element && same_type(a->element, b->element);
    default: return 1;
    }
}

/* same type, or int/float mix (not inside arrays: they are copied as they are) */
static int compatible(const ContractType *a, const ContractType *b) {
    if (numeric(a) && numeric(b)) return 1;
    return same_type(a, b);
}

static int check_compatible(Ctx *x, const ContractType *target, const ContractType *src, const char *what) {
    if (compatible(target, src)) return 0;
    return fail(x, "%s: a %s cannot take a %s", what, target->name ? target->name : "?",
                src->name ? src->name : "?");
}

static int check_assigns(Ctx *x, const ContractAssign *as, int n, int ntargets,
                         const RefLimits *l, const char *what) {
    if (n < 0 || (n > 0 && !as)) return fail(x, "%s table missing", what);
    for (int i = 0; i < n; i++) {
        if (ntargets >= 0 && (as[i].index < 0 || as[i].index >= ntargets))
            return fail(x, "%s %d: target %d out of range (%d)", what, i, as[i].index, ntargets);
        if (check_type(x, as[i].type, what)) return -1;
        if (check_ref(x, &as[i].src, l, what)) return -1;
        if (check_compatible(x, as[i].type, as[i].src.type, what)) return -1;
    }
    return 0;
}

static int check_settings(Ctx *x, const ContractParamSetting *s, int n, const RefLimits *l,
                          const char *what) {
    if (n < 0 || (n > 0 && !s)) return fail(x, "%s table missing", what);
    for (int i = 0; i < n; i++) {
        if (check_type(x, s[i].type, what)) return -1;
        for (int k = 0; k < s[i].nparts; k++)
            if (s[i].parts[k].offset + s[i].parts[k].type->size > s[i].type->size)
                return fail(x, "%s: part %d of port %d exceeds the port value", what, k, s[i].port);
        if (check_assigns(x, s[i].parts, s[i].nparts, -1, l, what)) return -1;
    }
    return 0;
}

static int check_schema(Ctx *x, const ContractSchema *s) {
    if (!s || !s->name) return fail(x, "schema without a name");
    char saved[256];
    memcpy(saved, x->where, sizeof saved);
    snprintf(x->where + strlen(x->where), sizeof x->where - strlen(x->where), " schema %s", s->name);
    if (s->kind != CONTRACT_SCHEMA_PERIODIC && s->kind != CONTRACT_SCHEMA_EVENT)
        return fail(x, "unknown kind %d", (int)s->kind);
    if (check_vars(x, s->params, s->nparams, s->params_size, "parameter")) return -1;
    if (s->nmodules < 0 || (s->nmodules > 0 && !s->modules)) return fail(x, "modules missing");
    RefLimits l = {0, s->nparams, NULL, 0, NULL, s->params};
    for (int m = 0; m < s->nmodules; m++) {
        if (!s->modules[m].module) return fail(x, "module %d has no name", m);
        if (check_settings(x, s->modules[m].settings, s->modules[m].nsettings, &l,
                           s->modules[m].module))
            return -1;
    }
    if (s->kind == CONTRACT_SCHEMA_PERIODIC) {
        if (s->period_ns <= 0) return fail(x, "period must be > 0");
        if (s->critical_delay_ns <= 0) return fail(x, "critical delay must be > 0");
        for (int i = 0; i < s->nprecedences; i++) {
            const ContractPrecedence *p = &s->precedences[i];
            if (p->before < 0 || p->before >= s->nmodules || p->after < 0 ||
                p->after >= s->nmodules || p->before == p->after)
                return fail(x, "precedence %d (%d -> %d) is not between two modules", i,
                            p->before, p->after);
        }
        for (int i = 0; i < s->ndata_flows; i++) {
            const ContractDataFlow *f = &s->data_flows[i];
            if (!f->src_module || !f->dst_module) return fail(x, "data flow %d lacks a module", i);
            if (f->periodicity < 1) return fail(x, "data flow %d has periodicity %d", i, f->periodicity);
        }
    } else {
        for (int i = 0; i < s->nevent_flows; i++)
            if (!s->event_flows[i].src_module || !s->event_flows[i].dst_module)
                return fail(x, "event flow %d lacks a module", i);
    }
    memcpy(x->where, saved, sizeof saved);
    return 0;
}

int contract_check_ord_vocabulary(const ContractOrdVocabulary *v, char *err, size_t errlen) {
    Ctx x = {err, errlen, "ORD"};
    if (!v) return fail(&x, "no tables");
    if (v->version != CONTRACT_VOCABULARY_VERSION)
        return fail(&x, "tables of version %d, this runtime reads version %d (regenerate)",
                    v->version, CONTRACT_VOCABULARY_VERSION);
    for (int i = 0; i < v->nmodules; i++)
        if (!v->modules[i].name) return fail(&x, "module %d has no name", i);
    for (int i = 0; i < v->nschemas; i++) {
        const ContractSchema *s = v->schemas[i];
        if (check_schema(&x, s)) return -1;
        if (s->kind != CONTRACT_SCHEMA_PERIODIC) return fail(&x, "schema %s is not periodic", s->name);
        for (int m = 0; m < s->nmodules && v->nmodules > 0; m++) {
            int listed = 0;
            for (int k = 0; k < v->nmodules; k++)
                if (strcmp(v->modules[k].name, s->modules[m].module) == 0) listed = 1;
            if (!listed)
                return fail(&x, "schema %s uses module %s, which the scheduler configuration does not list",
                            s->name, s->modules[m].module);
        }
    }
    for (int i = 0; i < v->nsupervisors; i++)
        if (!v->supervisors[i]) return fail(&x, "supervisor %d has no name", i);
    return 0;
}

static int check_condition(Ctx *x, const ContractSupervisorVocabulary *v, const ContractFunction *fn,
                           const ContractCondition *c, const char *which) {
    if (c->nclauses < 0 || (c->nclauses > 0 && !c->clauses)) return fail(x, "%s missing", which);
    RefLimits tl = {fn->nlocals, 0, v, 0, fn->locals, NULL};
    for (int k = 0; k < c->nclauses; k++) {
        const ContractClause *cl = &c->clauses[k];
        if (cl->nevents <= 0 || !cl->events) return fail(x, "%s clause %d is empty", which, k);
        for (int e = 0; e < cl->nevents; e++) {
            const ContractEvent *ev = &cl->events[e];
            char what[96];
            snprintf(what, sizeof what, "%s clause %d event %d", which, k, e);
            tl.allow_ord = 0;
            switch (ev->kind) {
            case CONTRACT_EV_MODULE:
                if (!ev->module) return fail(x, "%s has no module", what);
                tl.allow_ord = strcmp(ev->module, "ORD") == 0;
                /* -1: a delivery into any in port (docs/engines.md: an event that reads no port
                   variable of a module port subscribed to several, or several of them) */
                if (!tl.allow_ord && ev->in_port != -1) {
                    int ok = 0;
                    for (int i = 0; i < v->nin_ports; i++)
                        if (v->in_ports[i].port == ev->in_port) ok = 1;
                    if (!ok) return fail(x, "%s (%s:%d): no in event port :%d", what, ev->module,
                                         ev->port, ev->in_port);
                }
                for (int t = 0; t < ev->ntest_clauses; t++) {
                    const ContractTestClause *tc = &ev->test_clauses[t];
                    for (int i = 0; i < tc->ntests; i++) {
                        const ContractTest *ts = &tc->tests[i];
                        if (ts->op == CONTRACT_TEST_CALL) {
                            if (!ts->fn || !ts->fn->call)
                                return fail(x, "%s: test function missing", what);
                            if (ts->nargs != ts->fn->nargs)
                                return fail(x, "%s: %s takes %d arguments, %d given", what,
                                            ts->fn->name, ts->fn->nargs, ts->nargs);
                            for (int a = 0; a < ts->nargs; a++) {
                                if (check_ref(x, &ts->args[a], &tl, what)) return -1;
                                if (ts->fn->arg_types &&
                                    check_compatible(x, ts->fn->arg_types[a], ts->args[a].type, what))
                                    return -1;
                            }
                        } else if (ts->op >= CONTRACT_TEST_EQ && ts->op <= CONTRACT_TEST_GE) {
                            if (check_ref(x, &ts->lhs, &tl, what) || check_ref(x, &ts->rhs, &tl, what))
                                return -1;
                            if (check_compatible(x, ts->lhs.type, ts->rhs.type, what)) return -1;
                        } else {
                            return fail(x, "%s: unknown test operator %d", what, (int)ts->op);
                        }
                    }
                }
                break;
            case CONTRACT_EV_STARTED:
            case CONTRACT_EV_ENDOF:
            case CONTRACT_EV_DURATION:
                if (ev->rule < 0 || ev->rule >= fn->nrules)
                    return fail(x, "%s: rule %d out of range", what, ev->rule);
                if (ev->kind == CONTRACT_EV_DURATION && ev->time_ns <= 0)
                    return fail(x, "%s: duration must be > 0", what);
                break;
            case CONTRACT_EV_ELAPSED:
                if (ev->time_ns <= 0) return fail(x, "%s: elapsed time must be > 0", what);
                break;
            default:
                return fail(x, "%s: unknown event kind %d", what, (int)ev->kind);
            }
            if (ev->persist == CONTRACT_PERSIST_TIME && ev->persist_ns <= 0)
                return fail(x, "%s: persistence must be > 0", what);
            if (check_assigns(x, ev->extractions, ev->nextractions, fn->nlocals, &tl, what))
                return -1;
        }
    }
    return 0;
}

static int check_action(Ctx *x, const ContractSupervisorVocabulary *v, const ContractFunction *fn,
                        const ContractAction *a) {
    RefLimits l = {fn->nlocals, 0, v, 0, fn->locals, NULL};
    switch (a->kind) {
    case CONTRACT_ACT_SCHEMA:
        if (!a->schema) return fail(x, "activate schema without a schema");
        if (check_schema(x, a->schema)) return -1;
        if (a->schema->params_size > CONTRACT_MAX_ARGS_SIZE)
            return fail(x, "the parameters of %s take %zu bytes, more than a request carries (%d)",
                        a->schema->name, a->schema->params_size, CONTRACT_MAX_ARGS_SIZE);
        return check_assigns(x, a->assigns, a->nassigns, a->schema->nparams, &l, "schema parameter");
    case CONTRACT_ACT_PARAMETERIZE:
        if (!a->module) return fail(x, "parameterize without a module");
        return check_settings(x, a->settings, a->nsettings, &l, "parameterize");
    case CONTRACT_ACT_SUPERVISOR:
        if (!a->callee || !a->callee->supervisor || !a->callee->function)
            return fail(x, "activate supervisor without a callee");
        if (check_vars(x, a->callee->params, a->callee->nparams, a->callee->params_size,
                       "callee parameter"))
            return -1;
        if (a->callee->params_size > CONTRACT_MAX_ARGS_SIZE)
            return fail(x, "the parameters of %s.%s take %zu bytes, more than a request carries (%d)",
                        a->callee->supervisor, a->callee->function, a->callee->params_size,
                        CONTRACT_MAX_ARGS_SIZE);
        return check_assigns(x, a->assigns, a->nassigns, a->callee->nparams, &l, "callee parameter");
    case CONTRACT_ACT_RESTTIME_MODULE:
    case CONTRACT_ACT_CRITICAL_MODULE:
        if (!a->module) return fail(x, "activate module without a module");
        return 0;
    case CONTRACT_ACT_COMPUTE:
        if (!a->fn || !a->fn->call) return fail(x, "compute without a function");
        if (a->nargs != a->fn->nargs || a->nargs > 64)
            return fail(x, "compute %s: %d arguments for %d", a->fn->name, a->nargs, a->fn->nargs);
        for (int i = 0; i < a->nargs; i++) {
            if (check_ref(x, &a->args[i], &l, "compute argument")) return -1;
            if (a->fn->arg_types && check_compatible(x, a->fn->arg_types[i], a->args[i].type, "compute argument"))
                return -1;
        }
        return 0;
    case CONTRACT_ACT_SUBSCRIBE:
        if (!a->module) return fail(x, "subscribe without a module");
        for (int i = 0; i < v->nin_ports; i++)
            if (v->in_ports[i].port == a->in_port) return 0;
        return fail(x, "subscribe to :%d, which is not an in event port", a->in_port);
    case CONTRACT_ACT_NOTIFY:
        for (int i = 0; i < v->nout_ports; i++)
            if (v->out_ports[i].port == a->out_port) {
                for (int k = 0; k < a->nassigns; k++)
                    if (a->assigns[k].offset + a->assigns[k].type->size > v->out_ports[i].type->size)
                        return fail(x, "notify :%d assignment %d exceeds the port value",
                                    a->out_port, k);
                return check_assigns(x, a->assigns, a->nassigns, -1, &l, "notify");
            }
        return fail(x, "notify :%d, which is not an out event port", a->out_port);
    }
    return fail(x, "unknown action kind %d", (int)a->kind);
}

int contract_check_supervisor_vocabulary(const ContractSupervisorVocabulary *v, char *err,
                                         size_t errlen) {
    Ctx x = {err, errlen, "supervisor"};
    if (!v) return fail(&x, "no tables");
    if (!v->name) return fail(&x, "no name");
    snprintf(x.where, sizeof x.where, "%s", v->name);
    if (v->version != CONTRACT_VOCABULARY_VERSION)
        return fail(&x, "tables of version %d, this runtime reads version %d (regenerate)",
                    v->version, CONTRACT_VOCABULARY_VERSION);
    for (int i = 0; i < v->nin_ports; i++)
        if (check_type(&x, v->in_ports[i].type, "in port")) return -1;
    for (int i = 0; i < v->nout_ports; i++)
        if (check_type(&x, v->out_ports[i].type, "out port")) return -1;
    for (int f = 0; f < v->nfunctions; f++) {
        const ContractFunction *fn = &v->functions[f];
        if (!fn->name) return fail(&x, "function %d has no name", f);
        snprintf(x.where, sizeof x.where, "%s.%s", v->name, fn->name);
        if (check_vars(&x, fn->params, fn->nparams, fn->params_size, "parameter")) return -1;
        if (check_vars(&x, fn->locals, fn->nlocals, fn->locals_size, "local")) return -1;
        RefLimits il = {fn->nlocals, fn->nparams, NULL, 0, fn->locals, fn->params};
        if (check_assigns(&x, fn->local_inits, fn->nlocal_inits, fn->nlocals, &il, "local initialiser"))
            return -1;
        if (fn->nrules < 0 || (fn->nrules > 0 && !fn->rules)) return fail(&x, "rules missing");
        for (int r = 0; r < fn->nrules; r++) {
            const ContractRule *rule = &fn->rules[r];
            if (!rule->label) return fail(&x, "rule %d has no label", r);
            snprintf(x.where, sizeof x.where, "%s.%s rule %s", v->name, fn->name, rule->label);
            if (check_condition(&x, v, fn, &rule->pre, "precondition")) return -1;
            if (check_condition(&x, v, fn, &rule->post, "postcondition")) return -1;
            for (int a = 0; a < rule->nactions; a++) {
                snprintf(x.where, sizeof x.where, "%s.%s rule %s action %d", v->name, fn->name,
                         rule->label, a + 1);
                if (check_action(&x, v, fn, &rule->actions[a])) return -1;
            }
        }
    }
    return 0;
}
