/** docs/language-reference.md §5: every scheduler-configuration diagnostic code, raised and not raised by a near-identical case. */
import { describe, expect, it } from 'vitest';
import { architecture, supervisor } from './architecture-fixture.js';
import { describeCodeCases, type CodeCase } from './code-cases.js';
import { build } from './helpers.js';

const sched = (body: string) => architecture({ 'sched.contract': `scheduler configuration { ${body} }` });
/** sc2: MSB -> MSC -> MSD, C = 2.5ms in all. */
const sc2 = (period = '10ms') => `periodic schema sc2(TypeA consigne) {
    realtime { PERIOD=${period}; CRITICAL_DELAY=${period}; }
    modules { MSB (); MSC (consigne:0); MSD (); }
    scheduling graph { MSB -> MSC; MSC -> MSD; }
    communications { MSB:0 -> MSC:0 * 1; MSC:1 -> MSD:2 * 1; }
}`;
const activating = (schema: string) => supervisor(`R: [elapsed=1ms] activate schema ${schema}(consigne = temp_consigne) [elapsed=2ms]`);

const CASES: Record<string, CodeCase> = {
    'scheduler-duplicate': {
        raise: architecture({ 'sched2.contract': 'scheduler configuration { modules { MSB; } }' }),
        clean: architecture({ 'other.contract': 'datatype Other {int x};' }),
        message: 'The project already has a scheduler configuration (also in sched'
    },
    'scheduler-missing': {
        raise: architecture({ 'sched.contract': undefined }),
        clean: architecture(),
        message: "Add a file with 'scheduler configuration { modules { ... } schemas { sc1; } }'"
    },
    'scheduler-module-kind': {
        raise: sched('modules { MSA; MSB; MSC; MSD; MAA; } schemas { sc1; }'),
        clean: sched('modules { MSA; MSB; MSC; MSD; } schemas { sc1; }')
    },
    'scheduler-schema-kind': {
        raise: sched('modules { MSA; MSB; MSC; MSD; } schemas { sc1; ev; }'),
        clean: sched('modules { MSA; MSB; MSC; MSD; } schemas { sc1; }')
    },
    'scheduler-module-unlisted': {
        raise: sched('modules { MSA; MSB; MSC; } schemas { sc1; }'),
        clean: sched('modules { MSA; MSB; MSC; MSD; } schemas { sc1; }'),
        message: "Schema sc1 uses MSD, which is not listed in the 'modules' block",
        data: { modules: ['MSD'] }
    },
    'scheduler-schema-unlisted': {
        raise: architecture({ 'sc2.contract': sc2(), 'sup.contract': activating('sc2') }),
        clean: architecture({ 'sc2.contract': sc2(), 'sup.contract': activating('sc1') }),
        message: 'Periodic schema sc2 is activated here but not listed in the scheduler configuration',
        data: { schema: 'sc2' }
    },
    'scheduler-entry-duplicate': {
        raise: sched('modules { MSA; MSB; MSC; MSD; MSA; } schemas { sc1; }'),
        clean: sched('modules { MSA; MSB; MSC; MSD; } schemas { sc1; }')
    },
    'scheduler-utilisation': {
        // sc1 and sc2 each use 2.5ms per 3ms (0.83): together 1.67
        raise: architecture({
                'sc1.contract': `periodic schema sc1(TypeA consigne) { realtime { PERIOD=3ms; CRITICAL_DELAY=3ms; } modules { MSA (); MSC (consigne:0); MSD (); } scheduling graph { MSA -> MSC; MSC -> MSD; } }`,
                'sc2.contract': sc2('3ms'),
                'sched.contract': 'scheduler configuration { modules { MSA; MSB; MSC; MSD; } schemas { sc1; sc2; } }'
            }),
        clean: architecture({
                'sc1.contract': `periodic schema sc1(TypeA consigne) { realtime { PERIOD=3ms; CRITICAL_DELAY=3ms; } modules { MSA (); MSC (consigne:0); MSD (); } scheduling graph { MSA -> MSC; MSC -> MSD; } }`,
                'sc2.contract': sc2('20ms'),
                'sched.contract': 'scheduler configuration { modules { MSA; MSB; MSC; MSD; } schemas { sc1; sc2; } }'
            }),
        message: 'The listed schemas together use 1.67 of the processor (sum of C / PERIOD: sc1 0.83, sc2 0.83)'
    }
};

describeCodeCases('scheduler configuration diagnostics: each code raised by its case, not by a near-identical one', 'Scheduler configuration', CASES);

describe('scheduler configuration: more behaviour', () => {
    it('an activated periodic schema without any scheduler configuration is an error on the action', async () => {
        const built = await build(architecture({ 'sched.contract': undefined, 'sup.contract': activating('sc1') }));
        const found = built.diagnostics.filter((d) => d.code === 'scheduler-schema-unlisted');
        expect(found.map((d) => [d.file, d.severity])).toEqual([['sup.contract', 'error']]);
        expect(found[0]!.message).toContain('the project has no scheduler configuration');
    });

    it('an activated event schema need not be listed', async () => {
        const built = await build(architecture({ 'sup.contract': supervisor('R: [elapsed=1ms] activate schema ev() [elapsed=2ms]') }));
        expect(built.diagnostics.filter((d) => d.code.startsWith('scheduler-'))).toEqual([]);
    });

    it('a listed module whose file is not imported is one error, not also "not listed"', async () => {
        const built = await build({
            'cam.contract': 'synchronous module CAM { scheduling { C=1ms; } }',
            'look.contract': 'import "cam.contract";\nperiodic schema look() { realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; } modules { CAM (); } }',
            'sched.contract': 'import "look.contract";\nscheduler configuration { modules { CAM; } schemas { look; } }',
        });
        expect(built.diagnostics.filter((d) => d.severity === 'error').map((d) => `${d.file} ${d.code}`)).toEqual(['sched.contract import-not-imported']);
    });

    it('does not crash on unresolved entries', async () => {
        const built = await build(sched('modules { MSA; MZZ; } schemas { nosuch; sc1; }'));
        expect(built.diagnostics.filter((d) => d.code === 'linking-error').length).toBe(2);
        expect(built.diagnostics.filter((d) => d.code === 'scheduler-module-unlisted').map((d) => d.message))
            .toEqual(["Schema sc1 uses MSC, MSD, which are not listed in the 'modules' block of the scheduler configuration: list every module of a listed schema."]);
    });
});
