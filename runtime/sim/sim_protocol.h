/*
 * sim_protocol.h — the harness's input and output (docs/simulation.md §4): the runner
 * (packages/simulator) sends one step per line, tab-separated,
 *
 *     TIME_NS <TAB> LINE <TAB> VERB <TAB> ARGS...
 *
 * with VERB one of
 *     start SUP FN ARGS          stop SUP FN           event MODULE PORT VALUE
 *     crash MODULE               finish MODULE         finish-after MODULE NS once|always
 *     exec MODULE NS once|always
 *     expect-rule SUP FN RULE 1|0          expect-function SUP FN 1|0
 *     expect-schema NAME 1|0               expect-module MODULE 1|0
 *     expect-local SUP FN LOCAL VALUE      expect-count SCHEMA deadline-misses|overruns N
 *     end
 *     quiet                      (no step records but failed expectations and the end: benchmarks)
 * (VALUE in Cactal value syntax, escapes inside strings, never a raw tab), and the harness answers
 * each with one JSON object per line:
 *     {"line":L,"timeNs":T,"verb":"event","ok":true,"delivered":1,"error":"...",
 *      "expected":"...","actual":"...","rules":[...],"actions":[...],"log":[...],
 *      "records":[...],"schemas":[...],"locals":[...],"output":"...","dropped":N}
 * where rules/actions/log/records are what happened since the previous step (timers, releases
 * and the step itself), each with its own timeNs and "seq" (their order over the session, across the
 * four lists: at one time, a cause has a lower seq than its effects), and schemas/locals the state
 * after the step.
 * A record is a typed trace record as a real run's CSV holds it: {"timeNs","module","kind",
 * "peer","port"?,"detail"} (sim_world.h SimSink.record). Each list keeps at most
 * SIM_MAX_RECORDS_PER_STEP items a step; "dropped" counts what was left out. The `end`
 * record also has "eventsProcessed" and "wallNs" (the harness's own wall time, input included).
 * Input is hostile (a project's scenario): every line is bounded and validated; a bad line gives
 * a record with "ok":false and "error", never a crash.
 */
#ifndef CONTRACT_SIM_PROTOCOL_H
#define CONTRACT_SIM_PROTOCOL_H

#include <stdio.h>

#include "sim_world.h"

/** Longest input line read (a longer one is refused with an error record). */
#define SIM_MAX_LINE 65536

typedef struct SimSession SimSession;

/** `capture_fd`: a seekable file that the process's stdout (fd 1) writes to, read back for the
 *  user functions' output and the types' print_ (-1: no capture; structured locals then show as
 *  `<Type>`). */
SimSession *sim_session_create(const ContractSupervisorVocabulary *const *sups, int nsups,
                               const ContractOrdVocabulary *ord, FILE *out, int capture_fd,
                               char *err, size_t errlen);
void sim_session_destroy(SimSession *s);
/** Handles one input line (without its newline). Returns 1 after `end`, 0 otherwise. */
int sim_session_line(SimSession *s, char *line);
/** Count of failed expectations and refused steps so far. */
int sim_session_failures(const SimSession *s);

/** The session's virtual time (ns since the simulation started): what GetTime() returns to the project's functions. */
int64_t sim_session_now(const SimSession *s);

#endif
