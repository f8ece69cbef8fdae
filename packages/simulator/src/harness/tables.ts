/**
 * The C sources of a project's simulator (docs/simulation.md §3): the engines' tables that the
 * code generator writes (`modules/<SUP>_mod/vocabulary.c`, `ORD_mod/vocabulary.c` and the
 * headers they include, `common/Shared*.h`), generated in memory — never into the user's src-gen —
 * plus `sim_tables.c`, which lists them for sim_main.c. The protected regions of the user's own
 * `src-gen/.../common/*.h` (the bodies of test and compute functions, custom comparisons) are
 * carried over, read from the project folder as hostile input: regular files only, bounded, no
 * link followed out of it.
 */
import { readUserFile } from './user-file.js';
import { architectureFromModels, generateFiles, mergeRegions } from '@contract-studio/codegen';
import type { Model } from '@contract-studio/language';
import { ARCHITECTURE_DIR } from '@contract-studio/conventions';

export interface SimSource {
    /** Relative to the harness's build folder, `/` separators. */
    path: string;
    content: string;
}

export interface SimSources {
    files: SimSource[];
    /** The `.c` files to compile (paths of `files`). */
    units: string[];
    /** Include folders per unit (relative to the build folder). */
    includes: Map<string, string[]>;
    supervisors: string[];
    hasOrd: boolean;
    /** Carry-over problems (a user header that could not be read or merged): the generated default is used. */
    warnings: string[];
    /**
     * The project's src-gen folder the regions were read from (undefined: none given): a compile
     * error is told against its files (harness/compile-diagnostics.ts). A file of `files` is
     * `${ARCHITECTURE_DIR}/${path}` there; `sim_tables.c` is the simulator's own.
     */
    srcGen: string | undefined;
}

const ARCH = `${ARCHITECTURE_DIR}/`;
const C_NAME = /^[A-Za-z_][A-Za-z0-9_]*$/;

/**
 * `models` in the order generateArchitecture uses (documents sorted by URI), so that the tables
 * are those `contract generate` writes. `userSrcGen`: the project's src-gen folder (may not exist).
 */
export function simulationSources(models: Model[], userSrcGen: string | undefined): SimSources {
    const generated = generateFiles(architectureFromModels(models));
    const out: SimSources = { files: [], units: [], includes: new Map(), supervisors: [], hasOrd: false, warnings: [], srcGen: userSrcGen };
    for (const f of generated) {
        if (!f.path.startsWith(ARCH)) continue;
        const rel = f.path.slice(ARCH.length);
        const mod = /^modules\/([^/]+)_mod\/([^/]+)$/.exec(rel);
        const isCommon = /^common\/[^/]+\.h$/.test(rel);
        if (!isCommon && !(mod && (mod[2] === 'vocabulary.c' || mod[2]!.endsWith('.h')))) continue;
        let content = f.content;
        if (isCommon && userSrcGen) {
            const mine = readUserFile(userSrcGen, f.path);
            if (mine !== undefined) {
                try {
                    content = mergeRegions(f.content, mine, f.path, () => false).text;
                } catch (e) {
                    out.warnings.push(`src-gen/${f.path}: its protected regions cannot be read (${e instanceof Error ? e.message : String(e)}); the generated default is simulated`);
                }
            }
        }
        out.files.push({ path: rel, content });
        if (mod && mod[2] === 'vocabulary.c') {
            if (!C_NAME.test(mod[1]!)) continue;
            out.units.push(rel);
            out.includes.set(rel, [`modules/${mod[1]}_mod`, 'common']);
            if (mod[1] === 'ORD') out.hasOrd = true;
            else out.supervisors.push(mod[1]!);
        }
    }
    out.supervisors.sort();
    const decl = out.supervisors.map((s) => `extern const ContractSupervisorVocabulary ${s}_VOCABULARY;`);
    const table = [
        '// sim_tables.c (written by the simulator): the tables sim_main.c runs',
        '#include <stddef.h>',
        '#include <contract/vocabulary.h>',
        ...decl,
        out.hasOrd ? 'extern const ContractOrdVocabulary ORD_VOCABULARY;' : '',
        `const ContractSupervisorVocabulary *const SIM_SUPERVISORS[] = {${out.supervisors.map((s) => `&${s}_VOCABULARY, `).join('')}NULL};`,
        `const ContractOrdVocabulary *const SIM_ORD = ${out.hasOrd ? '&ORD_VOCABULARY' : 'NULL'};`,
        '',
    ].join('\n');
    out.files.push({ path: 'sim_tables.c', content: table });
    out.units.push('sim_tables.c');
    out.includes.set('sim_tables.c', []);
    return out;
}
