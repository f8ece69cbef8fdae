import { describe, expect, it } from 'vitest';
import { CSV_HEADER, parseRecordLine, parseTrace, renderStory, StoryTeller, type KnownRecord } from './index.js';

/** The story of a run's logs: each log's records (without their line ends) after the CSV header. */
const storyOf = (logs: Record<string, string[]>): string[] =>
    renderStory(parseTrace(Object.entries(logs).map(([name, lines]) => ({ name, text: [CSV_HEADER, ...lines, ''].join('\n') }))));

const MS = 1_000_000;

/** ORD connecting EST:1 -> CTL:0 for schema altHold at 1 ms, releasing CTL every 10 ms until `untilMs`, then disconnecting. */
function ordLog(untilMs: number): string[] {
    const lines = [
        `${1 * MS},w,ORD,scheduler,,,0,connect EST:1 -> CTL:0 * 1`,
        `${1 * MS + 1},w,ORD,scheduler,,,0,activate altHold (activation #4 from FLT)`,
    ];
    for (let t = 10; t < untilMs; t += 10) lines.push(`${t * MS},w,ORD,ord_release,CTL,,0,schema=altHold cycle=${t / 10} tick_ns=${t * MS} release_ns=${t * MS} release=${t}`);
    lines.push(`${untilMs * MS},w,ORD,scheduler,,,0,disconnect EST:1 -> CTL:0`);
    return lines;
}

/** EST posting on :1 to CTL:0 and CTL reading it, at each of `atMs`. */
function delivered(atMs: number[]): { EST: string[]; CTL: string[] } {
    return {
        EST: atMs.map((t) => `${t * MS},w,EST,data_posted,CTL,1,8,to_port=0`),
        CTL: atMs.map((t) => `${t * MS + 1000},w,CTL,data_received,EST,0,8,latency_ns=1000`),
    };
}

describe('a data flow ORD connected that delivered nothing', () => {
    it('is told at the end, with how long it was connected, its schema and its reader\'s releases, and counted', () => {
        const story = storyOf({ 'ORD_1.csv': ordLog(2000) });
        expect(story).toContain('data flow EST:1 -> CTL:0 connected for 1.999 s (schema altHold): 0 values delivered (EST posted none on its output :1); CTL read nothing in its 199 releases');
        expect(story.at(-1)).toContain(', 1 data flow that delivered nothing, ');
    });

    it('is told when its values were posted but never read', () => {
        const { EST } = delivered([20, 30, 40]);
        const story = storyOf({ 'ORD_1.csv': ordLog(2000), 'EST_1.csv': EST });
        expect(story).toContain('data flow EST:1 -> CTL:0 connected for 1.999 s (schema altHold): 3 values posted, none read (CTL never read its input :0: GetData or GetLatestData, in its 199 releases)');
    });

    it("is not told of a simulation (its modules run no code): one line says why, the counts name no silent flow", () => {
        const { EST } = delivered([20, 30, 40]);
        const records = parseTrace([{ name: 'ORD_1.csv', text: [CSV_HEADER, ...ordLog(2000), ''].join('\n') }, { name: 'EST_1.csv', text: [CSV_HEADER, ...EST, ''].join('\n') }]);
        const teller = new StoryTeller();
        teller.simulation();
        for (const r of records) teller.tell(r);
        expect(teller.flowLines()).toEqual(['a simulation runs no module code: data values are not simulated, nor the events its modules post: what 1 data flow connected over 1 s delivered is not told']);
        expect(teller.summary()).not.toContain('data flow');
    });

    it('is not told when connected less than 1 s in all, nor when it delivered about once a release', () => {
        const short = storyOf({ 'ORD_1.csv': ordLog(900) });
        expect(short.filter((l) => l.startsWith('data flow '))).toEqual([]);
        expect(short.at(-1)).not.toContain('data flow');
        const every = Array.from({ length: 199 }, (_, i) => 10 * (i + 1) + 2);
        const busy = storyOf({ 'ORD_1.csv': ordLog(2000), ...delivered(every) });
        expect(busy.filter((l) => l.startsWith('data flow '))).toEqual([]);
    });

    it('tells a flow written far less often than its reader is released, with both rates', () => {
        const story = storyOf({ 'ORD_1.csv': ordLog(2000), ...delivered([100, 600, 1100, 1600]) });
        expect(story).toContain('data flow EST:1 -> CTL:0 connected for 1.999 s (schema altHold): 4 values delivered (2 a second), read 4 times in CTL\'s 199 releases (100 a second): 1 value for 50 releases');
        expect(story.at(-1)).toContain(', 1 data flow written far less often than read, ');
    });
});

