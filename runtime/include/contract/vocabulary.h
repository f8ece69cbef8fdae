/*
 * contract/vocabulary.h — the data-table format of the ContrACT engines.
 *
 * Seam 2 of docs/architecture.md. The code generator writes, for the scheduler
 * (`modules/ORD_mod/vocabulary.c`) and for each supervisor (`modules/<SUP>_mod/vocabulary.c`),
 * constant C tables of the types below; the generated `module.c` only binds them:
 *
 *     extern const ContractOrdVocabulary ORD_VOCABULARY;
 *     int ModuleMain(int argc, const char *argv[]) {
 *         return contract_ord_main(&ORD_VOCABULARY, argc, argv);
 *     }
 *
 *     extern const ContractSupervisorVocabulary SUP_VOCABULARY;
 *     int ModuleMain(int argc, const char *argv[]) {
 *         return contract_supervisor_main(&SUP_VOCABULARY, argc, argv);
 *     }
 *
 * The module.c of ORD and of a supervisor may keep empty port tables (IUSE/IPRODUCE/IREACT/
 * IDETECT/PARAM_SIZE_* = their *_TERM only): the engines read the event ports from these tables
 * and keep their own subscriber lists.
 * The engines (runtime/src/engines/) are generic: no generated control flow, only data and
 * small generated adapter functions (type operations, user test/compute functions).
 * Semantics: docs/semantics.md (the rules) and docs/engines.md (how the engines carry them out).
 *
 * Conventions used throughout:
 *  - Counts are `int` and go with the pointer they describe (`x`, `nx`). A count of 0 allows
 *    a NULL pointer.
 *  - Module, supervisor and port designations use the Cactal names and port numbers
 *    ("MAA", port 2), not table indexes. Rules, locals, parameters are designated by their
 *    index in their own table (declaration order).
 *  - Times are int64 nanoseconds (RTIME of libmodule). `1ms` = 1000000.
 *  - A "field path" (`temp_consigne.k`, `temp_message.value`) is a byte offset into the
 *    variable (offsetof chain, e.g. `offsetof(TypeC, value)`) plus the ContractType of the field.
 *  - Cactal `int` -> C `long`, `float` -> `double`, `string` -> `char[256]` (always a full
 *    256-byte array, NUL-terminated: constants of type string must be `static const char x[256]`).
 *  - Every table must stay valid for the program's lifetime (static storage).
 *  - The engines check the tables when they start (indexes in range, types of both sides of
 *    an assignment compatible, sizes consistent) and refuse to start with a clear message
 *    naming the function/rule/action at fault.
 */
#ifndef CONTRACT_VOCABULARY_H
#define CONTRACT_VOCABULARY_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Bumped on any incompatible change of these tables; generated tables set `.version`. */
#define CONTRACT_VOCABULARY_VERSION 1

/** Maximum size in bytes of any one value (port variable, parameter, local) the engines move. */
#define CONTRACT_MAX_VALUE_SIZE 65536
/** Size of a Cactal string (C char[256]). */
#define CONTRACT_STRING_SIZE 256

/* ======================================================================================
 * 1. Types
 * ====================================================================================== */

typedef enum ContractTypeKind {
    CONTRACT_KIND_LONG = 1,   /* Cactal int   -> long                                       */
    CONTRACT_KIND_DOUBLE = 2, /* Cactal float -> double                                     */
    CONTRACT_KIND_STRING = 3, /* Cactal string -> char[256]                                 */
    CONTRACT_KIND_STRUCT = 4, /* a datatype (generated Shared<Type>.h)                       */
    /* Extensions of the report (docs/language-reference.md); see "Extension types" below.   */
    CONTRACT_KIND_BOOL = 5,   /* Cactal bool  -> C bool (<stdbool.h>), sizeof(bool) == 1      */
    CONTRACT_KIND_ENUM = 6,   /* an enumeration -> a C enum (read as a signed integer of
                                 `size` bytes: 1, 2, 4 or 8)                                 */
    CONTRACT_KIND_ARRAY = 7   /* T[n] -> C array of n T; T[n][m] -> an array of n T[m]       */
} ContractTypeKind;

struct ContractType;

/** A member of an enumeration: its Cactal name (`AUTO`, printed in logs) and C value. */
typedef struct ContractEnumMember {
    const char *name;
    long value;
} ContractEnumMember;

/** A field of a datatype, for readable logs (`{q=[0.1,0.2],mode=AUTO}`): Cactal name, offsetof
 *  in the C struct, type. Optional (a datatype without fields is logged as `{N bytes}`). */
