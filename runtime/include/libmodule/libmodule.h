/*
 * libmodule -- the ContrACT module runtime (C11 + POSIX).
 *
 * Every module, supervisor and the scheduler ORD is its own process. The library provides
 * `main`: it creates the module's request mailbox and one queue per input data port inside the
 * run directory (CONTRACT_RUN_DIR), opens the CSV log, sets the priority, then calls the
 * generated `ModuleMain`. Modules are addressed by name inside one run directory.
 *
 * Sections of this header, by audience:
 *   [GEN]    used by generated module.c files (report section 8.2) and by user code in them.
 *   [ENGINE] used by the ORD scheduler / supervisor engines, the control tools, the launcher
 *            and tests to drive *other* modules (requests, acks, raw events, waiting with fds).
 * docs/runtime-api.md documents semantics, the IPC, limits and the CSV log columns.
 */
#ifndef LIBMODULE_LIBMODULE_H
#define LIBMODULE_LIBMODULE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------ */
/* Limits                                                                                      */
/* ------------------------------------------------------------------------------------------ */

/** Longest module name + 1 (names are C identifiers, e.g. "MSC", "ORD", "GLB"). */
#define CONTRACT_NAME_MAX 64
/** The file contract-launch creates in the run directory when it starts stopping the modules:
 *  a request to a module that has already gone is then expected, not an error on stderr. */
#define CONTRACT_RUN_STOPPING_FILE "launcher.stopping"
/** Longest supervision-function name + 1 carried by a START request. */
#define CONTRACT_FUNCTION_MAX 64
/** Largest payload of a request (setparam value, event data, start arguments), in bytes.
 *  Bigger payloads are refused with a clear error (never truncated). */
#define CONTRACT_REQUEST_DATA_MAX 16384
/** Largest value of one data port (IUSE / IPRODUCE entry size), in bytes. Checked at start-up. */
#define CONTRACT_DATA_PORT_MAX 65536

/* ------------------------------------------------------------------------------------------ */
/* [GEN] Time                                                                                  */
/* ------------------------------------------------------------------------------------------ */

/** Nanoseconds on CLOCK_MONOTONIC (production / reception dates). */
typedef int64_t RTIME;

/** [GEN][ENGINE] Current CLOCK_MONOTONIC time in ns. */
RTIME GetTime(void);

/* ------------------------------------------------------------------------------------------ */
/* [GEN] Requests and acknowledgements                                                         */
/* ------------------------------------------------------------------------------------------ */

typedef enum {
    REQ_UNKNOWN = 0,   /* no request (loop state of the generated skeleton) */
    REQ_START,         /* activate the module (supervisor: start Param.Start.Function with Data args) */
    REQ_STOP,          /* interrupt the current run */
    REQ_KILL,          /* end the process (ModuleMain returns) */
    REQ_EVENT,         /* an event notification; data in Data, fetched by GetEventId */
    REQ_SETPARAM,      /* new value for parameter port Param.SetParam.Port; value in Data */
    REQ_SUBSCRIBE,     /* add a consumer to one of my output data ports */
    REQ_UNSUBSCRIBE,   /* remove it */
    REQ_SUB_EVENT,     /* add a subscriber to one of my output event ports */
    REQ_UNSUB_EVENT,   /* remove it */
    REQ_PURGE_MBX,     /* drop every pending value of my input data ports */
    REQ_ACK,           /* [ENGINE] an acknowledgement (Param.Ack) delivered to the requester */
    REQ_STATUS,        /* [ENGINE] status query; answered inside the library, never returned */
    REQ_STATUS_REPLY,  /* [ENGINE] answer to REQ_STATUS; Data holds a text line */
    REQ_PRIORITY,      /* [ENGINE] apply priority Param.Priority.Priority to yourself; answered
                          inside the library (ContractSetModulePriority), never returned */
    REQ_PRIORITY_REPLY /* [ENGINE] answer to REQ_PRIORITY: Param.Priority, Data = text detail;
                          returned only for ContractAskModulePriority's requests */
} RequestType;

/* Acknowledgement kinds: a bit mask. A requester puts the acks it wants in WantedAck;
 * ACK_NOTHING set means "no ack wanted" (then ModAck may be empty). */
