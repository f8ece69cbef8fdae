/*
 * itest_scenarios.h — the integration test's scenarios (one file each), run in this order by
 * itest.c. Each runs one architecture with contract-launch in root/<its name>/ and records its
 * checks (itest_support.h). `bin` holds the executables, `launcher` is contract-launch.
 */
#ifndef ITEST_SCENARIOS_H
#define ITEST_SCENARIOS_H

/** ORD + ISU + IMA/IMB/IMC: parameters, precedence, absolute ticks, `* 1`/`* 2`, ORD:1. */
void scenario_scheduler(const char *root, const char *bin, const char *launcher);
/** GLT activates SLV.work: event schema of the asynchronous AMX, notify between supervisors. */
void scenario_nested(const char *root, const char *bin, const char *launcher);
/** SHA and SHB share AMX through event schemas: started once, stopped by the last user. */
void scenario_shared_module(const char *root, const char *bin, const char *launcher);
/** RSU deactivates and at once reactivates RSC while RMB still runs a slow release. */
void scenario_reactivation(const char *root, const char *bin, const char *launcher);
/** HTA and HTB toggle event schemas sharing AMX hundreds of times, concurrently. */
void scenario_hold_toggles(const char *root, const char *bin, const char *launcher);
/** The same while AMX is paused 1.3 s (SIGSTOP): a status query with no answer, when the last
 *  decision on AMX was to stop it, means "stopped", and the next schema starts it. */
void scenario_hold_toggles_paused(const char *root, const char *bin, const char *launcher);
/** UPA and USM: refused activations and shared flows/schemas/priorities: undos undo only their own. */
void scenario_undo_own(const char *root, const char *bin, const char *launcher);
/** PQS and AMB (300 ms of its own code at each START): PQS does not wait for AMB's priority
 *  answers; the claims are recorded when they come, an undo that came before is done then. */
void scenario_late_priority_answer(const char *root, const char *bin, const char *launcher);
/** DLA and DLB claim the priorities of AMD and AME (both answering late) in opposite orders:
 *  neither waits for the other (answers settled before waiting for a lock). */
void scenario_crossed_claims(const char *root, const char *bin, const char *launcher);
/** SKS toggles FST on each of its deadline misses while FST's STK is stuck in its release (its
 *  mailbox full): ORD never blocks on STK, SLW keeps its ticks and ORD ends on its KILL. */
void scenario_stuck_module(const char *root, const char *bin, const char *launcher);
/** CRS, killed in its 5th release of CRH: ORD's stuck report, CSV record and stderr line alike,
 *  says it is no longer running (no advice about its exec region). */
void scenario_crashed_module(const char *root, const char *bin, const char *launcher);
/** SKS's undo (the STOP of AMS, busy in its own code, its mailbox full of SKS's values) is kept,
 *  fails 2 s later, and is tied back to its action: `error: not sent: ...`, its hold "still runs". */
void scenario_kept_stop(const char *root, const char *bin, const char *launcher);
/** A service manager's stop (SIGTERM to the launcher, twice, and to every module at once): the
 *  stop still goes supervisors first, RSU's undo reaches ORD (no module ends on that SIGTERM). */
void scenario_service_stop(const char *root, const char *bin, const char *launcher);

/** SKS activates FLD (1 ms) whose FLM takes 3 ms a release: ORD's deadline-miss and overrun lines
 *  on stdout stay a few a second (each kind once a second, then its count), its CSV log has each. */
void scenario_output_flood(const char *root, const char *bin, const char *launcher);

/** SKS activates EVF, where AMF floods AMC with events: AMC's START comes before them, and the
 *  priority change, parameter and STOP that SKS sends the flooded AMC reach it within 200 ms. */
void scenario_event_flood(const char *root, const char *bin, const char *launcher);

#endif
