/** contract trace's figure of each released module's CPU per release (module-cpu.ts), from run_finished's cpu_ns. */
import { describe, expect, it } from 'vitest';
import { CSV_HEADER, ModuleCpu, parseTrace, renderStory, type KnownRecord } from './index.js';

const W = '2026-12-07T11:02:48.568320Z';
const PERIOD = 10_000_000;
/** Lines as ORD, a supervisor and two modules write them (ord_core.c, mailbox.c): 100 cycles of schema loop, MSC's CPU 1 ms + 10 µs per cycle, cycle 57 taking 4 ms. */
function logs(withCpu = true) {
    const ord = [`1000000000,${W},ORD,module_started,,,0,pid=39 priority=50`, `1000000100,${W},ORD,run_started,SUP,,0,activation=1`];
    const msc = [`1000000000,${W},MSC,module_started,,,0,pid=41 priority=40`];
    const sup = [`1000000000,${W},SUP,module_started,,,0,pid=38 priority=40`, `1000000060,${W},SUP,run_started,contract-launch,,0,activation=1`];
    for (let k = 0; k < 100; k++) {
        const tick = 1_100_000_000 + k * PERIOD;
        const cpu = k === 57 ? 4_000_000 : 1_000_000 + k * 10_000;
        ord.push(`${tick},${W},ORD,ord_release,MSC,,0,schema=loop cycle=${k} tick_ns=${tick} release_ns=${tick + 20_000} release=${k + 1}`);
        msc.push(`${tick + 30_000},${W},MSC,run_started,ORD,,0,activation=${k + 1}`,
            `${tick + 30_000 + cpu + 100_000},${W},MSC,run_finished,,,0,activation=${k + 1}${withCpu ? ` cpu_ns=${cpu}` : ''} ACK_FINISHED`);
    }
    // ORD's and the supervisor's own runs end at the stop: their whole life, no release
    ord.push(`2200000000,${W},ORD,run_finished,SUP,,0,activation=1 cpu_ns=900000000 STOP`);
    sup.push(`2200000100,${W},SUP,run_finished,contract-launch,,0,activation=1 cpu_ns=700000000 STOP`);
    return [['ORD_1.csv', ord], ['MSC_1.csv', msc], ['SUP_1.csv', sup]].map(([name, lines]) => ({ name: name as string, text: `${CSV_HEADER}\n${(lines as string[]).join('\n')}\n` }));
}

describe("contract trace: each released module's CPU per release", () => {
    it('tells max (with its schema, cycle and share of the PERIOD), p99 and the releases, modules only', () => {
        const story = renderStory(parseTrace(logs()));
        const cpu = story.filter((l) => l.startsWith('module '));
        expect(cpu).toEqual(['module MSC: CPU per release max 4 ms (loop cycle 57, 40 % of its PERIOD 10 ms), p99 1.99 ms, 100 releases']);
        // told after the schema lines, before the counts
        expect(story.indexOf(cpu[0]!)).toBe(story.length - 2);
    });

    it('gives the same figure as an object (contract run --format json: moduleCpu)', () => {
        const c = new ModuleCpu();
        for (const r of parseTrace(logs())) if (r.kind !== 'unknown') c.see(r as KnownRecord);
        expect(c.figures()).toEqual([{ module: 'MSC', releases: 100, maxNs: 4_000_000, p99Ns: 1_990_000, maxSchema: 'loop', maxCycle: 57, periodNs: PERIOD, maxShareOfPeriod: 0.4 }]);
    });

    it('says nothing for logs of older versions (no cpu_ns)', () => {
        expect(renderStory(parseTrace(logs(false))).filter((l) => l.startsWith('module '))).toEqual([]);
    });
});

describe('a run its own code ended, with its cpu_ns', () => {
    it('is told as before: the CPU time is no part of the line', () => {
        const own = [`1000000000,${W},MAA,module_started,,,0,pid=42 priority=30`, `1100000000,${W},MAA,run_started,SUP,,0,activation=1`, `1102000000,${W},MAA,run_finished,,,0,activation=1 cpu_ns=1250000`];
        const story = renderStory(parseTrace([{ name: 'MAA_1.csv', text: `${CSV_HEADER}\n${own.join('\n')}\n` }]));
        expect(story.some((l) => l.endsWith('MAA  run #1 ended by its own code (started by SUP)'))).toBe(true);
    });
});