#define ACK_START    0x01  /* the run started */
#define ACK_FINISHED 0x02  /* the run finished normally */
#define ACK_STOPPED  0x04  /* the run was stopped by REQ_STOP */
#define ACK_KILLED   0x08  /* the module ends (REQ_KILL) */
#define ACK_NOTDONE  0x10  /* the request could not be carried out (e.g. STOP while idle) */
#define ACK_NOTHING  0x20  /* no acknowledgement wanted */
/* Spellings of the report's generated code (typos kept as aliases). */
#define ACK_NOHING   ACK_NOTHING
#define ACK_NOthing  ACK_NOTHING

/* Event subscription modes (IREACT "oneshot" column, SubscribeUserToEvent mode). */
#define EVENT_CONTINUOUS 0
#define EVENT_ONESHOT    1

typedef struct { char ModAck[CONTRACT_NAME_MAX]; int WantedAck; int AckID;
                 char Function[CONTRACT_FUNCTION_MAX]; /* supervisors: function to start ("" = default) */
} StartParam;
typedef struct { char ModAck[CONTRACT_NAME_MAX]; int WantedAck; int AckID; } StopParam;
typedef struct { char ModAck[CONTRACT_NAME_MAX]; int WantedAck; int AckID; } KillParam;
typedef struct { int sourcePort; char sourceModule[CONTRACT_NAME_MAX]; int targetPort; } EventParam;
typedef struct { int Port; char ModAck[CONTRACT_NAME_MAX]; int WantedAck; int AckID; } SetParamParam;
typedef struct { int SourcePort; char TargetModule[CONTRACT_NAME_MAX]; int TargetPort;
                 int Periodicity; int isContextual; } SubscribeParam;
typedef struct { int SourcePort; char TargetModule[CONTRACT_NAME_MAX]; int TargetPort; } UnsubscribeParam;
typedef struct { char targetModule[CONTRACT_NAME_MAX]; int targetPort; int sourcePort; int mode; } SubscribeEventParam;
typedef struct { char targetModule[CONTRACT_NAME_MAX]; int targetPort; int sourcePort; } UnsubscribeEventParam;
/** REQ_PRIORITY: Priority = the wanted priority 1..99. REQ_PRIORITY_REPLY: Priority = the
 *  priority before the request, Result = 1 (SCHED_FIFO), 0 (nice level), or CONTRACT_EPERM
 *  (not permitted: unchanged), Errno = the system's reason. */
typedef struct { int Priority; int Result; int Errno; unsigned Seq; } PriorityParam;
/** REQ_STATUS / REQ_STATUS_REPLY, and PriorityParam.Seq: the reply carries its query's Seq, so
 *  that a reply that came too late for its query (the module was stopped, or busy past the
 *  deadline) is never taken for the answer to a later one: it is dropped. */
typedef struct { unsigned Seq; } StatusParam;
/** REQ_ACK: `Module` acknowledges with `Ack` (one ACK_* bit) the request tagged `AckID`. */
typedef struct { char Module[CONTRACT_NAME_MAX]; int Ack; int AckID; int RequestType; } AckParam;

/**
 * One request, as delivered by WaitForRequest / LookForRequest. Only the Param member that
 * matches Type is meaningful. Payload bytes (setparam value, event data, start arguments as a
 * NUL-terminated text "p={1.0,2.0},q=3") are in Data[0 .. DataSize-1].
 */
typedef struct {
    RequestType Type;
    char Sender[CONTRACT_NAME_MAX];   /* name of the module / tool that sent it */
    RTIME ProductionTime;             /* sender's GetTime() when sent */
    RTIME ReceptionTime;              /* receiver's GetTime() when received */
    union {
        StartParam Start;
        StopParam Stop;
        KillParam Kil;                /* sic: the report's spelling */
        EventParam Event;
        SetParamParam SetParam;
        SubscribeParam Subscribe;
        UnsubscribeParam Unsubscribe;
        SubscribeEventParam SubscribeEvent;
        UnsubscribeEventParam UnsubscribeEvent;
        AckParam Ack;
        PriorityParam Priority;       /* REQ_PRIORITY / REQ_PRIORITY_REPLY */
        StatusParam Status;           /* REQ_STATUS / REQ_STATUS_REPLY */
    } Param;
    size_t DataSize;
    unsigned char Data[CONTRACT_REQUEST_DATA_MAX];
} RequestMessage;

