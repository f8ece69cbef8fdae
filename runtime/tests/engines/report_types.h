/*
 * report_types.h — the report's datatypes (§8.1 datatype.contract) written the way the
 * generator writes Shared<Type>.h (report §8.2): struct + eq_/diff_/inf_/sup_/infeq_/supeq_/
 * set_/get_/print_. Hand-written for the engine tests (no code generator involved).
 */
#ifndef ENGINES_TEST_REPORT_TYPES_H
#define ENGINES_TEST_REPORT_TYPES_H

#include <stdio.h>
#include <string.h>

typedef struct TypeA { double i; double j; double k; } TypeA;
typedef struct TypeB { TypeA coord; long frfrrrf; } TypeB;
typedef struct TypeC { char message[256]; long messagetype; TypeA value; } TypeC;
typedef struct TypeD { char dataname[256]; long datavalue; } TypeD;

static inline int eq_TypeA(TypeA *a, TypeA *b) { return a->i == b->i && a->j == b->j && a->k == b->k; }
static inline int diff_TypeA(TypeA *a, TypeA *b) { return !eq_TypeA(a, b); }
static inline int inf_TypeA(TypeA *a, TypeA *b) { return a->i < b->i && a->j < b->j && a->k < b->k; }
static inline int sup_TypeA(TypeA *a, TypeA *b) { return !inf_TypeA(a, b) && !eq_TypeA(a, b); }
static inline int infeq_TypeA(TypeA *a, TypeA *b) { return inf_TypeA(a, b) || eq_TypeA(a, b); }
static inline int supeq_TypeA(TypeA *a, TypeA *b) { return sup_TypeA(a, b) || eq_TypeA(a, b); }
static inline void set_TypeA(TypeA *d, TypeA *s) { *d = *s; }
static inline int get_TypeA(TypeA *a, char *t) {
    int n = 0;
    if (sscanf(t, " {%lf ,%lf ,%lf }%n", &a->i, &a->j, &a->k, &n) != 3 || n == 0) return -1;
    return n;
}
static inline void print_TypeA(TypeA *a) { printf("{%f,%f,%f}", a->i, a->j, a->k); }

static inline int eq_TypeB(TypeB *a, TypeB *b) { return eq_TypeA(&a->coord, &b->coord) && a->frfrrrf == b->frfrrrf; }
static inline int diff_TypeB(TypeB *a, TypeB *b) { return !eq_TypeB(a, b); }
static inline int inf_TypeB(TypeB *a, TypeB *b) { return inf_TypeA(&a->coord, &b->coord) && a->frfrrrf < b->frfrrrf; }
static inline int sup_TypeB(TypeB *a, TypeB *b) { return !inf_TypeB(a, b) && !eq_TypeB(a, b); }
static inline int infeq_TypeB(TypeB *a, TypeB *b) { return inf_TypeB(a, b) || eq_TypeB(a, b); }
static inline int supeq_TypeB(TypeB *a, TypeB *b) { return sup_TypeB(a, b) || eq_TypeB(a, b); }
static inline void set_TypeB(TypeB *d, TypeB *s) { *d = *s; }
static inline int get_TypeB(TypeB *a, char *t) { (void)a; (void)t; return -1; }
static inline void print_TypeB(TypeB *a) { print_TypeA(&a->coord); printf(",%ld", a->frfrrrf); }

static inline int eq_TypeC(TypeC *a, TypeC *b) {
    return strcmp(a->message, b->message) == 0 && a->messagetype == b->messagetype && eq_TypeA(&a->value, &b->value);
}
static inline int diff_TypeC(TypeC *a, TypeC *b) { return !eq_TypeC(a, b); }
static inline int inf_TypeC(TypeC *a, TypeC *b) { return a->messagetype < b->messagetype; }
static inline int sup_TypeC(TypeC *a, TypeC *b) { return a->messagetype > b->messagetype; }
static inline int infeq_TypeC(TypeC *a, TypeC *b) { return a->messagetype <= b->messagetype; }
static inline int supeq_TypeC(TypeC *a, TypeC *b) { return a->messagetype >= b->messagetype; }
static inline void set_TypeC(TypeC *d, TypeC *s) { *d = *s; }
static inline int get_TypeC(TypeC *a, char *t) { (void)a; (void)t; return -1; }
static inline void print_TypeC(TypeC *a) { printf("{%s,%ld}", a->message, a->messagetype); }

static inline int eq_TypeD(TypeD *a, TypeD *b) { return strcmp(a->dataname, b->dataname) == 0 && a->datavalue == b->datavalue; }
static inline int diff_TypeD(TypeD *a, TypeD *b) { return !eq_TypeD(a, b); }
static inline int inf_TypeD(TypeD *a, TypeD *b) { return a->datavalue < b->datavalue; }
static inline int sup_TypeD(TypeD *a, TypeD *b) { return a->datavalue > b->datavalue; }
static inline int infeq_TypeD(TypeD *a, TypeD *b) { return a->datavalue <= b->datavalue; }
static inline int supeq_TypeD(TypeD *a, TypeD *b) { return a->datavalue >= b->datavalue; }
static inline void set_TypeD(TypeD *d, TypeD *s) { *d = *s; }
static inline int get_TypeD(TypeD *a, char *t) { (void)a; (void)t; return -1; }
static inline void print_TypeD(TypeD *a) { printf("{%s,%ld}", a->dataname, a->datavalue); }

#endif