typedef struct ContractField {
    const char *name;
    size_t offset;
    const struct ContractType *type;
} ContractField;

/**
 * Type descriptor. One per datatype, emitted in vocabulary.c with CONTRACT_DEFINE_TYPE
 * (below), which wraps the functions of the generated Shared<Type>.h:
 *   int eq_TypeA(TypeA *, TypeA *) ... supeq_TypeA, void set_TypeA(TypeA *dst, TypeA *src),
 *   int get_TypeA(TypeA *, char *text)  (returns characters read, -1 on a parse error),
 *   void print_TypeA(TypeA *)           (prints to stdout).
 * Primitive types have built-in descriptors: contract_type_long / _double / _string / _bool.
 * Comparison functions return 1 (true) or 0 (false).
 *
 * Extension types (bool, enumerations, fixed-size arrays) are described by data alone: their
 * function pointers may be NULL (recommended), and the runtime then uses generic operations
 * driven by the descriptor (contract_value_* below). Non-NULL pointers are used as given.
 *  - bool: the built-in contract_type_bool (printed and parsed `true` / `false`; false < true).
 *  - enumeration `enum Mode { IDLE, TELEOP, AUTO }`: kind ENUM, size sizeof(the C enum),
 *    `members` in declaration order with their C values. Compared by value; printed and parsed
 *    by member name (`AUTO`; parsing also takes `Mode.AUTO` and the number). default_value NULL
 *    means all-zero bytes (value 0), so give one when 0 is not a member.
 *        static const ContractEnumMember contract_members_Mode[] = {
 *            {"IDLE", Mode_IDLE}, {"TELEOP", Mode_TELEOP}, {"AUTO", Mode_AUTO}};
 *        static const ContractType contract_type_Mode = CONTRACT_ENUM_TYPE(Mode,
 *            contract_members_Mode, 3, NULL);
 *  - array `float[180]`: kind ARRAY, `element` the element's descriptor, `count` its length,
 *    size == count * element->size (C layout, no padding). `float[3][3]` (C `double m[3][3]`)
 *    is an array of 3 `float[3]`. Arrays of any type, datatypes included. default_value NULL
 *    means every element takes the element type's default (recursively). Generic operations:
 *    eq when every element is eq, diff = !eq; inf/sup when every element is inf/sup (as the
 *    generated functions of datatypes do, field by field), infeq = inf or eq, supeq = sup or eq.
 *    Printed `[0.1,0.2,0.3]`; parsed from `{0.1, 0.2, 0.3}` (Cactal value syntax) or
 *    `[0.1, 0.2, 0.3]` with exactly `count` elements.
 *        static const ContractType contract_type_float_180 = CONTRACT_ARRAY_TYPE("float[180]",
 *            double[180], contract_type_double, 180, NULL);
 *    An element access with a constant index (`scan.ranges[90]`) is a field path like any
 *    other: offset offsetof(Scan, ranges) + 90 * sizeof(double), type contract_type_double.
 *  - datatypes may list their fields (`fields`, `nfields`; CONTRACT_DEFINE_TYPE_FIELDS) so that
 *    logs show `{x=1,q=[0.1,0.2],mode=AUTO}` instead of `{N bytes}` (and, without a `get`,
 *    are parsed from `{v1, v2, ...}` in field order).
 * The engines check these descriptors when they start (element/count/size agree, members
 * present, enum size 1/2/4/8, fields inside the struct).
 */
typedef struct ContractType {
    const char *name;          /* "TypeA", "int", "float", "string"                         */
    ContractTypeKind kind;
    size_t size;               /* sizeof the C type (256 for string)                        */
    const void *default_value; /* value when none is given: the datatype's field defaults
                                  ({0.0,0.0,0.0} for TypeA); NULL means all-zero bytes      */
    int (*eq)(void *a, void *b);
    int (*diff)(void *a, void *b);
    int (*inf)(void *a, void *b);
    int (*sup)(void *a, void *b);
    int (*infeq)(void *a, void *b);
    int (*supeq)(void *a, void *b);
    void (*set)(void *dst, void *src);     /* copy; NULL means memcpy(size)                 */
    int (*get)(void *dst, char *text);     /* parse the textual form used by control tools  */
    void (*print)(void *value);            /* human-readable print on stdout (logs)         */
    /* Extensions (zero/NULL for int, float, string and datatypes without a field table): */
    const struct ContractType *element;    /* ARRAY: type of the elements                    */
    int count;                             /* ARRAY: number of elements (>= 1)               */
    int nmembers;                          /* ENUM: members, declaration order (>= 1)        */
    const ContractEnumMember *members;
    int nfields;                           /* STRUCT (optional): its fields, for logs        */
    const ContractField *fields;
} ContractType;

