/* Private state and helpers shared by the libmodule sources (not installed). */
#ifndef CONTRACT_INTERNAL_H
#define CONTRACT_INTERNAL_H

#include <limits.h>
#include <stdio.h>
#include <sys/socket.h>
#include <sys/un.h>
#include "libmodule/libmodule.h"

#define WIRE_MAGIC 0x43414354u /* "CACT" */
#define WIRE_REQUEST 1u
#define WIRE_DATA 2u
#define SEND_TIMEOUT_MS 2000
#define LOG_FLUSH_NS 50000000LL /* flush the CSV log at most 50 ms after a record, when idle ...       */
#define LOG_FLUSH_WATCHED_MIN_NS 1000000LL /* ... or as the flush mark asks while watched, 1 ms..50 ms */

typedef struct { unsigned int magic; unsigned int kind; } WirePrefix;
typedef struct { char producer[CONTRACT_NAME_MAX]; RTIME production; int port; unsigned int size; } DataHeader;

/** Request header part of a RequestMessage (what travels before Data). */
#define REQUEST_HEADER_SIZE (offsetof(RequestMessage, Data))

typedef struct Subscriber {
    struct Subscriber *next;
    char module[CONTRACT_NAME_MAX];
    int port;          /* consumer's input port */
    int periodicity;   /* data: k >= 1; events: EVENT_CONTINUOUS / EVENT_ONESHOT */
    int contextual;
    long base;         /* producer's activations when subscribed */
    struct sockaddr_un addr;
    socklen_t addrlen;
    int fd;            /* connected sender socket, -1 until first use */
    /* events: PostEvent's sends to it that waited for room in its full mailbox since the last
     * `event_waited` record (eventflow.c): how many, how long in all and at most, since when */
    long waits;
    RTIME wait_ns, wait_max_ns, wait_since;
} Subscriber;

/* Who feeds an input data port (dataflow.c): its producer now, the one before it, how many values
   the producer now delivered since it took over, and when one last delivered a single value
   between two of the other's: twice within CONTRACT_INTERLEAVE_NS is two producers feeding the
   port at once (docs/runtime-api.md "One producer per input data port"). */
#define CONTRACT_INTERLEAVE_NS 1000000000LL
typedef struct InPortFeed {
    char producer[CONTRACT_NAME_MAX];
    char previous[CONTRACT_NAME_MAX];
    unsigned long values; /* values of `producer` since it took over the port */
    RTIME single_at;      /* when a producer last delivered one value between two of the other's (0: never) */
    int interleave_said;  /* the stderr warning was printed for this port */
} InPortFeed;

typedef struct Pending { struct Pending *next; int ctl; RequestMessage msg; } Pending; /* ctl: came by the control channel */

typedef struct {
    char name[CONTRACT_NAME_MAX];
    char run_dir[PATH_MAX];
    int run_dir_fd;         /* O_PATH fd, for socket paths longer than sun_path */
    int run_dir_created;    /* we created it (fresh dir under /tmp) */
    int mbx_fd;             /* <NAME>.mbx: the mailbox (events, the modules' requests and acks) */
    int ctl_fd;             /* <NAME>.ctl: its control channel (what supervisors, ORD and the launcher send), read first */
    int wait_fd;            /* MailboxFd(): an epoll fd readable when either has a request (-1 until asked for) */
    int is_module;          /* interface tables bound */
    ModuleUse *iuse; ModuleProduce *iproduce; ModuleReact *ireact; ModuleDetect *idetect;
    size_t *param_in; size_t *param_out;
    int n_iuse, n_iproduce, n_ireact, n_idetect;
    int *in_fds;            /* one per IUSE entry */
    InPortFeed *in_producer; /* who feeds each input port: its producer, the one before, the changes */
    unsigned char *scratch; /* receive buffer for data, CONTRACT_DATA_PORT_MAX + 1 */
    Subscriber **data_subs; /* per IPRODUCE entry */
    Subscriber **event_subs;/* per IDETECT entry */
    RequestMessage *last_event;
    Pending *pending_head, *pending_tail;
    int pending_count;
    long activations, requests;
    int running;
    long long run_cpu0_ns;  /* the CPU time of the thread that read the run's START, when it read it (run_finished's cpu_ns) */
    /* an event the module's handler took (GetEventId) and has not ended yet: it ends when the
     * module reads its mailbox again (its request loop), logged then as `event_handled` */
    struct { int on; int port, from_port; RTIME since; char from[CONTRACT_NAME_MAX]; } handling;
    char created[8][PATH_MAX]; /* files to remove at exit */
    int n_created;
    RTIME log_dirty_since;  /* 0 = nothing unflushed */
    int priority;           /* current priority 1..99 (0: never set) */
    int send_nowait;        /* ContractSetNonBlockingSends: requests never wait for a full mailbox */
    int send_queued;        /* ContractSetQueuedSends: requests to a full mailbox are kept (outbox.c) */
    RTIME send_waited_ns;   /* how long the last request sent waited for room in a full mailbox (0: it had room) */
    int ready;              /* a module: its <NAME>.ready is written (rt_mark_ready) */
    int engine;             /* RT_ENGINE_*: which engine runs in this process (its own record kinds: csvlog.c) */
} ContractRuntime;

