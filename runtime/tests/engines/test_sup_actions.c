/*
 * test_sup_actions.c — actions and their undos on a small supervisor ACT (virtual clock):
 * event schemas sharing a module (it runs until the last one is undone; a module someone else
 * started is never stopped), activate critical module on a stopped module (started, undo stops
 * it) and resttime on a running one (priority only, restored), activate supervisor of one of its
 * own functions with a parameter, ORD events with ord_schema tests and extractions.
 */
#include <string.h>

#include "fake_world.h"

#define MS 1000000LL

static TestLog LOG;

static const ContractEventPort act_out[] = {{0, "o", &contract_type_long, NULL}};

/* event schemas: E1 = {MAA, MAB} with MAA:0 =* MAB:0;  E2 = {MAA, MEX} */
static const ContractSchemaModule e1_modules[] = {{"MAA", 0, NULL}, {"MAB", 0, NULL}};
static const ContractEventFlow e1_flows[] = {{"MAA", 0, "MAB", 0, CONTRACT_CONTINUOUS}};
static const ContractSchema E1 = {"E1", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 2, e1_modules,
                                  0, NULL, 0, NULL, 1, e1_flows};
static const ContractSchemaModule e2_modules[] = {{"MAA", 0, NULL}, {"MEX", 0, NULL}};
static const ContractEventFlow e2_flows[] = {{"MEX", 1, "MAA", 1, CONTRACT_ONESHOT}};
static const ContractSchema E2 = {"E2", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 2, e2_modules,
                                  0, NULL, 0, NULL, 1, e2_flows};

#define ELAPSED(name, ms)                                                                  \
    static const ContractEvent name##_ev[] = {{.kind = CONTRACT_EV_ELAPSED, .time_ns = (ms)}}; \
    static const ContractClause name[] = {{1, name##_ev}};
ELAPSED(at05, MS / 2)
ELAPSED(at1, 1 * MS)
ELAPSED(at2, 2 * MS)
ELAPSED(at3, 3 * MS)
ELAPSED(at4, 4 * MS)

static const ContractAction a_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &E1}};
static const ContractAction b_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &E2}};
static const ContractAction c_actions[] = {{.kind = CONTRACT_ACT_CRITICAL_MODULE, .module = "MCR"}};
static const ContractAction d_actions[] = {{.kind = CONTRACT_ACT_RESTTIME_MODULE, .module = "MRT"}};
static const ContractRule schemas_rules[] = {
    {"A", {1, at1}, 1, a_actions, {1, at3}},
    {"B", {1, at2}, 1, b_actions, {1, at4}},
    {"C", {1, at1}, 1, c_actions, {1, at2}},
    {"D", {1, at1}, 1, d_actions, {1, at2}}};

/* caller: K: [elapsed=1ms] activate supervisor ACT.callee(x = 5) [elapsed=2ms]
   callee(int x): local { int lx = x; }  Q: [elapsed=500us] notify :0(o = lx) [] */
static const long k5 = 5;
static const ContractVar callee_params[] = {{"x", &contract_type_long, 0, NULL}};
static const ContractFunctionSignature sig_callee = {"ACT", "callee", 1, callee_params, sizeof(long)};
static const ContractAssign k_params[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_CONST, 0, 0, &contract_type_long, &k5}}};
static const ContractAction k_actions[] = {
    {.kind = CONTRACT_ACT_SUPERVISOR, .callee = &sig_callee, .nassigns = 1, .assigns = k_params}};
static const ContractRule caller_rules[] = {{"K", {1, at1}, 1, k_actions, {1, at2}}};
static const ContractVar callee_locals[] = {{"lx", &contract_type_long, 0, NULL}};
static const ContractAssign callee_inits[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_PARAM, 0, 0, &contract_type_long, NULL}}};
static const ContractAssign q_notify[] = {
    {0, 0, &contract_type_long, {CONTRACT_REF_LOCAL, 0, 0, &contract_type_long, NULL}}};
static const ContractAction q_actions[] = {
    {.kind = CONTRACT_ACT_NOTIFY, .out_port = 0, .nassigns = 1, .assigns = q_notify}};
static const ContractRule callee_rules[] = {{"Q", {1, at05}, 1, q_actions, {0, NULL}}};

