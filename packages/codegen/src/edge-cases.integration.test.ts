import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import type { Architecture } from './model/architecture.js';
import { generateFromArchitecture } from './generate-architecture.js';
import { readTree, tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';

/** Unusual but valid models: empty datatype, strings needing escapes, parameter ports with gaps,
 *  no-argument functions, a supervisor without functions, no scheduler configuration. */
const edgy: Architecture = {
    datatypes: [
        { name: 'Empty', fields: [] },
        { name: 'Deep', fields: [
            { name: 'e', type: { datatype: 'Empty' } },
            { name: 's', type: { primitive: 'string' }, default: { kind: 'string', value: 'q"uote\\n?\ttab é' } },
            { name: 'f', type: { primitive: 'float' }, default: { kind: 'real', value: -1e-7 } },
            { name: 'i', type: { primitive: 'int' }, default: { kind: 'int', value: -7 } },
        ] },
    ],
    functions: [
        { name: 'noargs', returns: 'void', args: [] },
        { name: 'check', returns: 'bool', args: [{ name: 'd', type: { datatype: 'Deep' } }, { name: 'n', type: { primitive: 'int' } }] },
    ],
    modules: [
        { name: 'MAX', kind: 'asynchronous', parameters: [{ name: 'label', index: 1, type: { primitive: 'string' }, initial: { kind: 'string', value: '??=' } }, { name: 'd', index: 3, type: { datatype: 'Deep' } }], dataIn: [], dataOut: [], eventIn: [], eventOut: [] },
        { name: 'MSY', kind: 'synchronous', parameters: [], dataIn: [], dataOut: [], eventIn: [], eventOut: [{ name: 'e', index: 4, type: { datatype: 'Empty' } }], wcetNs: 1000 },
    ],
    schemas: [],
    supervisors: [{ name: 'TOP', eventIn: [], eventOut: [], functions: [] }],
};

describe('edge-case models', () => {
    it('generate a tree that builds with -Werror', () => {
        const { dir, cleanup } = tempDir('codegen-edge-');
        try {
            const report = generateFromArchitecture(edgy, dir);
            expect(report.errors).toEqual([]);
            const tree = readTree(dir);
            expect(tree.get('generated/architecture/common/SharedDeep.h')).toContain('char s[256];');
            expect(tree.get('generated/architecture/modules/MAX_mod/module.c')).toContain('char label[256] = "\\?\\?=";');
            expect(tree.get('generated/architecture/Makefile')).toMatch(/^START \?= $/m); // no supervisor function to start
            ensureRuntimeLibrary();
            const out = run('make', ['-j2', '-C', join(dir, 'generated', 'architecture'), 'all', `CONTRACT_RUNTIME=${RUNTIME_DIR}`, 'EXTRA_CFLAGS=-Werror -O0']);
            expect(out).not.toMatch(/warning:/);
        } finally {
            cleanup();
        }
    }, 300_000);
});
