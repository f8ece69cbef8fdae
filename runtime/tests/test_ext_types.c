/* Values of the extension types (bool, enumeration, float[3][3], arrays of structs, a struct
 * with a float[180] scan) through real mailboxes: events there and back, a parameter, data
 * (tests/modules/emod.c echoes them), compared bytewise and with the engines' comparison, and
 * shown readably as the trace records show them. */
#define _GNU_SOURCE
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "harness.h"
#include "modules/ext_types_vocabulary.h"

static const ContractType *const port_types[EXT_NPORTS] = { &contract_type_bool, &t_mode, &t_mat, &t_cells4, &t_scan };

/* Sends `value` to ECHO's input event port `port` and returns what came back on the tester's
   port `port` (ECHO's output event port `port`), or NULL. */
static const void *round_trip(int port, const void *value, size_t size)
{
    RequestMessage *m = h_msg();
    if (SendEvent("ECHO", port, 9, value, size) != CONTRACT_OK) return NULL;
    if (!h_wait_event("ECHO", port, 2000, m)) return NULL;
    if (m->DataSize != size) return NULL;
    return m->Data;
}

static void check_same(int port, const void *sent, size_t size, const char *shown)
{
    const void *got = round_trip(port, sent, size);
    CHECK_MSG(got != NULL, "no echo on port %d", port);
    if (!got) return;
    CHECK_MSG(memcmp(got, sent, size) == 0, "port %d: bytes differ after the trip", port);
    CHECK(contract_value_compare(CONTRACT_TEST_EQ, port_types[port], got, sent));
    char text[400];
    contract_value_format(text, sizeof text, port_types[port], got);
    CHECK_MSG(strcmp(text, shown) == 0, "port %d shown as %s, expected %s", port, text, shown);
}

static void fill_scan(XScan *s)
{
    memset(s, 0, sizeof *s);
    for (int i = 0; i < 180; i++) s->ranges[i] = 0.5 + 0.01 * i;
    s->ranges[90] = 0.25;
    s->mode = XMode_AUTO;
    s->ok = true;
    s->cells[0] = (XCell){ 1, 0.5, "left" };
    s->cells[1] = (XCell){ 2, -1.5, "right \"wheel\"" };
    for (int i = 0; i < 3; i++) s->m[i][i] = 1.0;
    s->m[0][2] = 2.5;
}

