/**
 * Builds (or finds) a project's simulator executable with the host's gcc (docs/simulation.md §3,
 * docs/architecture.md "The simulator"): the engine cores and the harness are compiled once in the
 * runtime build (`make -C runtime sim`: build/sim/libcontractsim.a, build/sim/sim_main.o); per
 * project only the generated tables are compiled (-O0, in parallel) and linked. The result is
 * cached under `<build cache>/sim/sim-<hash>/contract-sim` (harness/cache.ts: the cache of
 * `contract build`), the hash covering every source, the harness objects and the compiler: the
 * same project twice builds nothing.
 *
 * Concurrent builds (two `contract simulate`, the IDE's POST /api/simulate, on one project and one
 * cache) are safe: `make` runs under an flock(2) of `<runtime>/build/sim.lock` (two makes would
 * remove and rewrite the same archive under each other's linker), the per-project compile and link
 * under an flock of `<cache>/sim/lock` (the second waits, then finds the first one's executable),
 * and each build is made in a private folder renamed into place, so a reader never sees half an
 * executable. The locks are held by child processes and dropped by the kernel when they exit,
 * even when this process is killed. The cache keeps the `keptSimulators` most recently used
 * simulators (a new key per model simulated).
 */
import { spawn } from 'node:child_process';
import { createHash } from 'node:crypto';
import { existsSync, mkdirSync, readFileSync, renameSync, rmSync, statSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { acquireProjectLock, CACHE_ENTRY_NAMES, markUsed, removeAbandonedBuilds, removeLeastRecentlyUsed, SERVICE_BOUNDS, type ProjectLock } from '@contract-studio/build-service/cache';
import { simulatorCacheDir } from './cache.js';
import type { Confinement } from './confine.js';
import type { SimSources } from './tables.js';
import { compileDiagnostics, describeCompileFailure, linkDiagnostics, withoutFolder, type CompileFailure } from './compile-diagnostics.js';

export interface HarnessBuild {
    exe: string;
    /** True when the executable was already in the cache. */
    cached: boolean;
    ms: number;
}

/** Why no simulator was built; `compile`: the project's C did not compile (its diagnostics at the user's files). */
export interface HarnessBuildError {
    error: string;
    compile?: CompileFailure;
}

export interface BuildOptions {
    /** The runtime source folder (has Makefile, include/, sim/). */
    runtimeDir: string;
    /**
     * The build cache folder (as `contract build --cache-dir`); the simulators go in its `sim/`.
     * Default: `$CONTRACT_CACHE_DIR`, else the XDG cache folder (harness/cache.ts).
     */
    cacheDir?: string;
    cc?: string;
    /**
     * How the project's own code is compiled and linked (harness/confine.ts): the compiler reads
     * what the sources name (`#include "/etc/…"`, `.incbin`), so it sees only the build folder and
     * the runtime. The runtime's own harness objects are built unconfined (trusted sources).
     */
    confinement: Confinement;
    /** Told once when another build holds a lock this one waits for. */
    onWait?: (what: string) => void;
}

const MAX_COMPILER_OUTPUT = 64 * 1024;

function run(cmd: string, args: string[], cwd: string, confined?: { confinement: Confinement; readWrite: string[]; readOnly: string[] }): Promise<{ code: number; output: string }> {
    return new Promise((resolvePromise) => {
        let output = '';
        let child;
        const argv = confined ? confined.confinement.wrap([cmd, ...args], { cwd, readWrite: confined.readWrite, readOnly: confined.readOnly }) : [cmd, ...args];
        try {
            child = spawn(argv[0]!, argv.slice(1), { cwd, stdio: ['ignore', 'pipe', 'pipe'] });
        } catch (e) {
            resolvePromise({ code: -1, output: e instanceof Error ? e.message : String(e) });
            return;
        }
        const add = (d: Buffer) => {
            if (output.length < MAX_COMPILER_OUTPUT) output += d.toString('utf8');
        };
        child.stdout.on('data', add);
        child.stderr.on('data', add);
        child.on('error', (e) => resolvePromise({ code: -1, output: output + e.message }));
        child.on('close', (code) => resolvePromise({ code: code ?? -1, output }));
    });
}

/** The harness objects of the runtime build, made when missing or out of date. */
async function harnessObjects(runtimeDir: string, cc: string): Promise<{ lib: string; main: string } | string> {
    const lib = join(runtimeDir, 'build', 'sim', 'libcontractsim.a');
    const main = join(runtimeDir, 'build', 'sim', 'sim_main.o');
    if (existsSync(join(runtimeDir, 'sim', 'sim.mk'))) {
        // up to date in a few ms; an installed runtime without sources keeps what it has
        const make = ['make', '-s', '-C', runtimeDir, 'sim', `CC=${cc}`];
        const lock = makeLockFile(runtimeDir);
        // flock(1) runs make with the lock held: no process more than make itself on the warm path
        let made = lock ? await run('flock', ['-x', lock, ...make], runtimeDir) : undefined;
        if (!made || made.code === -1) made = await run(make[0]!, make.slice(1), runtimeDir); // no flock(1): make alone
        if (made.code !== 0 && !(existsSync(lib) && existsSync(main))) return `cannot build the simulator's harness in ${runtimeDir}:\n${made.output}`;
    }
    if (!existsSync(lib) || !existsSync(main)) return `no simulator harness in ${runtimeDir}/build/sim (run make -C ${runtimeDir} sim)`;
    return { lib, main };
}

/**
 * The lock file of `make -C runtime sim` (`<runtime>/build/sim.lock`); none when the runtime folder
 * is not writable (an installed runtime: make builds nothing there either).
 */
function makeLockFile(runtimeDir: string): string | undefined {
    const dir = join(runtimeDir, 'build');
    try {
        mkdirSync(dir, { recursive: true });
        return join(dir, 'sim.lock');
    } catch {
        return undefined;
    }
}

let compilerId: string | undefined;
async function compilerIdentity(cc: string): Promise<string> {
    if (compilerId === undefined) compilerId = (await run(cc, ['--version'], tmpdir())).output.split('\n')[0] ?? cc;
    return compilerId;
}

export async function buildHarness(src: SimSources, options: BuildOptions): Promise<HarnessBuild | HarnessBuildError> {
    const t0 = performance.now();
    const cc = options.cc ?? process.env.CC ?? 'gcc';
    const onWait = options.onWait ?? (() => undefined);
    const cache = simulatorCacheDir(options.cacheDir);
    if ('error' in cache) return { error: cache.error };
    const objects = await harnessObjects(options.runtimeDir, cc);
    if (typeof objects === 'string') return { error: objects };
    const hash = createHash('sha256');
    hash.update(await compilerIdentity(cc)).update('\0');
    for (const f of [objects.lib, objects.main]) {
        const st = statSync(f);
        hash.update(f).update(`\0${st.size}\0${st.mtimeMs}\0`);
    }
    hash.update(options.runtimeDir).update('\0');
    for (const f of src.files) hash.update(f.path).update('\0').update(f.content).update('\0');
    const key = hash.digest('hex').slice(0, 20);
    const dir = join(cache.dir, `sim-${key}`);
    const exe = join(dir, 'contract-sim');
    // a simulator found built: marked used (the cache's bound keeps the recently used)
    const found = async (): Promise<HarnessBuild | undefined> => {
        if (!existsSync(exe)) return undefined;
        await markUsed(dir);
        return { exe, cached: true, ms: performance.now() - t0 };
    };
    const built = await found();
    if (built) return built;

    let lock: ProjectLock;
    try {
        lock = await acquireProjectLock(join(cache.dir, 'lock'), (holder) => onWait(`another simulator build in ${cache.dir} (${holder})`));
    } catch (e) {
        return { error: (e as Error).message };
    }
    try {
        // the build we waited for may have made this very executable
        const waited = await found();
        if (waited) return waited;
        await removeAbandonedBuilds(cache.dir, SIM_BUILDING);
        // a new simulator per model simulated: the least recently used beyond the bound go
        await removeLeastRecentlyUsed(cache.dir, CACHE_ENTRY_NAMES.sim, SERVICE_BOUNDS.keptSimulators - 1);
        return await compileAndLink(src, { cc, runtimeDir: options.runtimeDir, objects, key, dir, exe, t0, confinement: options.confinement });
    } finally {
        await lock.release();
    }
}

/** `sim-<key>.tmp-<pid>-<random>`: a harness being compiled by process pid (compileAndLink); one a
 *  killed build left is removed by the next build. */
export const SIM_BUILDING = /^sim-[0-9a-f]{20}\.tmp-(\d{1,10})-[0-9a-z]+$/;

interface CompileJob {
    cc: string;
    runtimeDir: string;
    objects: { lib: string; main: string };
    key: string;
    /** The cache entry `sim-<key>` and its executable. */
    dir: string;
    exe: string;
    t0: number;
    confinement: Confinement;
}

async function compileAndLink(src: SimSources, { cc, runtimeDir, objects, key, dir, exe, t0, confinement }: CompileJob): Promise<HarnessBuild | HarnessBuildError> {
    const work = `${dir}.tmp-${process.pid}-${Math.random().toString(36).slice(2)}`;
    mkdirSync(work, { recursive: true, mode: 0o700 });
    try {
        for (const f of src.files) {
            const p = join(work, f.path);
            mkdirSync(dirname(p), { recursive: true });
            writeFileSync(p, f.content, 'latin1');
        }
        const include = join(runtimeDir, 'include');
        // the project's C is compiled seeing only its build folder and the runtime (and the toolchain)
        const confined = { confinement, readWrite: [work], readOnly: [include, dirname(objects.lib), dirname(objects.main)] };
        const compiles = src.units.map((unit, i) => run(cc, [
            // -g1: line tables only, so that a link error names the user's file and line; DWARF 4,
            // whose line table binutils 2.40's ld reads right for a function of a header (with
            // DWARF 5 it names the unit that includes it)
            '-std=c11', '-O0', '-w', '-g1', '-gdwarf-4', '-D_POSIX_C_SOURCE=200809L', `-I${include}`,
            ...(src.includes.get(unit) ?? []).map((d) => `-I${join(work, d)}`),
            '-c', join(work, unit), '-o', join(work, `unit${i}.o`),
        ], work, confined));
        const results = await Promise.all(compiles);
        const failed = results.filter((r) => r.code !== 0);
        if (failed.length) {
            // told at the user's src-gen files, never at this temporary folder (harness/compile-diagnostics.ts)
            const compile = compileDiagnostics(failed.map((r) => r.output), work, src);
            return { error: describeCompileFailure(compile), compile };
        }
        const link = await run(cc, ['-o', join(work, 'contract-sim'), ...src.units.map((_, i) => join(work, `unit${i}.o`)), objects.main, objects.lib, '-lm'], work, confined);
        if (link.code !== 0) {
            // a function the user's code calls that nobody defines: at the user's file, line and region
            const failure = linkDiagnostics(link.output, work, src);
            if (failure.diagnostics.length) return { error: describeCompileFailure(failure), compile: failure };
            return { error: `cannot link the simulator:\n${withoutFolder(link.output, work)}` };
        }
        writeFileSync(join(work, 'key'), key);
        try {
            renameSync(work, dir);
        } catch {
            // a build that does not take the lock (an older version) stored the same key first: use theirs
            if (!existsSync(exe)) return { error: `cannot store the simulator in ${dir}` };
        }
        return { exe, cached: false, ms: performance.now() - t0 };
    } finally {
        rmSync(work, { recursive: true, force: true });
    }
}

/** The key file of a built harness (tests). */
export function harnessKey(exe: string): string {
    return readFileSync(join(dirname(exe), 'key'), 'utf8');
}
