/*
 * test_values_ext.c — the extension types of the vocabulary (bool, enumerations, fixed-size
 * arrays, datatype field tables): their generic operations (value_ops.c), the table checks,
 * and a supervisor whose tests and extractions use array elements, enum values and bools
 * (`<(scan.ranges[90] < 0.3)>`, `<(mode == Mode.AUTO)>`, `<(ok == true)>`).
 */
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include "engine_values.h"
#include "fake_world.h"

#define MS 1000000LL

typedef enum Mode { Mode_IDLE = 0, Mode_TELEOP = 1, Mode_AUTO = 2 } Mode;
typedef enum Level { Level_OK = 1, Level_STOP = 5 } Level; /* 0 is no member */
typedef struct Cell {
    long id;
    double w;
} Cell;
typedef struct Scan {
    double ranges[180];
    Mode mode;
    bool ok;
} Scan;

static const ContractEnumMember mode_members[] = {
    {"IDLE", Mode_IDLE}, {"TELEOP", Mode_TELEOP}, {"AUTO", Mode_AUTO}};
static const ContractType type_Mode = CONTRACT_ENUM_TYPE(Mode, mode_members, 3, NULL);
static const ContractEnumMember level_members[] = {{"OK", Level_OK}, {"STOP", Level_STOP}};
static const Level level_default = Level_OK;
static const ContractType type_Level = CONTRACT_ENUM_TYPE(Level, level_members, 2, &level_default);

static const ContractType type_float_3 =
    CONTRACT_ARRAY_TYPE("float[3]", double[3], contract_type_double, 3, NULL);
static const ContractType type_float_3_3 =
    CONTRACT_ARRAY_TYPE("float[3][3]", double[3][3], type_float_3, 3, NULL);
static const ContractType type_float_180 =
    CONTRACT_ARRAY_TYPE("float[180]", double[180], contract_type_double, 180, NULL);
static const ContractType type_int_4 = CONTRACT_ARRAY_TYPE("int[4]", long[4], contract_type_long, 4, NULL);
static const ContractType type_string_2 =
    CONTRACT_ARRAY_TYPE("string[2]", char[2][256], contract_type_string, 2, NULL);
static const ContractType type_bool_2 = CONTRACT_ARRAY_TYPE("bool[2]", bool[2], contract_type_bool, 2, NULL);
static const ContractType type_Mode_2 = CONTRACT_ARRAY_TYPE("Mode[2]", Mode[2], type_Mode, 2, NULL);

/* a datatype with a field table; its default has w = 0.5 */
static const ContractField cell_fields[] = {{"id", offsetof(Cell, id), &contract_type_long},
                                            {"w", offsetof(Cell, w), &contract_type_double}};
static const Cell cell_default = {0, 0.5};
static const ContractType type_Cell = {.name = "Cell", .kind = CONTRACT_KIND_STRUCT, .size = sizeof(Cell),
                                       .default_value = &cell_default, .nfields = 2, .fields = cell_fields};
static const ContractType type_Cell_3 = CONTRACT_ARRAY_TYPE("Cell[3]", Cell[3], type_Cell, 3, NULL);

static const ContractField scan_fields[] = {{"ranges", offsetof(Scan, ranges), &type_float_180},
                                            {"mode", offsetof(Scan, mode), &type_Mode},
                                            {"ok", offsetof(Scan, ok), &contract_type_bool}};
static const ContractType type_Scan = {.name = "Scan", .kind = CONTRACT_KIND_STRUCT, .size = sizeof(Scan),
                                       .nfields = 3, .fields = scan_fields};

static char *fmt(const ContractType *t, const void *v, size_t len) {
    static char buf[1024];
    contract_value_format(buf, len, t, v);
    return buf;
}

void test_ext_bool_values(void) {
    bool a = true, b = false;
    CHECK(contract_value_compare(CONTRACT_TEST_EQ, &contract_type_bool, &a, &a));
    CHECK(contract_value_compare(CONTRACT_TEST_NE, &contract_type_bool, &a, &b));
    CHECK(contract_value_compare(CONTRACT_TEST_GT, &contract_type_bool, &a, &b)); /* false < true */
    CHECK(strcmp(fmt(&contract_type_bool, &a, 64), "true") == 0);
    CHECK(strcmp(fmt(&contract_type_bool, &b, 64), "false") == 0);
    char t1[] = " false,", t2[] = "1", t3[] = "truer", t4[] = "yes";
    bool v = true;
    CHECK(contract_value_get(&contract_type_bool, &v, t1) == 6 && v == false);
    CHECK(contract_value_get(&contract_type_bool, &v, t2) == 1 && v == true);
    CHECK(contract_value_get(&contract_type_bool, &v, t3) == -1 && v == true);
    CHECK(contract_value_get(&contract_type_bool, &v, t4) == -1);
    /* a byte other than 0/1 reads as true without undefined behaviour */
    unsigned char odd = 2;
    CHECK(strcmp(fmt(&contract_type_bool, &odd, 64), "true") == 0);
}

