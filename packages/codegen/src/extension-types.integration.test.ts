/**
 * The extension types (docs/language-reference.md: bool, arrays, enumerations, named constants) end
 * to end in code generation: a robot-like project written in Cactal generates a tree that builds
 * with -Werror (make all), and the generated C has the expected shapes (C arrays, C enums,
 * descriptors and paths in the vocabulary tables, port sizes).
 */
import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { EmptyFileSystem } from 'langium';
import { createCactalServices } from '@contract-studio/language';
import { describe, expect, it } from 'vitest';
import { generateFromArchitecture } from './generate-architecture.js';
import { architectureFromModels } from './model/from-langium.js';
import { loadProject } from './test-support/load-project.js';
import { readTree, tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, STRICT_CFLAGS, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';

export const ROBOT_FILES: Record<string, string> = {
    'types.contract': `
const int NJOINTS = 6;
const float SAFE_DISTANCE = 0.3;
enum Mode { IDLE, TELEOP, AUTO }
enum Level { OK, WARN, STOP };
datatype Pose {float x, float y, float theta};
datatype Scan {float[180] ranges, Mode mode = Mode.AUTO, bool valid = true};
datatype Arm {float[NJOINTS] q = {0.0, 0.1, 0.2, 0.3, 0.4, 0.5}, float[3][3] rot = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}, Pose[2] waypoints, string[2] names = {"a", "b"}};
datatype Alarm {Level level, int code = NJOINTS};
function bool too_close(Scan scan, float[NJOINTS] q, float limit);
function void plan(Arm arm, Mode mode);
`,
    'laser.contract': `import "types.contract";
synchronous module LSR {
    parameters { float[2] gains = {1.0, 2.0} :0; Mode mode = Mode.TELEOP :1; bool enabled = true :2; }
    scheduling { C=1ms; }
    data flows { out :0 Scan scan; out :1 float[NJOINTS] q; }
    event flows { out :0 Alarm alarm; out :1 Mode mode_changed; }
}
`,
    'drive.contract': `import "types.contract";
synchronous module DRV {
    scheduling { C=1ms; }
    data flows { in :0 Scan scan; in :1 float[NJOINTS] q; }
}
`,
    'schema.contract': `import "types.contract";
import "laser.contract";
import "drive.contract";
periodic schema nav(Mode mode = Mode.AUTO, float[2] gains = {0.5, 0.5}) {
    realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; }
    modules { LSR (gains :0, mode :1); DRV (); }
    scheduling graph { LSR -> DRV; }
    communications { LSR:0 -> DRV:0; LSR:1 -> DRV:1; }
}
`,
    'sched.contract': `import "laser.contract";
import "drive.contract";
import "schema.contract";
scheduler configuration { modules { LSR; DRV; } schemas { nav; } }
`,
    'sup.contract': `import "types.contract";
import "laser.contract";
import "schema.contract";
supervisor SUP {
    event flows { in :1 Alarm alarm; in :2 Mode mode_in; out :3 Mode mode = Mode.IDLE; out :4 float[NJOINTS] target; }
    watch() {
        local { Level last = Level.OK; float d = 0.0; float[NJOINTS] q; Scan s; bool stopped = false; }
        rules {
            FIRST: [LSR:0<alarm.level == Level.STOP>(last = alarm.level, s.ranges[90] = SAFE_DISTANCE, q[2] = 1.5)]
                subscribe LSR:0 =* :1;
                activate schema nav(mode = Mode.TELEOP, gains = {d, 1.0});
                compute plan({q, {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}, {{0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}}, {"x", "y"}}, Mode.AUTO);
                notify :3 (mode = Mode.AUTO);
                notify :4 (target = q, target[0] = d)
                [LSR:1<mode_in == Mode.AUTO | (mode_in != Mode.IDLE & too_close(s, q, SAFE_DISTANCE))>{infinite}(stopped = true, d = s.ranges[NJOINTS])]
            SECOND: [(LSR:0<(alarm.level > Level.WARN)>{1s} and started(FIRST){infinite})]
                subscribe LSR:1 => :2
                [elapsed=1s]
        }
    }
}
`,
};

describe('extension types (bool, arrays, enumerations, constants)', () => {
    it('a robot project generates C that builds with -Werror', async () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        const { models, errors } = await loadProject(services, ROBOT_FILES);
        expect(errors).toEqual([]);
        const { dir, cleanup } = tempDir('codegen-ext-');
        try {
            const report = generateFromArchitecture(architectureFromModels(models), dir);
            expect(report.errors).toEqual([]);
            const tree = readTree(dir);
            const arm = tree.get('generated/architecture/common/SharedArm.h')!;
            expect(arm).toContain('double q[6];');
            expect(arm).toContain('double rot[3][3];');
            expect(arm).toContain('Pose waypoints[2];');
            expect(arm).toContain('char names[2][256];');
            expect(tree.get('generated/architecture/common/SharedMode.h')).toContain('typedef enum Mode { Mode_IDLE = 0, Mode_TELEOP = 1, Mode_AUTO = 2 } Mode;');
            expect(tree.get('generated/architecture/common/SharedScan.h')).toContain('#include <stdbool.h>');
            const laser = tree.get('generated/architecture/modules/LSR_mod/module.c')!;
            expect(laser).toContain('double gains[2] = { 1.0, 2.0 };');
            expect(laser).toContain('Mode mode = Mode_TELEOP;');
            expect(laser).toContain('sizeof(double[6])');
            const vocabulary = tree.get('generated/architecture/modules/SUP_mod/vocabulary.c')!;
            expect(vocabulary).toContain('CONTRACT_ENUM_TYPE(Level, contract_members_Level, 3, NULL)');
            expect(vocabulary).toContain('CONTRACT_ARRAY_TYPE("float[6]", double[6], contract_type_double, 6, NULL)');
            expect(vocabulary).toContain('offsetof(Scan, ranges[90])');
            expect(vocabulary).toContain('2 * sizeof(double)');
            expect(vocabulary).toContain('offsetof(Alarm, level), &contract_type_Level');
            // datatypes holding extension fields list them for readable traces, each field type defined before
            expect(vocabulary).toContain('{"ranges", offsetof(Scan, ranges), &contract_array_float_180}');
            expect(vocabulary).toContain('CONTRACT_DEFINE_TYPE_FIELDS(Scan, &contract_default_Scan, 3, contract_fields_Scan)');
            expect(vocabulary.indexOf('static const ContractType contract_array_float_180 ')).toBeLessThan(vocabulary.indexOf('contract_fields_Scan[]'));
            expect(vocabulary.indexOf('CONTRACT_DEFINE_TYPE_FIELDS(Arm,')).toBeGreaterThan(vocabulary.indexOf('CONTRACT_DEFINE_TYPE(Pose,'));
            // a control tool whose parameter ports use the extension types parses and shows values by their descriptors
            const tool = tree.get('generated/architecture/tools/controlLSR.c')!;
            expect(tool).toContain('return ControlMainTyped("LSR", PARAMS, argc, argv);');
            expect(tool).toMatch(/\{ 0, &contract_array_float_2 \},\s*\{ 1, &contract_type_Mode \},\s*\{ 2, &contract_type_bool \},\s*CONTROL_TYPED_PARAM_TERM/);
            expect(tree.get('generated/architecture/tools/controlDRV.c')).toContain('return ControlMain("DRV", PARAMS, argc, argv);');
            ensureRuntimeLibrary();
            const out = run('make', ['-j2', '-C', join(dir, 'generated', 'architecture'), 'all', `CONTRACT_RUNTIME=${RUNTIME_DIR}`, 'EXTRA_CFLAGS=-Werror -O0']);
            expect(out).not.toMatch(/warning:/);
            // the engines accept the tables (types of both sides of assignments and tests, paths inside their variables, descriptors)
            const arch = join(dir, 'generated', 'architecture');
            const check = join(dir, 'check_tables.c');
            writeFileSync(check, [
                '#include <stdio.h>',
                '#include <contract/vocabulary.h>',
                'extern const ContractSupervisorVocabulary SUP_VOCABULARY;',
                'extern const ContractOrdVocabulary ORD_VOCABULARY;',
                'int main(void) {',
                '    char err[512];',
                '    if (contract_check_supervisor_vocabulary(&SUP_VOCABULARY, err, sizeof err) != 0) { printf("SUP: %s\\n", err); return 1; }',
                '    if (contract_check_ord_vocabulary(&ORD_VOCABULARY, err, sizeof err) != 0) { printf("ORD: %s\\n", err); return 1; }',
                '    printf("TABLES OK\\n");',
                '    return 0;',
                '}',
            ].join('\n'));
            const objects = ['SUP', 'ORD'].map((m) => {
                const obj = join(dir, `${m}_vocabulary.o`);
                run('gcc', ['-c', ...STRICT_CFLAGS, `-I${RUNTIME_DIR}/include`, `-I${join(arch, 'modules', `${m}_mod`)}`, `-I${join(arch, 'common')}`, join(arch, 'modules', `${m}_mod`, 'vocabulary.c'), '-o', obj]);
                return obj;
            });
            const exe = join(dir, 'check_tables');
            run('gcc', [...STRICT_CFLAGS, `-I${RUNTIME_DIR}/include`, check, ...objects, join(RUNTIME_DIR, 'build', 'libmodule.a'), '-lpthread', '-lrt', '-lm', '-o', exe]);
            expect(run(exe, [])).toContain('TABLES OK');
        } finally {
            cleanup();
        }
    }, 300_000);
});
