/** contract trace's figure of each released module's CPU per release (module-cpu.ts), from run_finished's cpu_ns. */
import { describe, expect, it } from 'vitest';
import { CSV_HEADER, ModuleCpu, StoryTeller, parseTrace, renderStory, type KnownRecord } from './index.js';

const W = '2026-12-07T11:02:48.568320Z';
const PERIOD = 10_000_000;
/** Lines as ORD, a supervisor and two modules write them (ord_core.c, mailbox.c): 100 cycles of schema loop, MSC's CPU 1 ms + 10 µs per cycle, cycle 57 taking 4 ms. */
function logs(withCpu = true, unknownAt: readonly number[] = []) {
    const ord = [`1000000000,${W},ORD,module_started,,,0,pid=39 priority=50`, `1000000100,${W},ORD,run_started,SUP,,0,activation=1`];
    const msc = [`1000000000,${W},MSC,module_started,,,0,pid=41 priority=40`];
    const sup = [`1000000000,${W},SUP,module_started,,,0,pid=38 priority=40`, `1000000050,${W},SUP,supervisor,,,0,function action() started`, `1000000060,${W},SUP,run_started,contract-launch,,0,activation=1`];
    for (let k = 0; k < 100; k++) {
        const tick = 1_100_000_000 + k * PERIOD;
        const cpu = unknownAt.includes(k) ? -1 : k === 57 ? 4_000_000 : 1_000_000 + k * 10_000;
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
        // told after the schema lines, then ORD's and the supervisor's own CPU, before the counts
        expect(story.indexOf(cpu[0]!)).toBe(story.length - 4);
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

describe('releases whose thread CPU clock could not be read (cpu_ns=-1)', () => {
    it('are counted as releases without a CPU time, in no figure: the max and p99 are those of the others', () => {
        // cycle 57 (the 4 ms) and the 10 last said -1: a -1 counted as a duration would not change the max, so the p99 and the count tell
        const unknown = [57, 90, 91, 92, 93, 94, 95, 96, 97, 98, 99];
        const story = renderStory(parseTrace(logs(true, unknown)));
        expect(story.filter((l) => l.startsWith('module '))).toEqual(['module MSC: CPU per release max 1.89 ms (loop cycle 89, 18.9 % of its PERIOD 10 ms), p99 1.89 ms, 89 releases, 11 releases without a CPU time']);
        const c = new ModuleCpu();
        for (const r of parseTrace(logs(true, unknown))) if (r.kind !== 'unknown') c.see(r as KnownRecord);
        expect(c.figures()).toEqual([{ module: 'MSC', releases: 89, releasesWithoutCpu: 11, maxNs: 1_890_000, p99Ns: 1_890_000, maxSchema: 'loop', maxCycle: 89, periodNs: PERIOD, maxShareOfPeriod: 0.189 }]);
    });

    it('a module none of whose releases said one: its line says so, its figure has no max', () => {
        const all = Array.from({ length: 100 }, (_, k) => k);
        const story = renderStory(parseTrace(logs(true, all)));
        expect(story.filter((l) => l.startsWith('module '))).toEqual(["module MSC: 100 releases without a CPU time (its thread's CPU clock could not be read)"]);
        const c = new ModuleCpu();
        for (const r of parseTrace(logs(true, all))) if (r.kind !== 'unknown') c.see(r as KnownRecord);
        expect(c.figures()).toEqual([{ module: 'MSC', releases: 0, releasesWithoutCpu: 100 }]);
    });
});

describe("ORD's and the supervisors' own CPU (their runs' cpu_ns)", () => {
    it('is told after the modules: the CPU of their runs, the runs\' length and the share of one CPU', () => {
        const story = renderStory(parseTrace(logs()));
        // ORD ran 1.1999 s (1000000100 to 2200000000), SUP 1.20004 s; a supervisor is a module that wrote a supervisor record
        expect(story.slice(-3, -1)).toEqual(['ORD (scheduler): own CPU 900 ms in 1 run of 1.2 s (75 % of one CPU)', 'supervisor SUP: own CPU 700 ms in 1 run of 1.2 s (58.3 % of one CPU)']);
        const c = new StoryTeller();
        for (const r of parseTrace(logs())) c.tell(r);
        expect(c.engineCpuFigures()).toEqual([
            { module: 'ORD', role: 'scheduler', runs: 1, cpuNs: 900_000_000, runNs: 1_199_999_900, shareOfCpu: 900_000_000 / 1_199_999_900 },
            { module: 'SUP', role: 'supervisor', runs: 1, cpuNs: 700_000_000, runNs: 1_200_000_040, shareOfCpu: 700_000_000 / 1_200_000_040 },
        ]);
    });

    it('is told of no simulation (its engines run no measured code)', () => {
        const sim = new StoryTeller();
        sim.simulation();
        for (const r of parseTrace(logs())) sim.tell(r);
        expect(sim.engineCpuFigures()).toEqual([]);
        expect(sim.moduleCpuLines()).toEqual(['module MSC: CPU per release max 4 ms (loop cycle 57, 40 % of its PERIOD 10 ms), p99 1.99 ms, 100 releases']);
    });

    it('sums a supervisor\'s runs and counts those without a CPU time; a module no ORD released and no supervisor is none of them', () => {
        const sup = [`1000000000,${W},SUP,module_started,,,0,pid=38 priority=40`, `1000000050,${W},SUP,supervisor,,,0,function action() started`,
            `1000000000,${W},SUP,run_started,GLB,,0,activation=1`, `1500000000,${W},SUP,run_finished,GLB,,0,activation=1 cpu_ns=5000000 STOP`,
            `2000000000,${W},SUP,run_started,GLB,,0,activation=2`, `2500000000,${W},SUP,run_finished,GLB,,0,activation=2 cpu_ns=10000000 STOP`,
            `3000000000,${W},SUP,run_started,GLB,,0,activation=3`, `3500000000,${W},SUP,run_finished,GLB,,0,activation=3 cpu_ns=-1 KILL`];
        const maa = [`1100000000,${W},MAA,run_started,SUP,,0,activation=1`, `1102000000,${W},MAA,run_finished,,,0,activation=1 cpu_ns=1250000`];
        const story = renderStory(parseTrace([{ name: 'SUP_1.csv', text: `${CSV_HEADER}\n${sup.join('\n')}\n` }, { name: 'MAA_1.csv', text: `${CSV_HEADER}\n${maa.join('\n')}\n` }]));
        expect(story.filter((l) => /^(ORD|supervisor|module) /.test(l))).toEqual(['supervisor SUP: own CPU 15 ms in 2 runs of 1 s (1.5 % of one CPU), 1 run without a CPU time']);
    });
});

describe('a run its own code ended, with its cpu_ns', () => {
    it('is told as before: the CPU time is no part of the line', () => {
        const own = [`1000000000,${W},MAA,module_started,,,0,pid=42 priority=30`, `1100000000,${W},MAA,run_started,SUP,,0,activation=1`, `1102000000,${W},MAA,run_finished,,,0,activation=1 cpu_ns=1250000`];
        const story = renderStory(parseTrace([{ name: 'MAA_1.csv', text: `${CSV_HEADER}\n${own.join('\n')}\n` }]));
        expect(story.some((l) => l.endsWith('MAA  run #1 ended by its own code (started by SUP)'))).toBe(true);
    });
});
