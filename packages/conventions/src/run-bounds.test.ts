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
});