/** [GEN] Block until a request arrives; fills *msg. Returns msg, or NULL on error (message on
 *  stderr). Status queries are answered inside and never returned. */
RequestMessage *WaitForRequest(RequestMessage *msg);
/** [GEN] Non-blocking: fills *msg and returns msg if a request is pending, else NULL
 *  (*msg untouched). Also reads the requests waiting behind it (up to 64, returned by the next
 *  reads in their order), so that status and priority queries among them are answered now. */
RequestMessage *LookForRequest(RequestMessage *msg);
/** [GEN] Send acknowledgement `ack` (one ACK_* bit) for request `ackId` to `module`.
 *  Nothing is sent (returns 0) when `wantedAck` has ACK_NOTHING or `module` is empty.
 *  Returns 0 on success, -1 on error (message on stderr). */
int SendAck(const char *module, int wantedAck, int ack, int ackId);

/* ------------------------------------------------------------------------------------------ */
/* [GEN] Interface tables (defined by the generated module.c)                                  */
/* ------------------------------------------------------------------------------------------ */

/** Input data port: {&var, port, size, "producer"|"---", producerPort, periodicity}. */
typedef struct { void *Variable; int Port; size_t Size; const char *SourceModule; int SourcePort;
                 int Periodicity; } ModuleUse;
/** Output data port: {&var, port, size}. */
typedef struct { void *Variable; int Port; size_t Size; } ModuleProduce;
/** Input event port: {&var, port, size, "producer"|"---", producerPort, oneshot}. */
typedef struct { void *Variable; int Port; size_t Size; const char *SourceModule; int SourcePort;
                 int OneShot; } ModuleReact;
/** Output event port: {&var, port, size}. */
typedef struct { void *Variable; int Port; size_t Size; } ModuleDetect;

#define IUSE_TERM       { NULL, -1, 0, NULL, -1, 0 }
#define IPRODUCE_TERM   { NULL, -1, 0 }
#define IREACT_TERM     { NULL, -1, 0, NULL, -1, 0 }
#define IDETECT_TERM    { NULL, -1, 0 }
#define PARAM_SIZE_TERM ((size_t)0)
/** "no module": the connection is made later by a subscription request. */
#define NO_MODULE "---"

/* Symbols the generated module.c defines (declared here so the library can use them). */
extern char MODULE_NAME[];
extern int MODULE_PRIORITY;           /* 1..99, higher = more urgent */
extern ModuleUse IUSE[];
extern ModuleProduce IPRODUCE[];
extern ModuleReact IREACT[];
extern ModuleDetect IDETECT[];
extern size_t PARAM_SIZE_IN[];        /* size of each parameter port, in port order */
extern size_t PARAM_SIZE_OUT[];       /* sizes this module sends with SetModuleParam */
int ModuleMain(int argc, const char *argv[]);

/* MODULE_DESCRIPTION("text"); MODULE_AUTHOR("name"); -- kept in the executable, shown by status. */
#define MODULE_DESCRIPTION(text) const char ContractModuleDescription[] = text
#define MODULE_AUTHOR(text) const char ContractModuleAuthor[] = text

/* ------------------------------------------------------------------------------------------ */
/* [GEN] Data flows                                                                            */
/* ------------------------------------------------------------------------------------------ */

/** Consume the oldest pending value of the input port whose IUSE variable is `var` into it.
 *  Returns 1 if a value was read, 0 if none was pending (var unchanged), -1 on error. */
int GetData(void *var, RTIME *productionTime, RTIME *receptionTime);
/** Consume every pending value; `var` gets the newest. Same returns as GetData. */
int GetLatestData(void *var, RTIME *productionTime, RTIME *receptionTime);
/** Send the value of the output port whose IPRODUCE variable is `var` to each consumer whose
 *  periodicity k divides the number of activations since it subscribed.
 *  Returns the number of consumers it reached, -1 on error. */
int PostData(void *var);
/** Drop the pending values of the input port of `var`, or of every input port if NULL.
 *  Returns the number of values dropped. */
int PurgeData(void *var);

