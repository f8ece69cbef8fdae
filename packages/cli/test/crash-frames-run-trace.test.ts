/**
 * A real crash in inlined code told the same by `contract run --verbose` (the service's frames,
 * mapped in the sandbox) and by `contract trace` (the logs' crash file, mapped in the executable
 * beside the logs): one frame formatter (build-service crash-frames.ts), a frame in inlined code as
 * one line `#0 store_bad at FILE:L (inlined into _exec_module_state at FILE:L2)`. The tutorial's MAA
 * stores through a null pointer in an always-inline function of its own, called from its exec
 * region; the same sources are run in the bwrap sandbox through the build service, and built and
 * run on the host with the generated Makefile (`make run`, as on a robot), whose logs folder
 * `contract trace` reads.
 */
import { execFileSync, spawnSync } from 'node:child_process';
import { chmodSync, cpSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { REPO } from './e2e/harness.js';
import { capture } from './capture-io.js';
import { removeScratch } from './scratch.js';
import { seedRuntime } from '@contract-studio/build-service/test-support/runtime-seed';

const hasBwrap = spawnSync('bwrap', ['--ro-bind', '/', '/', 'true']).status === 0;
const MAA_C = 'src-gen/generated/architecture/modules/MAA_mod/module.c';
const DECL = '/*PROTECTED REGION ID(protect_internal_functions_decl_MAA) ENABLED START*/';
const EXEC = '/*PROTECTED REGION ID(protect_exec_MAA) ENABLED START*/';

let root: string;
let project: string;
beforeAll(async () => {
    root = mkdtempSync(join(tmpdir(), 'contract-crash-frames-'));
    chmodSync(root, 0o711);
    process.env.CONTRACT_CACHE_DIR = join(root, 'cache');
    await seedRuntime(join(root, 'cache'));
    project = join(root, 'robot');
    cpSync(join(REPO, 'examples/tutorial'), project, { recursive: true, filter: (src) => !/[/]logs$/.test(src) });
    const c = readFileSync(join(project, MAA_C), 'utf8');
    expect(c).toContain(DECL);
    expect(c).toContain(EXEC);
    writeFileSync(join(project, MAA_C), c
        .replace(DECL, `${DECL}\nstatic double *volatile bad_target;\nstatic inline __attribute__((always_inline)) void store_bad(double v)\n{\n    *bad_target = v; /* the crash */\n}`)
        .replace(EXEC, `${EXEC}\n    { static int calls = 0; if (++calls == 3) store_bad(1.0); /* the call */ }`));
}, 240_000);
afterAll(() => {
    delete process.env.CONTRACT_CACHE_DIR;
    removeScratch(root);
});

describe.skipIf(!hasBwrap)('a crash in inlined code: contract run --verbose and contract trace', () => {
    it('tell the same frames, the inlined place joined to its frame', async () => {
        const lines = readFileSync(join(project, MAA_C), 'utf8').split('\n');
        const crashLine = lines.findIndex((l) => l.includes('/* the crash */')) + 1;
        const callLine = lines.findIndex((l) => l.includes('/* the call */')) + 1;

        const run = capture(root);
        expect(await runCli(['run', 'robot', '--duration', '2s', '--sandbox', 'bwrap', '--verbose'], run)).toBe(1);
        const ran = run.stderr.split('\n').flatMap((l) => /^MAA crash frame (#\d+ .*)$/.exec(l)?.[1] ?? []);

        // the same sources built and run on the host by the generated Makefile: its logs folder has MAA.crash, its executable beside it
        const arch = join(project, 'src-gen/generated/architecture');
        const runtime = join(root, 'runtime');
        execFileSync('cp', ['-a', join(REPO, 'runtime'), runtime]);
        execFileSync('make', ['-s', '-C', arch, `CONTRACT_RUNTIME=${runtime}`], { stdio: 'pipe' });
        expect(spawnSync('make', ['-s', '-C', arch, 'run', `CONTRACT_RUNTIME=${runtime}`, 'DURATION=2'], { stdio: 'pipe', timeout: 60_000 }).status).not.toBe(0);
        const trace = capture(root);
        expect(await runCli(['trace', join(arch, 'logs')], trace)).toBe(0);
        const told = trace.stdout.slice(trace.stdout.indexOf('\ncrash sites (the logs\' crash files):\nMAA crashed: signal 11 (SIGSEGV)'));
        expect(told).toContain('crash sites');
        const traced = told.split('\n').flatMap((l) => /^ {2}(#\d+ .*)$/.exec(l)?.[1] ?? []);

        const inlined = `#0 store_bad at ${MAA_C}:${crashLine} (inlined into _exec_module_state at ${MAA_C}:${callLine})`;
        expect(ran[0]).toBe(inlined);
        expect(ran.filter((f) => f.startsWith('#0 '))).toHaveLength(1);
        expect(ran).toContainEqual(expect.stringMatching(/^#\d+ main at runtime\/src\/module_main\.c:\d+$/));
        // contract trace tells each frame as the run did: the project's files and the runtime's named alike
        expect(traced).toEqual(ran);
    }, 240_000);
});
