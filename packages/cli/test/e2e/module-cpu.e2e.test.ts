/**
 * run_finished's cpu_ns on a real run (docs/runtime-api.md "Trace records"): the tutorial's MSA
 * burns 2 ms of CPU in its exec region at each release of schemaCommande1 (PERIOD 1 s); its
 * run_finished records say each release's CPU time of its own thread, 2 ms and a little more (the
 * rest of the region: a printf, PostData), and `contract trace` tells the figure of it.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { readLogs } from './csv-log.js';
import { contract, seededScratchCopy, type CliRun, type Scratch } from './harness.js';

const BURN_NS = 2_000_000;
let scratch: Scratch;
let run: CliRun;
let story: CliRun;

beforeAll(async () => {
    scratch = await seededScratchCopy('tutorial');
    const src = join(scratch.project, 'src-gen/generated/architecture/modules/MSA_mod/module.c');
    const code = readFileSync(src, 'utf8');
    const at = '    //one period: a coordinate that drifts away, so that MSC\'s command grows\n';
    expect(code).toContain(at);
    // 2 ms of the process's CPU time (clock(): its only busy thread is this one), in a busy loop
    writeFileSync(src, code.replace(at, `    { clock_t c0 = clock(); while ((double)(clock() - c0) * 1e9 / CLOCKS_PER_SEC < ${BURN_NS}) {} }\n${at}`)
        .replace('/*PROTECTED REGION ID(protect_additional_import_MSA) ENABLED START*/', '/*PROTECTED REGION ID(protect_additional_import_MSA) ENABLED START*/\n#include <time.h>'));
    run = contract(['run', 'tutorial', '--sandbox', 'bwrap', '--duration', '4s', '--logs', scratch.logs, '--format', 'json'], scratch);
    story = contract(['trace', scratch.logs], scratch);
}, 300_000);
afterAll(() => scratch?.dispose());

describe("a release's CPU time on a real run (bwrap)", () => {
    it("MSA's run_finished says 2 ms of CPU per release, within a tolerance", () => {
        expect(run.code, run.stderr).toBe(0);
        const finished = readLogs(scratch.logs).filter((r) => r.module === 'MSA' && r.event === 'run_finished');
        expect(finished.length).toBeGreaterThanOrEqual(2);
        for (const r of finished) {
            const m = /^activation=\d+ cpu_ns=(\d+) ACK_FINISHED$/.exec(r.detail);
            expect(m, r.detail).not.toBeNull();
            const ns = Number(m![1]);
            expect(ns).toBeGreaterThanOrEqual(BURN_NS * 0.95);
            expect(ns).toBeLessThan(BURN_NS + 3_000_000);
        }
    });

    it('contract trace tells the figure in its story, contract run --format json as moduleCpu', () => {
        expect(story.code).toBe(0);
        expect(story.stdout).toMatch(/^module MSA: CPU per release max 2\.\d+ ms \(schemaCommande1 cycle \d+, 0\.2\d* % of its PERIOD 1 s\), p99 2\.\d+ ms, \d+ releases$/m);
        const fig = (JSON.parse(run.stdout) as { moduleCpu: Array<{ module: string; maxNs: number; periodNs?: number }> }).moduleCpu;
        const msa = fig.find((o) => o.module === 'MSA');
        expect(msa?.periodNs).toBe(1_000_000_000);
        expect(msa!.maxNs).toBeGreaterThanOrEqual(BURN_NS * 0.95);
        // modules only: no figure for ORD or a supervisor
        expect(fig.map((o) => o.module)).not.toContain('ORD');
        expect(fig.map((o) => o.module)).not.toContain('SUP');
    });

    it("tells ORD's and the supervisors' own CPU, from their runs' run_finished cpu_ns, in the story and as engineCpu", () => {
        // the records: ORD's run (started by SUP) and each supervisor's end at the stop with their thread's CPU
        const logs = readLogs(scratch.logs);
        for (const engine of ['ORD', 'SUP', 'GLB']) {
            const ends = logs.filter((r) => r.module === engine && r.event === 'run_finished');
            expect(ends.length, engine).toBeGreaterThanOrEqual(1);
            for (const r of ends) expect(r.detail, engine).toMatch(/^activation=\d+ cpu_ns=\d+ (STOP|KILL)$/);
        }
        expect(story.stdout).toMatch(/^ORD \(scheduler\): own CPU [\d.]+ (ns|µs|ms|s) in 1 run of [\d.]+ s \([\d.e-]+ % of one CPU\)$/m);
        expect(story.stdout).toMatch(/^supervisor SUP: own CPU [\d.]+ (ns|µs|ms|s) in 1 run of [\d.]+ s \([\d.e-]+ % of one CPU\)$/m);
        const engines = (JSON.parse(run.stdout) as { engineCpu: Array<{ module: string; role: string; runs: number; cpuNs: number; runNs: number; shareOfCpu: number }> }).engineCpu;
        expect(engines.map((e) => [e.module, e.role])).toEqual([['ORD', 'scheduler'], ['GLB', 'supervisor'], ['SUP', 'supervisor']]);
        for (const e of engines) {
            expect(e.runs).toBe(1);
            expect(e.cpuNs).toBeGreaterThan(0);
            // a run of at least a second (ORD's: from SUP's START, MAA's 2 s mission first, to the stop of the 4 s run), a small share of one CPU
            expect(e.runNs).toBeGreaterThan(1e9);
            expect(e.shareOfCpu).toBeGreaterThan(0);
            expect(e.shareOfCpu).toBeLessThan(0.5);
        }
    });
});