/* ordev: local { string ls; }  R: [ORD:0<(ord_schema == "S1")>(ls = ord_schema)] [ORD:1] */
static const char k_s1[256] = "S1";
static const ContractVar ordev_locals[] = {{"ls", &contract_type_string, 0, NULL}};
static const ContractTest r_tests[] = {
    {CONTRACT_TEST_EQ, {CONTRACT_REF_ORD_SCHEMA, 0, 0, &contract_type_string, NULL},
     {CONTRACT_REF_CONST, 0, 0, &contract_type_string, k_s1}, NULL, 0, NULL}};
static const ContractTestClause r_tc[] = {{1, r_tests}};
static const ContractAssign r_extr[] = {
    {0, 0, &contract_type_string, {CONTRACT_REF_ORD_SCHEMA, 0, 0, &contract_type_string, NULL}}};
static const ContractEvent r_pre_ev[] = {
    {.kind = CONTRACT_EV_MODULE, .module = "ORD", .port = 0, .in_port = -1, .ntest_clauses = 1,
     .test_clauses = r_tc, .nextractions = 1, .extractions = r_extr}};
static const ContractClause r_pre[] = {{1, r_pre_ev}};
static const ContractEvent r_post_ev[] = {{.kind = CONTRACT_EV_MODULE, .module = "ORD", .port = 1, .in_port = -1}};
static const ContractClause r_post[] = {{1, r_post_ev}};
static const ContractRule ordev_rules[] = {{"R", {1, r_pre}, 0, NULL, {1, r_post}}};

static const ContractFunction act_functions[] = {
    {"schemas", 0, NULL, 0, 0, NULL, 0, 0, NULL, 4, schemas_rules},
    {"caller", 0, NULL, 0, 0, NULL, 0, 0, NULL, 1, caller_rules},
    {"callee", 1, callee_params, sizeof(long), 1, callee_locals, sizeof(long), 1, callee_inits, 1, callee_rules},
    {"ordev", 0, NULL, 0, 1, ordev_locals, 256, 0, NULL, 1, ordev_rules}};
static const ContractSupervisorVocabulary ACT = {
    CONTRACT_VOCABULARY_VERSION, "ACT", 90, 40, 5, 70, 0, NULL, 1, act_out, 4, act_functions};

static SupCore *make(FakeWorld *w) {
    log_clear(&LOG);
    return fake_make_sup(w, &LOG, &ACT, NULL);
}

void test_actions_event_schemas_share_modules_and_module_activation(void) {
    FakeWorld w;
    SupCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    fake_set_running(&w, "MEX", 33); /* started by someone else */
    fake_set_running(&w, "MRT", 33);
    sup_core_start_function(c, 0, "schemas", NULL, 0);
    sup_core_advance(c, 10 * MS);
    CHECK_LOG(&LOG, "function schemas() started",
              /* 1 ms */
              "rule schemas.A active", "start MAB prio 40", "connect MAA:0 =* MAB:0", "start MAA prio 40",
              "rule schemas.C active", "start MCR prio 70",
              "rule schemas.D active", "priority MRT 5 (was 33)",
              /* 2 ms: postconditions first, then B's precondition */
              "rule schemas.C inactive", "stop MCR",
              "rule schemas.D inactive", "priority MRT 33 (was 5)",
              "rule schemas.B active", "connect MEX:1 => MAA:1", "share MEX",
              /* 3 ms: MAA still used by E2 */
              "rule schemas.A inactive", "disconnect MAA:0 =* MAB:0", "stop MAB",
              /* 4 ms: the last user of MAA; MEX was not started here: only
                 released (the binding stops it if a supervisor started it and no one holds it) */
              "rule schemas.B inactive", "disconnect MEX:1 => MAA:1", "stop MAA", "unshare MEX");
    CHECK(fake_is_running(&w, "MEX") && fake_is_running(&w, "MRT"));
    CHECK(!fake_is_running(&w, "MAA") && !fake_is_running(&w, "MCR"));
    /* every start/share and stop/unshare decision under the module's lock (atomic across
       supervisors): start MAA, MAB, MCR; share MEX; stop MCR, MAB, MAA; unshare MEX; and a hold
       taken while the module is already held here (MAA by B), asked whether its run ended by
       itself since (no: it still runs, no start). MRT's priority needs none. */
    CHECK(w.nlocks == 9);
    CHECK(w.unlocked_effects == 0);
    CHECK(w.locked[0] == '\0');
    sup_core_destroy(c);
}

