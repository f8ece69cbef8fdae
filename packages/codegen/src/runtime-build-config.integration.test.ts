/**
 * A runtime folder copied with its build/ (runtime/README.md, docs/codegen.md "Makefiles") is
 * rebuilt when the architecture's make asks for another compiler or other flags: the runtime's
 * Makefile records them in build/build-config, and every object depends on that file. Nothing is
 * rebuilt when they are the same (make -q says it is up to date).
 */
import { appendFileSync, chmodSync, existsSync, mkdirSync, readFileSync, renameSync, writeFileSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';

const TUTORIAL = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..', 'examples', 'tutorial');
const LIBRARY = ['build/libmodule.a', 'build/contract-launch'];
/** A line of make's output that runs a compiler or an archiver (make -n prints them too). */
const COMPILER_LINE = /^(\S*\/)?(gcc|cc|ar|aarch64-test-linux-gcc|aarch64-test-linux-ar) /m;

describe('a copied runtime with its build/ and another toolchain', () => {
    let dir: string;
    let cleanup: () => void;
    let runtime: string;
    let arch: string;
    let calls: string;
    let cross: string[];
    beforeAll(() => {
        ({ dir, cleanup } = tempDir('codegen-rt-config-'));
        ensureRuntimeLibrary();
        // what a tester copies to the robot's build machine: the sources and the host's build/ (times kept)
        runtime = join(dir, 'runtime');
        run('cp', ['-a', RUNTIME_DIR, runtime]);
        run('cp', ['-a', join(TUTORIAL, 'src-gen'), join(dir, 'src-gen')]);
        arch = join(dir, 'src-gen', 'generated', 'architecture');
        // a "cross" gcc and ar: the host's, named otherwise, saying what they were asked to do; the
        // gcc says it is for another machine (-dumpmachine), as a cross gcc does
        calls = join(dir, 'calls.log');
        writeFileSync(calls, '');
        for (const [name, tool] of [['aarch64-test-linux-gcc', 'gcc'], ['aarch64-test-linux-ar', 'ar']] as const) {
            const target = tool === 'gcc' ? 'case "$1" in -dumpmachine) echo aarch64-test-linux-gnu; exit 0;; -dump*) exec gcc "$@";; esac\n' : '';
            writeFileSync(join(dir, name), `#!/bin/sh\n${target}echo "${name} $*" >> '${calls}'\nexec ${tool} "$@"\n`);
            chmodSync(join(dir, name), 0o755);
        }
        cross = [`CC=${join(dir, 'aarch64-test-linux-gcc')}`, `AR=${join(dir, 'aarch64-test-linux-ar')}`];
    }, 120_000);
    afterAll(() => cleanup());

    /** `make -q` on the runtime's library and launcher: true when make would build nothing. */
    const upToDate = (...vars: string[]): boolean => {
        const r = spawnSync('make', ['-q', '-C', runtime, ...LIBRARY, ...vars], { encoding: 'utf8' });
        return r.status === 0;
    };

    it('the copy is up to date for the toolchain that built it', () => {
        expect(existsSync(join(runtime, 'build', 'build-config'))).toBe(true);
        expect(upToDate()).toBe(true);
    });

    it('make -C architecture with CC/AR of a cross gcc rebuilds the runtime with them, once', () => {
        const out = run('make', ['-j2', '-C', arch, 'MSA', `CONTRACT_RUNTIME=${runtime}`, ...cross]);
        expect(out).not.toContain("'build/libmodule.a' is up to date");
        const log = readFileSync(calls, 'utf8');
        expect(log).toMatch(/aarch64-test-linux-gcc .* -c src\/core\.c -o build\/obj\/core\.o/);
        expect(log).toMatch(/aarch64-test-linux-ar rcs build\/libmodule\.a /);
        const record = readFileSync(join(runtime, 'build', 'build-config'), 'utf8');
        expect(record).toContain(`BUILT_CC := ${join(dir, 'aarch64-test-linux-gcc')}`);
        expect(record).toContain('BUILT_TARGET := aarch64-test-linux-gnu');

        // incremental: the same make again compiles nothing
        expect(upToDate(...cross)).toBe(true);
        appendFileSync(calls, '--- again\n');
        run('make', ['-j2', '-C', arch, 'MSA', `CONTRACT_RUNTIME=${runtime}`, ...cross]);
        expect(readFileSync(calls, 'utf8').split('--- again\n')[1]).toBe('');
    }, 180_000);

    it('copied (times kept) to a robot without the cross gcc, the built tree builds nothing: make all and make -n run name no compiler, build-config is kept', () => {
        run('make', ['-j2', '-C', arch, 'all', `CONTRACT_RUNTIME=${runtime}`, ...cross]);
        const robot = join(dir, 'robot');
        mkdirSync(robot);
        run('cp', ['-a', runtime, join(robot, 'contract-runtime')]);
        run('cp', ['-a', join(dir, 'src-gen'), join(robot, 'src-gen')]);
        const robotRuntime = join(robot, 'contract-runtime');
        const robotArch = join(robot, 'src-gen', 'generated', 'architecture');
        const record = readFileSync(join(robotRuntime, 'build', 'build-config'), 'utf8');
        // the robot has no aarch64-test-linux-gcc (nor ar): the record's compiler cannot be run there
        for (const tool of ['aarch64-test-linux-gcc', 'aarch64-test-linux-ar']) renameSync(join(dir, tool), join(dir, `${tool}.away`));
        try {
            const dry = run('make', ['-n', '-C', robotArch, 'run', `CONTRACT_RUNTIME=${robotRuntime}`]);
            expect(dry).not.toMatch(COMPILER_LINE);
            const built = run('make', ['-C', robotArch, 'all', `CONTRACT_RUNTIME=${robotRuntime}`]);
            expect(built).not.toMatch(COMPILER_LINE);
            expect(built).not.toContain('rebuilding');
            expect(readFileSync(join(robotRuntime, 'build', 'build-config'), 'utf8')).toBe(record);
        } finally {
            for (const tool of ['aarch64-test-linux-gcc', 'aarch64-test-linux-ar']) renameSync(join(dir, `${tool}.away`), join(dir, tool));
        }
    }, 180_000);

    it('installed (make install PREFIX=), the cross-built runtime refuses another compiler with a make error naming both; none given, the modules take its own', () => {
        const installed = join(dir, 'installed');
        run('make', ['-s', '-C', runtime, 'install', `PREFIX=${installed}`]);
        const host = spawnSync('make', ['-C', arch, 'MSA', `CONTRACT_RUNTIME=${installed}`, 'CC=gcc'], { encoding: 'utf8' });
        expect(host.status).not.toBe(0);
        expect(host.stderr).toContain(`the runtime installed in ${installed} was built with CC=${join(dir, 'aarch64-test-linux-gcc')} (target aarch64-test-linux-gnu`);
        expect(host.stderr).toMatch(/not CC=gcc \(target x86_64[^)]*\): its build\/libmodule\.a does not link with that compiler/);
        expect(host.stderr).not.toContain('file in wrong format');
        appendFileSync(calls, '--- installed\n');
        run('make', ['-B', '-C', join(arch, 'modules', 'MSA_mod'), `CONTRACT_RUNTIME=${installed}`]);
        expect(readFileSync(calls, 'utf8').split('--- installed\n')[1]).toMatch(/^aarch64-test-linux-gcc .* -o MSA /m);
    }, 180_000);

    it('the host compiler, other CFLAGS or WERROR= after it are a rebuild too (make -q says so); none given, the record\'s are taken', () => {
        expect(upToDate()).toBe(true);
        expect(upToDate('CC=gcc', 'AR=ar')).toBe(false);
        expect(upToDate(...cross, 'CFLAGS=-O1')).toBe(false);
        expect(upToDate(...cross, 'WERROR=')).toBe(false);
        expect(upToDate(...cross)).toBe(true);
    });

    it('-Werror is the default (the tests\' too) and WERROR= lifts it: a gcc that warns (here -Wconversion) still builds the runtime', () => {
        const tests = run('make', ['-n', '-B', '-C', runtime, 'build/tests/runner']);
        expect(tests).toMatch(/-Wall -Wextra -Werror .* -o build\/tests\/runner/);
        const strict = spawnSync('make', ['-C', runtime, 'build/libmodule.a', 'CFLAGS=-O0 -Wconversion'], { encoding: 'utf8' });
        expect(strict.status).not.toBe(0);
        expect(strict.stderr).toMatch(/error: .* \[-Werror=[a-z-]*conversion\]/);
        const lax = run('make', ['-j2', '-C', runtime, 'build/libmodule.a', 'CFLAGS=-O0 -Wconversion', 'WERROR=']);
        expect(lax).not.toContain('-Werror');
        expect(lax).toMatch(/-O0 -Wconversion .*-c src\/core\.c/);
    }, 180_000);
});

