/**
 * The simulator runs the project's own C (the user functions of the datatype files), so it runs
 * it confined (harness/confine.ts, docs/simulation.md "What runs where"): a function that reads a
 * host file or writes outside its folder finds nothing there, and a header that includes a host
 * file does not compile, with nothing of that file in the message. The same project with
 * `sandbox: 'none'` does reach the host (the test would see a confinement that does nothing).
 */
import { cpSync, existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { DEFAULT_RUNTIME_DIR, loadScenario, prepareProject, readScenarioFile, runLoadedScenario, type SimulatorSandboxChoice } from '../src/index.js';
import { CACHE, TUTORIAL } from './support.js';

const scratch = mkdtempSync(join(tmpdir(), 'contract-sim-confine-'));
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

const HEADERS = join('src-gen', 'generated', 'architecture', 'common');
const SECRET = join(scratch, 'host-secret.txt');
writeFileSync(SECRET, 'HOST-SECRET-CONTENT\n', { mode: 0o644 });

/** A copy of the tutorial whose `testit` and `doit` reach for the host when called. */
function hostileCopy(name: string, body: string): string {
    const dir = join(scratch, name);
    cpSync(TUTORIAL, dir, { recursive: true });
    for (const fn of ['testit', 'doit']) {
        const header = join(dir, HEADERS, `SharedFunction${fn}.h`);
        const text = readFileSync(header, 'utf8');
        const start = text.indexOf(`ID(protect_function_impl_${fn}) ENABLED START*/`);
        expect(start).toBeGreaterThan(0);
        const at = text.indexOf('\n', start) + 1;
        writeFileSync(header, text.slice(0, at) + body.replaceAll('FN', fn) + '\n' + text.slice(at));
    }
    return dir;
}

const reachHost = `{ FILE *in_ = fopen(${JSON.stringify(SECRET)}, "r"); if (in_) { char b_[64] = {0}; if (fgets(b_, sizeof b_, in_)) printf("READ %s", b_); fclose(in_); }
  FILE *out_ = fopen(${JSON.stringify(join(scratch, 'written-by-FN'))}, "w"); if (out_) { fputs("x", out_); fclose(out_); } }`;

async function simulate(dir: string, sandbox: SimulatorSandboxChoice) {
    const p = await prepareProject(dir, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir: CACHE, sandbox });
    if (!('build' in p)) return { problems: p };
    const file = join(dir, 'scenarios', 'commutation.scenario');
    const text = readScenarioFile(file);
    if (typeof text !== 'string') throw new Error(text.error);
    const s = loadScenario(file, 'commutation.scenario', text, p.index);
    const result = await runLoadedScenario(p, s);
    return { p, result, output: result.steps.map((st) => st.record.output ?? "").join("") };
}

describe('the simulator confines the project\'s C', () => {
    it('a user function cannot read host files nor write outside; unconfined it can', async () => {
        const dir = hostileCopy('reach', reachHost);
        const confined = await simulate(dir, 'bwrap');
        if (!('result' in confined) || !confined.result) throw new Error(JSON.stringify(confined.problems));
        expect(confined.p.confinement.kind).toBe('bwrap');
        expect(confined.result.error).toBeUndefined();
        expect(confined.output).toMatch(/testit\(|doit\(/); // the functions did run, confined
        expect(confined.output).not.toContain('HOST-SECRET');
        expect(existsSync(join(scratch, 'written-by-testit'))).toBe(false);
        expect(existsSync(join(scratch, 'written-by-doit'))).toBe(false);

        const open = await simulate(dir, 'none');
        if (!('result' in open) || !open.result) throw new Error(JSON.stringify(open.problems));
        expect(open.output).toContain('READ HOST-SECRET-CONTENT');
        expect(existsSync(join(scratch, 'written-by-testit')) || existsSync(join(scratch, 'written-by-doit'))).toBe(true);
    }, 120_000);

    it('a header including a host file does not compile, and the message holds nothing of the file', async () => {
        const dir = hostileCopy('include', `#include ${JSON.stringify(SECRET)}`);
        const confined = await simulate(dir, 'bwrap');
        expect('problems' in confined && confined.problems?.buildError).toMatch(/cannot compile .* for the simulator/);
        expect(JSON.stringify(confined)).not.toContain('HOST-SECRET');
    }, 120_000);
});
