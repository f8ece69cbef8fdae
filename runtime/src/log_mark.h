/* The layout of a CSV log's flush mark, <log>.mark (csvlog.c writes it, log_recover.c reads it
 * after its module died). One file mapped shared by the module:
 *
 *   page 0, 64-bit words
 *     0  STATE  what the log file lacks: 0 nothing, 1 a record is being logged, else the mono_ns
 *               of the oldest record not written yet (the build service's live trace reads it)
 *     1  FLUSH  the flush delay a live reader asks for, in ns (written by the build service)
 *     2  MAGIC  MARK_MAGIC once the words below are set; 0 again when the log is closed
 *     3  PID    the module's process id
 *     4  BASE   bytes of the log file before the module's first record (its header, an older run's)
 *     5  BROKEN 1 once the file holds bytes that are not the module's records in order (a
 *               `log-capped` record, a write the disk refused, a crash record): no recovery
 *     6, 7  START(0), LEN(0)  buffer 0 holds the bytes [START, START + LEN) of the module's
 *     8, 9  START(1), LEN(1)  records (counted from its first record), buffer 1 likewise
 *   then the two log buffers, LOG_BUF bytes each (the module formats its records there)
 *
 * So whatever instant a SIGKILL (the kernel's OOM killer, RLIMIT_RTTIME's hard limit) stops the
 * module at, the records it had logged and not written are in the file's buffers, and
 * FILE_SIZE - BASE says how many bytes of its records the log holds: the bytes past that, in START
 * order, are the ones it lacks, to the byte (a write cut inside a record is completed). */
#ifndef CONTRACT_LOG_MARK_H
#define CONTRACT_LOG_MARK_H

#define LOG_BUF 65536
/* A record's room: its fields at their bounds, each quoted with every byte a doubled quote (the
 * detail with its cut mark), the separators and the line end: 20 + 27 + 63 + 2 * (2 + 2 * 64)
 * + 10 + 20 + (2 + 2 * (400 + 3)) + 8 = 1216 bytes. */
#define RECORD_MAX 1280
#define MARK_PAGE 4096
#define MARK_FILE_BYTES (MARK_PAGE + 2 * LOG_BUF)

#define MARK_WORD_STATE 0
#define MARK_WORD_FLUSH 1
#define MARK_WORD_MAGIC 2
#define MARK_WORD_PID 3
#define MARK_WORD_BASE 4
#define MARK_WORD_BROKEN 5
#define MARK_WORD_START(i) (6 + 2 * (i))
#define MARK_WORD_LEN(i) (7 + 2 * (i))
#define MARK_WORDS 10

/* "CTLOGBF1" */
#define MARK_MAGIC 0x314642474f4c5443ULL

#endif