describe('a copied runtime with its build/ on a machine whose gcc is for another target', () => {
    let dir: string;
    let cleanup: () => void;
    let runtime: string;
    let path: string;
    beforeAll(() => {
        ({ dir, cleanup } = tempDir('codegen-rt-target-'));
        ensureRuntimeLibrary();
        runtime = join(dir, 'runtime');
        run('cp', ['-a', RUNTIME_DIR, runtime]);
        // a native ARM robot's gcc: the same name, another target (here the host's gcc, saying so)
        const bin = join(dir, 'bin');
        mkdirSync(bin);
        writeFileSync(join(bin, 'gcc'), '#!/bin/sh\nif [ "$1" = -dumpmachine ]; then echo aarch64-linux-gnu; exit 0; fi\nexec /usr/bin/gcc "$@"\n');
        chmodSync(join(bin, 'gcc'), 0o755);
        path = `${bin}:${process.env.PATH ?? ''}`;
    }, 120_000);
    afterAll(() => cleanup());

    const upToDate = (env: NodeJS.ProcessEnv, ...vars: string[]): boolean =>
        spawnSync('make', ['-q', '-C', runtime, ...LIBRARY, ...vars], { encoding: 'utf8', env }).status === 0;

    it('is rebuilt, given CC=gcc or not (build-config records the compiler\'s target: gcc -dumpmachine)', () => {
        expect(upToDate(process.env)).toBe(true);
        expect(upToDate({ ...process.env, PATH: path })).toBe(false);
        expect(upToDate({ ...process.env, PATH: path }, 'CC=gcc')).toBe(false);
        const out = run('env', [`PATH=${path}`, 'make', '-s', '-C', runtime, ...LIBRARY]);
        expect(out).toMatch(/runtime: compiler or flags other than build\/build-config's: rebuilding build with CC=gcc .*TARGET=aarch64-linux-gnu/);
        expect(upToDate({ ...process.env, PATH: path })).toBe(true);
        expect(readFileSync(join(runtime, 'build', 'build-config'), 'utf8')).toMatch(/^BUILT_TARGET := aarch64-linux-gnu$/m);
    }, 180_000);
});
