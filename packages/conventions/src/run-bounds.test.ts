import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { DEFAULT_PROCESS_LIMIT, LAUNCHER_MAX_MODULES, modulesUnderProcessLimit, runBoundsHeader, runThreads } from './run-bounds.js';

describe('run bounds', () => {
    it('the launcher\'s header is the one written from run-bounds.ts (npm run run-bounds -w packages/conventions)', () => {
        const header = readFileSync(fileURLToPath(new URL('../../../runtime/launcher/run_bounds.h', import.meta.url)), 'utf8');
        expect(header).toBe(runBoundsHeader());
        expect(header).toContain(`#define CONTRACT_LAUNCHER_MAX_MODULES ${LAUNCHER_MAX_MODULES}\n`);
    });

    it('counts two threads per module and the run\'s own processes', () => {
        // 120 modules + 7 supervisors + ORD: 256 threads of modules, past the default limit with make and the launcher
        expect(runThreads(128)).toBeGreaterThan(DEFAULT_PROCESS_LIMIT);
        expect(runThreads(modulesUnderProcessLimit(DEFAULT_PROCESS_LIMIT))).toBeLessThanOrEqual(DEFAULT_PROCESS_LIMIT);
        expect(runThreads(modulesUnderProcessLimit(DEFAULT_PROCESS_LIMIT) + 1)).toBeGreaterThan(DEFAULT_PROCESS_LIMIT);
        expect(modulesUnderProcessLimit(DEFAULT_PROCESS_LIMIT)).toBe(126);
    });

    it('the docs give the same numbers (docs/runtime-api.md, language-reference.md, sandbox.md)', () => {
        const doc = (name: string) => readFileSync(fileURLToPath(new URL(`../../../docs/${name}`, import.meta.url)), 'utf8').replace(/\s+/g, ' ');
        const fit = modulesUnderProcessLimit(DEFAULT_PROCESS_LIMIT);
        expect(doc('runtime-api.md')).toContain(`Takes at most ${LAUNCHER_MAX_MODULES} module executables`);
        expect(doc('runtime-api.md')).toContain(`at most ${LAUNCHER_MAX_MODULES + 1 - 1} (ORD and the supervisors count)`);
        expect(doc('runtime-api.md')).toContain(`default process limit of ${DEFAULT_PROCESS_LIMIT} (docs/sandbox.md), at most ${fit} module processes fit`);
        expect(doc('language-reference.md')).toContain(`\`contract-launch\` starts at most ${LAUNCHER_MAX_MODULES} module processes in one run`);
        expect(doc('language-reference.md')).toContain(`at most ${fit} module processes fit under the default`);
        expect(doc('sandbox.md')).toContain(`${fit} module processes fit under ${DEFAULT_PROCESS_LIMIT}`);
        expect(doc('sandbox.md')).toContain(`contract-launch itself takes at most ${LAUNCHER_MAX_MODULES} module processes`);
    });
});
