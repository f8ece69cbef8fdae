/**
 * Where the simulators are kept and how their builds are locked (docs/simulation.md §3): in `sim/`
 * of the build cache, each under `sim-<hash>/`; two builds of one project on a cold cache at once
 * compile it once (the second waits for the lock, then finds the first one's executable); a link
 * planted in place of `sim/` is refused with the build cache's sentence, nothing executed; the
 * folder of a build that was killed (SIGKILL) is removed by the next build; the cache keeps the most
 * recently used simulators only.
 */
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, rmSync, statSync, symlinkSync, utimesSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { SERVICE_BOUNDS } from '@contract-studio/build-service/cache';
import { afterAll, describe, expect, it } from 'vitest';
import { DEFAULT_RUNTIME_DIR, harnessKey, prepareProject, simulatorCacheDir } from '../src/index.js';
import { TUTORIAL } from './support.js';

const scratch = mkdtempSync(join(tmpdir(), 'contract-sim-cache-'));
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

describe('the simulators in the build cache', () => {
    it('two builds of one project at once on a cold cache: one compiles, the other waits and reuses it', async () => {
        const cacheDir = join(scratch, 'cold');
        const [a, b] = await Promise.all([1, 2].map(() => prepareProject(TUTORIAL, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir })));
        if (!a || !b || !('build' in a) || !('build' in b)) throw new Error(`not built: ${JSON.stringify([a, b].map((p) => p && !('build' in p) ? p : 'ok'))}`);
        expect([a.build.cached, b.build.cached].sort()).toEqual([false, true]);
        expect(a.build.exe).toBe(b.build.exe);
        expect(harnessKey(a.build.exe)).toBe(harnessKey(b.build.exe));
        expect(a.build.exe.startsWith(join(cacheDir, 'sim', 'sim-'))).toBe(true);
        expect(readdirSync(join(cacheDir, 'sim')).filter((n) => n.startsWith('sim-'))).toHaveLength(1);
    });

    it('the folder a killed build left (sim-<key>.tmp-<pid>-...) is removed by the next build', async () => {
        const cacheDir = join(scratch, 'killed');
        mkdirSync(join(cacheDir, 'sim'), { recursive: true, mode: 0o700 });
        const dead = spawnSync('true').pid!;
        const left = join(cacheDir, 'sim', `sim-0123456789abcdef0123.tmp-${dead}-k1lled`);
        mkdirSync(left);
        writeFileSync(join(left, 'unit0.o'), 'half a build');
        const old = (Date.now() - 20 * 60_000) / 1000;
        utimesSync(left, old, old);
        const p = await prepareProject(TUTORIAL, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir });
        if (!p || !('build' in p)) throw new Error(`not built: ${JSON.stringify(p)}`);
        expect(p.build.cached).toBe(false);
        expect(existsSync(left)).toBe(false);
        expect(readdirSync(join(cacheDir, 'sim')).filter((n) => n.includes('.tmp-'))).toEqual([]);
    });

    it('keeps the keptSimulators most recently used: a new build removes the least recently used beyond it; a hit marks its simulator used', async () => {
        const cacheDir = join(scratch, 'bounded');
        const sim = join(cacheDir, 'sim');
        mkdirSync(sim, { recursive: true, mode: 0o700 });
        const kept = SERVICE_BOUNDS.keptSimulators;
        // kept + 1 simulators of earlier models, the first two last used 3 and 2 days ago, the others 1 day ago
        const names = Array.from({ length: kept + 1 }, (_, i) => `sim-${String(i).padStart(20, '0')}`);
        names.forEach((n, i) => {
            mkdirSync(join(sim, n));
            writeFileSync(join(sim, n, 'contract-sim'), 'an earlier model');
            const used = (Date.now() - (i === 0 ? 3 : i === 1 ? 2 : 1) * 86_400_000 + i * 1000) / 1000;
            utimesSync(join(sim, n), used, used);
        });
        const built = await prepareProject(TUTORIAL, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir });
        if (!built || !('build' in built)) throw new Error(`not built: ${JSON.stringify(built)}`);
        expect(built.build.cached).toBe(false);
        const left = readdirSync(sim).filter((n) => /^sim-[0-9a-f]{20}$/.test(n));
        // kept - 1 old ones stay, plus the new one: the two least recently used went
        expect(names.filter((n) => !left.includes(n))).toEqual([names[0], names[1]]);
        expect(left).toHaveLength(kept);
        // a hit marks the simulator used: it is now the most recent
        const stamp = (Date.now() - 5 * 86_400_000) / 1000;
        utimesSync(dirname(built.build.exe), stamp, stamp);
        const again = await prepareProject(TUTORIAL, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir });
        if (!again || !('build' in again)) throw new Error(`not built: ${JSON.stringify(again)}`);
        expect(again.build.cached).toBe(true);
        expect(Date.now() - statSync(dirname(built.build.exe)).mtimeMs).toBeLessThan(60_000);
    });

    it('refuses a link planted in place of sim/ (nothing built or executed there)', async () => {
        const cacheDir = join(scratch, 'planted');
        mkdirSync(cacheDir, { mode: 0o700 });
        mkdirSync(join(scratch, 'elsewhere'));
        symlinkSync(join(scratch, 'elsewhere'), join(cacheDir, 'sim'));
        expect(simulatorCacheDir(cacheDir)).toEqual({ error: expect.stringMatching(/sim is a symbolic link \(planted\?\)/) });
        const p = await prepareProject(TUTORIAL, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir });
        expect(p).toMatchObject({ buildError: expect.stringMatching(/sim is a symbolic link/) });
        expect(readdirSync(join(scratch, 'elsewhere'))).toEqual([]);
    });
});
