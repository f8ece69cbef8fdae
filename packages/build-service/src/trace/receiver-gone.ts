/**
 * The receiver a runtime error record says is gone: a request that could not be delivered because
 * its receiver no longer runs, in the runtime's words (core.c, sup_main.c): `START request to SRT:
 * module not running (its mailbox is stale) ...`, `STOP request to ORD: not sent, it has ended
 * (...)`, `UNSUBSCRIBE request to SRT: unknown module (...)`. Read by the story (ended-mid-run.ts)
 * and the IDE's Monitor (its gone signs), each taking the ways it tells; and ORD's `stuck:` record
 * that says its module is no longer running.
 */

/** How the request found its receiver gone. */
export type ReceiverGoneWay = 'not running' | 'ended' | 'unknown';

const RECEIVER_GONE = /^[A-Z_]+ request to ([A-Za-z0-9_.-]+): (module not running|not sent, it has ended|unknown module)/;

const WAYS: Record<string, ReceiverGoneWay> = { 'module not running': 'not running', 'not sent, it has ended': 'ended', 'unknown module': 'unknown' };

/** The receiver an `error` record's detail says is gone, and how; undefined for any other detail. */
export function receiverGone(detail: string): { module: string; way: ReceiverGoneWay } | undefined {
    const m = RECEIVER_GONE.exec(detail);
    return m ? { module: m[1]!, way: WAYS[m[2]!]! } : undefined;
}
/** What a `stuck:` line says instead of the advice when its module is no longer running (crashed, killed). */
const STUCK_GONE = /: it is no longer running \(it crashed or was killed\)/;

/** Whether the detail of ORD's `stuck:` record says its module is no longer running (the story and the IDE's Monitor). */
export function stuckSaysGone(detail: string): boolean {
    return STUCK_GONE.test(detail);
}

