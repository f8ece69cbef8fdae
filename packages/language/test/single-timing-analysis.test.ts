/**
 * One implementation of schema timing (PERIOD, CRITICAL_DELAY, utilisation, critical path):
 * `src/validation/timing-analysis.ts`, used by validation and by hover. No other source file, and
 * no compiled file the package ships (dist/), defines those functions.
 */
import { existsSync, readdirSync, readFileSync } from 'node:fs';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const root = fileURLToPath(new URL('..', import.meta.url));
const TIMING_FUNCTIONS = /\bfunction\s+(schemaTiming|criticalPath|schemaUtilisation|combinedUtilisation|longestPath)\b/;

function filesUnder(dir: string, suffix: string): string[] {
    if (!existsSync(dir)) return [];
    return readdirSync(dir, { withFileTypes: true, recursive: true })
        .filter((e) => e.isFile() && e.name.endsWith(suffix))
        .map((e) => relative(root, join(e.parentPath, e.name)));
}

function definersOfTiming(files: string[]): string[] {
    return files.filter((f) => TIMING_FUNCTIONS.test(readFileSync(join(root, f), 'utf8'))).sort();
}

describe('schema timing has a single implementation', () => {
    it('only src/validation/timing-analysis.ts defines the timing functions', () => {
        expect(definersOfTiming(filesUnder(join(root, 'src'), '.ts'))).toEqual(['src/validation/timing-analysis.ts']);
    });

    it('the hover provider takes its schema timing from timing-analysis', () => {
        const hover = readFileSync(join(root, 'src/lsp/cactal-hover-provider.ts'), 'utf8');
        expect(hover).toMatch(/from '\.\.\/validation\/timing-analysis\.js'/);
    });

    it.skipIf(!existsSync(join(root, 'dist')))('dist/ holds no compiled file without a source (a deleted duplicate stays out of the package)', () => {
        const stale = filesUnder(join(root, 'dist'), '.js')
            .filter((f) => !existsSync(join(root, 'src', relative('dist', f).replace(/\.js$/, '.ts'))));
        expect(stale).toEqual([]);
        expect(definersOfTiming(filesUnder(join(root, 'dist'), '.js'))).toEqual(['dist/validation/timing-analysis.js']);
    });
});
