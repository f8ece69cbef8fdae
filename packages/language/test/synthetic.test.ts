/** The benchmark's synthetic architecture generator produces valid Cactal (a small instance). */
import { describe, expect, it } from 'vitest';
import { generateSyntheticArchitecture, threeLetterName } from '../bench/synthetic-architecture.js';
import { build } from './helpers.js';

describe('synthetic architecture generator', () => {
    it('never generates ORD and generates distinct three-letter names', () => {
        const names = Array.from({ length: 2000 }, (_v, i) => threeLetterName(i));
        expect(new Set(names).size).toBe(2000);
        expect(names).not.toContain('ORD');
        expect(names.every((n) => /^[A-Z]{3}$/.test(n))).toBe(true);
    });

    it('generates the requested sizes with default 1,000 modules / 200 schemas / 20 supervisors', () => {
        const files = [...generateSyntheticArchitecture().keys()];
        expect(files.filter((f) => f.startsWith('modules/')).length).toBe(1000);
        expect(files.filter((f) => f.startsWith('schemas/')).length).toBe(200);
        expect(files.filter((f) => f.startsWith('supervisors/')).length).toBe(20);
        expect(files.length).toBeGreaterThan(1200);
    });

    it('a small instance checks with zero diagnostics', async () => {
        const files = generateSyntheticArchitecture({ typeFiles: 2, periodicSchemas: 4, eventSchemas: 2, supervisors: 3 });
        const built = await build(Object.fromEntries(files));
        expect(built.lines).toEqual([]);
    });
});
