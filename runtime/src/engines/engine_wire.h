/*
 * engine_wire.h — how the engines talk to each other over libmodule requests (supervisor ->
 * ORD schema activation, supervisor -> supervisor function activation). See sup_main.c for
 * the conventions and docs/engines.md.
 */
#ifndef CONTRACT_ENGINE_WIRE_H
#define CONTRACT_ENGINE_WIRE_H

#include <stddef.h>

#include "libmodule/libmodule.h"

/** Prefix of a binary argument block in a REQ_START's Data (text arguments never start
 *  with a control character). */
#define CONTRACT_BINARY_ARGS_MAGIC "\001CTRB"
#define CONTRACT_BINARY_ARGS_MAGIC_LEN 5

/** REQ_START to `module` for `function` (a supervision function or, to ORD, a schema) with a
 *  binary parameter block, tagged ackId (the activation id); `wantedAck`: ACK_NOTHING (ORD:
 *  a refusal is the ORD:1 event) or ACK_START | ACK_NOTDONE (a supervisor answers whether it
 *  started the function). Returns a CONTRACT_* code. */
int engine_send_start(const char *module, const char *function, const void *block, size_t size,
                      int ackId, int wantedAck);
/** REQ_STOP to `module` naming `function` (or schema) in Data; tagged ackId (the activation
 *  id to undo; 0: whichever activation runs). */
int engine_send_stop(const char *module, const char *function, int ackId);
/** 1 and the block when the request's Data is a binary argument block, else 0. */
int engine_binary_args(const RequestMessage *m, const unsigned char **block, size_t *size);
/** NUL-terminates every fixed-size name field of a received request (a malformed sender must
 *  not make the engines read past them). */
void engine_terminate_names(RequestMessage *m);
/** Copies the request's Data as a NUL-terminated string (truncated to n-1). */
void engine_data_string(const RequestMessage *m, char *out, size_t n);

#endif
