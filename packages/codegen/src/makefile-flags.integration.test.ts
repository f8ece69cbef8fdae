/**
 * The flags of the generated Makefiles (docs/codegen.md, "Makefiles"): what the generated C needs
 * (C11, POSIX 2008, the runtime's and the tree's include folders, the runtime library) is given
 * whatever CFLAGS, CPPFLAGS or LDLIBS make's command line sets; CFLAGS replaces the optimisation,
 * debug and warning flags (-Wall -Wextra -O2 -g), EXTRA_CFLAGS adds to them.
 */
import { cpSync, readdirSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadWorkspace } from '@contract-studio/language/node';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { generateArchitecture } from './generate-architecture.js';
import { tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';

const TUTORIAL = resolve(fileURLToPath(new URL('.', import.meta.url)), '..', '..', '..', 'examples', 'tutorial');

describe('generated Makefiles: the flags the generated C needs are always given', () => {
    let arch: string;
    let cleanup: () => void;
    beforeAll(async () => {
        let dir: string;
        ({ dir, cleanup } = tempDir('codegen-flags-'));
        for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) cpSync(join(TUTORIAL, f), join(dir, f));
        const ws = await loadWorkspace(dir);
        expect(generateArchitecture(ws.documents, join(dir, 'src-gen')).errors).toEqual([]);
        arch = join(dir, 'src-gen', 'generated', 'architecture');
    });
    afterAll(() => cleanup());

    /** The words of the command that `make` would run to build the module MSA (or a tool), with `vars` on its command line. */
    const compileLine = (vars: string[], where: string[] = ['-C', join(arch, 'modules', 'MSA_mod'), '-f', 'Makefile']): string[] => {
        const out = run('make', ['-n', '-B', ...where, `CONTRACT_RUNTIME=${RUNTIME_DIR}`, ...vars]);
        const line = out.split('\n').find((l) => / -o (MSA|controlMSA) /.test(l));
        expect(line, out).toBeDefined();
        return line!.split(/\s+/);
    };
    const NEEDED = ['-std=c11', '-D_POSIX_C_SOURCE=200809L', `-I${RUNTIME_DIR}/include`, '-I.', '-I../../common', `${RUNTIME_DIR}/build/libmodule.a`, '-lpthread', '-lrt', '-lm'];

    it('by default: C11, POSIX 2008, the include folders and the library, with -Wall -Wextra -O2 -g', () => {
        expect(compileLine([])).toEqual(expect.arrayContaining([...NEEDED, '-Wall', '-Wextra', '-O2', '-g']));
    });

    it('CFLAGS=-Werror replaces -Wall -Wextra -O2 -g only: -std=c11 and -D_POSIX_C_SOURCE stay', () => {
        const words = compileLine(['CFLAGS=-Werror']);
        expect(words).toEqual(expect.arrayContaining([...NEEDED, '-Werror']));
        for (const gone of ['-Wall', '-Wextra', '-O2', '-g']) expect(words).not.toContain(gone);
    });

    it('a cross build: CFLAGS=-mtune=generic -O2 keeps C11 (not gcc\'s gnu17 default)', () => {
        const words = compileLine(['CFLAGS=-mtune=generic -O2']);
        expect(words).toEqual(expect.arrayContaining([...NEEDED, '-mtune=generic', '-O2']));
        // the language first: a -std= of the user's own CFLAGS comes after it, and wins
        expect(words.indexOf('-std=c11')).toBeLessThan(words.indexOf('-mtune=generic'));
    });

    it('EXTRA_CFLAGS adds to the defaults, and to CFLAGS given on the command line too', () => {
        expect(compileLine(['EXTRA_CFLAGS=-Werror'])).toEqual(expect.arrayContaining([...NEEDED, '-Wall', '-Wextra', '-O2', '-g', '-Werror']));
        const both = compileLine(['CFLAGS=-O1', 'EXTRA_CFLAGS=-fdiagnostics-format=json']);
        expect(both).toEqual(expect.arrayContaining([...NEEDED, '-O1', '-fdiagnostics-format=json']));
        expect(both).not.toContain('-O2');
    });

    it('CPPFLAGS and LDLIBS on the command line add to what the generated C needs', () => {
        expect(compileLine(['CPPFLAGS=-DROBOT_ID=2', 'LDLIBS=-lgpiod'])).toEqual(expect.arrayContaining([...NEEDED, '-DROBOT_ID=2', '-lgpiod']));
    });

    it('the control tools\' Makefiles too', () => {
        const words = compileLine(['CFLAGS=-Werror'], ['-C', join(arch, 'tools'), '-f', 'makecontrolMSA']);
        expect(words).toEqual(expect.arrayContaining(['-std=c11', '-D_POSIX_C_SOURCE=200809L', '-I../common', `${RUNTIME_DIR}/build/libmodule.a`, '-Werror']));
        expect(words).not.toContain('-O2');
    });

    it('a module builds with CFLAGS=-Werror given alone (the generated C warns of nothing under C11)', () => {
        ensureRuntimeLibrary();
        const out = run('make', ['-B', '-C', join(arch, 'modules', 'MSA_mod'), '-f', 'Makefile', `CONTRACT_RUNTIME=${RUNTIME_DIR}`, 'CFLAGS=-Werror']);
        expect(out).toMatch(/-std=c11 -Werror/);
    }, 60_000);
});
