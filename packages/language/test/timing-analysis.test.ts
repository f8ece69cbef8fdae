/** Timing analysis of periodic schemas: utilisation, critical path, precedence cycles (exported for hover). */
import { describe, expect, it } from 'vitest';
import { isSchema, type Schema } from '../src/generated/ast.js';
import {
    combinedUtilisation, criticalPath, precedenceCycle, schemaModules, schemaTiming, schemaUtilisation
} from '../src/validation/timing-analysis.js';
import { architecture } from './architecture-fixture.js';
import { build } from './helpers.js';

/** Builds the fixture with sc1 replaced and returns the parsed schemas by name. */
async function schemas(changes: Record<string, string>): Promise<Map<string, Schema>> {
    const built = await build(architecture(changes));
    const result = new Map<string, Schema>();
    for (const doc of built.docs.values()) {
        for (const e of doc.parseResult.value.elements) if (isSchema(e)) result.set(e.name, e);
    }
    return result;
}

const schema = (graph: string, realtime = 'PERIOD=10ms; CRITICAL_DELAY=10ms;') =>
    `periodic schema sc1(TypeA consigne) { realtime { ${realtime} } modules { MSA (); MSB (); MSC (consigne:0); MSD (); } scheduling graph { ${graph} } }`;
const names = (xs: Array<{ name: string }> | undefined) => xs?.map((x) => x.name);

describe('timing analysis', () => {
    it('takes the longest branch of a diamond (MSA 0.5ms, MSB 0.5ms, MSC 1ms, MSD 1ms)', async () => {
        const s = (await schemas({ 'sc1.contract': schema('MSA -> MSB; MSA -> MSC; MSB -> MSD; MSC -> MSD;') })).get('sc1')!;
        const path = criticalPath(s)!;
        expect(names(path.modules)).toEqual(['MSA', 'MSC', 'MSD']);
        expect(path.ns).toBe(2_500_000);
        expect(schemaUtilisation(s)).toBeCloseTo(0.3, 10);
    });

    it('counts a module without precedences as a path of its own', async () => {
        const s = (await schemas({ 'sc1.contract': schema('') })).get('sc1')!;
        const path = criticalPath(s)!;
        expect(names(path.modules)).toEqual(['MSC']);
        expect(path.ns).toBe(1_000_000);
        expect(names(schemaModules(s))).toEqual(['MSA', 'MSB', 'MSC', 'MSD']);
    });

    it('finds a cycle and then gives no critical path', async () => {
        const s = (await schemas({ 'sc1.contract': schema('MSA -> MSB; MSB -> MSC; MSC -> MSB;') })).get('sc1')!;
        expect(names(precedenceCycle(s))).toEqual(['MSB', 'MSC', 'MSB']);
        expect(criticalPath(s)).toBeUndefined();
        expect(schemaTiming(s)).toMatchObject({ periodNs: 10_000_000, criticalDelayNs: 10_000_000, totalComputeNs: 3_000_000, criticalPath: undefined });
    });

    it('sums the utilisation of schemas and ignores schemas without a period', async () => {
        const all = await schemas({
            'sc1.contract': schema('MSA -> MSB;', 'PERIOD=3ms; CRITICAL_DELAY=3ms;'),
            'sc2.contract': 'periodic schema sc2() { realtime { CRITICAL_DELAY=3ms; } modules { MSA (); } }'
        });
        expect(schemaUtilisation(all.get('sc2')!)).toBeUndefined();
        expect(combinedUtilisation([all.get('sc1')!, all.get('sc2')!])).toBeCloseTo(1, 10);
    });
});
