#!/usr/bin/env node
/**
 * Records the steps the Monitor's simulation tests fold, each a scenario of examples/tutorial
 * simulated by the current simulator and answered as POST /api/simulate answers it
 * (server/simulate-api.ts stepOf):
 * - src/simulate/fixtures/tutorial-mission-steps.json: the tutorial's scenarios/mission.scenario
 *   (src/simulate/simulation-in-monitor.test.ts, simulation-model.test.ts);
 * - src/simulate/fixtures/tutorial-flows-steps.json: src/monitor/fixtures/simulated-flows/flows.scenario,
 *   whose trace file is that folder's flows.jsonl (src/simulate/simulation-model.test.ts).
 * Run it again after a change of the simulator, the harness's records or the scenarios, from the
 * repository's root:
 *
 *     npm run build:server -w packages/web-ide && node packages/web-ide/scripts/record-mission-steps.mjs
 *
 * The harness is compiled in a temporary build cache, removed at the end. Exits 1 and writes
 * nothing more when a scenario does not pass.
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { DEFAULT_RUNTIME_DIR, loadScenario, prepareProject, readScenarioFile, runLoadedScenario } from '@contract-studio/simulator';
import { MAX_ITEMS_PER_ANSWER, stepOf } from '../dist-server/simulate-api.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial/', import.meta.url));
const fixture = (name) => fileURLToPath(new URL(`../src/simulate/fixtures/${name}`, import.meta.url));
/** Each scenario (its path, and its name as the steps' file names it) and the fixture its steps are written to. */
const RECORDED = [
    { path: join(TUTORIAL, 'scenarios/mission.scenario'), name: 'scenarios/mission.scenario', fixture: 'tutorial-mission-steps.json' },
    { path: fileURLToPath(new URL('../src/monitor/fixtures/simulated-flows/flows.scenario', import.meta.url)), name: 'flows.scenario', fixture: 'tutorial-flows-steps.json' },
];

const cache = mkdtempSync(join(tmpdir(), 'contract-mission-steps-'));
try {
    const project = await prepareProject(TUTORIAL, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir: cache });
    if (!('build' in project)) throw new Error(`cannot prepare examples/tutorial: ${project.buildError ?? project.sandboxError ?? project.modelErrors.map((d) => d.message).join('; ')}`);
    for (const { path, name, fixture: file } of RECORDED) {
        const text = readScenarioFile(path);
        if (typeof text !== 'string') throw new Error(`${name}: ${text.error}`);
        const scenario = loadScenario(path, name, text, project.index);
        if (scenario.diagnostics.some((d) => d.severity === 'error')) throw new Error(`${name}: ${scenario.diagnostics.map((d) => `${d.line}:${d.column} ${d.message}`).join('; ')}`);
        const r = await runLoadedScenario(project, scenario);
        if (r.error || !r.passed) throw new Error(`${name} did not pass: ${r.error ?? r.failures.map((f) => `line ${f.line}: ${f.message}`).join('; ')}`);
        const budget = { left: MAX_ITEMS_PER_ANSWER };
        const steps = r.steps.map((s) => stepOf(s, budget));
        writeFileSync(fixture(file), JSON.stringify(steps, null, 1) + '\n');
        process.stdout.write(`${steps.length} steps of ${name} written to src/simulate/fixtures/${file}\n`);
    }
} catch (e) {
    process.stderr.write(`record-mission-steps: ${e instanceof Error ? e.message : String(e)}\n`);
    process.exitCode = 1;
} finally {
    rmSync(cache, { recursive: true, force: true });
}
