#!/usr/bin/env node
// The simulator's benchmark (docs/simulation.md "Figures"), written to bench/parts/simulate.json:
//   simulate.events_per_s      engine inputs per second of the harness's wall time (module events,
//                              timers, supervisor messages, release acks) in a 60 s mobile-robot
//                              scenario with an event every millisecond (quiet mode: records of
//                              failures only), reading its input included
//   simulate.sixty_s_ms        wall time of that 60 s scenario seen from Node (process start,
//                              pipes and the 60,000 input lines included)
//   simulate.cold_ms           from a changed .contract file to the first simulated step, in
//                              process (load + check the project, generate the tables, compile
//                              and link the harness, run the tutorial's commutation scenario)
//   simulate.warm_ms           the same with nothing changed (harness found in the cache)
//   simulate.cli_cold_ms       `contract simulate` as a new process after a change (node start-up included)
// Under 60 s in total.
import { spawnSync } from 'node:child_process';
import { cpSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { DEFAULT_RUNTIME_DIR, loadScenario, prepareProject, runLoadedScenario } from '../dist/index.js';

const repo = fileURLToPath(new URL('../../../', import.meta.url));
const cache = mkdtempSync(join(tmpdir(), 'contract-sim-bench-'));
const opts = { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir: cache };
const out = {};

async function prepare(dir) {
    const p = await prepareProject(dir, opts);
    if (!('build' in p)) throw new Error(p.buildError ?? p.sandboxError ?? JSON.stringify(p.modelErrors));
    return p;
}

// ---- throughput: 60 s of the robot, an event every millisecond
{
    const project = await prepare(join(repo, 'examples', 'mobile-robot'));
    const lines = ['until 60s', 'start MIS.mission()', 't=200ms TEL:1 "auto"'];
    for (let ms = 201; ms < 60_000; ms++) {
        if (ms % 2) lines.push(`t=${ms}ms TEL:0 {0.3, 0.1}`);
        else lines.push(`t=${ms}ms OBS:0 ${ms % 1000 < 500 ? '0.3' : '1.5'}`);
    }
    const s = loadScenario('bench.scenario', 'bench.scenario', lines.join('\n'), project.index);
    if (s.diagnostics.length) throw new Error(JSON.stringify(s.diagnostics.slice(0, 3)));
    const best = { ms: Infinity, harnessMs: Infinity, events: 0 };
    for (let i = 0; i < 5; i++) {
        const r = await runLoadedScenario(project, s, { quiet: true });
        if (!r.passed) throw new Error(r.error ?? JSON.stringify(r.failures.slice(0, 3)));
        best.ms = Math.min(best.ms, r.ms);
        best.harnessMs = Math.min(best.harnessMs, r.harnessMs);
        best.events = r.eventsProcessed;
    }
    out['simulate.events_per_s'] = Math.round(best.events / (best.harnessMs / 1000));
    out['simulate.sixty_s_ms'] = Math.round(best.ms);
    out['simulate.sixty_s_events'] = best.events;
}

// ---- cold: a changed .contract file -> the first simulated step
{
    const work = mkdtempSync(join(tmpdir(), 'contract-sim-bench-project-'));
    const dir = join(work, 'tutorial');
    cpSync(join(repo, 'examples', 'tutorial'), dir, { recursive: true });
    const scenarioText = readFileSync(join(dir, 'scenarios', 'commutation.scenario'), 'utf8');
    const file = join(dir, 'supervisor.contract');
    const original = readFileSync(file, 'utf8');
    const colds = [];
    const warms = [];
    for (let i = 0; i < 3; i++) {
        // a new local initial value: new tables, new hash, a new harness to build
        writeFileSync(file, original.replace('string temp_mess_type;', `string temp_mess_type = "bench${Date.now()}${i}";`));
        const t0 = performance.now();
        const project = await prepare(dir);
        const s = loadScenario('c.scenario', 'c.scenario', scenarioText, project.index);
        const r = await runLoadedScenario(project, s);
        colds.push(performance.now() - t0);
        if (project.build.cached || !r.steps.length) throw new Error('the cold run found a cached harness or ran nothing');
        const t1 = performance.now();
        const again = await prepare(dir);
        await runLoadedScenario(again, loadScenario('c.scenario', 'c.scenario', scenarioText, again.index));
        warms.push(performance.now() - t1);
    }
    out['simulate.cold_ms'] = Math.round(Math.min(...colds));
    out['simulate.warm_ms'] = Math.round(Math.min(...warms));
    writeFileSync(file, original.replace('string temp_mess_type;', `string temp_mess_type = "cli${Date.now()}";`));
    const t2 = performance.now();
    const cli = spawnSync(process.execPath, [join(repo, 'packages/cli/bin/contract.js'), 'simulate', dir, join(dir, 'scenarios', 'commutation.scenario'), '--cache-dir', cache], { encoding: 'utf8' });
    out['simulate.cli_cold_ms'] = Math.round(performance.now() - t2);
    if (cli.status !== 0) throw new Error(`contract simulate exited ${cli.status}: ${cli.stderr}`);
    rmSync(work, { recursive: true, force: true });
}

rmSync(cache, { recursive: true, force: true });
const parts = join(repo, 'bench', 'parts');
mkdirSync(parts, { recursive: true });
writeFileSync(join(parts, 'simulate.json'), JSON.stringify(out, null, 2) + '\n');
console.log(JSON.stringify(out, null, 2));