/** Built-in descriptors of the primitive types (defined by the runtime). */
extern const ContractType contract_type_long;
extern const ContractType contract_type_double;
extern const ContractType contract_type_string;
extern const ContractType contract_type_bool;   /* extension: Cactal bool, C bool */

/** Descriptor of an enumeration: CONTRACT_ENUM_TYPE(Mode, members, nmembers, default_ptr) with
 *  `Mode` the C enum type (named "Mode" in messages). */
#define CONTRACT_ENUM_TYPE(E, members_, nmembers_, default_ptr)                                \
    {.name = #E, .kind = CONTRACT_KIND_ENUM, .size = sizeof(E), .default_value = (default_ptr), \
     .nmembers = (nmembers_), .members = (members_)}

/** Descriptor of an array: CONTRACT_ARRAY_TYPE("float[180]", double[180], contract_type_double,
 *  180, default_ptr): Cactal name, C type (for its size), element descriptor (an lvalue),
 *  element count, default (NULL: element defaults). */
#define CONTRACT_ARRAY_TYPE(cactal_name, ctype, element_, count_, default_ptr)                 \
    {.name = (cactal_name), .kind = CONTRACT_KIND_ARRAY, .size = sizeof(ctype),                \
     .default_value = (default_ptr), .element = &(element_), .count = (count_)}

/**
 * CONTRACT_DEFINE_TYPE(TypeA, default_ptr) defines `static const ContractType contract_type_TypeA`
 * with type-safe adapters around the generated eq_/diff_/inf_/sup_/infeq_/supeq_/set_/get_/print_
 * functions (no call through an incompatible function pointer), marked unused so that a type no
 * table refers to does not warn. No semicolon after it. Use after including
 * SharedTypeA.h, e.g.
 *     static const TypeA contract_default_TypeA = {0.0, 0.0, 0.0};
 *     CONTRACT_DEFINE_TYPE(TypeA, &contract_default_TypeA)
 */
#define CONTRACT_DEFINE_TYPE(T, default_ptr) CONTRACT_DEFINE_TYPE_FIELDS(T, default_ptr, 0, NULL)

/** As CONTRACT_DEFINE_TYPE, with the datatype's field table for readable logs (extension):
 *     static const ContractField contract_fields_Scan[] = {
 *         {"ranges", offsetof(Scan, ranges), &contract_type_float_180},
 *         {"mode", offsetof(Scan, mode), &contract_type_Mode}};
 *     CONTRACT_DEFINE_TYPE_FIELDS(Scan, &contract_default_Scan, 2, contract_fields_Scan)  */
#define CONTRACT_DEFINE_TYPE_FIELDS(T, default_ptr, nfields_, fields_)                         \
    static int contract_eq_##T(void *a, void *b) { return eq_##T((T *)a, (T *)b); }            \
    static int contract_diff_##T(void *a, void *b) { return diff_##T((T *)a, (T *)b); }        \
    static int contract_inf_##T(void *a, void *b) { return inf_##T((T *)a, (T *)b); }          \
    static int contract_sup_##T(void *a, void *b) { return sup_##T((T *)a, (T *)b); }          \
    static int contract_infeq_##T(void *a, void *b) { return infeq_##T((T *)a, (T *)b); }      \
    static int contract_supeq_##T(void *a, void *b) { return supeq_##T((T *)a, (T *)b); }      \
    static void contract_set_##T(void *d, void *s) { set_##T((T *)d, (T *)s); }               \
    static int contract_get_##T(void *d, char *text) { return get_##T((T *)d, text); }         \
    static void contract_print_##T(void *v) { print_##T((T *)v); }                             \
    __attribute__((unused)) static const ContractType contract_type_##T = {                    \
        .name = #T, .kind = CONTRACT_KIND_STRUCT, .size = sizeof(T),                           \
        .default_value = (default_ptr), .eq = contract_eq_##T, .diff = contract_diff_##T,      \
        .inf = contract_inf_##T, .sup = contract_sup_##T, .infeq = contract_infeq_##T,         \
        .supeq = contract_supeq_##T, .set = contract_set_##T, .get = contract_get_##T,         \
        .print = contract_print_##T, .nfields = (nfields_), .fields = (fields_)};