/** At first activation: ask each producer named in IUSE (not "---") to send us its port. */
int SubscribeVariables(void);
/** At exit: cancel those subscriptions. */
int UnsubscribeVariables(void);
/** REQ_SUBSCRIBE handler: add `targetModule`:`targetPort` as consumer of my output data port
 *  `sourcePort`, with periodicity k >= 1. isContextual: made by a schema activation (logged). */
int SubscribeUser(int sourcePort, const char *targetModule, int targetPort, int periodicity, int isContextual);
/** REQ_UNSUBSCRIBE handler. */
int UnsubscribeUser(int sourcePort, const char *targetModule, int targetPort);

/* ------------------------------------------------------------------------------------------ */
/* [GEN] Event flows                                                                           */
/* ------------------------------------------------------------------------------------------ */

/** Notify the subscribers of the output event port whose IDETECT variable is `var`
 *  (one-shot subscribers are removed after this notification). Returns subscribers reached, -1 on error. */
int PostEvent(void *var);
/** After WaitForRequest/LookForRequest returned a REQ_EVENT: copy its data into the IREACT
 *  variable of the target port and return that port (-1 if unknown port or size mismatch). */
int GetEventId(RTIME *productionTime, RTIME *receptionTime);
/** At first activation: subscribe to each producer named in IREACT (not "---"). */
int SubscribeEvent(void);
/** At exit: cancel those subscriptions. */
int UnsubscribeEvent(void);
/** REQ_SUB_EVENT handler: `targetModule`:`targetPort` subscribes to my output event port
 *  `sourcePort`, mode EVENT_CONTINUOUS or EVENT_ONESHOT. */
int SubscribeUserToEvent(const char *targetModule, int targetPort, int sourcePort, int mode);
/** REQ_UNSUB_EVENT handler. */
int UnsubscribeUserToEvent(const char *targetModule, int targetPort, int sourcePort);

/* ------------------------------------------------------------------------------------------ */
/* [GEN] Parameters                                                                            */
/* ------------------------------------------------------------------------------------------ */

/** Send a REQ_SETPARAM for parameter port `port` of `module` with `size` bytes of `data`.
 *  Returns 0, or -1 (unknown/not running module, size > CONTRACT_REQUEST_DATA_MAX). */
int SetModuleParam(const char *moduleName, unsigned char port, void *data, unsigned long size);
/** Copy the value of a REQ_SETPARAM into `dst` of `size` bytes. The sizes must match (and match
 *  PARAM_SIZE_IN[port] when listed), else nothing is copied and -1 is returned. */
int GetDataFromSetParamRequest(RequestMessage *msg, void *dst, size_t size,
                               RTIME *productionTime, RTIME *receptionTime);

/* ------------------------------------------------------------------------------------------ */
/* [ENGINE] Driving other modules (ORD, supervisors, control tools, launcher, tests)           */
/* ------------------------------------------------------------------------------------------ */
/* All Send* functions return 0 on success, or a negative CONTRACT_E* code with a message on
 * stderr. wantedAck is a mask of ACK_* (ACK_NOTHING: none); acks come back as REQ_ACK requests
 * in the sender's own mailbox, tagged with ackId. */

#define CONTRACT_OK            0
#define CONTRACT_EUNKNOWN     -2   /* no such module in the run directory */
#define CONTRACT_ENOTRUNNING  -3   /* its mailbox exists but nobody reads it (crashed) */
#define CONTRACT_ETOOBIG      -4   /* payload larger than the limit */
#define CONTRACT_EBUSY        -5   /* its mailbox stayed full past the send timeout (2 s; at once
                                       after ContractSetNonBlockingSends(1)) */
#define CONTRACT_EINVAL       -6   /* bad argument */
#define CONTRACT_ESYS         -7   /* other system error (errno kept) */
#define CONTRACT_EPERM        -8   /* not permitted (e.g. raising another module's priority unprivileged) */
/** Text for a CONTRACT_E* code. */
const char *ContractStrError(int code);
/** Name of a request type (REQ_STOP: "STOP"), as the runtime's records and lines write it. */
const char *ContractRequestName(int type);

int SendStart(const char *module, int wantedAck, int ackId);
/** Start a supervision function: `function` name and textual arguments "p={1.0,2.0},q=3"
 *  (NULL/"" = defaults); the arguments travel in Data (NUL-terminated). */
