import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import { loadWorkspace } from '@contract-studio/language/node';
import { writeSyntheticArchitecture } from '@contract-studio/language/bench';
import { describe, expect, it } from 'vitest';
import { generateArchitecture } from './generate-architecture.js';
import { tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';

describe("the benchmark's synthetic architecture (reduced size)", () => {
    it('generates a tree that builds with -Wall -Wextra -Werror, deterministically', async () => {
        const { dir, cleanup } = tempDir('codegen-synthetic-');
        try {
            writeSyntheticArchitecture(join(dir, 'project'), { typeFiles: 2, periodicSchemas: 2, eventSchemas: 1, modulesPerSchema: 3, supervisors: 2 });
            const ws = await loadWorkspace(join(dir, 'project'));
            expect(ws.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
            const first = generateArchitecture(ws.documents, join(dir, 'a'));
            const second = generateArchitecture(ws.documents, join(dir, 'b'));
            expect(first.errors).toEqual([]);
            expect(second.created).toEqual(first.created);
            run('diff', ['-r', join(dir, 'a'), join(dir, 'b')]);
            ensureRuntimeLibrary();
            const arch = join(dir, 'a', 'generated', 'architecture');
            const out = run('make', ['-j2', '-C', arch, 'all', `CONTRACT_RUNTIME=${RUNTIME_DIR}`, 'EXTRA_CFLAGS=-Werror -O0']);
            expect(out).not.toMatch(/warning:/);
            const executables = readdirSync(join(arch, 'modules')).map((d) => d.replace('_mod', ''));
            for (const exe of executables) expect(readdirSync(join(arch, 'modules', `${exe}_mod`))).toContain(exe);
        } finally {
            cleanup();
        }
    }, 300_000);
});
