/**
 * A runtime folder copied with its build/ (runtime/README.md, docs/codegen.md "Makefiles") is
 * rebuilt when the architecture's make asks for another compiler or other flags: the runtime's
 * Makefile records them in build/build-config, and every object depends on that file. Nothing is
 * rebuilt when they are the same (make -q says it is up to date).
 */
import { appendFileSync, chmodSync, existsSync, readFileSync, writeFileSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';

const TUTORIAL = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..', 'examples', 'tutorial');
const LIBRARY = ['build/libmodule.a', 'build/contract-launch'];

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
        // a "cross" gcc and ar: the host's, named otherwise, saying what they were asked to do
        calls = join(dir, 'calls.log');
        writeFileSync(calls, '');
        for (const [name, tool] of [['aarch64-test-linux-gcc', 'gcc'], ['aarch64-test-linux-ar', 'ar']] as const) {
            writeFileSync(join(dir, name), `#!/bin/sh\necho "${name} $*" >> '${calls}'\nexec ${tool} "$@"\n`);
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
        expect(readFileSync(join(runtime, 'build', 'build-config'), 'utf8')).toContain(`CC=${join(dir, 'aarch64-test-linux-gcc')}`);

        // incremental: the same make again compiles nothing
        expect(upToDate(...cross)).toBe(true);
        appendFileSync(calls, '--- again\n');
        run('make', ['-j2', '-C', arch, 'MSA', `CONTRACT_RUNTIME=${runtime}`, ...cross]);
        expect(readFileSync(calls, 'utf8').split('--- again\n')[1]).toBe('');
    }, 180_000);

    it('the host compiler, other CFLAGS or WERROR= after it are a rebuild too (make -q says so)', () => {
        expect(upToDate()).toBe(false);
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