void test_ext_enum_values(void) {
    Mode idle = Mode_IDLE, aut = Mode_AUTO;
    CHECK(contract_value_compare(CONTRACT_TEST_EQ, &type_Mode, &aut, &aut));
    CHECK(!contract_value_compare(CONTRACT_TEST_EQ, &type_Mode, &aut, &idle));
    CHECK(contract_value_compare(CONTRACT_TEST_LT, &type_Mode, &idle, &aut)); /* by value */
    CHECK(strcmp(fmt(&type_Mode, &aut, 64), "AUTO") == 0);
    Mode odd = (Mode)7;
    CHECK(strcmp(fmt(&type_Mode, &odd, 64), "7") == 0); /* not a member: the number */
    Mode m = Mode_IDLE;
    char t1[] = " TELEOP}", t2[] = "Mode.AUTO", t3[] = "2", t4[] = "Other.AUTO", t5[] = "FAST", t6[] = "9";
    CHECK(contract_value_get(&type_Mode, &m, t1) == 7 && m == Mode_TELEOP);
    CHECK(contract_value_get(&type_Mode, &m, t2) == 9 && m == Mode_AUTO);
    m = Mode_IDLE;
    CHECK(contract_value_get(&type_Mode, &m, t3) == 1 && m == Mode_AUTO);
    m = Mode_IDLE;
    CHECK(contract_value_get(&type_Mode, &m, t4) == -1 && m == Mode_IDLE);
    CHECK(contract_value_get(&type_Mode, &m, t5) == -1 && m == Mode_IDLE);
    CHECK(contract_value_get(&type_Mode, &m, t6) == -1 && m == Mode_IDLE);
    /* the default: the given one when 0 is no member */
    Level l = Level_STOP;
    engine_default_value(&l, &type_Level, NULL);
    CHECK(l == Level_OK);
}