int SendStartFunction(const char *module, const char *function, const char *args, int wantedAck, int ackId);
int SendStop(const char *module, int wantedAck, int ackId);
int SendKill(const char *module, int wantedAck, int ackId);
/** KILL saying why the run stops (`why`: text, NUL-terminated in Data, at most
 *  CONTRACT_KILL_WHY_MAX characters kept): the receiver's request_received record reads
 *  `KILL (why)`. contract-launch sends it when the build service asked the stop with a reason. */
int SendKillWhy(const char *module, const char *why);
#define CONTRACT_KILL_WHY_MAX 120
int SendSetParam(const char *module, int port, const void *value, size_t size, int wantedAck, int ackId);
/** Connect producer:sourcePort -> consumer:targetPort * periodicity (request to the producer). */
int SendSubscribe(const char *producer, int sourcePort, const char *consumer, int targetPort,
                  int periodicity, int isContextual);
int SendUnsubscribe(const char *producer, int sourcePort, const char *consumer, int targetPort);
/** Connect producer:sourcePort =* / => consumer:targetPort (mode EVENT_CONTINUOUS/EVENT_ONESHOT). */
int SendSubscribeEvent(const char *producer, int sourcePort, const char *consumer, int targetPort, int mode);
int SendUnsubscribeEvent(const char *producer, int sourcePort, const char *consumer, int targetPort);
int SendPurge(const char *module);
/** Post an event with raw bytes to `module`'s input event port `targetPort`, as if it came
 *  from my output port `sourcePort` (ORD:0 / ORD:1 notifications, supervisor notify). */
int SendEvent(const char *module, int targetPort, int sourcePort, const void *data, size_t size);
/** Send a prepared request (Sender, ProductionTime are filled in). */
int SendRequest(const char *module, RequestMessage *msg);
/** [ENGINE] on = 1: this process's requests (every Send* above, SendAck, the library's own
 *  answers) never wait: one whose receiver's mailbox is full (its queue depth reached) fails at
 *  once with CONTRACT_EBUSY, with the usual `error` record and stderr line, instead of after the
 *  2 s the sender otherwise waits for room. on = 0 is every process's default (modules, control
 *  tools): a module briefly behind then still gets the request. ORD sets it at start: a periodic
 *  scheduler must not stop serving every schema while one module does not read its mailbox
 *  (docs/engines.md §4). Data values (PostData) never wait, whatever the setting. Returns the
 *  setting before the call. */
int ContractSetNonBlockingSends(int on);
/** [ENGINE] on = 1: a request of this process whose receiver's mailbox is full is neither waited
 *  for nor dropped: it is kept and the call returns CONTRACT_OK. Kept requests are sent again
 *  every 5 ms while the process waits for requests (WaitForRequestUntil and every wait built on
 *  it; a process with a wait of its own calls ContractRetryQueuedSends), until the receiver has
 *  room; one still not sent 2 s after its call fails then, with the usual `error` record and
 *  stderr line, and the handler of ContractSetKeptSendFailed hears of it. A later request to the
 *  same receiver is kept behind it (a receiver gets its requests in order); others go at once.
 *  Room: 64 kept requests per receiver, 256 in all (one more fails at once). A new value for a
 *  parameter port that has one kept replaces it (it goes behind the others, and fails 2 s after
 *  the first value that could not be sent). The records of a request sent (setparam_sent,
 *  ack_sent) are written when it is sent, not when it is kept. Questions that wait for their
 *  answer (QueryStatus, ContractSetModulePriority) are never kept: CONTRACT_EBUSY at once for a
 *  receiver whose mailbox is full or has requests kept. At exit the process tries its kept
 *  requests 0.5 s more, then fails those left (the run is stopping: their receivers are about to
 *  be stopped too). Supervisors set it at start: a supervisor keeps reacting to events while one
 *  module does not read its mailbox (docs/engines.md §3). Takes precedence over
 *  ContractSetNonBlockingSends. Returns the setting before the call. */
int ContractSetQueuedSends(int on);
/** [ENGINE] Sends again the requests kept by ContractSetQueuedSends (those whose receivers have
 *  room now), fails those kept 2 s. Returns when to call it again (CLOCK_MONOTONIC ns), or 0 when
 *  none is kept. */
