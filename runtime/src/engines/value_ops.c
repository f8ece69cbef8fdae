/* value_ops.c — operations on any value described by a ContractType (contract/vocabulary.h):
 * comparison, default, parsing, printing and the short readable form of trace records.
 * A descriptor's own functions are used when present; bool, enumerations and arrays (the
 * extension kinds, normally without functions) get generic operations driven by the descriptor:
 * element by element for arrays, by value for enums and bools. */
#define _POSIX_C_SOURCE 200809L
#include "engine_values.h"

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- bool ------------------------------------------------------------------------------- */

static int read_bool(const void *p) {
    unsigned char b; /* read as a byte: a C bool holding another value must not trap UBSan */
    memcpy(&b, p, 1);
    return b != 0;
}

static int is_ident_char(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

/* Length of the identifier at p (0 if none). */
static size_t ident_len(const char *p) {
    size_t n = 0;
    if (!((p[0] >= 'a' && p[0] <= 'z') || (p[0] >= 'A' && p[0] <= 'Z') || p[0] == '_')) return 0;
    while (is_ident_char(p[n])) n++;
    return n;
}

static const char *skip_blanks(const char *p) {
    while (*p == ' ' || *p == '\t' || *p == '\n' || *p == '\r') p++;
    return p;
}

static int bool_get(void *dst, char *text) {
    const char *p = skip_blanks(text);
    size_t n = ident_len(p);
    bool v;
    if (n == 4 && strncmp(p, "true", 4) == 0) v = true;
    else if (n == 5 && strncmp(p, "false", 5) == 0) v = false;
    else if ((p[0] == '0' || p[0] == '1') && !is_ident_char(p[1])) {
        v = p[0] == '1';
        n = 1;
    } else {
        return -1;
    }
    memcpy(dst, &v, sizeof v);
    return (int)(p + n - text);
}

static void bool_print(void *v) { fputs(read_bool(v) ? "true" : "false", stdout); }

const ContractType contract_type_bool = {.name = "bool", .kind = CONTRACT_KIND_BOOL,
                                         .size = sizeof(bool), .get = bool_get,
                                         .print = bool_print};

/* ---- enumerations ----------------------------------------------------------------------- */

static long read_enum(const void *p, size_t size) {
    switch (size) {
    case 1: { int8_t v; memcpy(&v, p, 1); return v; }
    case 2: { int16_t v; memcpy(&v, p, 2); return v; }
    case 4: { int32_t v; memcpy(&v, p, 4); return v; }
    default: { int64_t v; memcpy(&v, p, 8); return (long)v; }
    }
}

static void write_enum(void *p, size_t size, long value) {
    switch (size) {
    case 1: { int8_t v = (int8_t)value; memcpy(p, &v, 1); return; }
    case 2: { int16_t v = (int16_t)value; memcpy(p, &v, 2); return; }
    case 4: { int32_t v = (int32_t)value; memcpy(p, &v, 4); return; }
    default: { int64_t v = value; memcpy(p, &v, 8); return; }
    }
}

/* The member name of an enum value, or NULL when the value is no member. */
static const char *enum_name(const ContractType *t, long value) {
    for (int i = 0; i < t->nmembers; i++)
        if (t->members[i].value == value) return t->members[i].name;
    return NULL;
}

/* `AUTO`, `Mode.AUTO` (with the enum's own name) or a number that is a member's value. */
static int enum_get(const ContractType *t, void *dst, const char *text) {
    const char *p = skip_blanks(text);
    size_t n = ident_len(p);
    if (n > 0 && p[n] == '.' && t->name && strlen(t->name) == n && strncmp(p, t->name, n) == 0) {
        p += n + 1;
        n = ident_len(p);
    }
    if (n > 0) {
        for (int i = 0; i < t->nmembers; i++)
            if (strlen(t->members[i].name) == n && strncmp(p, t->members[i].name, n) == 0) {
                write_enum(dst, t->size, t->members[i].value);
                return (int)(p + n - text);
            }
        return -1;
    }
    char *end;
    long v = strtol(p, &end, 10);
    if (end == p || is_ident_char(*end) || *end == '.' || !enum_name(t, v)) return -1;
    write_enum(dst, t->size, v);
    return (int)(end - text);
}

/* ---- numbers of any scalar kind ---------------------------------------------------------- */

static int is_scalar(const ContractType *t) {
    return t->kind == CONTRACT_KIND_LONG || t->kind == CONTRACT_KIND_DOUBLE ||
           t->kind == CONTRACT_KIND_BOOL || t->kind == CONTRACT_KIND_ENUM;
}

static double scalar_value(const void *p, const ContractType *t) {
    switch (t->kind) {
    case CONTRACT_KIND_LONG: { long v; memcpy(&v, p, sizeof v); return (double)v; }
    case CONTRACT_KIND_BOOL: return read_bool(p);
    case CONTRACT_KIND_ENUM: return (double)read_enum(p, t->size);
    default: { double v; memcpy(&v, p, sizeof v); return v; }
    }
}

static int compare_numbers(ContractTestOp op, double x, double y) {
    switch (op) {
    case CONTRACT_TEST_EQ: return x == y;
    case CONTRACT_TEST_NE: return x != y;
    case CONTRACT_TEST_LT: return x < y;
    case CONTRACT_TEST_GT: return x > y;
    case CONTRACT_TEST_LE: return x <= y;
    case CONTRACT_TEST_GE: return x >= y;
    default: return 0;
    }
}

/* ---- comparison ------------------------------------------------------------------------- */

/* Arrays: eq/inf/sup when every element is; diff = !eq; infeq = inf or eq; supeq = sup or eq
   (the rule of the generated datatype functions, field by field). */
static int compare_arrays(ContractTestOp op, const unsigned char *a, const ContractType *at,
                          const unsigned char *b, const ContractType *bt) {
    if (op == CONTRACT_TEST_NE) return !compare_arrays(CONTRACT_TEST_EQ, a, at, b, bt);
    if (op == CONTRACT_TEST_LE)
        return compare_arrays(CONTRACT_TEST_LT, a, at, b, bt) ||
               compare_arrays(CONTRACT_TEST_EQ, a, at, b, bt);
    if (op == CONTRACT_TEST_GE)
        return compare_arrays(CONTRACT_TEST_GT, a, at, b, bt) ||
               compare_arrays(CONTRACT_TEST_EQ, a, at, b, bt);
    if (at->count != bt->count || !at->element || !bt->element) return 0;
    for (int i = 0; i < at->count; i++)
        if (!engine_compare(op, a + (size_t)i * at->element->size, at->element,
                            b + (size_t)i * bt->element->size, bt->element))
            return 0;
    return 1;
}

int engine_compare(ContractTestOp op, const void *a, const ContractType *at, const void *b,
                   const ContractType *bt) {
    if (is_scalar(at) && is_scalar(bt) && (at->kind != bt->kind || !at->eq))
        return compare_numbers(op, scalar_value(a, at), scalar_value(b, bt));
    if (at->kind == CONTRACT_KIND_ARRAY && bt->kind == CONTRACT_KIND_ARRAY && !at->eq)
        return compare_arrays(op, a, at, b, bt);
    /* the type functions take non-const pointers but do not write through them */
    void *pa = (void *)(uintptr_t)a, *pb = (void *)(uintptr_t)b;
    int (*f)(void *, void *) = NULL;
    switch (op) {
    case CONTRACT_TEST_EQ: f = at->eq; break;
    case CONTRACT_TEST_NE: f = at->diff; break;
    case CONTRACT_TEST_LT: f = at->inf; break;
    case CONTRACT_TEST_GT: f = at->sup; break;
    case CONTRACT_TEST_LE: f = at->infeq; break;
    case CONTRACT_TEST_GE: f = at->supeq; break;
    default: break;
    }
    if (f) return f(pa, pb) ? 1 : 0;
    int c = memcmp(a, b, at->size); /* a descriptor without functions: bytewise */
    return compare_numbers(op, c, 0);
}

int contract_value_compare(ContractTestOp op, const ContractType *t, const void *a, const void *b) {
    return engine_compare(op, a, t, b, t);
}

/* ---- default ---------------------------------------------------------------------------- */

void engine_default_value(void *dst, const ContractType *t, const void *explicit_default) {
    const void *d = explicit_default ? explicit_default : t->default_value;
    if (d) {
        memcpy(dst, d, t->size);
    } else if (t->kind == CONTRACT_KIND_ARRAY && t->element) {
        for (int i = 0; i < t->count; i++)
            engine_default_value((unsigned char *)dst + (size_t)i * t->element->size, t->element,
                                 NULL);
    } else {
        memset(dst, 0, t->size);
    }
}

/* ---- parsing ---------------------------------------------------------------------------- */

/* An array `{e1, e2, ...}` or `[e1, e2, ...]` with exactly count elements, or a datatype without
   its own get (its field table) `{f1, f2, ...}` in field order, parsed into tmp. */
static int list_get(const ContractType *t, unsigned char *tmp, const char *text) {
    int is_array = t->kind == CONTRACT_KIND_ARRAY;
    int count = is_array ? t->count : t->nfields;
    const char *p = skip_blanks(text);
    char close = *p == '{' ? '}' : (*p == '[' && is_array) ? ']' : 0;
    if (!close || (is_array && !t->element)) return -1;
    p++;
    for (int i = 0; i < count; i++) {
        if (i > 0) {
            p = skip_blanks(p);
            if (*p != ',') return -1;
            p++;
        }
        const ContractType *et = is_array ? t->element : t->fields[i].type;
        unsigned char *at = is_array ? tmp + (size_t)i * t->element->size : tmp + t->fields[i].offset;
        int n = contract_value_get(et, at, (char *)p);
        if (n < 0) return -1;
        p += n;
    }
    p = skip_blanks(p);
    if (*p != close) return -1;
    return (int)(p + 1 - text);
}

int contract_value_get(const ContractType *t, void *dst, char *text) {
    if (!t || !dst || !text) return -1;
    if (t->get) return t->get(dst, text);
    switch (t->kind) {
    case CONTRACT_KIND_ENUM: return enum_get(t, dst, text);
    case CONTRACT_KIND_STRUCT:
        if (t->nfields <= 0 || !t->fields) return -1;
        __attribute__((fallthrough));
    case CONTRACT_KIND_ARRAY: {
        unsigned char *tmp = malloc(t->size);
        if (!tmp) return -1;
        memcpy(tmp, dst, t->size); /* bytes no element covers (padding) are kept */
        int n = list_get(t, tmp, text);
        if (n >= 0) memcpy(dst, tmp, t->size);
        free(tmp);
        return n;
    }
    default: return -1;
    }
}

/* ---- short readable form ---------------------------------------------------------------- */

/* A bounded writer: text goes into buf[0 .. cap), buf[n] stays the end of the text. */
typedef struct Writer {
    char *buf;
    size_t n, cap;
    int max_items; /* array elements shown before `...` (so that later fields keep room) */
} Writer;

static int put(Writer *w, const char *s) {
    size_t k = strlen(s);
    if (w->n + k > w->cap) return 0;
    memcpy(w->buf + w->n, s, k);
    w->n += k;
    w->buf[w->n] = 0;
    return 1;
}

/* Length of the well-formed UTF-8 sequence at s[i] (at most `left` bytes), or 0 if it is not one. */
static size_t utf8_length(const unsigned char *s, size_t left) {
    unsigned char c = s[0];
    size_t len = c >= 0xF0 && c <= 0xF4 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 && c < 0xE0 ? 2 : 0;
    if (c >= 0xF5 || len == 0 || len > left) return 0;
    for (size_t k = 1; k < len; k++)
        if ((s[k] & 0xC0) != 0x80) return 0;
    if (len == 3 && ((c == 0xE0 && s[1] < 0xA0) || (c == 0xED && s[1] >= 0xA0))) return 0; /* overlong, surrogate */
    if (len == 4 && ((c == 0xF0 && s[1] < 0x90) || (c == 0xF4 && s[1] >= 0x90))) return 0; /* overlong, past U+10FFFF */
    return len;
}

/* `"text"`: quotes and backslashes escaped, control characters and bytes that are no UTF-8 as
   `?`, cut after 64 bytes with `...` — never inside a character, so the line stays UTF-8. */
static void quote_string(char out[140], const char *s) {
    size_t n = 0, i = 0;
    out[n++] = '"';
    size_t end = 0; /* the string's bytes (not NUL-terminated at CONTRACT_STRING_SIZE) */
    while (end < CONTRACT_STRING_SIZE && s[end]) end++;
    const unsigned char *u = (const unsigned char *)s;
    while (i < end && i < 64) {
        unsigned char ch = u[i];
        if (ch < 0x80) {
            if (ch == '"' || ch == '\\') out[n++] = '\\';
            out[n++] = ch < 0x20 || ch == 0x7f ? '?' : (char)ch;
            i++;
            continue;
        }
        size_t len = utf8_length(u + i, end - i);
        if (len == 0 || (len == 2 && ch == 0xC2 && u[i + 1] < 0xA0)) { /* not UTF-8, or a C1 control: ? */
            out[n++] = '?';
            i += len ? len : 1;
            continue;
        }
        if (i + len > 64) break; /* the cut falls inside this character: cut before it */
        memcpy(out + n, u + i, len);
        n += len;
        i += len;
    }
    if (i < end) {
        memcpy(out + n, "...", 3);
        n += 3;
    }
    out[n++] = '"';
    out[n] = 0;
}

static int format_into(Writer *w, const ContractType *t, const unsigned char *v, int depth);

/* Room kept for the `,...]` of a cut list. */
#define CUT_ROOM 5

/* Items of a list `[a,b]` / `{x=a,y=b}`; cut with `...` when the rest does not fit. */
static int format_list(Writer *w, const ContractType *t, const unsigned char *v, int depth) {
    int is_array = t->kind == CONTRACT_KIND_ARRAY;
    int count = is_array ? t->count : t->nfields;
    if (w->n + 2 + CUT_ROOM > w->cap) return 0;
    put(w, is_array ? "[" : "{");
    w->cap -= CUT_ROOM;
    for (int i = 0; i < count; i++) {
        size_t mark = w->n;
        if (is_array && i >= w->max_items) {
            w->cap += CUT_ROOM;
            put(w, ",...]");
            return 1;
        }
        const ContractType *et = is_array ? t->element : t->fields[i].type;
        const unsigned char *ev = is_array ? v + (size_t)i * t->element->size : v + t->fields[i].offset;
        int ok = (i == 0 || put(w, ",")) && (is_array || (put(w, t->fields[i].name) && put(w, "="))) &&
                 format_into(w, et, ev, depth + 1);
        if (!ok) {
            w->n = mark;
            w->buf[w->n] = 0;
            w->cap += CUT_ROOM;
            put(w, i > 0 ? ",..." : "...");
            put(w, is_array ? "]" : "}");
            return 1;
        }
    }
    w->cap += CUT_ROOM;
    put(w, is_array ? "]" : "}");
    return 1;
}

/* A float as Cactal writes it: 15 significant digits (%g kept 6: 1234567.0 was 1.23457e+06; 17
   would show 0.5 + 7 * 0.01 as 0.57000000000000006), with a decimal point when it would look like
   an int (1.0, not 1: a float parameter shown as `speed = 1` read as an int) */
static void format_double(char *out, size_t size, double x) {
    snprintf(out, size, "%.15g", x);
    if (strpbrk(out, ".eEni") == NULL && strlen(out) + 2 < size) strcat(out, ".0");
}

static int format_into(Writer *w, const ContractType *t, const unsigned char *v, int depth) {
    char tmp[160];
    if (depth > 8) return put(w, "?");
    switch (t->kind) {
    case CONTRACT_KIND_LONG: {
        long x;
        memcpy(&x, v, sizeof x);
        snprintf(tmp, sizeof tmp, "%ld", x);
        return put(w, tmp);
    }
    case CONTRACT_KIND_DOUBLE: {
        double x;
        memcpy(&x, v, sizeof x);
        format_double(tmp, sizeof tmp, x);
        return put(w, tmp);
    }
    case CONTRACT_KIND_STRING:
        quote_string(tmp, (const char *)v);
        return put(w, tmp);
    case CONTRACT_KIND_BOOL: return put(w, read_bool(v) ? "true" : "false");
    case CONTRACT_KIND_ENUM: {
        long x = read_enum(v, t->size);
        const char *name = enum_name(t, x);
        if (name) return put(w, name);
        snprintf(tmp, sizeof tmp, "%ld", x); /* not a member: the number */
        return put(w, tmp);
    }
    case CONTRACT_KIND_ARRAY:
        if (!t->element) return put(w, "?");
        return format_list(w, t, v, depth);
    case CONTRACT_KIND_STRUCT:
        if (t->nfields > 0 && t->fields) return format_list(w, t, v, depth);
        snprintf(tmp, sizeof tmp, "{%zu bytes}", t->size);
        return put(w, tmp);
    }
    return put(w, "?");
}

void contract_value_format(char *buf, size_t len, const ContractType *t, const void *value) {
    if (!buf || len == 0) return;
    buf[0] = 0;
    if (!value || !t) {
        snprintf(buf, len, "?");
        return;
    }
    Writer w = {buf, 0, len - 1, CONTRACT_FORMAT_MAX_ITEMS};
    if (!format_into(&w, t, value, 0)) snprintf(buf, len, "?");
}

void engine_format_value(char *buf, size_t len, const void *value, const ContractType *type) {
    contract_value_format(buf, len, type, value);
}

void engine_format_param_port(char *buf, size_t len, const char *module, int port, const char *name) {
    if (!buf || len == 0) return;
    if (name && name[0]) snprintf(buf, len, "%s:%d %s", module ? module : "?", port, name);
    else snprintf(buf, len, "%s:%d", module ? module : "?", port);
}

void engine_format_parameterize(char *buf, size_t len, const char *module, int port, const char *name,
                                const void *value, size_t size, const ContractType *type) {
    char v[ACTION_VALUE_MAX], target[ENGINE_PARAM_PORT_MAX];
    engine_format_value(v, sizeof v, value, type);
    engine_format_param_port(target, sizeof target, module, port, name);
    snprintf(buf, len, "parameterize %s (%zu bytes) = %s", target, size, v);
}

void engine_format_event_flow(char *buf, size_t len, const ContractEventFlow *f) {
    snprintf(buf, len, "%s:%d %s %s:%d", f->src_module, f->src_port, f->mode == CONTRACT_ONESHOT ? "=>" : "=*",
             f->dst_module, f->dst_port);
}

void engine_flow_hold_name(char *out, size_t n, const char *src, int src_port, const char *dst, int dst_port) {
    char full[3 * ENGINE_HOLD_NAME_MAX];
    snprintf(full, sizeof full, "flow-%s-%d-%s-%d", src, src_port, dst, dst_port);
    if (strlen(full) < ENGINE_HOLD_NAME_MAX) {
        snprintf(out, n, "%s", full);
        return;
    }
    /* FNV-1a's arithmetic: a stable name per flow (its offset basis is not FNV's usual
       0xcbf29ce484222325, but names already written depend on it: kept) */
    unsigned long long h = 1469598103934665603ULL;
    for (const char *p = full; *p; p++) h = (h ^ (unsigned char)*p) * 1099511628211ULL;
    snprintf(out, n, "flow-%016llx", h);
}

void engine_format_data_flow(char *buf, size_t len, const ContractDataFlow *f) {
    snprintf(buf, len, "%s:%d -> %s:%d", f->src_module, f->src_port, f->dst_module, f->dst_port);
}

void engine_format_params(char *buf, size_t len, const ContractVar *vars, int nvars, const void *block) {
    if (!buf || len == 0) return;
    buf[0] = 0;
    if (nvars == 0 && len >= 3) { /* none: written as the source writes the call, `f()` */
        memcpy(buf, "()", 3);
        return;
    }
    if (!vars || nvars < 0 || !block || len < 8) return;
    char all[4 * ACTION_VALUE_MAX];
    size_t n = 0;
    all[n++] = '(';
    for (int i = 0; i < nvars && n < sizeof all - 1; i++) {
        char value[ACTION_VALUE_MAX];
        engine_format_value(value, sizeof value, (const unsigned char *)block + vars[i].offset, vars[i].type);
        int w = snprintf(all + n, sizeof all - n, "%s%s = %s", i ? ", " : "", vars[i].name, value);
        if (w < 0) break;
        n += (size_t)w < sizeof all - n ? (size_t)w : sizeof all - n - 1;
    }
    if (n < sizeof all - 1) all[n++] = ')';
    all[n] = 0;
    if (n < len) {
        memcpy(buf, all, n + 1);
        return;
    }
    /* too long: cut on a character boundary, then `...)` */
    size_t keep = len - 5;
    while (keep > 0 && ((unsigned char)all[keep] & 0xC0) == 0x80) keep--;
    memcpy(buf, all, keep);
    memcpy(buf + keep, "...)", 5);
}

/* ---- printing (stdout) ------------------------------------------------------------------ */


void contract_value_print(const ContractType *t, const void *value) {
    if (!t || !value) return;
    if (t->print) {
        t->print((void *)(uintptr_t)value);
        return;
    }
    char buf[16384];
    Writer w = {buf, 0, sizeof buf - 1, 1 << 30};
    buf[0] = 0;
    if (!format_into(&w, t, value, 0)) snprintf(buf, sizeof buf, "?");
    fputs(buf, stdout);
}
