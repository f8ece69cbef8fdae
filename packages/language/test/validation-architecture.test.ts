/**
 * docs/language-reference.md §7: an architecture with more processes than contract-launch starts,
 * or than the build service's default process limit runs, is told by `contract check` before any
 * build (the numbers of packages/conventions/src/run-bounds.ts).
 */
import { EmptyFileSystem } from 'langium';
import { beforeAll, describe, expect, it } from 'vitest';
import { DEFAULT_PROCESS_LIMIT, LAUNCHER_MAX_MODULES } from '@contract-studio/conventions';
import { createCactalServices, type CactalServices } from '../src/cactal-module.js';
import { describeCodeCases, type CodeCase, type Files } from './code-cases.js';
import { build } from './helpers.js';
import { threeLetterName } from '../bench/synthetic-architecture.js';

/** An architecture of `modules` synchronous modules (in files of 20) and `supervisors` supervisors. */
function architecture(modules: number, supervisors: number): Files {
    const files: Files = {};
    for (let m = 0; m < modules; m++) {
        const file = `m${String(Math.floor(m / 20)).padStart(2, '0')}.contract`;
        files[file] = `${files[file] ?? ''}synchronous module ${threeLetterName(m)} { scheduling { C=1ms; } }\n`;
    }
    for (let s = 0; s < supervisors; s++) files[`s${s}.contract`] = `supervisor ${threeLetterName(1000 + s)} { f() { rules { R: [elapsed=1ms] [elapsed=2ms] } } }`;
    return files;
}

export const CASES: Record<string, CodeCase> = {
    // 250 modules + 7 supervisors + ORD = 258 processes, past the launcher's 256; 248 + 7 + 1 = 256 are taken
    'architecture-too-many-processes': {
        raise: architecture(LAUNCHER_MAX_MODULES - 6, 7), clean: architecture(LAUNCHER_MAX_MODULES - 8, 7),
        message: `This architecture runs ${LAUNCHER_MAX_MODULES + 2} processes (${LAUNCHER_MAX_MODULES - 6} modules, 7 supervisors and ORD): contract-launch starts at most ${LAUNCHER_MAX_MODULES} in one run`,
        data: { processes: LAUNCHER_MAX_MODULES + 2, max: LAUNCHER_MAX_MODULES }
    },
    // the field tester's 120 modules + 7 supervisors + ORD: 128 processes, 260 with their threads; 118 fit
    'architecture-over-process-limit': {
        raise: architecture(120, 7), clean: architecture(118, 7),
        message: `This architecture runs 128 processes (120 modules, 7 supervisors and ORD), 2 threads each: with make and the launcher, 260 processes and threads, more than the build service's default process limit of ${DEFAULT_PROCESS_LIMIT} (126 module processes fit)`,
        data: { processes: 128, threads: 260, limit: DEFAULT_PROCESS_LIMIT, suggested: 320 }
    }
};

describeCodeCases('architecture size diagnostics: each code raised by its case, not by a near-identical one', 'Architecture size', CASES);

describe('architecture size: told once', () => {
    let services: CactalServices;
    beforeAll(() => { services = createCactalServices(EmptyFileSystem).Cactal; });

    it('one diagnostic for the whole architecture, on the first process past the bound, with how to raise the limit', async () => {
        const built = await build(architecture(120, 7), services);
        const found = built.diagnostics.filter((d) => d.code === 'architecture-over-process-limit');
        expect(found).toHaveLength(1);
        // ORD is process 1, the 120 modules processes 2..121, the 7 supervisors 122..128: the sixth supervisor, process 127, is the first that does not fit
        expect(found[0]!.message).toContain(`${threeLetterName(1005)} is process 127`);
        expect(found[0]!.message).toContain('contract run --limit processes=320');
        expect(built.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
    });

    it('past the launcher\'s bound the error alone is told (not the process limit\'s warning too)', async () => {
        const built = await build(architecture(LAUNCHER_MAX_MODULES, 0), services);
        expect(built.diagnostics.filter((d) => d.code === 'architecture-too-many-processes')).toHaveLength(1);
        expect(built.diagnostics.filter((d) => d.code === 'architecture-over-process-limit')).toEqual([]);
    });
});
