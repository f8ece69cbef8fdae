/* engine_values.c — see engine_values.h; also the built-in descriptors of int/float/string
 * (bool and the generic operations of the extension kinds: value_ops.c). */
#define _POSIX_C_SOURCE 200809L
#include "engine_values.h"
#include "../string_escape.h"

#include <stdio.h>
#include <string.h>

/* ---- built-in primitive descriptors ------------------------------------------------- */

#define NUM_OPS(T, N)                                                                  \
    static int N##_eq(void *a, void *b) { return *(T *)a == *(T *)b; }                 \
    static int N##_diff(void *a, void *b) { return *(T *)a != *(T *)b; }               \
    static int N##_inf(void *a, void *b) { return *(T *)a < *(T *)b; }                 \
    static int N##_sup(void *a, void *b) { return *(T *)a > *(T *)b; }                 \
    static int N##_infeq(void *a, void *b) { return *(T *)a <= *(T *)b; }              \
    static int N##_supeq(void *a, void *b) { return *(T *)a >= *(T *)b; }              \
    static void N##_set(void *d, void *s) { *(T *)d = *(T *)s; }

NUM_OPS(long, prim_long)
NUM_OPS(double, prim_double)

static int prim_long_get(void *d, char *text) {
    int n = 0;
    if (sscanf(text, " %ld%n", (long *)d, &n) != 1) return -1;
    return n;
}
static int prim_double_get(void *d, char *text) {
    int n = 0;
    if (sscanf(text, " %lf%n", (double *)d, &n) != 1) return -1;
    return n;
}
static void prim_long_print(void *v) { printf("%ld", *(long *)v); }
static void prim_double_print(void *v) { printf("%f", *(double *)v); }

static int str_cmp(void *a, void *b) { return strncmp((char *)a, (char *)b, CONTRACT_STRING_SIZE); }
static int prim_string_eq(void *a, void *b) { return str_cmp(a, b) == 0; }
static int prim_string_diff(void *a, void *b) { return str_cmp(a, b) != 0; }
static int prim_string_inf(void *a, void *b) { return str_cmp(a, b) < 0; }
static int prim_string_sup(void *a, void *b) { return str_cmp(a, b) > 0; }
static int prim_string_infeq(void *a, void *b) { return str_cmp(a, b) <= 0; }
static int prim_string_supeq(void *a, void *b) { return str_cmp(a, b) >= 0; }
static void prim_string_set(void *d, void *s) { engine_set_string((char *)d, (const char *)s); }
static int prim_string_get(void *d, char *text) {
    /* "quoted text" with the language's escapes (a scenario's or a start request's value is
       written as in a .contract file), or a bare word up to ',' '}' or end */
    const char *p = text;
    int i = 0;
    char *out = (char *)d;
    while (*p == ' ' || *p == '\t') p++;
    if (*p == '"') {
        p++;
        while (*p && *p != '"') {
            char c = *p++;
            if (c == '\\') {
                if (!*p) return -1;
                c = contract_string_escape(*p++);
            }
            if (i < CONTRACT_STRING_SIZE - 1) out[i++] = c;
        }
        if (*p != '"') return -1;
        p++;
    } else {
        while (*p && *p != ',' && *p != '}' && *p != ']') {
            if (i < CONTRACT_STRING_SIZE - 1) out[i++] = *p;
            p++;
        }
    }
    out[i] = '\0';
    return (int)(p - text);
}
static void prim_string_print(void *v) { printf("\"%.*s\"", CONTRACT_STRING_SIZE, (char *)v); }

const ContractType contract_type_long = {
    .name = "int", .kind = CONTRACT_KIND_LONG, .size = sizeof(long), .eq = prim_long_eq,
    .diff = prim_long_diff, .inf = prim_long_inf, .sup = prim_long_sup, .infeq = prim_long_infeq,
    .supeq = prim_long_supeq, .set = prim_long_set, .get = prim_long_get, .print = prim_long_print};
const ContractType contract_type_double = {
    .name = "float", .kind = CONTRACT_KIND_DOUBLE, .size = sizeof(double), .eq = prim_double_eq,
    .diff = prim_double_diff, .inf = prim_double_inf, .sup = prim_double_sup,
    .infeq = prim_double_infeq, .supeq = prim_double_supeq, .set = prim_double_set,
    .get = prim_double_get, .print = prim_double_print};
