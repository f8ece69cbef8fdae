/*
 * prio_requests.h — a supervisor's priority changes of other modules, without waiting for the
 * module (docs/engines.md §4). A module applies a priority to itself and answers when it next
 * reads its mailbox, which may be long after (its own code runs): the supervisor goes on taking
 * its events meanwhile. Each request stays here until its answer (a REQ_PRIORITY_REPLY, matched
 * by Seq) or its deadline (1 s), and what it was for is finished then:
 *   - a claim (`activate resttime|critical module M` on a running M): recorded (prio_claims.h)
 *     with the priority M had before, under M's lock, which is held from the request to the
 *     answer so that the claims of all supervisors are made one at a time, in M's order;
 *   - its undo, when it comes before the answer: done as soon as the claim is recorded;
 *   - a restore (the undo of the latest claim) and a start's priority: logged.
 * A supervisor never blocks on another module's lock while it holds locks for answers to come
 * (which only it can read): holds_lock first settles them (prio_requests_settle, installed with
 * holds_before_block), so that two supervisors never wait for each other.
 * Every outcome is a module_priority CSV record; stderr says only what cannot be done.
 */
#ifndef CONTRACT_PRIO_REQUESTS_H
#define CONTRACT_PRIO_REQUESTS_H

#include <stdint.h>

#include "libmodule/libmodule.h"

/** Claim `id` on `module`: asks for `prio`; recorded once answered. 0, or -1 (not sent: logged). */
int prio_request_claim(const char *module, uint32_t id, int prio);
/** Undoes claim `id` on `module` (restores the priority before it when it is the latest claim;
 *  when its answer has not come yet, once it comes). */
void prio_request_release(const char *module, uint32_t id);
/** The priority a module starts its run at (sent before its START, which it reads after). */
void prio_request_start(const char *module, int prio);
/** A REQ_PRIORITY_REPLY read by the supervisor's loop: finishes its request (another one: ignored). */
void prio_request_answered(const RequestMessage *reply);
/** The earliest deadline of the requests waiting for their answer (INT64_MAX: none). */
int64_t prio_requests_next_deadline(void);
/** Ends the requests whose deadline passed at `t`: no answer, so nothing recorded (logged). */
void prio_requests_expire(int64_t t);
/** Waits for the answer to every request in flight (each until its deadline), finishing them. */
void prio_requests_settle(void);
/** Requests waiting for their answer. */
int prio_requests_in_flight(void);

#endif
