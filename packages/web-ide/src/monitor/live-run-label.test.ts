import { describe, it, expect } from 'vitest';
import { csvLogsRunLabel, endedRunLabel, endKnownAfterLossLabel, liveRunLabel, streamedRunLabel } from './live-run-label.js';
import { CONNECTION_LOST, LOST_TRACE } from './live-follow-protocol.js';
import { LOST_WITH_SERVER } from '../build/job-end.js';

describe("a live job's label in the Monitor's run list", () => {
  it('says how the job ended whichever reaches the page first, its end or its CSV logs', () => {
    // the usual order: the end, then the logs
    const ended = endedRunLabel(liveRunLabel('j-1'), true, 'cancelled');
    expect(ended).toBe('Build & Run job j-1 · ended: cancelled');
    expect(streamedRunLabel('j-1', 'cancelled')).toBe('Build & Run job j-1 · as streamed · ended: cancelled');
    // the logs first (the stream's end came past the wait, or only the build panel's end says it): the end still says how
    expect(endedRunLabel(streamedRunLabel('j-1', undefined), false, 'cancelled')).toBe('Build & Run job j-1 · as streamed · ended: cancelled');
  });

  it("keeps what the stream missed: while it runs, and counted from the logs once they are shown", () => {
    expect(endedRunLabel(`${liveRunLabel('j-2')} (trace not whole: 12 records not received)`, true, 'succeeded'))
      .toBe('Build & Run job j-2 · ended: succeeded (trace not whole: 12 records not received)');
    expect(streamedRunLabel('j-2', 'succeeded', { streamed: 40_000, logged: 52_500 }))
      .toBe('Build & Run job j-2 · as streamed (40,000 of the 52,500 records of its logs: 12,500 not received) · ended: succeeded');
    // nothing streamed (an older build service), or all of it: no count
    expect(streamedRunLabel('j-2', 'failed', { streamed: 0, logged: 10 })).toBe('Build & Run job j-2 · as streamed · ended: failed');
    expect(streamedRunLabel('j-2', 'failed', { streamed: 10, logged: 10 })).toBe('Build & Run job j-2 · as streamed · ended: failed');
  });

  it('the run of its CSV logs: what the replay lacks, and how the job ended when it carries that', () => {
    expect(csvLogsRunLabel('j-3', [])).toBe('Build & Run job j-3 · CSV logs');
    expect(csvLogsRunLabel('j-3', ['MSC_1.csv capped', 'LOC_1.csv not downloaded'], 'cancelled'))
      .toBe('Build & Run job j-3 · CSV logs (not whole: MSC_1.csv capped; LOC_1.csv not downloaded) · ended: cancelled');
    // the crash sites the build service mapped after the run, at the end (as a folder's crash files are told)
    expect(csvLogsRunLabel('j-3', [], 'failed', undefined, ['MAA crashed: signal 11 (SIGSEGV) at address 0x0', '  #0 f at src-gen/x/module.c:74 (inlined into g at src-gen/x/module.c:268)']))
      .toBe('Build & Run job j-3 · CSV logs · ended: failed — crash sites (mapped by the build service): MAA crashed: signal 11 (SIGSEGV) at address 0x0; #0 f at src-gen/x/module.c:74 (inlined into g at src-gen/x/module.c:268)');
    // its outcome given later, by the build panel's end
    expect(endedRunLabel(csvLogsRunLabel('j-3', []), false, 'failed')).toBe('Build & Run job j-3 · CSV logs · ended: failed');
  });

  it("a lost stream's outcome gives way to the job's end known after: gone with the IDE server, its promise of CSV logs dropped", () => {
    const lost = endedRunLabel(`${liveRunLabel('j-4')} (trace not whole: ${LOST_TRACE})`, true, CONNECTION_LOST);
    expect(endKnownAfterLossLabel(lost, CONNECTION_LOST, LOST_TRACE, LOST_WITH_SERVER)).toBe(`Build & Run job j-4 · ended: ${LOST_WITH_SERVER}`);
    // another note of the stream stays
    const missed = endedRunLabel(`${liveRunLabel('j-4')} (trace not whole: 12 records not received; ${LOST_TRACE})`, true, CONNECTION_LOST);
    expect(endKnownAfterLossLabel(missed, CONNECTION_LOST, LOST_TRACE, LOST_WITH_SERVER)).toBe(`Build & Run job j-4 · ended: ${LOST_WITH_SERVER} (trace not whole: 12 records not received)`);
  });
});