const ContractType contract_type_string = {
    .name = "string", .kind = CONTRACT_KIND_STRING, .size = CONTRACT_STRING_SIZE,
    .eq = prim_string_eq, .diff = prim_string_diff, .inf = prim_string_inf, .sup = prim_string_sup,
    .infeq = prim_string_infeq, .supeq = prim_string_supeq, .set = prim_string_set,
    .get = prim_string_get, .print = prim_string_print};

/* ---- helpers ------------------------------------------------------------------------ */

void engine_set_string(char *dst, const char *src) {
    size_t n = strnlen(src, CONTRACT_STRING_SIZE - 1);
    memmove(dst, src, n);
    memset(dst + n, 0, CONTRACT_STRING_SIZE - n);
}

static int is_numeric(const ContractType *t) {
    return t->kind == CONTRACT_KIND_LONG || t->kind == CONTRACT_KIND_DOUBLE;
}

static double as_double(const void *p, const ContractType *t) {
    if (t->kind == CONTRACT_KIND_LONG) {
        long v;
        memcpy(&v, p, sizeof v);
        return (double)v;
    }
    double d;
    memcpy(&d, p, sizeof d);
    return d;
}

void engine_copy_value(void *dst, const ContractType *dt, const void *src, const ContractType *st) {
    if (dst == src) return;
    if (dt->kind != st->kind && is_numeric(dt) && is_numeric(st)) {
        double d = as_double(src, st);
        if (dt->kind == CONTRACT_KIND_LONG) {
            long l = (long)d;
            memcpy(dst, &l, sizeof l);
        } else {
            memcpy(dst, &d, sizeof d);
        }
        return;
    }
    if (dt->kind == CONTRACT_KIND_STRING) {
        engine_set_string((char *)dst, (const char *)src);
        return;
    }
    size_t n = dt->size < st->size ? dt->size : st->size;
    memmove(dst, src, n);
}

const unsigned char *engine_ref_ptr(const EngineScope *s, const ContractRef *r) {
    const unsigned char *base = NULL;
    switch (r->kind) {
    case CONTRACT_REF_CONST:
        return (const unsigned char *)r->constant;
    case CONTRACT_REF_LOCAL:
        if (!s->fn || !s->locals || r->index < 0 || r->index >= s->fn->nlocals) return NULL;
        base = s->locals + s->fn->locals[r->index].offset;
        break;
    case CONTRACT_REF_PARAM:
        if (!s->params || !s->param_vars || r->index < 0 || r->index >= s->nparam_vars) return NULL;
        base = s->params + s->param_vars[r->index].offset;
        break;
    case CONTRACT_REF_IN_PORT:
        if (s->occ_data && r->index == s->occ_port) {
            base = s->occ_data;
        } else if (s->port_value) {
            const ContractType *t = NULL;
            base = s->port_value(s->port_ctx, r->index, &t);
        }
        if (!base) return NULL;
        break;
    case CONTRACT_REF_ORD_SCHEMA:
        return (const unsigned char *)s->ord_schema;
    default:
        return NULL;
    }
    return base + r->offset;
}

int engine_apply_assign(const EngineScope *s, const ContractAssign *as, unsigned char *base,
                        const ContractVar *vars) {
    const unsigned char *src = engine_ref_ptr(s, &as->src);
    if (!src) return -1;
    unsigned char *dst = base + (vars ? vars[as->index].offset : 0) + as->offset;
    engine_copy_value(dst, as->type, src, as->src.type);
    return 0;
}

void engine_init_block(unsigned char *block, const ContractVar *vars, int nvars) {
    for (int i = 0; i < nvars; i++)
        engine_default_value(block + vars[i].offset, vars[i].type, vars[i].default_value);
}

int engine_build_setting(const EngineScope *s, const ContractParamSetting *setting, void *dst) {
    engine_default_value(dst, setting->type, NULL);
    for (int i = 0; i < setting->nparts; i++)
        if (engine_apply_assign(s, &setting->parts[i], (unsigned char *)dst, NULL) != 0) return -1;
    return 0;
}
