/* tools.h helpers and the report's generated SharedTypeA.h / hand-written TypeB, TypeD. */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "harness.h"
#include "tools.h"
#include "SharedTypeA.h"
#include "SharedTypeB.h"
#include "SharedTypeD.h"

void test_tools_parse(void)
{
    double d = 0;
    char in1[] = "  -1.5,";
    CHECK(get_float(&d, in1) == 6 && d == -1.5);
    char in2[] = "2.";
    CHECK(get_float(&d, in2) == 2 && d == 2.0);
    char in3[] = "1e-3}";
    CHECK(get_float(&d, in3) == 4 && fabs(d - 0.001) < 1e-12);
    char in4[] = "3";
    CHECK(get_float(&d, in4) == 1 && d == 3.0);
    char bad1[] = "abc", bad2[] = "0x10", bad3[] = "inf", bad4[] = "", bad5[] = "1.2.3";
    d = 42;
    CHECK(get_float(&d, bad1) == -1 && get_float(&d, bad2) == -1 && get_float(&d, bad3) == -1);
    CHECK(get_float(&d, bad4) == -1 && get_float(&d, bad5) == -1 && d == 42);

    long l = 0;
    char i1[] = " 42 ", i2[] = "-7,", i3[] = "2.5", i4[] = "99999999999999999999999";
    CHECK(get_int(&l, i1) == 3 && l == 42);
    CHECK(get_int(&l, i2) == 2 && l == -7);
    CHECK(get_int(&l, i3) == -1 && get_int(&l, i4) == -1 && l == -7);

    char s[256];
    char s1[] = " \"a b\\\"c\" rest";
    CHECK(get_string(s, s1) == 9 && strcmp(s, "a b\"c") == 0);
    char s2[] = "\"unterminated";
    CHECK(get_string(s, s2) == -1);
    /* the language's escapes: \n \t \r, any other character itself (\x -> x), as a .contract literal */
    char s3[] = "\"a\\r\\x\\n\"";
    CHECK(get_string(s, s3) == 9 && strcmp(s, "a\rx\n") == 0);
    char s4[] = "\"ends in a backslash\\";
    CHECK(get_string(s, s4) == -1);
    char longs[400];
    longs[0] = '"';
    memset(longs + 1, 'x', 300);
    longs[301] = '"';
    longs[302] = '\0';
    CHECK(get_string(s, longs) == -1);
    longs[256] = '"';
    longs[257] = '\0';
    CHECK(get_string(s, longs) == 257 && strlen(s) == 255);

    char sym = '{';
    char m1[] = "  {1", m2[] = "x{";
    CHECK(increment_until_markerfound(m1, &sym) == 3);
    CHECK(increment_until_markerfound(m2, &sym) == -1);
    CHECK(only_blanks_remain("  \n") && !only_blanks_remain(" x"));

    TypeA a = { 9, 9, 9 };
    char t1[] = "{1.0, 2.5,-3}";
    CHECK(get_TypeA(&a, t1) == (int)strlen(t1) && a.i == 1.0 && a.j == 2.5 && a.k == -3.0);
    char t2[] = "{1.0,2.0}", t3[] = "{1.0,2.0,3.0,4.0}", t4[] = "{1.0,\"x\",3}";
    CHECK(get_TypeA(&a, t2) == -1 && get_TypeA(&a, t4) == -1);
    int n = get_TypeA(&a, t3);
    CHECK(n == -1);
    TypeB b;
    char t5[] = "{{1,2,3},4}";
    CHECK(get_TypeB(&b, t5) == (int)strlen(t5) && b.coord.k == 3.0 && b.frfrrrf == 4);
    char t6[] = "{{1,2,3},4.5}";
    CHECK(get_TypeB(&b, t6) == -1);
    TypeD dd;
    char t7[] = "{\"problem\", -30}";
    CHECK(get_TypeD(&dd, t7) == (int)strlen(t7) && strcmp(dd.dataname, "problem") == 0 && dd.datavalue == -30);
}

void test_tools_serialize(void)
{
    unsigned char buf[1024];
    TypeA a = { 1.25, -2.5, 1e10 }, a2 = { 0, 0, 0 };
    unsigned int n = serialize_TypeA(&a, buf);
    CHECK(n == 3 * sizeof(double));
    CHECK(deserialize_TypeA(&a2, buf) == n && eq_TypeA(&a, &a2) && !diff_TypeA(&a, &a2));
    TypeD d = { "name", 77 }, d2;
    memset(&d2, 0x55, sizeof d2);
    n = serialize_TypeD(&d, buf);
    CHECK(n == CONTRACT_STRING_SIZE + sizeof(long));
    CHECK(deserialize_TypeD(&d2, buf) == n && strcmp(d2.dataname, "name") == 0 && d2.datavalue == 77);
    TypeB b = { { 1, 2, 3 }, 5 }, b2;
    n = serialize_TypeB(&b, buf);
    CHECK(deserialize_TypeB(&b2, buf) == n && b2.frfrrrf == 5 && b2.coord.j == 2);
    CHECK(extract_int(buf, 3, -9) == sizeof(long));
    long l = 0;
    CHECK(fill_int(&l, 3, buf) == sizeof(long) && l == -9);
}

void test_tools_bool_enum(void)
{
    unsigned char buf[4] = { 7, 7, 7, 7 };
    bool b = false;
    CHECK(extract_bool(buf, 1, true) == 1 && buf[1] == 1 && buf[0] == 7 && buf[2] == 7);
    CHECK(fill_bool(&b, 1, buf) == 1 && b);
    char t1[] = "  false }", t2[] = "1", t3[] = "truth", t4[] = "1.5";
    CHECK(get_bool(&b, t1) == 7 && !b);
    CHECK(get_bool(&b, t2) == 1 && b);
    CHECK(get_bool(&b, t3) == -1 && get_bool(&b, t4) == -1);

    static const char *const names[] = { "IDLE", "TELEOP", "AUTO" };
    static const long values[] = { 0, 1, 5 };
    long v = -1;
    char e1[] = " AUTO,", e2[] = "Mode.TELEOP", e3[] = "5", e4[] = "Other.AUTO", e5[] = "2", e6[] = "AUTOX";
    CHECK(get_enum(&v, e1, "Mode", names, values, 3) == 5 && v == 5);
    CHECK(get_enum(&v, e2, "Mode", names, values, 3) == (int)strlen(e2) && v == 1);
    CHECK(get_enum(&v, e3, "Mode", names, values, 3) == 1 && v == 5);
    v = -1;
    CHECK(get_enum(&v, e4, "Mode", names, values, 3) == -1 && v == -1);
    CHECK(get_enum(&v, e5, "Mode", names, values, 3) == -1 && v == -1); /* 2 is no member */
    CHECK(get_enum(&v, e6, "Mode", names, values, 3) == -1);
    CHECK(strcmp(enum_member_name(5, names, values, 3), "AUTO") == 0 && enum_member_name(2, names, values, 3) == NULL);
}