void test_ext_types_round_trip(void)
{
    REQUIRE(h_setup("ext") == 0);
    REQUIRE(h_spawn_module("ECHO", "ECHO") > 0);
    for (int p = 0; p < EXT_NPORTS; p++)
        CHECK(SendSubscribeEvent("ECHO", p, "tester", p, EVENT_CONTINUOUS) == 0 &&
              h_wait_ack("ECHO", 800 + p, ACK_FINISHED, 2000, NULL));

    bool yes = true, no = false;
    check_same(0, &yes, sizeof yes, "true");
    check_same(0, &no, sizeof no, "false");
    XMode mode = XMode_TELEOP;
    check_same(1, &mode, sizeof mode, "TELEOP");
    double mat[3][3] = { { 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, 9.5 } };
    check_same(2, mat, sizeof mat, "[[1.0,2.0,3.0],[4.0,5.0,6.0],[7.0,8.0,9.5]]");
    XCell cells[4] = { { 1, 0.25, "a" }, { 2, 0.5, "b" }, { 3, 0.75, "" }, { -4, 1e9, "d,e" } };
    check_same(3, cells, sizeof cells,
               "[{id=1,w=0.25,tag=\"a\"},{id=2,w=0.5,tag=\"b\"},{id=3,w=0.75,tag=\"\"},{id=-4,w=1000000000.0,tag=\"d,e\"}]");
    static XScan scan;
    fill_scan(&scan);
    check_same(4, &scan, sizeof scan,
               "{ranges=[0.5,0.51,0.52,0.53,0.54,0.55,0.56,0.57,0.58,0.59,...],mode=AUTO,ok=true,"
               "cells=[{id=1,w=0.5,tag=\"left\"},{id=2,w=-1.5,tag=\"right \\\"wheel\\\"\"}],"
               "m=[[1.0,0.0,2.5],[0.0,1.0,0.0],[0.0,0.0,1.0]]}");
    /* one element more or less is not the same value */
    static XScan other;
    other = scan;
    other.ranges[179] += 0.001;
    CHECK(contract_value_compare(CONTRACT_TEST_NE, &t_scan, &scan, &other));

    /* a parameter, then data: setparam (XScan) -> ECHO posts it on its data port 0 to itself ->
       a run reads it and posts it as an event on port 4 */
    CHECK(SendSubscribe("ECHO", 0, "ECHO", 0, 1, 1) == 0 && h_wait_ack("ECHO", 900, ACK_FINISHED, 2000, NULL));
    other.mode = XMode_IDLE;
    other.cells[1].id = 42;
    CHECK(SendSetParam("ECHO", 0, &other, sizeof other, ACK_NOTHING, -1) == CONTRACT_OK);
    /* the data reaches ECHO's own mailbox after the setparam: run until a run has read it */
    RequestMessage *m = h_msg();
    int got = 0;
    for (int attempt = 0; attempt < 20 && !got; attempt++) {
        CHECK(SendStart("ECHO", ACK_NOTHING, 7 + attempt) == CONTRACT_OK);
        got = h_wait_event("ECHO", 4, 250, m);
    }
    CHECK(got && m->DataSize == sizeof other && memcmp(m->Data, &other, sizeof other) == 0);

    /* the typed control tool: reads the Cactal value syntax, prints what it read readably */
    char out[600];
    snprintf(out, sizeof out, "%s/control.out", h_work_dir);
    char value[4096];
    int n = snprintf(value, sizeof value, "{{");
    for (int i = 0; i < 180; i++) n += snprintf(value + n, sizeof value - (size_t)n, "%s%g", i ? ", " : "", i == 90 ? 0.2 : 1.0);
    snprintf(value + n, sizeof value - (size_t)n, "}, XMode.TELEOP, true, {{1, 0.5, \"l\"}, {2, 0.5, \"r\"}}, "
                                                  "{{1,0,0},{0,1,0},{0,0,1}}}");
    char *argv[] = { "controlECHO", "setparam", "0", value, NULL };
    CHECK(h_run(argv, out, 5000) == 0);
    char *text = h_read_file(out);
    CHECK_MSG(text && strstr(text, "ECHO: parameter 0 set to {ranges=[1.0,1.0,1.0,1.0,1.0,1.0,1.0,1.0,1.0,1.0,...],mode=TELEOP,ok=true,"
                                   "cells=[{id=1,w=0.5,tag=\"l\"},{id=2,w=0.5,tag=\"r\"}],m=[[1.0,0.0,0.0],[0.0,1.0,0.0],[0.0,0.0,1.0]]}"),
              "control tool printed: %s", text ? text : "(nothing)");
    free(text);
    got = 0;
    for (int attempt = 0; attempt < 20 && !got; attempt++) {
        CHECK(SendStart("ECHO", ACK_NOTHING, 40 + attempt) == CONTRACT_OK);
        got = h_wait_event("ECHO", 4, 250, m);
    }
    XScan sent;
    memcpy(&sent, m->Data, sizeof sent);
    CHECK(got && sent.ranges[90] == 0.2 && sent.ranges[179] == 1.0 && sent.mode == XMode_TELEOP && sent.ok &&
          sent.cells[1].id == 2 && sent.m[2][2] == 1.0);
    char bad[] = "{{1, 2}, AUTO, true, {{1, 0.5, \"l\"}, {2, 0.5, \"r\"}}, {{1,0,0},{0,1,0},{0,0,1}}}";
    char *argv_bad[] = { "controlECHO", "setparam", "0", bad, NULL };
    CHECK(h_run(argv_bad, out, 5000) == 4); /* 2 ranges instead of 180 */
    text = h_read_file(out);
    CHECK(text && strstr(text, "of type XScan"));
    free(text);
    h_teardown();
}