RTIME ContractRetryQueuedSends(void);
/** [ENGINE] The number of requests kept for full mailboxes (ContractSetQueuedSends), in all or
 *  for one receiver (after a Send* that returned CONTRACT_OK: was it kept?). */
int ContractQueuedSends(void);
int ContractQueuedFor(const char *module);
/** [ENGINE] Told of a kept request that failed after all (its error already logged and said):
 *  the receiver, the request (header; its Data holds DataSize bytes) and the CONTRACT_E* code.
 *  It may send requests. Not called for those that fail at the exit. NULL: none (the default). */
typedef void (*ContractKeptSendFailed)(const char *module, const RequestMessage *request, int code);
void ContractSetKeptSendFailed(ContractKeptSendFailed handler);

/** Wait for a request until the absolute CLOCK_MONOTONIC `deadline` (ns; <= 0: no wait,
 *  INT64_MAX: forever). Returns 1 (msg filled), 0 (deadline passed), -1 (error / EINTR). */
int WaitForRequestUntil(RequestMessage *msg, RTIME deadline);
/** A file descriptor to poll together with other fds (POLLIN: call LookForRequest): an epoll fd
 *  readable when a request waits in the mailbox or in the control channel (the mailbox's own fd
 *  when there is no control channel).
 *  Call LookForRequest until NULL before polling: requests kept by WaitForAck or read ahead are
 *  not in the fd. */
int MailboxFd(void);
/** Number of requests kept by WaitForAck or read ahead by LookForRequest, not yet returned. */
int PendingRequests(void);
/** Wait for the REQ_ACK from `module` tagged `ackId` whose Ack is in `ackMask`, until `deadline`;
 *  other requests received meanwhile are kept, in order, and returned by the next
 *  WaitForRequest/LookForRequest. Returns 1 (ack in *ack, may be NULL), 0 timeout, -1 error. */
int WaitForAck(const char *module, int ackId, int ackMask, RTIME deadline, RequestMessage *ack);
/** Ask `module` for its status line (pid, activations, requests...). Returns 0 and fills text,
 *  CONTRACT_EBUSY when no answer came before `deadline`. WaitForAck, QueryStatus and
 *  ContractSetModulePriority wait until their deadline through signals (EINTR: a handler ran,
 *  or this process was stopped and continued, as under a debugger or Ctrl-Z). */
int QueryStatus(const char *module, char *text, size_t textSize, RTIME deadline);
/** Does `module` exist / run in the run directory? CONTRACT_OK, CONTRACT_EUNKNOWN, CONTRACT_ENOTRUNNING. */
int ModuleState(const char *module);

/** For programs that are not modules (control tools, launcher, tests, benches): open a mailbox
 *  named `name` in the run directory so that acks can come back. Removed at exit. Returns 0/-1. */
int ContractClientInit(const char *name);
/** Close the mailbox and remove every file this process created in the run directory. */
void ContractShutdown(void);
/** The run directory in use (CONTRACT_RUN_DIR, or the fresh one created at start-up). */
const char *ContractRunDir(void);
/** 1 once the launcher has begun stopping the run (its `launcher.stopping` mark is in the run
 *  directory), else 0: a request to a peer that has already gone is then expected, not an error. */
int ContractRunStopping(void);
/** 1 when a request failed with `rc` because its peer had gone (CONTRACT_EUNKNOWN,
 *  CONTRACT_ENOTRUNNING) while the launcher stops the run: expected then, not an error. libmodule
 *  logs such a request as an `error` record ending "; the run is stopping" and prints nothing;
 *  a caller that reports its own failures (the engines) stays as quiet. */
int ContractPeerGoneAtStop(int rc);
/** This process's module name. */
const char *ContractSelfName(void);
/** [ENGINE] Lines of one kind on stderr, `NAME: <lead>TEXT`, of which the same line again within 1 s
 *  of its last print is counted rather than printed: the count is said with the kind's next print
 *  (another line, or the same 1 s later) or by ContractSayRepeats at the end, `NAME: <countLead>(the
 *  same <noun> N more times in X s)`. libmodule's own error lines are one such kind (`error: `,
 *  `error: `, "error"); a supervisor's `cannot ...` lines another. Zero-initialize all but the three
 *  texts. Not thread-safe: one thread per kind. */
