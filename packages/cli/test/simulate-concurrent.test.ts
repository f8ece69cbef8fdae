/**
 * Two `contract simulate` processes at once on one project, one runtime folder and one build
 * cache, all cold (the runtime's harness objects not built, no simulator in the cache): both
 * succeed with the same records, one simulator ends up in the cache and no build folder is left
 * behind. What makes it safe (packages/simulator/src/harness/build.ts): `make -C runtime sim` under
 * `<runtime>/build/sim.lock`, the project's compile and link under `<cache>/sim/lock`, each build
 * made in a private folder renamed into place.
 */
import { spawn } from 'node:child_process';
import { cpSync, existsSync, mkdtempSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, describe, expect, it } from 'vitest';

const REPO = fileURLToPath(new URL('../../../', import.meta.url));
const TUTORIAL = join(REPO, 'examples', 'tutorial');
const scratch = mkdtempSync(join(tmpdir(), 'contract-simulate-concurrent-'));
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

function simulate(runtime: string, cache: string): Promise<{ code: number | null; stdout: string; stderr: string }> {
    return new Promise((resolvePromise) => {
        const child = spawn(process.execPath, [
            join(REPO, 'packages/cli/bin/contract.js'), 'simulate', TUTORIAL,
            join(TUTORIAL, 'scenarios', 'commutation.scenario'), join(TUTORIAL, 'scenarios', 'mission.scenario'),
            '--runtime', runtime, '--cache-dir', cache, '--format', 'json',
        ], { cwd: scratch, stdio: ['ignore', 'pipe', 'pipe'] });
        let stdout = '';
        let stderr = '';
        child.stdout.on('data', (d: Buffer) => (stdout += d.toString('utf8')));
        child.stderr.on('data', (d: Buffer) => (stderr += d.toString('utf8')));
        child.on('close', (code) => resolvePromise({ code, stdout, stderr }));
    });
}

/** The report without its wall times (`ms`, `wallNs`): what the engines decided. */
const decisions = (json: string): unknown => JSON.parse(json, (key, value: unknown) => (key === 'ms' || key === 'wallNs' ? undefined : value));

describe('contract simulate, twice at once on a cold cache', () => {
    it('both succeed with identical records; one simulator in the cache, no half-built folder left', async () => {
        // a runtime folder of its own, without build/: both processes find the harness objects missing
        const runtime = join(scratch, 'runtime');
        const built = join(REPO, 'runtime', 'build'); // the folder, not build-config.mk beside it
        cpSync(join(REPO, 'runtime'), runtime, { recursive: true, filter: (src) => src !== built && !src.startsWith(`${built}/`) });
        const cache = join(scratch, 'cache');
        const [a, b] = await Promise.all([simulate(runtime, cache), simulate(runtime, cache)]);
        expect(a.code, a.stderr).toBe(0);
        expect(b.code, b.stderr).toBe(0);
        const recordsA = decisions(a.stdout) as { scenarios: Array<{ passed: boolean; steps: unknown[] }> };
        expect(recordsA.scenarios.map((s) => s.passed)).toEqual([true, true]);
        expect(recordsA.scenarios[0]!.steps.length).toBeGreaterThan(10);
        expect(decisions(b.stdout)).toEqual(recordsA);

        const entries = readdirSync(join(cache, 'sim'));
        expect(entries.filter((n) => n.startsWith('sim-'))).toHaveLength(1);
        expect(entries.filter((n) => n.includes('.tmp-'))).toEqual([]);
        expect(existsSync(join(runtime, 'build', 'sim', 'libcontractsim.a'))).toBe(true);
    }, 240_000);
});
