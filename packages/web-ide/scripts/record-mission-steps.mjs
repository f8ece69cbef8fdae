#!/usr/bin/env node
/**
 * Records src/simulate/fixtures/tutorial-mission-steps.json, the steps the Monitor's simulation
 * tests fold (src/simulate/simulation-in-monitor.test.ts): examples/tutorial's
 * scenarios/mission.scenario simulated by the current simulator and answered as POST /api/simulate
 * answers it (server/simulate-api.ts stepOf). Run it again after a change of the simulator, the
 * harness's records or the scenario, from the repository's root:
 *
 *     npm run build:server -w packages/web-ide && node packages/web-ide/scripts/record-mission-steps.mjs
 *
 * The harness is compiled in a temporary build cache, removed at the end. Exits 1 and writes
 * nothing when the scenario does not pass.
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { DEFAULT_RUNTIME_DIR, loadScenario, prepareProject, readScenarioFile, runLoadedScenario } from '@contract-studio/simulator';
import { MAX_ITEMS_PER_ANSWER, stepOf } from '../dist-server/simulate-api.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial/', import.meta.url));
const SCENARIO = 'scenarios/mission.scenario';
const FIXTURE = fileURLToPath(new URL('../src/simulate/fixtures/tutorial-mission-steps.json', import.meta.url));

const cache = mkdtempSync(join(tmpdir(), 'contract-mission-steps-'));
try {
    const project = await prepareProject(TUTORIAL, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir: cache });
    if (!('build' in project)) throw new Error(`cannot prepare examples/tutorial: ${project.buildError ?? project.sandboxError ?? project.modelErrors.map((d) => d.message).join('; ')}`);
    const text = readScenarioFile(join(TUTORIAL, SCENARIO));
    if (typeof text !== 'string') throw new Error(`${SCENARIO}: ${text.error}`);
    const scenario = loadScenario(join(TUTORIAL, SCENARIO), SCENARIO, text, project.index);
    if (scenario.diagnostics.some((d) => d.severity === 'error')) throw new Error(`${SCENARIO}: ${scenario.diagnostics.map((d) => `${d.line}:${d.column} ${d.message}`).join('; ')}`);
    const r = await runLoadedScenario(project, scenario);
    if (r.error || !r.passed) throw new Error(`${SCENARIO} did not pass: ${r.error ?? r.failures.map((f) => `line ${f.line}: ${f.message}`).join('; ')}`);
    const budget = { left: MAX_ITEMS_PER_ANSWER };
    const steps = r.steps.map((s) => stepOf(s, budget));
    writeFileSync(FIXTURE, JSON.stringify(steps, null, 1) + '\n');
    process.stdout.write(`${steps.length} steps of ${SCENARIO} written to src/simulate/fixtures/tutorial-mission-steps.json\n`);
} catch (e) {
    process.stderr.write(`record-mission-steps: ${e instanceof Error ? e.message : String(e)}\n`);
    process.exitCode = 1;
} finally {
    rmSync(cache, { recursive: true, force: true });
}
