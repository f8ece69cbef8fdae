/** docs/diagnostics.md is generated from the code tables; this fails when it is stale. */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { allCodes, CODE_AREAS, renderDiagnosticsDoc } from '../src/validation/codes/index.js';

describe('docs/diagnostics.md', () => {
    it('is up to date with the code tables (run `npm run docs:diagnostics -w packages/language`)', () => {
        const doc = readFileSync(fileURLToPath(new URL('../../../docs/diagnostics.md', import.meta.url)), 'utf8');
        expect(doc).toBe(renderDiagnosticsDoc(CODE_AREAS));
    });

    it('declares each code once, kebab-case, with a description and an example', () => {
        const all = allCodes();
        expect(new Set(all.map((c) => c.code)).size).toBe(all.length);
        for (const c of all) {
            expect(c.code).toMatch(/^[a-z]+(-[a-z]+)*$/);
            expect(c.description.length).toBeGreaterThan(20);
            expect(c.example.length).toBeGreaterThan(0);
            expect(['error', 'warning', 'info', 'hint']).toContain(c.severity);
        }
    });
});