typedef struct {
    const char *lead, *countLead, *noun;
    char last[512];
    RTIME said;
    unsigned repeats;
} ContractSaidLines;
void ContractSay(ContractSaidLines *lines, const char *text);
void ContractSayRepeats(ContractSaidLines *lines);
/** Number of START requests received so far (activations). */
long ContractActivations(void);

/** Add a record to this module's CSV log (see docs/runtime-api.md for the columns). */
void ContractLog(const char *event, const char *peer, int port, size_t size, const char *detail);
/** Write every record logged so far to the CSV log; returns once they are in the file (it waits
 *  for the log's writer thread). */
void ContractLogFlush(void);
/** [ENGINE] Hand the buffered records to the log's writer thread if the oldest waited at least
 *  `ageNs` (no wait: when the writer still writes the previous buffer they stay for the next
 *  try). For time-critical loops (ORD): call it when about to wait with time to spare. */
void ContractLogFlushIfOlder(RTIME ageNs);
/** [ENGINE] How old a record may get in the buffer while the module waits: 50 ms, or the shorter
 *  delay a live monitor asks for through the flush mark (docs/runtime-api.md "CSV log"). */
RTIME ContractLogFlushDelay(void);
/** [ENGINE] When the buffered records are due to be written with flush delay `delayNs`: the first
 *  multiple of `delayNs` on CLOCK_MONOTONIC (GetTime) after the oldest of them, so that every
 *  module of a run writes at the same instants (while the writer thread still writes the previous
 *  buffer: the next multiple after now); 0 when nothing waits. */
RTIME ContractLogFlushDue(RTIME delayNs);
/** [ENGINE] Hand the buffered records to the log's writer thread if `now` has reached their first
 *  boundary (ContractLogFlushDue(delayNs) with the writer idle); never waits. For time-critical
 *  loops (ORD): call it when about to wait with time to spare. */
void ContractLogFlushIfDue(RTIME now, RTIME delayNs);

/** [ENGINE] When the oldest record not yet handed to the log's writer thread was logged (GetTime),
 *  0 when none waits: an engine that goes idle wakes to hand it over (readers tail the log while it
 *  runs). */
RTIME ContractLogPendingSince(void);

/** Apply a priority 1..99: SCHED_FIFO if permitted, else one warning on stderr and a nice level.
 *  CONTRACT_SCHED=other skips SCHED_FIFO. Returns 1 if SCHED_FIFO, 0 if nice fallback. */
int ContractSetPriority(int priority);
/** [ENGINE] Ask `module` to apply priority 1..99 to itself (supervisors: `activate critical|
 *  resttime module`, event schemas, undo). The module does it inside the library the next time
 *  it reads its mailbox: SCHED_FIFO where permitted, else the nice level of that priority --
 *  which an unprivileged process may lower but not raise. Waits up to 1 s for the answer.
 *  *previous (may be NULL) gets the module's priority before the request (the one to restore).
 *  Returns 1 (SCHED_FIFO), 0 (nice level), CONTRACT_EPERM (not permitted: nothing changed), or
 *  another CONTRACT_E* code (unknown / not running module, no answer: CONTRACT_EBUSY).
 *  No message on stderr: the caller decides what to say. */
int ContractSetModulePriority(const char *module, int priority, int *previous);
/** The same request without the wait (the supervisor engine: a busy module answers when it next
 *  reads its mailbox): sends it and puts its Seq in *seq. The answer comes later as a
 *  REQ_PRIORITY_REPLY with that Seq, returned by WaitForRequest/LookForRequest (no CSV record)
 *  or ContractWaitModulePriority. Returns CONTRACT_OK or a CONTRACT_E* code (not sent). */
int ContractAskModulePriority(const char *module, int priority, unsigned *seq);
/** Waits until `deadline` for the next answer to a ContractAskModulePriority request (one an
 *  earlier wait kept comes first); other requests are kept for the next reads. 1 (the answer in
 *  *reply), 0 timeout, -1 error. */
int ContractWaitModulePriority(RTIME deadline, RequestMessage *reply);
/** This process's current priority 1..99 (MODULE_PRIORITY, or the last one applied). */
int ContractPriority(void);

#ifdef __cplusplus
}
#endif
#endif /* LIBMODULE_LIBMODULE_H */