/** SUP's rule run.RELAY activating event schema relay at 1 ms (connecting PRD:0 =* CNS:0), and its end at `untilMs` (disconnecting it). */
function supLog(untilMs: number, sup = 'SUP', arrow = '=*'): string[] {
    return [
        `${1 * MS},w,${sup},supervisor,,,0,rule run.RELAY active`,
        `${1 * MS + 1},w,${sup},sup_rule,,,0,run.RELAY active cause=elapsed=1000000ns`,
        `${1 * MS + 2},w,${sup},supervisor,,,0,activate schema relay() (event schema)`,
        `${1 * MS + 3},w,${sup},supervisor,PRD,,0,connect PRD:0 ${arrow} CNS:0`,
        `${1 * MS + 4},w,${sup},flow_hold,flow-PRD-0-CNS-0,,0,hold taken`,
        `${untilMs * MS},w,${sup},supervisor,,,0,rule run.RELAY inactive`,
        `${untilMs * MS + 1},w,${sup},supervisor,,,0,undo: deactivate schema relay (event schema)`,
        `${untilMs * MS + 2},w,${sup},supervisor,PRD,,0,undo: disconnect PRD:0 ${arrow} CNS:0`,
    ];
}

/** PRD posting on :0 to CNS:0 at each of `atMs`, and CNS taking them when `taken`. */
function events(atMs: number[], taken = true): { PRD: string[]; CNS: string[] } {
    return {
        PRD: atMs.map((t) => `${t * MS},w,PRD,event_posted,CNS,0,4,to_port=0`),
        CNS: taken ? atMs.map((t) => `${t * MS + 1000},w,CNS,event_received,PRD,0,4,from_port=0 latency_ns=1000`) : [],
    };
}

describe('an event flow a supervisor connected that delivered nothing', () => {
    it('is told at the end with who connected it and its schema, and counted', () => {
        const story = storyOf({ 'SUP_1.csv': supLog(2000), 'END_1.csv': [`${2500 * MS},w,END,module_exit,,,0,status=0 records=1`] });
        expect(story).toContain("event flow PRD:0 =* CNS:0 connected for 1.999 s (schema relay, connected by SUP's rule run.RELAY): 0 events delivered (PRD posted none on its output :0); CNS received nothing");
        expect(story.at(-1)).toContain(', 1 event flow a supervisor connected that delivered nothing, ');
    });

    it('counts up to the last record when still connected, and tells events posted but never taken', () => {
        const { PRD } = events([20, 30, 40]);
        const story = storyOf({ 'SUP_1.csv': supLog(2000).slice(0, 5), 'PRD_1.csv': [...PRD, `${1501 * MS},w,PRD,module_exit,,,0,status=0 records=4`] });
        expect(story).toContain("event flow PRD:0 =* CNS:0 connected for 1.5 s (schema relay, connected by SUP's rule run.RELAY): 3 events posted, none taken (CNS never took one from its input :0: GetEventId)");
    });

    it('is not told when it delivered, when connected less than 1 s, nor for events posted while disconnected', () => {
        const told = (logs: Record<string, string[]>) => storyOf(logs).filter((l) => l.startsWith('event flow '));
        expect(told({ 'SUP_1.csv': supLog(2000), ...events([500]) })).toEqual([]);
        expect(told({ 'SUP_1.csv': supLog(900) })).toEqual([]);
        const late = events([2100], true);
        expect(told({ 'SUP_1.csv': supLog(2000), ...late })).toHaveLength(1);
    });

    it('stays connected while another supervisor holds it, and names both; a one-shot flow is named with its arrow', () => {
        const two = storyOf({ 'SUP_1.csv': supLog(600), 'TWO_1.csv': supLog(1800, 'TWO') });
        expect(two).toContain("event flow PRD:0 =* CNS:0 connected for 1.799 s (schema relay, connected by SUP's rule run.RELAY, TWO's rule run.RELAY): 0 events delivered (PRD posted none on its output :0); CNS received nothing");
        const once = storyOf({ 'SUP_1.csv': supLog(2000, 'SUP', '=>') });
        expect(once.filter((l) => l.startsWith('event flow PRD:0 => CNS:0 connected for 1.999 s'))).toHaveLength(1);
    });
});