void test_ext_array_values(void) {
    double a[3] = {1, 2, 3}, b[3] = {1, 2, 3}, c[3] = {2, 3, 4}, d[3] = {2, 1, 4};
    CHECK(contract_value_compare(CONTRACT_TEST_EQ, &type_float_3, a, b));
    CHECK(!contract_value_compare(CONTRACT_TEST_NE, &type_float_3, a, b));
    CHECK(contract_value_compare(CONTRACT_TEST_LT, &type_float_3, a, c)); /* every element */
    CHECK(!contract_value_compare(CONTRACT_TEST_LT, &type_float_3, a, d)); /* not every one */
    CHECK(contract_value_compare(CONTRACT_TEST_LE, &type_float_3, a, b));  /* eq */
    CHECK(contract_value_compare(CONTRACT_TEST_GE, &type_float_3, c, a));  /* every sup */
    CHECK(!contract_value_compare(CONTRACT_TEST_GE, &type_float_3, d, a));
    CHECK(strcmp(fmt(&type_float_3, a, 64), "[1.0,2.0,3.0]") == 0);

    /* 2-D: C layout m[i][j], printed and parsed row by row */
    double m[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, n[3][3];
    CHECK(strcmp(fmt(&type_float_3_3, m, 128), "[[1.0,0.0,0.0],[0.0,1.0,0.0],[0.0,0.0,1.0]]") == 0);
    char tm[] = "{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, [0, 0, 1]} rest";
    CHECK(contract_value_get(&type_float_3_3, n, tm) == (int)strlen("{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, [0, 0, 1]}"));
    CHECK(memcmp(m, n, sizeof m) == 0);
    CHECK(contract_value_compare(CONTRACT_TEST_EQ, &type_float_3_3, m, n));
    n[2][1] = 0.5;
    CHECK(contract_value_compare(CONTRACT_TEST_NE, &type_float_3_3, m, n));

    /* wrong length, bad element or missing bracket: -1 and the value is unchanged */
    long v[4] = {9, 9, 9, 9};
    char short_[] = "{1, 2, 3}", long_[] = "{1,2,3,4,5}", bad[] = "{1,2,x,4}", open_[] = "{1,2,3,4", ok[] = "[1, -2, 3, 4]";
    CHECK(contract_value_get(&type_int_4, v, short_) == -1);
    CHECK(contract_value_get(&type_int_4, v, long_) == -1);
    CHECK(contract_value_get(&type_int_4, v, bad) == -1);
    CHECK(contract_value_get(&type_int_4, v, open_) == -1);
    CHECK(v[0] == 9 && v[1] == 9 && v[2] == 9 && v[3] == 9);
    CHECK(contract_value_get(&type_int_4, v, ok) == (int)strlen(ok) && v[1] == -2 && v[3] == 4);

    /* strings, bools and enums inside arrays */
    char s[2][256];
    char ts[] = "{\"a, b\", c}";
    CHECK(contract_value_get(&type_string_2, s, ts) == (int)strlen(ts));
    CHECK(strcmp(s[0], "a, b") == 0 && strcmp(s[1], "c") == 0);
    CHECK(strcmp(fmt(&type_string_2, s, 64), "[\"a, b\",\"c\"]") == 0);
    bool bs[2];
    char tb[] = "[true, false]";
    CHECK(contract_value_get(&type_bool_2, bs, tb) == (int)strlen(tb) && bs[0] && !bs[1]);
    CHECK(strcmp(fmt(&type_bool_2, bs, 64), "[true,false]") == 0);
    Mode ms[2];
    char tms[] = "{AUTO, Mode.IDLE}";
    CHECK(contract_value_get(&type_Mode_2, ms, tms) == (int)strlen(tms) && ms[0] == Mode_AUTO && ms[1] == Mode_IDLE);
    CHECK(strcmp(fmt(&type_Mode_2, ms, 64), "[AUTO,IDLE]") == 0);
}

void test_ext_array_of_structs_defaults_and_fields(void) {
    Cell cells[3];
    memset(cells, 0xff, sizeof cells);
    engine_default_value(cells, &type_Cell_3, NULL); /* each element takes the datatype's default */
    CHECK(cells[0].id == 0 && cells[0].w == 0.5 && cells[2].w == 0.5);
    cells[1].id = 7;
    CHECK(strcmp(fmt(&type_Cell_3, cells, 128), "[{id=0,w=0.5},{id=7,w=0.5},{id=0,w=0.5}]") == 0);
    /* a datatype without its own get is read through its field table, in field order */
    char tc[] = "[{1, 0.25}, {2, -1}, {3, 1e3}]", tbad[] = "[{1, 0.25}, {2}, {3, 1}]";
    CHECK(contract_value_get(&type_Cell_3, cells, tc) == (int)strlen(tc));
    CHECK(cells[0].id == 1 && cells[0].w == 0.25 && cells[1].w == -1 && cells[2].w == 1000);
    CHECK(contract_value_get(&type_Cell_3, cells, tbad) == -1 && cells[1].w == -1);
    /* a datatype without a field table keeps its short form */
    ContractType plain = type_Cell;
    plain.nfields = 0;
    plain.fields = NULL;
    char expect[32];
    snprintf(expect, sizeof expect, "{%zu bytes}", sizeof(Cell));
    CHECK(strcmp(fmt(&plain, &cells[0], 64), expect) == 0);
}

void test_ext_format_is_cut_but_well_formed(void) {
    Scan s;
    memset(&s, 0, sizeof s);
    for (int i = 0; i < 180; i++) s.ranges[i] = 0.25 * i;
    s.mode = Mode_AUTO;
    s.ok = true;
    const char *out = fmt(&type_Scan, &s, 60);
    CHECK(strlen(out) <= 59);
    CHECK(strncmp(out, "{ranges=[0.0,0.25,0.5,", 22) == 0);
    CHECK(strcmp(out + strlen(out) - 6, ",...]}") == 0 || strcmp(out + strlen(out) - 5, ",...}") == 0);
    /* arrays show their first CONTRACT_FORMAT_MAX_ITEMS elements, so later fields keep room */
    out = fmt(&type_Scan, &s, 200);
    CHECK(strcmp(out, "{ranges=[0.0,0.25,0.5,0.75,1.0,1.25,1.5,1.75,2.0,2.25,...],mode=AUTO,ok=true}") == 0);
    /* nothing fits: "?" */
    CHECK(strcmp(fmt(&type_Scan, &s, 4), "?") == 0);
}

/* a string value is cut after 64 bytes, never inside a UTF-8 character; bytes that are no UTF-8
   and C1 controls are shown as ?, so a trace line is always UTF-8 */
void test_ext_string_cut_keeps_utf8_whole(void) {
    char v[256];
    char out[200];
    for (int lead = 60; lead <= 64; lead++) { /* the 4-byte character straddles the cut at each offset */
        memset(v, 0, sizeof v);
        memset(v, 'A', (size_t)lead);
        strcat(v, "\xf0\x9f\x98\x80tail");
        engine_format_value(out, sizeof out, v, &contract_type_string);
        size_t len = strlen(out);
        CHECK(strcmp(out + len - 4, "...\"") == 0);
        /* every byte at or above 0x80 belongs to a whole character */
        for (size_t i = 0; i < len;) {
            unsigned char c = (unsigned char)out[i];
            size_t n = c < 0x80 ? 1 : c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : 2;
            for (size_t k = 1; k < n; k++) CHECK(((unsigned char)out[i + k] & 0xC0) == 0x80);
            i += n;
        }
        CHECK((lead <= 60) == (strstr(out, "\xf0\x9f\x98\x80") != NULL));
    }
    strcpy(v, "a\xff\xfe b \xc2\x9b[2J \xc3\xa9 \xed\xa0\x80 z");
    engine_format_value(out, sizeof out, v, &contract_type_string);
    CHECK(strcmp(out, "\"a?? b ?[2J \xc3\xa9 ??? z\"") == 0);
}

/* a parameter block as `function F(...) started` and `activate schema S(...)` name it */
void test_ext_params_are_named_and_cut_on_a_character(void) {
    typedef struct Block {
        Mode mode;
        double speed;
        char label[256];
    } Block;
    const ContractVar vars[] = {{"mode", &type_Mode, offsetof(Block, mode), NULL},
                                {"speed", &contract_type_double, offsetof(Block, speed), NULL},
                                {"label", &contract_type_string, offsetof(Block, label), NULL}};
    Block b;
    memset(&b, 0, sizeof b);
    b.mode = Mode_AUTO;
    b.speed = 0.3;
    strcpy(b.label, "dock");
    char out[200];
    engine_format_params(out, sizeof out, vars, 3, &b);
    CHECK(strcmp(out, "(mode = AUTO, speed = 0.3, label = \"dock\")") == 0);
    engine_format_param_port(out, sizeof out, "MSC", 0, "consigne"); /* a parameter port by its name too */
    CHECK(strcmp(out, "MSC:0 consigne") == 0);
    engine_format_param_port(out, sizeof out, "MSC", 2, NULL); /* tables without names */
    CHECK(strcmp(out, "MSC:2") == 0);
    engine_format_param_port(out, sizeof out, "MSC", 2, "");
    CHECK(strcmp(out, "MSC:2") == 0);
    /* the action words a run and the simulator share */
    long three = 3;
    engine_format_parameterize(out, sizeof out, "CTL", 0, "setpoint", &three, sizeof three, &contract_type_long);
    CHECK(strcmp(out, "parameterize CTL:0 setpoint (8 bytes) = 3") == 0);
    const ContractEventFlow ef = {"GCS", 0, "REC", 1, CONTRACT_ONESHOT};
    engine_format_event_flow(out, sizeof out, &ef);
    CHECK(strcmp(out, "GCS:0 => REC:1") == 0);
    const ContractDataFlow df = {"ALT", 0, "CTL", 2, 4};
    engine_format_data_flow(out, sizeof out, &df);
    CHECK(strcmp(out, "ALT:0 -> CTL:2") == 0);
    engine_format_params(out, sizeof out, vars, 0, &b); /* none: the call as the source writes it */
    CHECK(strcmp(out, "()") == 0);
    engine_format_params(out, sizeof out, NULL, 0, NULL);
    CHECK(strcmp(out, "()") == 0);
    engine_format_params(out, sizeof out, vars, -1, &b); /* not known (a block of another size) */
    CHECK(strcmp(out, "") == 0);
    engine_format_params(out, sizeof out, vars, 3, NULL);
    CHECK(strcmp(out, "") == 0);
    /* too long for its room: cut before a multi-byte character, never inside it, then `...)` */
    strcpy(b.label, "\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9\xc3\xa9");
    char small[36];
    engine_format_params(small, sizeof small, vars, 3, &b);
    CHECK(strlen(small) <= sizeof small - 1);
    CHECK(strncmp(small, "(mode = AUTO, speed = 0.3, label", 32) == 0 || strncmp(small, "(mode = AUTO, speed = 0.3, la", 29) == 0);
    CHECK(strcmp(small + strlen(small) - 4, "...)") == 0);
    for (size_t i = 0; small[i]; i++) /* no lone continuation byte before the cut */
        if (((unsigned char)small[i] & 0xC0) == 0xC0) CHECK(((unsigned char)small[i + 1] & 0xC0) == 0x80);
    char tiny[12];
    engine_format_params(tiny, sizeof tiny, vars, 3, &b);
    CHECK(strcmp(tiny, "(mode =...)") == 0);
}

/* ---- table checks ---------------------------------------------------------------------- */

static const ContractType bad_array_size =
    {.name = "float[3]", .kind = CONTRACT_KIND_ARRAY, .size = 16, .element = &contract_type_double, .count = 3};
static const ContractType bad_enum = {.name = "E", .kind = CONTRACT_KIND_ENUM, .size = 4};
static const ContractType bad_bool = {.name = "bool", .kind = CONTRACT_KIND_BOOL, .size = 4};

static int check_port_type(const ContractType *t, char *err, size_t len) {
    ContractEventPort in[] = {{0, "p", t, NULL}};
    ContractFunction fn[] = {{"f", 0, NULL, 0, 0, NULL, 0, 0, NULL, 0, NULL}};
    ContractSupervisorVocabulary v = {CONTRACT_VOCABULARY_VERSION, "CHK", 90, 40, 5, 70, 1, in, 0, NULL, 1, fn};
    return contract_check_supervisor_vocabulary(&v, err, len);
}

void test_ext_invalid_descriptors_are_refused(void) {
    char err[256] = "";
    CHECK(check_port_type(&type_Scan, err, sizeof err) == 0);
    CHECK(check_port_type(&type_float_3_3, err, sizeof err) == 0);
    CHECK(check_port_type(&type_Cell_3, err, sizeof err) == 0);
    CHECK(check_port_type(&bad_array_size, err, sizeof err) == -1 && strstr(err, "is not 3 x 8 bytes"));
    CHECK(check_port_type(&bad_enum, err, sizeof err) == -1 && strstr(err, "enum type E has no members"));
    CHECK(check_port_type(&bad_bool, err, sizeof err) == -1 && strstr(err, "bool type bool of size 4"));

    /* an element past the end of an array (ranges[3] of a float[3]) is refused, ranges[2] is not */
    static const double one = 1.0;
    for (int index = 2; index <= 3; index++) {
        ContractEventPort in[] = {{0, "r", &type_float_3, NULL}};
        ContractTest t[] = {{CONTRACT_TEST_LT, {CONTRACT_REF_IN_PORT, 0, (size_t)index * sizeof(double), &contract_type_double, NULL},
                             {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &one}, NULL, 0, NULL}};
        ContractTestClause tc[] = {{1, t}};
        ContractEvent ev[] = {{.kind = CONTRACT_EV_MODULE, .module = "X", .port = 0, .in_port = 0, .ntest_clauses = 1, .test_clauses = tc}};
        ContractClause cl[] = {{1, ev}};
        ContractRule rules[] = {{"R", {1, cl}, 0, NULL, {0, NULL}}};
        ContractFunction fn[] = {{"f", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, rules}};
        ContractSupervisorVocabulary v = {CONTRACT_VOCABULARY_VERSION, "CHK", 90, 40, 5, 70, 1, in, 0, NULL, 1, fn};
        int rc = contract_check_supervisor_vocabulary(&v, err, sizeof err);
        if (index == 2) CHECK(rc == 0);
        else CHECK(rc == -1 && strstr(err, "field path at offset 24 (+8 bytes) exceeds its float[3] of 24 bytes"));
    }
}

/* A module event's in port: one of the supervisor's, or -1 (a delivery into any of them: the event
 * reads no port variable of a module port subscribed to several); a port it does not have is refused.
 * Before, -1 was refused too, so a supervisor with `[CTL:0]` over two subscribes of CTL:0 ran nowhere. */
void test_module_event_of_any_in_port_is_accepted(void) {
    char err[256] = "";
    ContractEventPort in[] = {{2, "status", &type_Scan, NULL}, {3, "status2", &type_Scan, NULL}};
    const int ports[] = {2, 3, -1, 4};
    for (int i = 0; i < 4; i++) {
        ContractEvent ev[] = {{.kind = CONTRACT_EV_MODULE, .module = "CTL", .port = 0, .in_port = ports[i]}};
        ContractClause cl[] = {{1, ev}};
        ContractRule rules[] = {{"SEEN", {1, cl}, 0, NULL, {0, NULL}}};
        ContractFunction fn[] = {{"fly", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, rules}};
        ContractSupervisorVocabulary v = {CONTRACT_VOCABULARY_VERSION, "FLT", 90, 40, 5, 70, 2, in, 0, NULL, 1, fn};
        int rc = contract_check_supervisor_vocabulary(&v, err, sizeof err);
        if (ports[i] != 4) CHECK(rc == 0);
        else CHECK(rc == -1 && strstr(err, "(CTL:0): no in event port :4"));
    }
}

/* ---- a supervisor on these types ----------------------------------------------------------
 * SCN: in :0 Scan scan; in :1 Mode mode; in :2 bool flag; out :0 float[180] near_out.
 * function watch(): locals float[180] near; Mode m; bool seen.
 *   S:    [elapsed=1ms] subscribe X:0 =* :0; X:1 =* :1; X:2 =* :2 []
 *   NEAR: [X:0<(scan.ranges[90] < 0.3)>(near = scan.ranges, m = scan.mode)]
 *           notify :0(near_out = near) [X:0<(scan.ranges[90] > 1.0)>]
 *   AUTO: [X:1<(mode == Mode.AUTO)>] [X:1<(mode != Mode.AUTO)>]
 *   FLAG: [X:2<(flag == true)>(seen = flag)] [X:2<(flag == false)>]                          */
typedef struct WatchLocals {
    double near[180];
    Mode m;
    bool seen;
} WatchLocals;

static const double k0_3 = 0.3, k1_0 = 1.0;
static const Mode kAUTO = Mode_AUTO;
static const bool kTRUE = true, kFALSE = false;
static const ContractEventPort scn_in[] = {
    {0, "scan", &type_Scan, NULL}, {1, "mode", &type_Mode, NULL}, {2, "flag", &contract_type_bool, NULL}};
static const ContractEventPort scn_out[] = {{0, "near_out", &type_float_180, NULL}};
static const ContractVar watch_locals[] = {
    {"near", &type_float_180, offsetof(WatchLocals, near), NULL},
    {"m", &type_Mode, offsetof(WatchLocals, m), NULL},
    {"seen", &contract_type_bool, offsetof(WatchLocals, seen), NULL}};

static const ContractEvent s_ev[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = 1 * MS}};
static const ContractClause s_cl[] = {{1, s_ev}};
static const ContractAction s_act[] = {
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "X", .src_port = 0, .in_port = 0},
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "X", .src_port = 1, .in_port = 1},
    {.kind = CONTRACT_ACT_SUBSCRIBE, .module = "X", .src_port = 2, .in_port = 2}};