#include "log_engine.h" /* RT_ENGINE_*: g_rt.engine */

extern ContractRuntime g_rt;

/* core.c */
int rt_valid_name(const char *name);
int rt_init_run_dir(void);
int rt_addr(const char *file, struct sockaddr_un *sa, socklen_t *len);
int rt_module_addr(const char *module, const char *suffix, struct sockaddr_un *sa, socklen_t *len);
int rt_bind_dgram(const char *file, int *fd_out);
/* Binds g_rt.name's mailbox <NAME>.mbx and its control channel <NAME>.ctl (mailbox.c's header
 * says what travels on each). 0, or -1 (said). */
int rt_bind_mailbox(void);
/* A datagram socket connected to sa (the path is resolved once, not at every send). */
int rt_connect_peer(const struct sockaddr_un *sa, socklen_t len, int nonblock);
void rt_close_peers(void);
void rt_register_file(const char *file);
int rt_errno_to_code(int err);
/* `NAME: error: TEXT` on stderr and an `error` record; the same line again within 1 s of its last
 * print is only counted, said with its next print, before another line, or at the end
 * (rt_error_repeats_say). */
void rt_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void rt_error_repeats_say(void);
/* Whether the launcher is stopping the run (CONTRACT_RUN_STOPPING_FILE in the run directory). */
int rt_run_stopping(void);
const char *rt_request_name(int type);
const char *rt_ack_name(int ack);
int rt_write_pid_file(void);
void rt_mark_ready(void);
/* SIGTERM, SIGINT, SIGHUP end the module (its log's last records written, its files removed), but
 * one a module started by contract-launch gets from another process (a service manager's stop,
 * which signals every process of the service at once; `kill PID` by hand) is passed to the
 * launcher, which stops the whole architecture in order: the supervisors first, so that their undo
 * still reaches ORD. The launcher's pid is $CONTRACT_LAUNCHER_PID (the launcher sets it); a module
 * whose parent is not that process any more (the launcher died) ends on the signal as before. */
void rt_install_signal_cleanup(void);
#define CONTRACT_LAUNCHER_PID_ENV "CONTRACT_LAUNCHER_PID"

/* mailbox.c */
int rt_send_request_to(const char *module, RequestMessage *msg);
/* One datagram (a request's header and payload) to module's mailbox, or to its control channel
 * when this process never waits for a full mailbox (queued or non-blocking sends): 0 sent, else
 * its errno (EAGAIN: full; dontwait = 0 waits SEND_TIMEOUT_MS for room first). */
int rt_send_datagram(const char *module, const void *request, size_t len, int dontwait);
/* The `error` record and stderr line of a request that could not be sent (why_more: the end of
 * its parenthesis); returns the CONTRACT_E* code of err. */
int rt_send_failed(const char *module, int type, int err, const char *why_more);
/* The record of a request sent (sent = 1) or not: setparam_sent (detail: `detail`, NULL: none),
 * ack_sent / ack_failed (other requests have none: a failure is an `error` record,
 * rt_send_failed). At the send itself, also for a request kept for a full mailbox (outbox.c),
 * not when it is kept. */
void rt_log_sent(const char *module, const RequestMessage *request, int sent, const char *detail);

