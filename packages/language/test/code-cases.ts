/**
 * Runs raise/clean cases for diagnostic codes: each case raises its code (with the severity of the
 * code table) and a near-identical case does not. Also checks that every code of the given code
 * areas (titles of CODE_AREAS) has a case.
 */
import { EmptyFileSystem } from 'langium';
import { beforeAll, describe, expect, it } from 'vitest';
import { createCactalServices, type CactalServices } from '../src/cactal-module.js';
import { CODE_AREAS } from '../src/validation/codes/index.js';
import { build, codes } from './helpers.js';

export type Files = Record<string, string>;
export interface CodeCase {
    raise: Files;
    clean: Files;
    /** Text the raised message must contain. */
    message?: string;
    /** Fields the raised diagnostic's data must hold. */
    data?: Record<string, unknown>;
}

export function describeCodeCases(title: string, areaTitles: string | readonly string[], cases: Record<string, CodeCase>): void {
    const titles = typeof areaTitles === 'string' ? [areaTitles] : areaTitles;
    describe(title, () => {
        let services: CactalServices;
        beforeAll(() => { services = createCactalServices(EmptyFileSystem).Cactal; });

        it(`has a case for every code of its area${titles.length > 1 ? 's' : ''}`, () => {
            for (const areaTitle of titles) {
                const area = CODE_AREAS.find((a) => a.title === areaTitle);
                expect(area, `no code area titled ${areaTitle}`).toBeDefined();
                expect(area!.codes.map((c) => c.code).filter((c) => !(c in cases)), areaTitle).toEqual([]);
            }
        });

        for (const [code, c] of Object.entries(cases)) {
            it(`${code}: raised`, async () => {
                const built = await build(c.raise, services);
                const found = built.diagnostics.filter((d) => d.code === code);
                expect(found.length, built.lines.join('\n')).toBeGreaterThan(0);
                const declared = CODE_AREAS.flatMap((a) => a.codes).find((d) => d.code === code)!;
                expect(found[0]!.severity).toBe(declared.severity);
                if (c.message) expect(found.map((d) => d.message).join('\n')).toContain(c.message);
                if (c.data) expect(found[0]!.data).toMatchObject(c.data);
            });
            it(`${code}: not raised by the near-identical case`, async () => {
                const built = await build(c.clean, services);
                expect(codes(built), built.lines.join('\n')).not.toContain(code);
            });
        }
    });
}
