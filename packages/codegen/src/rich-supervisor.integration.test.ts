import { cpSync, writeFileSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadWorkspace } from '@contract-studio/language/node';
import { describe, expect, it } from 'vitest';
import { generateArchitecture } from './generate-architecture.js';
import { tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, STRICT_CFLAGS, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';

/** A project using what the tutorial does not: ORD events, durations, persistence times, relational
 *  tests on field paths, `or` conditions, notify, compute on a local, parameterize with a mixed
 *  structured value, critical modules, string and int parameters. */
const FIXTURE = resolve(fileURLToPath(new URL('.', import.meta.url)), 'test-support', 'fixtures', 'rich');

const CHECK = String.raw`
#include <stdio.h>
#include <contract/vocabulary.h>
extern const ContractSupervisorVocabulary SUP_VOCABULARY;
int main(void) {
    char err[512];
    if (contract_check_supervisor_vocabulary(&SUP_VOCABULARY, err, sizeof err) != 0) { printf("SUP: %s\n", err); return 1; }
    const ContractFunction *f = &SUP_VOCABULARY.functions[0];
    printf("SUP ok %s rules=%d locals=%d inits=%d post_clauses=%d\n", f->name, f->nrules, f->nlocals, f->nlocal_inits, f->rules[0].post.nclauses);
    return 0;
}
`;
const CHECK_ORD = String.raw`
#include <stdio.h>
#include <contract/vocabulary.h>
extern const ContractOrdVocabulary ORD_VOCABULARY;
int main(void) {
    char err[512];
    if (contract_check_ord_vocabulary(&ORD_VOCABULARY, err, sizeof err) != 0) { printf("ORD: %s\n", err); return 1; }
    printf("ORD ok schemas=%d period=%lld\n", ORD_VOCABULARY.nschemas, (long long)ORD_VOCABULARY.schemas[0]->period_ns);
    return 0;
}
`;

describe('a supervisor using every kind of condition and action', () => {
    it('generates tables that build with -Werror and pass the engines\' own table checks', async () => {
        const { dir, cleanup } = tempDir('codegen-rich-');
        try {
            cpSync(FIXTURE, join(dir, 'project'), { recursive: true });
            const ws = await loadWorkspace(join(dir, 'project'));
            expect(ws.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
            const report = generateArchitecture(ws.documents, join(dir, 'out'));
            expect(report.errors).toEqual([]);
            const lib = ensureRuntimeLibrary();
            const arch = join(dir, 'out', 'generated', 'architecture');
            expect(run('make', ['-j2', '-C', arch, 'all', `CONTRACT_RUNTIME=${RUNTIME_DIR}`, 'EXTRA_CFLAGS=-Werror -O0'])).not.toMatch(/warning:/);
            const includes = [`-I${RUNTIME_DIR}/include`, `-I${join(arch, 'common')}`];
            for (const [name, program, mod] of [['check_sup', CHECK, 'SUP_mod'], ['check_ord', CHECK_ORD, 'ORD_mod']] as const) {
                const src = join(dir, `${name}.c`);
                writeFileSync(src, program);
                run('gcc', [...STRICT_CFLAGS, '-fsanitize=address,undefined', ...includes, `-I${join(arch, 'modules', mod)}`, src, join(arch, 'modules', mod, 'vocabulary.c'), lib, '-o', join(dir, name)]);
            }
            expect(run(join(dir, 'check_sup'), [])).toContain('SUP ok run rules=2 locals=5 inits=2 post_clauses=2');
            expect(run(join(dir, 'check_ord'), [])).toContain('ORD ok schemas=1 period=10000000');
        } finally {
            cleanup();
        }
    }, 300_000);
});
