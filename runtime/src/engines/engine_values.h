/*
 * engine_values.h — values described by ContractType: copy with long<->double conversion,
 * comparisons (struct/string through the type's functions, int/float mixed numerically),
 * reading value references and applying assignments. Shared by both engines.
 */
#ifndef CONTRACT_ENGINE_VALUES_H
#define CONTRACT_ENGINE_VALUES_H

#include "contract/vocabulary.h"

/** Where the variables a reference may designate live, for one evaluation. Any may be NULL. */
typedef struct EngineScope {
    const ContractFunction *fn;   /* locals/params layout                                     */
    unsigned char *locals;        /* the running function's locals block                      */
    const unsigned char *params;  /* PARAM refs: function params or schema params block       */
    const ContractVar *param_vars;/* layout of `params` (fn->params or schema->params)        */
    int nparam_vars;
    /* IN_PORT refs: current port variables of the supervisor */
    const unsigned char *(*port_value)(void *ctx, int port, const ContractType **type);
    void *port_ctx;
    /* IN_PORT refs that designate the port of the occurrence at hand read its data instead */
    int occ_port;                 /* -1: none                                                 */
    const unsigned char *occ_data;
    const char *ord_schema;       /* ORD_SCHEMA refs; NULL when not an ORD event              */
} EngineScope;

/** Pointer to the value a reference designates (field offset applied), or NULL if it cannot
 *  be resolved in this scope. */
const unsigned char *engine_ref_ptr(const EngineScope *s, const ContractRef *r);

/** Copies a value of type `st` at `src` into a place of type `dt` at `dst`, converting
 *  long<->double; other mismatches copy min(size) bytes (checked tables never do that). */
void engine_copy_value(void *dst, const ContractType *dt, const void *src, const ContractType *st);

/** Writes the default value of `t` (or `explicit_default` when non-NULL) at dst. */
void engine_default_value(void *dst, const ContractType *t, const void *explicit_default);

/** Evaluates `a op b` (op: EQ..GE). Returns 1/0. */
int engine_compare(ContractTestOp op, const void *a, const ContractType *at, const void *b,
                   const ContractType *bt);

/** Applies assignment `as` to the block whose variables start at `base + vars[as->index]
 *  .offset` (vars != NULL) or, when vars == NULL, to `base` directly (+ as->offset).
 *  Returns 0, or -1 when its source cannot be resolved. */
int engine_apply_assign(const EngineScope *s, const ContractAssign *as, unsigned char *base,
                        const ContractVar *vars);

/** Fills a block from its variables' defaults. */
void engine_init_block(unsigned char *block, const ContractVar *vars, int nvars);

/** Builds the value of a module parameter port into dst (size setting->type->size). */
int engine_build_setting(const EngineScope *s, const ContractParamSetting *setting, void *dst);

/** The room for a value in a readable trace line (a rule's cause, a notified or parameterized
 *  value): with the rest of the line it fits the 400-byte CSV detail. */
#define ACTION_VALUE_MAX 200

/** Writes a short readable form of a value into buf (trace records, docs/runtime-api.md "Trace
 *  records"): int `12`, float `1.0` / `0.35` (15 significant digits, always a decimal point),
 *  string `"text"` (quotes and backslashes escaped, control characters as `?`, cut at 64
 *  characters with `...`), enum member, bool, array and datatype `{a,b}` / `{x=1.5,y=2.0}` (at
 *  most CONTRACT_FORMAT_MAX_ITEMS elements, then `...`; a datatype without a field table
 *  `{N bytes}`); no value or type: `?`. Never longer than len - 1. */
void engine_format_value(char *buf, size_t len, const void *value, const ContractType *type);

/** Room for engine_format_param_port: two names of up to 63 bytes, a port number, a colon, a space. */
#define ENGINE_PARAM_PORT_MAX 160

/** A parameter port as the trace names it: `MSC:0 consigne` (its name from the tables), or
 *  `MSC:0` when the tables have none (name NULL or ""). `parameterize MSC:0 consigne (N bytes) = V`. */
void engine_format_param_port(char *buf, size_t len, const char *module, int port, const char *name);

/* ---- the words of the engines' actions --------------------------------------------------------
   One place for a run's engines (sup_main.c, ord_main.c) and the simulator (sim_world.c), so that
   `contract trace` and `contract simulate --verbose` tell an action alike. A run's log prefixes an
   undo with `undo: `; the simulator's harness reports it bare and its trace conversion adds the
   prefix (steps-to-trace.ts actionAsLogged). */
#define ACTION_START_MODULE "start module %s (priority %d)"       /* module, priority            */
#define ACTION_STOP_MODULE "stop module %s"                       /* module                      */
#define ACTION_CLAIM_PRIORITY "set priority of %s to %d (claim #%u)" /* module, priority, claim  */
#define ACTION_RELEASE_PRIORITY "release priority claim #%u on %s" /* claim, module              */

/** Room for the lines below: a parameterize line is the longest (a port, a value, the rest). */
#define ACTION_LINE_MAX (ACTION_VALUE_MAX + ENGINE_PARAM_PORT_MAX + 48)

/** `parameterize MSC:0 consigne (24 bytes) = {i=1,j=2,k=3}`: a parameter port set (its value as
 *  engine_format_value writes it, its port as engine_format_param_port names it). */
void engine_format_parameterize(char *buf, size_t len, const char *module, int port, const char *name,
                                const void *value, size_t size, const ContractType *type);

/** An event schema's event flow as its actions name it: `A:p =* B:i` (`=>` one shot). */
void engine_format_event_flow(char *buf, size_t len, const ContractEventFlow *f);

/** The name of an event flow's holds, in the run's hold files and flow_hold records (and the
 *  simulator's): `flow-SRC-o-DST-i`, or `flow-<16 hex digits>` (a hash of it) when that is
 *  ENGINE_HOLD_NAME_MAX characters or more. */
#define ENGINE_HOLD_NAME_MAX 64 /* a module name's room, libmodule.h CONTRACT_NAME_MAX (module_holds.c checks) */
void engine_flow_hold_name(char *out, size_t n, const char *src, int src_port, const char *dst, int dst_port);

/** A data flow as ORD's actions name it: `A:p -> B:i` (`connect` adds ` * k`, its periodicity). */
void engine_format_data_flow(char *buf, size_t len, const ContractDataFlow *f);

/** Writes the values of a parameter block as a trace line names them, `(speed = 0.3, mode =
 *  AUTO)` (each value as engine_format_value writes it), cut with `...)` to fit len - 1 bytes;
 *  `()` for no parameters (nvars 0: as the source writes the call); "" when the values are not
 *  known (nvars < 0: a block of another size than the parameters'). `function F(...) started`,
 *  `activate schema S(...)`, `activate supervisor SUP.f(...)`. */
void engine_format_params(char *buf, size_t len, const ContractVar *vars, int nvars, const void *block);

/** Copies a NUL-terminated string into a string value (char[256]), truncating. */
void engine_set_string(char *dst, const char *src);

#endif