#define RANGE90 {CONTRACT_REF_IN_PORT, 0, offsetof(Scan, ranges) + 90 * sizeof(double), &contract_type_double, NULL}
static const ContractTest near_t[] = {
    {CONTRACT_TEST_LT, RANGE90, {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k0_3}, NULL, 0, NULL}};
static const ContractTestClause near_tc[] = {{1, near_t}};
static const ContractAssign near_ex[] = {
    {0, 0, &type_float_180, {CONTRACT_REF_IN_PORT, 0, offsetof(Scan, ranges), &type_float_180, NULL}},
    {1, 0, &type_Mode, {CONTRACT_REF_IN_PORT, 0, offsetof(Scan, mode), &type_Mode, NULL}}};
static const ContractEvent near_ev[] = {{.kind = CONTRACT_EV_MODULE, .module = "X", .port = 0, .in_port = 0,
                                         .ntest_clauses = 1, .test_clauses = near_tc, .nextractions = 2,
                                         .extractions = near_ex}};
static const ContractClause near_cl[] = {{1, near_ev}};
static const ContractAssign near_notify[] = {
    {0, 0, &type_float_180, {CONTRACT_REF_LOCAL, 0, 0, &type_float_180, NULL}}};
static const ContractAction near_act[] = {
    {.kind = CONTRACT_ACT_NOTIFY, .out_port = 0, .nassigns = 1, .assigns = near_notify}};