void test_actions_activate_own_function_with_parameter(void) {
    FakeWorld w;
    SupCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    sup_core_start_function(c, 0, "caller", NULL, 0);
    sup_core_advance(c, 1 * MS);
    CHECK(sup_core_function_running(c, "callee"));
    CHECK(*(const long *)sup_core_local(c, "callee", "lx") == 5);
    /* a second activation while it runs is refused */
    CHECK(sup_core_start_function(c, 1 * MS + 1, "callee", NULL, 0) == -1);
    sup_core_advance(c, 3 * MS);
    CHECK(!sup_core_function_running(c, "callee"));
    CHECK_LOG(&LOG, "function caller() started", "rule caller.K active", "function callee(x = 5) started",
              "refused: function callee already running", "rule callee.Q active", "notify :0 5",
              "rule caller.K inactive", "rule callee.Q inactive", "function callee stopped");
    sup_core_destroy(c);
}

void test_actions_ord_events_ord_schema(void) {
    FakeWorld w;
    SupCore *c = make(&w);
    if (!c) { CHECK(0); return; }
    sup_core_start_function(c, 0, "ordev", NULL, 0);
    sup_core_ord_event(c, 1 * MS, 0, "S2");
    CHECK(sup_core_rule_active(c, "ordev", "R") == 0);
    sup_core_ord_event(c, 2 * MS, 0, "S1");
    CHECK(sup_core_rule_active(c, "ordev", "R") == 1);
    CHECK(strcmp(sup_core_local(c, "ordev", "ls"), "S1") == 0);
    sup_core_ord_event(c, 3 * MS, 1, "S9"); /* ORD:1 ends R, no subscription needed */
    CHECK(sup_core_rule_active(c, "ordev", "R") == 0);
    sup_core_destroy(c);
}

/* An event schema's activation starts each consumer before it connects the flows that feed it,
   and connects a producer's flows before it starts the producer: every mailbox reads in order, so
   no event of the schema reaches a module ahead of its START (field test: EVA's burst of 30
   events filled EVB's mailbox ahead of EVB's START, which waited 1.5 s behind them), and no
   event a producer posts at its start is lost. A chain C <- B <- A starts C, B, A; a cycle is
   broken in the modules' order. */
static const ContractSchemaModule chain_modules[] = {{"PA", 0, NULL}, {"PB", 0, NULL}, {"PC", 0, NULL}};
static const ContractEventFlow chain_flows[] = {{"PA", 0, "PB", 0, CONTRACT_CONTINUOUS},
                                                {"PB", 0, "PC", 0, CONTRACT_CONTINUOUS}};
static const ContractSchema CHAIN = {"CHAIN", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 3, chain_modules,
                                     0, NULL, 0, NULL, 2, chain_flows};
static const ContractSchemaModule loop_modules[] = {{"LX", 0, NULL}, {"LY", 0, NULL}};
static const ContractEventFlow loop_flows[] = {{"LX", 0, "LY", 0, CONTRACT_CONTINUOUS},
                                               {"LY", 0, "LX", 0, CONTRACT_ONESHOT}};
static const ContractSchema LOOP = {"LOOP", CONTRACT_SCHEMA_EVENT, 0, 0, 0, NULL, 0, 2, loop_modules,
                                    0, NULL, 0, NULL, 2, loop_flows};
static const ContractAction chain_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &CHAIN}};
static const ContractAction loop_actions[] = {{.kind = CONTRACT_ACT_SCHEMA, .schema = &LOOP}};
static const ContractRule order_rules[] = {{"CH", {1, at1}, 1, chain_actions, {0, NULL}},
                                           {"LO", {1, at2}, 1, loop_actions, {0, NULL}}};
static const ContractFunction order_functions[] = {{"order", 0, NULL, 0, 0, NULL, 0, 0, NULL, 2, order_rules}};
static const ContractSupervisorVocabulary ORDER = {
    CONTRACT_VOCABULARY_VERSION, "ORS", 90, 40, 5, 70, 0, NULL, 0, NULL, 1, order_functions};

void test_actions_event_schema_starts_consumers_before_their_flows(void) {
    FakeWorld w;
    log_clear(&LOG);
    SupCore *c = fake_make_sup(&w, &LOG, &ORDER, NULL);
    if (!c) { CHECK(0); return; }
    sup_core_start_function(c, 0, "order", NULL, 0);
    sup_core_advance(c, 5 * MS);
    CHECK_LOG(&LOG, "function order() started",
              "rule order.CH active", "start PC prio 40", "connect PB:0 =* PC:0", "start PB prio 40",
              "connect PA:0 =* PB:0", "start PA prio 40",
              "rule order.LO active", "connect LX:0 =* LY:0", "start LX prio 40", "connect LY:0 => LX:0",
              "start LY prio 40");
    sup_core_destroy(c);
}
