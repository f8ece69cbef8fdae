/*
 * engine_trace.h — the cores' trace lines (ord_core.c, sup_core.c): one formatted line per
 * rule transition, release, refusal..., handed to the io's trace callback with the core's
 * current time. Header-only: the cores stay free of any other object file.
 */
#ifndef CONTRACT_ENGINE_TRACE_H
#define CONTRACT_ENGINE_TRACE_H

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>

typedef void (*EngineTraceFn)(void *ctx, int64_t t, const char *line);

/** Formats one line (truncated to 511 characters) and gives it to fn; fn NULL: nothing. */
static inline void engine_vtrace(EngineTraceFn fn, void *ctx, int64_t t, const char *fmt, va_list ap) {
    if (!fn) return;
    char line[512];
    vsnprintf(line, sizeof line, fmt, ap);
    fn(ctx, t, line);
}

/** Defines `static void trace(Core *c, const char *fmt, ...)` for a core type with `io.trace`,
 *  `io.ctx` and `now` members. */
#define ENGINE_DEFINE_TRACE(Core)                                                            \
    static void trace(Core *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));  \
    static void trace(Core *c, const char *fmt, ...) {                                       \
        va_list ap;                                                                          \
        va_start(ap, fmt);                                                                   \
        engine_vtrace(c->io.trace, c->io.ctx, c->now, fmt, ap);                              \
        va_end(ap);                                                                          \
    }

#endif