static const ContractTest far_t[] = {
    {CONTRACT_TEST_GT, RANGE90, {CONTRACT_REF_CONST, 0, 0, &contract_type_double, &k1_0}, NULL, 0, NULL}};
static const ContractTestClause far_tc[] = {{1, far_t}};
static const ContractEvent far_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "X", .port = 0, .in_port = 0, .ntest_clauses = 1, .test_clauses = far_tc}};
static const ContractClause far_cl[] = {{1, far_ev}};

#define MODE_REF {CONTRACT_REF_IN_PORT, 1, 0, &type_Mode, NULL}
static const ContractTest auto_t[] = {
    {CONTRACT_TEST_EQ, MODE_REF, {CONTRACT_REF_CONST, 0, 0, &type_Mode, &kAUTO}, NULL, 0, NULL}};
static const ContractTestClause auto_tc[] = {{1, auto_t}};
static const ContractEvent auto_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "X", .port = 1, .in_port = 1, .ntest_clauses = 1, .test_clauses = auto_tc}};
static const ContractClause auto_cl[] = {{1, auto_ev}};
static const ContractTest notauto_t[] = {
    {CONTRACT_TEST_NE, MODE_REF, {CONTRACT_REF_CONST, 0, 0, &type_Mode, &kAUTO}, NULL, 0, NULL}};