/* ======================================================================================
 * 2. User functions (function prototypes of datatype files)
 * ====================================================================================== */

/**
 * A bool (test) or void (compute) function. Every argument is passed by pointer, so that compute
 * functions can assign the supervisor's locals (docs/codegen.md "The tree").
 * The generator emits one adapter per function:
 *     static int call_testit(void **args) { return testit((char *)args[0], (TypeA *)args[1]); }
 *     static int call_doit(void **args) { doit((char *)args[0], (double *)args[1]); return 0; }
 * For compute, arguments that are locals are passed as pointers into the function's locals
 * (so the function may assign them); constants and port variables go through temporaries.
 */
typedef struct ContractUserFunction {
    const char *name;                      /* "testit"                                     */
    int returns_bool;                      /* 1: test function, 0: compute (void) function */
    int nargs;
    const ContractType *const *arg_types;  /* nargs entries                                */
    int (*call)(void **args);              /* the adapter; result used for bool only       */
} ContractUserFunction;

/* ======================================================================================
 * 3. Variables, value references and assignments
 * ====================================================================================== */

/**
 * A named variable in a block of memory: a schema parameter, a supervision function's
 * parameter, or a local. The engine allocates `size` bytes for the block (see
 * ContractSchema.params_size, ContractFunction.params_size/locals_size) and finds each
 * variable at `offset`. Offsets must be aligned for the type (the generator may simply
 * use the offsets of a generated struct, or a running sum rounded up to 8).
 */
typedef struct ContractVar {
    const char *name;          /* "consigne"                                                */
    const ContractType *type;
    size_t offset;             /* byte offset in the block                                  */
    const void *default_value; /* declared default (`TypeA consigne = {..}`); NULL: the
                                  type's default_value                                      */
} ContractVar;

/** What a value reference designates. */
typedef enum ContractRefKind {
    CONTRACT_REF_CONST = 1,    /* a constant: `constant` points to a value of `type`            */
    CONTRACT_REF_LOCAL = 2,    /* local `index` of the running function, + field offset          */
    CONTRACT_REF_PARAM = 3,    /* parameter `index` (function parameter for local initialisers;
                                  schema parameter in a ContractSchemaModule setting)            */
    CONTRACT_REF_IN_PORT = 4,  /* supervisor in event port number `index` (its port variable),
                                  + field offset. In tests: its current value (for the tested
                                  event's own port, the data of that occurrence). In
                                  extractions: the data of the occurrence of the clause that
                                  arrived on that port (falls back to the current value).        */
    CONTRACT_REF_ORD_SCHEMA = 5 /* `ord_schema`: the schema name carried by an ORD event (string) */
} ContractRefKind;

/** A value reference: constant or variable with field path. */
typedef struct ContractRef {
    ContractRefKind kind;
    int index;                 /* LOCAL/PARAM: table index; IN_PORT: Cactal port number      */
    size_t offset;             /* field path as byte offset inside the variable (0 = whole)  */
    const ContractType *type;  /* type of the designated value (the field's type)            */
    const void *constant;      /* CONST only: pointer to a static value of `type`             */
} ContractRef;

/**
 * An elementary assignment `target[index] (+offset) = src`. Used for local initialisers,
 * extractions (target = local), parameter assignments of activations (target = the schema's /
 * function's parameter), notify (target = the supervisor's out port variable, index = port
 * number). A structured value written in Cactal is flattened by the generator into one
 * assignment per field (or one assignment of a whole constant). `type` is the type at the
 * target; if `src.type` differs, only long<->double conversions are performed.
 */
typedef struct ContractAssign {
    int index;                 /* target variable (table index, or port number for notify)  */
    size_t offset;             /* field path in the target                                   */
    const ContractType *type;  /* type of the target field                                   */
    ContractRef src;
} ContractAssign;

/**
 * The value given to a parameter port of a module: start from `type->default_value`, then
 * apply `parts` in order (each: `offset` + `type` in the port value, `src`; `index` unused).
 * `MSC (consigne:0)` -> {port 0, TypeA, 1 part {0, 0, TypeA, PARAM consigne}}.
 */
typedef struct ContractParamSetting {
    int port;                  /* parameter port number of the module                       */
    const ContractType *type;  /* type of that parameter port                                */
    int nparts;
    const ContractAssign *parts;
    const char *name;          /* the port's name in the module's declaration ("consigne"),
                                  for the trace (`parameterize MSC:0 consigne ...`); NULL: none */
} ContractParamSetting;

