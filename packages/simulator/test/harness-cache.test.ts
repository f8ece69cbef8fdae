/**
 * Where the simulators are kept and how their builds are locked (docs/simulation.md §3): in `sim/`
 * of the build cache, each under `sim-<hash>/`; two builds of one project on a cold cache at once
 * compile it once (the second waits for the lock, then finds the first one's executable); a link
 * planted in place of `sim/` is refused with the build cache's sentence, nothing executed; the
 * folder of a build that was killed (SIGKILL) is removed by the next build.
 */
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, rmSync, symlinkSync, utimesSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
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
