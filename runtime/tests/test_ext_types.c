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
#include "contract/vocabulary.h"
#include "modules/ext_types.h"

static const ContractEnumMember mode_members[] = { { "IDLE", XMode_IDLE }, { "TELEOP", XMode_TELEOP }, { "AUTO", XMode_AUTO } };
static const ContractType t_mode = CONTRACT_ENUM_TYPE(XMode, mode_members, 3, NULL);
static const ContractType t_row = CONTRACT_ARRAY_TYPE("float[3]", double[3], contract_type_double, 3, NULL);
static const ContractType t_mat = CONTRACT_ARRAY_TYPE("float[3][3]", double[3][3], t_row, 3, NULL);
static const ContractType t_ranges = CONTRACT_ARRAY_TYPE("float[180]", double[180], contract_type_double, 180, NULL);
static const ContractField cell_fields[] = { { "id", offsetof(XCell, id), &contract_type_long },
                                             { "w", offsetof(XCell, w), &contract_type_double },
                                             { "tag", offsetof(XCell, tag), &contract_type_string } };
static const ContractType t_cell = { .name = "XCell", .kind = CONTRACT_KIND_STRUCT, .size = sizeof(XCell),
                                     .nfields = 3, .fields = cell_fields };
static const ContractType t_cells4 = CONTRACT_ARRAY_TYPE("XCell[4]", XCell[4], t_cell, 4, NULL);
static const ContractType t_cells2 = CONTRACT_ARRAY_TYPE("XCell[2]", XCell[2], t_cell, 2, NULL);
static const ContractField scan_fields[] = { { "ranges", offsetof(XScan, ranges), &t_ranges },
                                             { "mode", offsetof(XScan, mode), &t_mode },
                                             { "ok", offsetof(XScan, ok), &contract_type_bool },
                                             { "cells", offsetof(XScan, cells), &t_cells2 },
                                             { "m", offsetof(XScan, m), &t_mat } };
static const ContractType t_scan = { .name = "XScan", .kind = CONTRACT_KIND_STRUCT, .size = sizeof(XScan),
                                     .nfields = 5, .fields = scan_fields };
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
    check_same(2, mat, sizeof mat, "[[1,2,3],[4,5,6],[7,8,9.5]]");
    XCell cells[4] = { { 1, 0.25, "a" }, { 2, 0.5, "b" }, { 3, 0.75, "" }, { -4, 1e9, "d,e" } };
    check_same(3, cells, sizeof cells,
               "[{id=1,w=0.25,tag=\"a\"},{id=2,w=0.5,tag=\"b\"},{id=3,w=0.75,tag=\"\"},{id=-4,w=1e+09,tag=\"d,e\"}]");
    static XScan scan;
    fill_scan(&scan);
    check_same(4, &scan, sizeof scan,
               "{ranges=[0.5,0.51,0.52,0.53,0.54,0.55,0.56,0.57,0.58,0.59,...],mode=AUTO,ok=true,"
               "cells=[{id=1,w=0.5,tag=\"left\"},{id=2,w=-1.5,tag=\"right \\\"wheel\\\"\"}],"
               "m=[[1,0,2.5],[0,1,0],[0,0,1]]}");
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
    h_teardown();
}