/* ======================================================================================
 * 4. Schemas (shared by ORD and supervisors)
 * ====================================================================================== */

typedef enum ContractSchemaKind {
    CONTRACT_SCHEMA_PERIODIC = 1, /* carried out by ORD                                     */
    CONTRACT_SCHEMA_EVENT = 2     /* carried out by the supervisor engine itself             */
} ContractSchemaKind;

/** A module of a schema with its parameterisation `MSC (consigne:0)`. */
typedef struct ContractSchemaModule {
    const char *module;                   /* "MSC"                                          */
    int nsettings;
    const ContractParamSetting *settings; /* src refs: CONST, or PARAM = schema parameter   */
} ContractSchemaModule;

/** Precedence edge `MSA -> MSC`: indexes into ContractSchema.modules. */
typedef struct ContractPrecedence {
    int before;
    int after;
} ContractPrecedence;

/** Data communication `A:o -> B:i * k` (periodic schemas). */
typedef struct ContractDataFlow {
    const char *src_module; int src_port;  /* out data port of A                            */
    const char *dst_module; int dst_port;  /* in data port of B                             */
    int periodicity;                       /* k >= 1: delivered on every k-th activation of A */
} ContractDataFlow;

typedef enum ContractEventMode {
    CONTRACT_CONTINUOUS = 0,  /* `=*`                                                        */
    CONTRACT_ONESHOT = 1      /* `=>`: unsubscribed after the first notification            */
} ContractEventMode;

/** Event communication `A:o =* B:i` / `A:o => B:i` (event schemas). */
typedef struct ContractEventFlow {
    const char *src_module; int src_port;
    const char *dst_module; int dst_port;
    ContractEventMode mode;
} ContractEventFlow;

/** A schema. The same descriptor is emitted for ORD (periodic ones) and for any supervisor
 *  that activates it (the supervisor needs its parameter layout; for event schemas, all). */
typedef struct ContractSchema {
    const char *name;                     /* "schemaCommande1"                               */
    ContractSchemaKind kind;
    int64_t period_ns;                    /* periodic only                                   */
    int64_t critical_delay_ns;            /* periodic only                                   */
    int nparams;
    const ContractVar *params;            /* schema parameters with their defaults           */
    size_t params_size;                   /* bytes of the parameter block                    */
    int nmodules;
    const ContractSchemaModule *modules;
    int nprecedences;
    const ContractPrecedence *precedences; /* periodic only; acyclic                          */
    int ndata_flows;
    const ContractDataFlow *data_flows;   /* periodic only                                   */
    int nevent_flows;
    const ContractEventFlow *event_flows; /* event only                                      */
} ContractSchema;

/* ======================================================================================
 * 5. Scheduler (ORD)
 * ====================================================================================== */

/** A synchronous module known to ORD. */
typedef struct ContractOrdModule {
    const char *name;          /* "MSC"                                                      */
    int priority;              /* fixed priority computed by the generator (higher = more)  */
    int64_t wcet_ns;           /* its `C` (scheduling block), informative (logs, checks)     */
} ContractOrdModule;

typedef struct ContractOrdVocabulary {
    int version;               /* CONTRACT_VOCABULARY_VERSION                                */
    int nmodules;
    const ContractOrdModule *modules;      /* the scheduler configuration's `modules`        */
    int nschemas;
    const ContractSchema *const *schemas;  /* the scheduler configuration's `schemas`        */
    int nsupervisors;
    const char *const *supervisors;        /* every supervisor: receives ORD:0 and ORD:1      */
} ContractOrdVocabulary;

/** ORD's out event ports (Cactal `ORD:0`, `ORD:1`); data: the schema name (string). */
#define CONTRACT_ORD_EVENT_DEADLINE_MISS 0
#define CONTRACT_ORD_EVENT_CONFLICT 1

/* ======================================================================================
 * 6. Supervisors
 * ====================================================================================== */

/** An event port of the supervisor (`in :2 string connection_status;`). */
typedef struct ContractEventPort {
    int port;                  /* Cactal port number                                          */
    const char *name;          /* port variable name                                          */
    const ContractType *type;
    const void *initial_value; /* NULL: the type's default                                    */
} ContractEventPort;

/** Persistence of an event occurrence. Windows are inclusive: present on [t, t + ns]. */
typedef enum ContractPersistKind {
    CONTRACT_PERSIST_NONE = 0,     /* present only while it is being processed               */
    CONTRACT_PERSIST_TIME = 1,     /* `{500ms}`: persist_ns                                   */
    CONTRACT_PERSIST_INFINITE = 2  /* `{infinite}`: until the function ends                   */
} ContractPersistKind;