static const ContractTestClause notauto_tc[] = {{1, notauto_t}};
static const ContractEvent notauto_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "X", .port = 1, .in_port = 1, .ntest_clauses = 1, .test_clauses = notauto_tc}};
static const ContractClause notauto_cl[] = {{1, notauto_ev}};

#define FLAG_REF {CONTRACT_REF_IN_PORT, 2, 0, &contract_type_bool, NULL}
static const ContractTest flag_t[] = {
    {CONTRACT_TEST_EQ, FLAG_REF, {CONTRACT_REF_CONST, 0, 0, &contract_type_bool, &kTRUE}, NULL, 0, NULL}};
static const ContractTestClause flag_tc[] = {{1, flag_t}};
static const ContractAssign flag_ex[] = {{2, 0, &contract_type_bool, FLAG_REF}};
static const ContractEvent flag_ev[] = {{.kind = CONTRACT_EV_MODULE, .module = "X", .port = 2, .in_port = 2,
                                         .ntest_clauses = 1, .test_clauses = flag_tc, .nextractions = 1,
                                         .extractions = flag_ex}};
static const ContractClause flag_cl[] = {{1, flag_ev}};
static const ContractTest unflag_t[] = {
    {CONTRACT_TEST_EQ, FLAG_REF, {CONTRACT_REF_CONST, 0, 0, &contract_type_bool, &kFALSE}, NULL, 0, NULL}};
