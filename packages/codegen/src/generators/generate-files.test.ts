import { describe, expect, it } from 'vitest';
import { parseRegions } from '../regions/parse-regions.js';
import { tutorialModel } from '../test-support/tutorial-model.js';
import { computePriorities } from '../model/priorities.js';
import { generateFiles } from './generate-files.js';

const byPath = () => new Map(generateFiles(tutorialModel()).map((f) => [f.path, f.content]));
const regionIds = (text: string) => parseRegions(text, 'f').regions.map((r) => r.id);

describe('generateFiles on the report example', () => {
    it('is deterministic: two generations are byte-identical', () => {
        expect([...byPath().entries()]).toEqual([...byPath().entries()]);
    });

    it('produces every file of the generated tree: common headers, ORD, modules, supervisors, tools, Makefiles', () => {
        const paths = [...byPath().keys()].sort();
        const arch = 'generated/architecture';
        for (const p of ['Makefile', 'common/SharedTypeA.h', 'common/SharedTypeE.h', 'common/SharedFunctiontestit.h',
            'modules/ORD_mod/module.c', 'modules/ORD_mod/schedtypes.h', 'modules/ORD_mod/tools.h', 'modules/ORD_mod/schedmessages.h',
            'modules/ORD_mod/vocabulary.c', 'modules/ORD_mod/Makefile', 'modules/MAA_mod/module.c', 'modules/MAA_mod/Makefile',
            'modules/SUP_mod/module.c', 'modules/SUP_mod/suptypes.h', 'modules/SUP_mod/vocabulary.c', 'modules/GLB_mod/Makefile',
            'tools/controlMSC.c', 'tools/makecontrolMSC', 'tools/controlGLB.c', 'tools/Makefile']) {
            expect(paths).toContain(`${arch}/${p}`);
        }
    });

    it("uses the report's region IDs, with the async hooks only where they apply", () => {
        const files = byPath();
        const maa = regionIds(files.get('generated/architecture/modules/MAA_mod/module.c')!);
        expect(maa).toEqual(['protect_additional_import_MAA', 'protect_description_MAA', 'protect_author_MAA', 'protect_param_out_MAA',
            'protect_internal_vars_MAA', 'protect_internal_functions_decl_MAA', 'protect_init_MAA', 'protect_exit_MAA', 'protect_exec_MAA',
            'protect_event_MAA', 'protect_param_MAA', 'protect_internal_functions_impl_MAA']);
        const msc = regionIds(files.get('generated/architecture/modules/MSC_mod/module.c')!);
        expect(msc).not.toContain('protect_event_MSC');
        expect(msc).not.toContain('protect_param_MSC');
        const mab = files.get('generated/architecture/modules/MAB_mod/module.c')!;
        expect(regionIds(mab)).toContain('protect_event_MAB');
        expect(regionIds(mab)).not.toContain('protect_param_MAB');
        expect(mab).not.toContain('_react_to_parameterizing');
        expect(regionIds(files.get('generated/architecture/common/SharedTypeA.h')!)).toEqual(['protect_additional_import_TypeA', 'protect_additional_decl_TypeA',
            'protect_eq_TypeA', 'protect_diff_TypeA', 'protect_inf_TypeA', 'protect_sup_TypeA', 'protect_infeq_TypeA', 'protect_supeq_TypeA', 'protect_additional_impl_TypeA']);
        expect(regionIds(files.get('generated/architecture/common/SharedFunctiontestit.h')!)).toEqual(['protect_additional_import_function_testit', 'protect_function_impl_testit']);
        expect(regionIds(files.get('generated/architecture/modules/SUP_mod/vocabulary.c')!)).toEqual([]);
    });

    it('writes the interface tables and port variables of report §8.2', () => {
        const maa = byPath().get('generated/architecture/modules/MAA_mod/module.c')!;
        expect(maa).toContain('char controlevent[256] = "\\0";');
        expect(maa).toContain('TypeE received_message = { { "\\0", 0, { 0.0, 0.0, 0.0 } }, { "\\0", 0 } };');
        expect(maa).toContain('TypeA param = { 22.12, 6.98, 897.34 };');
        expect(maa).toContain('ModuleReact IREACT[] = { { &controlevent, 0, sizeof(char)*256, "---", 0, 0}, IREACT_TERM };');
        expect(maa).toContain('ModuleDetect IDETECT[] = { { &message_type_notification, 0, sizeof(TypeC)}, { &received_message, 1, sizeof(TypeE)}, { &connection_status, 2, sizeof(char)*256}, IDETECT_TERM };');
        expect(maa).toContain('size_t PARAM_SIZE_IN[] = { sizeof(TypeA), PARAM_SIZE_TERM };');
        expect(maa).toContain('__attribute__((fallthrough));');
        expect(maa).toContain('(void)argc; (void)argv;');
        expect(maa).toContain('_react_to_parameterizing(0, &productionTime, &receptionTime);');
        const msc = byPath().get('generated/architecture/modules/MSC_mod/module.c')!;
        expect(msc).toContain('TypeB out_coordinates_commmmand = { { 1.0, 1.0, 1.0 }, 1 };');
        expect(msc).toContain('ModuleUse IUSE[] = { { &in_coordinates, 0, sizeof(TypeA), "---", 0, 0}, IUSE_TERM };');
        expect(msc).not.toContain('_react_to_event(');
    });

    it('computes fixed priorities (supervisors by level, ORD, rate-monotonic modules, interaction) and writes them in module.c and the tables', () => {
        const p = computePriorities(tutorialModel());
        expect(p.of.get('GLB')).toBe(99); // top supervisor
        expect(p.of.get('SUP')).toBe(98); // activated by GLB
        expect(p.ord).toBe(90);
        expect(p.of.get('MSC')).toBe(84); // period 1 s, the only period
        expect(p.of.get('MAA')).toBe(30); // interaction (event schema), even though also activated as resttime
        const files = byPath();
        expect(files.get('generated/architecture/modules/MSC_mod/module.c')).toContain('int MODULE_PRIORITY = 84;');
        expect(files.get('generated/architecture/modules/ORD_mod/vocabulary.c')).toContain('{"MSC", 84, 1000000}');
    });

    it('ranks synchronous modules rate-monotonically and places critical/resttime modules', () => {
        const arch = tutorialModel();
        arch.schemas.find((s) => s.name === 'schemaCommande2')!.periodNs = 1e8; // MSB, MSC, MSD now also at 100 ms
        arch.modules.push({ name: 'MAC', kind: 'asynchronous', parameters: [], dataIn: [], dataOut: [], eventIn: [], eventOut: [] });
        arch.modules.push({ name: 'MAD', kind: 'asynchronous', parameters: [], dataIn: [], dataOut: [], eventIn: [], eventOut: [] });
        const rules = arch.supervisors[0]!.functions[0]!.rules;
        rules[0]!.actions.push({ kind: 'critical', module: 'MAC' }, { kind: 'resttime', module: 'MAD' });
        const p = computePriorities(arch);
        expect(p.of.get('MSB')).toBe(84);
        expect(p.of.get('MSA')).toBe(83); // only in the 1 s schema
        expect(p.of.get('MAC')).toBe(85);
        expect(p.of.get('MAD')).toBe(10);
    });

    it('names the default START after the top supervisor', () => {
        expect(byPath().get('generated/architecture/Makefile')).toContain('START ?= GLB.mission()');
    });

    it('names the makefile of every recursive make (-f), so a GNUmakefile or makefile beside a generated Makefile is never read', () => {
        const makes = [...byPath().entries()]
            .filter(([path]) => /(^|\/)(Makefile|makecontrol\w+)$/.test(path))
            .flatMap(([path, text]) => text.split('\n').filter((line) => line.includes('$(MAKE)')).map((line) => `${path}: ${line.trim()}`));
        expect(makes.length).toBeGreaterThan(10);
        for (const line of makes) expect(line).toMatch(/\$\(MAKE\) (-C \S+ )?-f (Makefile|makecontrol\w+)( |$)/);
    });

    it('makes each executable depend on the headers of common/ it includes (closed over their includes), not on every one', () => {
        const files = byPath();
        const line = (path: string, start: string) => files.get(`generated/architecture/${path}`)!.split('\n').find((l) => l.startsWith(start));
        const common = (names: string[]) => names.map((n) => `Shared${n}.h`).join(' ');
        // MSA's module.c includes SharedTypeA.h; MAA's includes SharedTypeE.h, which includes TypeC (and so TypeA) and TypeD
        expect(line('modules/MSA_mod/Makefile', 'COMMON_HEADERS =')).toBe(`COMMON_HEADERS = ${common(['TypeA'])}`);
        expect(line('modules/MAA_mod/Makefile', 'COMMON_HEADERS =')).toBe(`COMMON_HEADERS = ${common(['TypeA', 'TypeC', 'TypeD', 'TypeE'])}`);
        expect(line('tools/makecontrolMSA', 'COMMON_HEADERS =')).toBe('COMMON_HEADERS =');
        expect(line('tools/makecontrolMAA', 'COMMON_HEADERS =')).toBe(`COMMON_HEADERS = ${common(['TypeA'])}`);
        const generated = common(['Functiondoit', 'Functiontestit', 'TypeA', 'TypeB', 'TypeC', 'TypeD', 'TypeE', 'TypeF']);
        expect(line('modules/MSA_mod/Makefile', 'GENERATED_COMMON_HEADERS =')).toBe(`GENERATED_COMMON_HEADERS = ${generated}`);
        // a file of your own in common/ is a dependency only of the executables that include it (none here)
        expect(line('modules/MSA_mod/Makefile', 'MSA:')).toBe('MSA: Makefile $(SOURCES) $(OWN_FILES) $(wildcard *.h *.c *.inc) $(addprefix ../../common/,$(COMMON_HEADERS)) $(CONTRACT_LIB)');
        expect(line('tools/makecontrolMSA', 'controlMSA:')).toBe('controlMSA: makecontrolMSA controlMSA.c $(OWN_FILES) $(addprefix ../common/,$(COMMON_HEADERS)) $(CONTRACT_LIB)');
    });
});