/** Test operators inside `<...>` of a module event. */
typedef enum ContractTestOp {
    CONTRACT_TEST_EQ = 1,   /* ==                                                            */
    CONTRACT_TEST_NE,       /* !=                                                            */
    CONTRACT_TEST_LT,       /* <   (inf_)                                                    */
    CONTRACT_TEST_GT,       /* >   (sup_)                                                    */
    CONTRACT_TEST_LE,       /* <=  (infeq_)                                                  */
    CONTRACT_TEST_GE,       /* >=  (supeq_)                                                  */
    CONTRACT_TEST_CALL      /* boolFunction(args...)                                         */
} ContractTestOp;

/** One test: `lhs op rhs`, or a call of a bool user function with `args`. */
typedef struct ContractTest {
    ContractTestOp op;
    ContractRef lhs, rhs;                 /* comparisons (int and float mix numerically)      */
    const ContractUserFunction *fn;       /* CALL                                             */
    int nargs;
    const ContractRef *args;              /* CALL: positional, by pointer (temporaries)      */
} ContractTest;

/** `(t1 & t2 & ...)`: all tests true. */
typedef struct ContractTestClause {
    int ntests;
    const ContractTest *tests;
} ContractTestClause;

typedef enum ContractEventKind {
    CONTRACT_EV_MODULE = 1,   /* `MAA:2<...>{p}(...)`, `ORD:0`, `SUP:1` (another supervisor)  */
    CONTRACT_EV_STARTED,      /* `started(L)`                                                */
    CONTRACT_EV_ENDOF,        /* `endof(L)`                                                  */
    CONTRACT_EV_DURATION,     /* `duration(L)=t`: t after L became active, if still active   */
    CONTRACT_EV_ELAPSED       /* `elapsed=t`: t after the function started                    */
} ContractEventKind;

/** One event of a clause. */
typedef struct ContractEvent {
    ContractEventKind kind;
    /* MODULE: */
    const char *module;        /* source module/supervisor name, or "ORD"                     */
    int port;                  /* its out event port                                          */
    int in_port;               /* the supervisor in port that receives this flow (from the
                                  function's `subscribe M:o =* :i`, the one whose variable the
                                  event reads); -1: any of them (an event reading none of
                                  them, or several), and for ORD events                        */
    int ntest_clauses;         /* tests `<c1 | c2 | ...>`; 0 = no test (always significant)  */
    const ContractTestClause *test_clauses;
    /* STARTED / ENDOF / DURATION: */
    int rule;                  /* rule index in the function                                  */
    /* DURATION / ELAPSED: */
    int64_t time_ns;
    /* all kinds: */
    ContractPersistKind persist;
    int64_t persist_ns;        /* PERSIST_TIME only                                           */
    int nextractions;          /* `(local = v, ...)`, targets are locals                      */
    const ContractAssign *extractions;
} ContractEvent;

/** `(e1 and e2 and ...)`. */
typedef struct ContractClause {
    int nevents;
    const ContractEvent *events;
} ContractClause;

/** `c1 or c2 or ...`. */
typedef struct ContractCondition {
    int nclauses;
    const ContractClause *clauses;
} ContractCondition;

typedef enum ContractActionKind {
    CONTRACT_ACT_SCHEMA = 1,        /* activate schema S(p = v, ...)          undo: deactivate */
    CONTRACT_ACT_PARAMETERIZE,      /* parameterize M(v :N, ...)              no undo          */
    CONTRACT_ACT_SUPERVISOR,        /* activate supervisor SUP.fn(p = v, ...) undo: stop it    */
    CONTRACT_ACT_RESTTIME_MODULE,   /* activate resttime module M             undo: §4.3       */
    CONTRACT_ACT_CRITICAL_MODULE,   /* activate critical module M             undo: §4.3       */
    CONTRACT_ACT_COMPUTE,           /* compute f(args)                        no undo          */
    CONTRACT_ACT_SUBSCRIBE,         /* subscribe M:o =* :i / M:o => :i        undo: unsubscribe*/
    CONTRACT_ACT_NOTIFY             /* notify :o (var = v, ...)               no undo          */
} ContractActionKind;