static const ContractTestClause unflag_tc[] = {{1, unflag_t}};
static const ContractEvent unflag_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "X", .port = 2, .in_port = 2, .ntest_clauses = 1, .test_clauses = unflag_tc}};
static const ContractClause unflag_cl[] = {{1, unflag_ev}};

static const ContractRule watch_rules[] = {
    {"S", {1, s_cl}, 3, s_act, {0, NULL}},
    {"NEAR", {1, near_cl}, 1, near_act, {1, far_cl}},
    {"AUTO", {1, auto_cl}, 0, NULL, {1, notauto_cl}},
    {"FLAG", {1, flag_cl}, 0, NULL, {1, unflag_cl}}};
static const ContractFunction scn_functions[] = {
    {"watch", 0, NULL, 0, 3, watch_locals, sizeof(WatchLocals), 0, NULL, 4, watch_rules}};
static const ContractSupervisorVocabulary SCN = {
    CONTRACT_VOCABULARY_VERSION, "SCN", 90, 40, 5, 70, 3, scn_in, 1, scn_out, 1, scn_functions};

typedef struct Causes {
    int n;
    char lines[16][400];
} Causes;
static Causes CAUSES;
static void record_rule(void *ctx, int64_t t, const char *function, const char *rule, int active, const char *cause) {
    (void)ctx;
    (void)t;
    if (CAUSES.n < 16)
        snprintf(CAUSES.lines[CAUSES.n++], sizeof CAUSES.lines[0], "%s.%s %s cause=%s", function, rule,
                 active ? "active" : "inactive", cause);
}