/* outbox.c: requests kept for full mailboxes (ContractSetQueuedSends) */
int rt_outbox_holds(const char *module);
int rt_outbox_add(const char *module, const RequestMessage *request, size_t len);
void rt_outbox_drain(void); /* at exit: tries the kept requests 0.5 s more, then fails those left */

/* priority.c: $CONTRACT_REQUIRE_REALTIME=1 asks for SCHED_FIFO or no run (1 when it does); the
 * ways to grant it, said by the module refused it and by contract-launch. */
#define CONTRACT_REQUIRE_REALTIME_ENV "CONTRACT_REQUIRE_REALTIME"
#define CONTRACT_REALTIME_HOWTO "Grant real-time priorities: run as root, or give the process CAP_SYS_NICE " \
    "(systemd: AmbientCapabilities=CAP_SYS_NICE), or raise the user's rtprio limit (a line `USER - rtprio 99` " \
    "in /etc/security/limits.d/, then log in again; systemd: LimitRTPRIO=99); check with `ulimit -r`"
int rt_realtime_required(void);
/* priority.c: apply `priority` to this process without a stderr warning (requests from a
 * supervisor). Returns 1 SCHED_FIFO, 0 nice, CONTRACT_EPERM (errno set) when not permitted. */
int rt_apply_priority(int priority, const char *requester);
/* Real-time processes (SCHED_FIFO granted): lock the memory (mlockall current + future) and
 * prefault the stack, unless CONTRACT_MLOCK=0 or under ASan. 1 locked, 0 not (CSV record). */
int rt_lock_memory(void);

/* csvlog.c */
int rt_log_open(void);
int rt_log_enabled(void);
void rt_log_close(void);
/* Records logged since the log was opened (written or not: see CONTRACT_LOG_MAX_BYTES). */
unsigned long long rt_log_records(void);
void rt_log_maybe_flush(RTIME now);
/* Hands the buffered records to the log's writer thread (written at once without one); 1 when
 * handed. wait = 0: returns 0 when the writer still writes the previous buffer. */
int rt_log_hand_off(int wait);
/* LOG_FLUSH_NS, or the shorter delay the flush mark asks for while a live monitor watches. */
RTIME rt_log_flush_ns(void);
/* CONTRACT_LOG_MAX_BYTES as the log reads it (the default when unset or wrong), without a word. */
unsigned long long rt_log_max_bytes(void);

/* log_recover.c: what rt_log_recover did for a module that died. */
typedef struct {
    char log[256];              /* the log's name in its folder ("" when no mark named the pid) */
    unsigned long long records; /* records written from the module's buffers                   */
    unsigned long long bytes;
    int broken;                 /* the mark's words did not say which bytes the log lacks: left as it was */
    int dropped;                /* the log's bound left some of them out                       */
} RecoveredLog;
/* For the module `pid` that died: writes to its log, in dir (CONTRACT_LOG_DIR; NULL or "": "."),
 * the records it had logged and not written, from its flush mark's buffers, then removes the
 * mark. 1 when a mark named it (out says what was done), 0 when none did. */
int rt_log_recover(const char *dir, long pid, RecoveredLog *out);

/* crash_report.c: the block a crash writes on stderr, each line beginning with RT_CRASH_MARK
 * (its format: crash_report.c; read by the build service). rt_crash_report_prepare at start-up,
 * rt_crash_report_write in the crash handler (async-signal-safe). */
#define RT_CRASH_MARK "==contract-crash=="
#include <signal.h>
void rt_crash_report_prepare(void);
void rt_crash_report_write(int sig, const siginfo_t *info, const void *context);
const char *rt_crash_signal_name(int sig);

/* At a fatal signal (core.c): writes what the log holds and has not written yet, then, for a crash
 * (`crashed`), a `module_crashed` record; a stop signal writes none (async-signal-safe). */
void rt_log_at_signal(int sig, int crashed);

/* dataflow.c / eventflow.c */
int rt_dataflow_setup(void);
void rt_dataflow_teardown(void);
int rt_eventflow_setup(void);
void rt_eventflow_teardown(void);
/* Writes the `event_waited` record of every streak of waits not told yet (before the log closes). */
void rt_eventflow_say_waits(void);
void rt_remember_event(const RequestMessage *msg);

#endif