/** Parameter layout of a supervision function as seen by a caller (`activate supervisor`). */
typedef struct ContractFunctionSignature {
    const char *supervisor;    /* "SUP"                                                       */
    const char *function;      /* "action"                                                    */
    int nparams;
    const ContractVar *params; /* same layout as the callee's ContractFunction.params         */
    size_t params_size;
} ContractFunctionSignature;

typedef struct ContractAction {
    ContractActionKind kind;
    /* SCHEMA: */
    const ContractSchema *schema;
    /* PARAMETERIZE, RESTTIME/CRITICAL_MODULE: target module; SUBSCRIBE: source module: */
    const char *module;
    /* PARAMETERIZE: */
    int nsettings;
    const ContractParamSetting *settings;  /* src refs: CONST, LOCAL, IN_PORT                */
    /* SUPERVISOR: */
    const ContractFunctionSignature *callee;
    /* SCHEMA (target: schema parameter index), SUPERVISOR (callee parameter index),
       NOTIFY (target: out port number): */
    int nassigns;
    const ContractAssign *assigns;
    /* COMPUTE: */
    const ContractUserFunction *fn;
    int nargs;
    const ContractRef *args;
    /* SUBSCRIBE: */
    int src_port;              /* out event port of `module`                                  */
    int in_port;               /* the supervisor's in event port                              */
    ContractEventMode mode;
    /* NOTIFY: */
    int out_port;              /* the supervisor's out event port                             */
} ContractAction;

typedef struct ContractRule {
    const char *label;         /* "SECOND"                                                    */
    ContractCondition pre;
    int nactions;
    const ContractAction *actions;
    ContractCondition post;
} ContractRule;

typedef struct ContractFunction {
    const char *name;          /* "action"                                                    */
    int nparams;
    const ContractVar *params;
    size_t params_size;
    int nlocals;
    const ContractVar *locals; /* default_value: the type default or a constant initialiser  */
    size_t locals_size;
    int nlocal_inits;          /* initialisers applied in order after defaults; src refs:
                                  CONST or PARAM (function parameter, with field path)         */
    const ContractAssign *local_inits;
    int nrules;
    const ContractRule *rules;
} ContractFunction;

typedef struct ContractSupervisorVocabulary {
    int version;               /* CONTRACT_VOCABULARY_VERSION                                */
    const char *name;          /* "SUP"                                                       */
    int priority;              /* its own fixed priority                                      */
    int priority_interaction;  /* priority of modules started by event schemas                */
    int priority_resttime;     /* `activate resttime module`                                  */
    int priority_critical;     /* `activate critical module`                                  */
    int nin_ports;
    const ContractEventPort *in_ports;
    int nout_ports;
    const ContractEventPort *out_ports;
    int nfunctions;
    const ContractFunction *functions;
} ContractSupervisorVocabulary;

/* ======================================================================================
 * 7. Entry points (called from the generated module.c's ModuleMain)
 * ====================================================================================== */

/** Operations on any described value (the engines' own; also for tools and tests). They use
 *  the descriptor's functions when present, otherwise the generic ones described above.
 *  compare: op EQ..GE, returns 1/0 (int and float mix numerically). get: parses the textual
 *  form at `text`, returns characters read or -1 (dst unchanged). print: on stdout.
 *  format: a short readable form into buf (at most len - 1 characters; arrays show their first
 *  CONTRACT_FORMAT_MAX_ITEMS elements, then `...`; cut with `...` when longer), as in the trace
 *  records (docs/runtime-api.md "Trace records"); print shows every element. */
#define CONTRACT_FORMAT_MAX_ITEMS 10
int contract_value_compare(ContractTestOp op, const ContractType *t, const void *a, const void *b);
int contract_value_get(const ContractType *t, void *dst, char *text);
void contract_value_print(const ContractType *t, const void *value);
void contract_value_format(char *buf, size_t len, const ContractType *t, const void *value);

/** Runs the scheduler until stopped/killed. Returns 0 on a clean stop, non-zero on error
 *  (including invalid tables, with a message on stderr). */
int contract_ord_main(const ContractOrdVocabulary *v, int argc, const char *argv[]);

/** Runs a supervisor until stopped/killed. Same return convention. */
int contract_supervisor_main(const ContractSupervisorVocabulary *v, int argc, const char *argv[]);

/** Table checks (also done by the *_main functions). Return 0 when valid, otherwise -1 and a
 *  message in err (NUL-terminated, at most errlen bytes). */
int contract_check_ord_vocabulary(const ContractOrdVocabulary *v, char *err, size_t errlen);
int contract_check_supervisor_vocabulary(const ContractSupervisorVocabulary *v, char *err,
                                         size_t errlen);