void test_ext_supervisor_tests_and_extractions_on_arrays_enums_bools(void) {
    static TestLog log;
    static FakeWorld w;
    log_clear(&log);
    memset(&w, 0, sizeof w);
    memset(&CAUSES, 0, sizeof CAUSES);
    w.log = &log;
    SupIo io = fake_sup_io(&w);
    io.rule = record_rule;
    char err[256] = "";
    SupCore *c = sup_core_create(&SCN, &io, err, sizeof err);
    if (!c) {
        fprintf(stderr, "  %s\n", err);
        CHECK(c != NULL);
        return;
    }
    CHECK(sup_core_start_function(c, 0, "watch", NULL, 0) == 0);
    sup_core_advance(c, 1 * MS);

    Scan s;
    memset(&s, 0, sizeof s);
    for (int i = 0; i < 180; i++) s.ranges[i] = 2.0;
    s.mode = Mode_TELEOP;
    sup_core_module_event(c, 2 * MS, "X", 0, -1, &s, sizeof s); /* ranges[90] = 2.0: not near */
    CHECK(!sup_core_rule_active(c, "watch", "NEAR"));
    s.ranges[90] = 0.25; /* only the element tested changes */
    s.ranges[0] = 0.1;
    s.mode = Mode_AUTO;
    sup_core_module_event(c, 3 * MS, "X", 0, -1, &s, sizeof s);
    CHECK(sup_core_rule_active(c, "watch", "NEAR"));
    const double *near = sup_core_local(c, "watch", "near");
    const Mode *m = sup_core_local(c, "watch", "m");
    CHECK(near && memcmp(near, s.ranges, sizeof s.ranges) == 0); /* the whole array extracted */
    CHECK(m && *m == Mode_AUTO);
    /* the notify carried the array: logged by the fake world through contract_value_format */
    int notified = 0;
    for (int i = 0; i < log.n; i++)
        if (strcmp(log.lines[i], "notify :0 [0.1,2.0,2.0,2.0,2.0,2.0,2.0,2.0,2.0,2.0,...]") == 0) notified++;
    CHECK(notified == 1);
    /* the cause of the rule change shows the value readably */
    CHECK(CAUSES.n >= 1 && strstr(CAUSES.lines[CAUSES.n - 1], "watch.NEAR active cause=X:0 value={ranges=[0.1,2.0,2.0,2.0,2.0,2.0,2.0,2.0,2.0,2.0,...],mode=AUTO,ok=false}") != NULL);
    s.ranges[90] = 1.5;
    sup_core_module_event(c, 4 * MS, "X", 0, -1, &s, sizeof s);
    CHECK(!sup_core_rule_active(c, "watch", "NEAR"));

    Mode mode = Mode_TELEOP;
    sup_core_module_event(c, 5 * MS, "X", 1, -1, &mode, sizeof mode);
    CHECK(!sup_core_rule_active(c, "watch", "AUTO"));
    mode = Mode_AUTO;
    sup_core_module_event(c, 6 * MS, "X", 1, -1, &mode, sizeof mode);
    CHECK(sup_core_rule_active(c, "watch", "AUTO"));
    CHECK(strstr(CAUSES.lines[CAUSES.n - 1], "watch.AUTO active cause=X:1 value=AUTO") != NULL);
    mode = Mode_IDLE;
    sup_core_module_event(c, 7 * MS, "X", 1, -1, &mode, sizeof mode);
    CHECK(!sup_core_rule_active(c, "watch", "AUTO"));
    CHECK(strstr(CAUSES.lines[CAUSES.n - 1], "watch.AUTO inactive cause=X:1 value=IDLE") != NULL);

    bool flag = false;
    sup_core_module_event(c, 8 * MS, "X", 2, -1, &flag, sizeof flag);
    CHECK(!sup_core_rule_active(c, "watch", "FLAG"));
    flag = true;
    sup_core_module_event(c, 9 * MS, "X", 2, -1, &flag, sizeof flag);
    CHECK(sup_core_rule_active(c, "watch", "FLAG"));
    const bool *seen = sup_core_local(c, "watch", "seen");
    CHECK(seen && *seen);
    CHECK(strstr(CAUSES.lines[CAUSES.n - 1], "watch.FLAG active cause=X:2 value=true") != NULL);
    flag = false;
    sup_core_module_event(c, 10 * MS, "X", 2, -1, &flag, sizeof flag);
    CHECK(!sup_core_rule_active(c, "watch", "FLAG"));
    sup_core_destroy(c);
}

void test_ext_supervisor_text_parameters_of_new_types(void) {
    /* start a function with parameters of each kind in text form, as a control tool does */
    typedef struct P {
        double q[3];
        Mode mode;
        bool on;
    } P;
    static const ContractVar params[] = {{"q", &type_float_3, offsetof(P, q), NULL},
                                         {"mode", &type_Mode, offsetof(P, mode), NULL},
                                         {"on", &contract_type_bool, offsetof(P, on), NULL}};
    static const ContractVar locals[] = {{"lq", &type_float_3, 0, NULL}};
    static const ContractAssign inits[] = {{0, 0, &type_float_3, {CONTRACT_REF_PARAM, 0, 0, &type_float_3, NULL}}};
    static const ContractFunction fns[] = {{"go", 3, params, sizeof(P), 1, locals, sizeof(double[3]), 1, inits, 0, NULL}};
    static const ContractSupervisorVocabulary V = {CONTRACT_VOCABULARY_VERSION, "PRM", 90, 40, 5, 70, 0, NULL, 0, NULL, 1, fns};
    static TestLog log;
    static FakeWorld w;
    memset(&w, 0, sizeof w);
    log_clear(&log);
    w.log = &log;
    SupIo io = fake_sup_io(&w);
    char err[256] = "";
    SupCore *c = sup_core_create(&V, &io, err, sizeof err);
    CHECK(c != NULL);
    if (!c) return;
    CHECK(sup_core_start_function_text(c, 0, "go", "q={0.1, 0.2, 0.3} mode=Mode.AUTO on=true", err, sizeof err) == 0);
    const double *lq = sup_core_local(c, "go", "lq");
    CHECK(lq && lq[0] == 0.1 && lq[1] == 0.2 && lq[2] == 0.3);
    CHECK(sup_core_stop_function(c, 1, "go") == 0);
    CHECK(sup_core_start_function_text(c, 2, "go", "q={0.1, 0.2}", err, sizeof err) == -1);
    CHECK(strstr(err, "cannot read a float[3] for parameter 'q'") != NULL);
    CHECK(sup_core_start_function_text(c, 3, "go", "mode=FAST", err, sizeof err) == -1);
    CHECK(strstr(err, "cannot read a Mode for parameter 'mode'") != NULL);
    sup_core_destroy(c);
}