describe('event posts that waited for room in a full mailbox', () => {
    const bat = [
        `${1000 * MS},w,BAT,event_posted,GCS,0,256,to_port=0`,
        `${1200 * MS},w,BAT,event_waited,GCS,0,256,to_port=0 waits=48 wait_ns=940000000 max_wait_ns=21000000 streak_ns=1001000000`,
        `${2400 * MS},w,BAT,event_waited,GCS,0,256,to_port=0 waits=52 wait_ns=990000000 max_wait_ns=25000000 streak_ns=1000000000`,
    ];
    const gcs = [
        `${1010 * MS},w,GCS,event_received,BAT,0,256,from_port=0 latency_ns=10000000`,
        `${2500 * MS},w,GCS,event_received,BAT,0,256,from_port=0 latency_ns=527000000`,
        `${2600 * MS},w,GCS,event_received,MOT,1,256,from_port=3 latency_ns=900000000`,
    ];

    it('reads the counts and times of a streak as numbers', () => {
        expect((parseRecordLine('BAT_1.csv', 2, bat[1]!) as KnownRecord).fields)
            .toEqual({ to_port: 0, waits: 48, wait_ns: 940000000, max_wait_ns: 21000000, streak_ns: 1001000000 });
    });

    it('tells a flow\'s first streak where it happens, and at the end its waits with its deliveries\' longest latency, counted', () => {
        const story = storyOf({ 'BAT_1.csv': bat, 'GCS_1.csv': gcs });
        expect(story).toContain("+0.200000s BAT  events BAT:0 -> GCS:0 waited for room in GCS's full mailbox 48 times in 1.001 s (940 ms in all, up to 21 ms each): GCS takes its events slower than BAT posts them; later waits are counted at the end");
        expect(story.filter((l) => l.includes('waited for room in'))).toHaveLength(1); // the second streak only counted
        expect(story).toContain("BAT's events to GCS (BAT:0 -> GCS:0) waited for room 100 times (1.93 s in all, up to 25 ms): GCS takes its events slower than BAT posts them; delivery latency up to 527 ms");
        expect(story.at(-1)).toContain(', 100 event posts that waited for room, ');
    });

    it('says nothing of a flow whose posts never waited', () => {
        const story = storyOf({ 'GCS_1.csv': gcs });
        expect(story.filter((l) => l.includes('waited for room'))).toEqual([]);
        expect(story.at(-1)).not.toContain('waited for room');
    });
});

describe('event posts that failed: the events lost', () => {
    // BAT posts to GCS: two posts fail during the run (GCS's mailbox full for 2 s), one at the run's
    // stop to a GCS already gone (the runtime's error record just before says so): no loss
    const BAT = [
        `${10 * MS},w,BAT,event_posted,GCS,0,8,to_port=1`,
        `${2100 * MS},w,BAT,error,,,0,"EVENT request to GCS: mailbox full (Resource temporarily unavailable)"`,
        `${2100 * MS + 1},w,BAT,event_posted,GCS,0,8,to_port=1 failed`,
        `${4200 * MS},w,BAT,error,,,0,"EVENT request to GCS: mailbox full (Resource temporarily unavailable)"`,
        `${4200 * MS + 1},w,BAT,event_posted,GCS,0,8,to_port=1 failed`,
        `${5000 * MS},w,BAT,error,,,0,EVENT request to GCS: unknown module (No such file or directory; the run is stopping)`,
        `${5000 * MS + 1},w,BAT,event_posted,GCS,0,8,to_port=1 failed`,
    ];

    it('are counted in the line of counts and told per flow at the end, those at the run\'s stop left out', () => {
        const story = storyOf({ 'BAT_1.csv': BAT });
        expect(story.at(-1)).toContain(', 2 event posts that failed (the event lost), ');
        expect(story).toContain('2 events BAT posted to GCS were lost (BAT:0 -> GCS:1): their posts failed (PostEvent gives up after waiting 2 s for room in GCS\'s full mailbox, at once when GCS is not running); the last: EVENT request to GCS: mailbox full (Resource temporarily unavailable)');
    });

    it('are not counted when every failure was at the run\'s stop', () => {
        const story = storyOf({ 'BAT_1.csv': [BAT[0]!, ...BAT.slice(5)] });
        expect(story.at(-1)).not.toContain('failed');
        expect(story.filter((l) => l.includes(' lost ('))).toEqual([]);
    });
});