/* ======================================================================================
 * 8. Worked example: the report's rule SECOND of SUP.action (§4.7, §8.1)
 * ======================================================================================
 *
 *   SECOND:[(MAA:2<(connection_status == "disconnected" & testit("dedede", temp_consigne))>
 *            and started(FIRST){infinite})]
 *       subscribe MSC:1 => :3;
 *       activate schema schemaCommande1(consigne = temp_consigne)
 *       [MSC:1(failure_data = failure, temp_mess_type = "commutation")]
 *
 * With locals of `action` in declaration order: 0 temp_message (TypeC), 1 temp_mess_type
 * (string), 2 failure_data (TypeD), 3 temp_consigne (TypeA); rules 0 FIRST, 1 SECOND, ...;
 * in ports 1 message_received (TypeC), 2 connection_status (string), 3 failure (TypeD):
 *
 *   static const char k_disconnected[256] = "disconnected";
 *   static const char k_dedede[256] = "dedede";
 *   static const char k_commutation[256] = "commutation";
 *   static const ContractType *const testit_args[] = {&contract_type_string, &contract_type_TypeA};
 *   static int call_testit(void **a) { return testit((char *)a[0], (TypeA *)a[1]); }
 *   static const ContractUserFunction fn_testit = {"testit", 1, 2, testit_args, call_testit};
 *
 *   static const ContractRef second_testit_args[] = {
 *       {CONTRACT_REF_CONST, 0, 0, &contract_type_string, k_dedede},
 *       {CONTRACT_REF_LOCAL, 3, 0, &contract_type_TypeA, NULL}};
 *   static const ContractTest second_tests[] = {
 *       {CONTRACT_TEST_EQ, {CONTRACT_REF_IN_PORT, 2, 0, &contract_type_string, NULL},
 *                          {CONTRACT_REF_CONST, 0, 0, &contract_type_string, k_disconnected},
 *        NULL, 0, NULL},
 *       {CONTRACT_TEST_CALL, {0}, {0}, &fn_testit, 2, second_testit_args}};
 *   static const ContractTestClause second_test_clauses[] = {{2, second_tests}};   // one & clause
 *   static const ContractEvent second_pre_events[] = {
 *       {.kind = CONTRACT_EV_MODULE, .module = "MAA", .port = 2, .in_port = 2,
 *        .ntest_clauses = 1, .test_clauses = second_test_clauses,
 *        .persist = CONTRACT_PERSIST_NONE},
 *       {.kind = CONTRACT_EV_STARTED, .rule = 0, .persist = CONTRACT_PERSIST_INFINITE}};
 *   static const ContractClause second_pre[] = {{2, second_pre_events}};
 *
 *   static const ContractAssign second_post_extr[] = {
 *       {2, 0, &contract_type_TypeD, {CONTRACT_REF_IN_PORT, 3, 0, &contract_type_TypeD, NULL}},
 *       {1, 0, &contract_type_string, {CONTRACT_REF_CONST, 0, 0, &contract_type_string,
 *                                      k_commutation}}};
 *   static const ContractEvent second_post_events[] = {
 *       {.kind = CONTRACT_EV_MODULE, .module = "MSC", .port = 1, .in_port = 3,
 *        .persist = CONTRACT_PERSIST_NONE, .nextractions = 2, .extractions = second_post_extr}};
 *   static const ContractClause second_post[] = {{1, second_post_events}};
 *
 *   static const ContractAssign second_schema_params[] = {   // consigne (param 0) = temp_consigne
 *       {0, 0, &contract_type_TypeA, {CONTRACT_REF_LOCAL, 3, 0, &contract_type_TypeA, NULL}}};
 *   static const ContractAction second_actions[] = {
 *       {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "MSC", .src_port = 1, .in_port = 3,
 *        .mode = CONTRACT_ONESHOT},
 *       {.kind = CONTRACT_ACT_SCHEMA, .schema = &schema_schemaCommande1,
 *        .nassigns = 1, .assigns = second_schema_params}};
 *
 *   // in the function's rule table, index 1:
 *   {"SECOND", {1, second_pre}, 2, second_actions, {1, second_post}},
 *
 * A field path such as `temp_consigne.k` is {CONTRACT_REF_LOCAL, 3, offsetof(TypeA, k), &contract_type_double, NULL}.
 */

#ifdef __cplusplus
}
#endif

#endif /* CONTRACT_VOCABULARY_H */
