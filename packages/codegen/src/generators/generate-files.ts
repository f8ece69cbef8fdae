import type { Architecture } from '../model/architecture.js';
import { ArchitectureIndex } from '../model/lookup.js';
import { computePriorities } from '../model/priorities.js';
import type { GeneratedFile } from '../writer/write-tree.js';
import { ARCHITECTURE_MAKEFILE, generateArchitectureMakefile } from './architecture-makefile.js';
import { controlMakefilePath, controlSourcePath, generateControlMakefile, generateControlSource, generateToolsMakefile, TOOLS_DIR } from './control-tool.js';
import { executableMakefiles, type ExecutableMakefile } from './executable-makefile.js';
import { generateModuleMakefile, moduleDir, moduleMakefilePath } from './module-makefile.js';
import { generateModuleSource, moduleSourcePath } from './module-source.js';
import { engineBindingSource, ORD_DIR, schedMessagesHeader, schedTypesHeader, toolsHeader } from './ord-module.js';
import { generateSharedFunctionHeader, sharedFunctionPath } from './shared-function-header.js';
import { generateSharedTypeHeader, sharedTypePath } from './shared-type-header.js';
import { generateSharedEnumHeader, sharedEnumPath } from './shared-enum-header.js';
import { constantsHeaderPath, generateConstantsHeader } from './constants-header.js';
import { supTypesHeader } from './supervisor-module.js';
import { generateOrdVocabulary } from './vocabulary/ord-vocabulary.js';
import { generateSupervisorVocabulary } from './vocabulary/supervisor-vocabulary.js';
import { architectureExecutables } from './run-executables.js';
import { architecturePath } from '@contract-studio/conventions';

/** Every file of the generated tree (docs/codegen.md "The tree") for an architecture (paths relative to the output folder). */
export function generateFiles(arch: Architecture): GeneratedFile[] {
    const index = new ArchitectureIndex(arch);
    const priorities = computePriorities(arch);
    const files: GeneratedFile[] = [];
    const add = (path: string, content: string) => files.push({ path, content });
    /** Makefiles of executables: generated last, from the headers the other files include (executable-makefile.ts). */
    const makefiles: ExecutableMakefile[] = [];
    const addModuleMakefile = (name: string, sources: string[]) => {
        const own = moduleDir(name);
        makefiles.push({ path: moduleMakefilePath(name), own, sources: sources.map((s) => `${own}/${s}`), render: (deps) => generateModuleMakefile(name, sources, deps) });
    };

    for (const e of arch.enums ?? []) add(sharedEnumPath(e.name), generateSharedEnumHeader(e));
    for (const t of arch.datatypes) add(sharedTypePath(t.name), generateSharedTypeHeader(t));
    for (const f of arch.functions) add(sharedFunctionPath(f.name), generateSharedFunctionHeader(f));
    if ((arch.constants ?? []).length > 0) add(constantsHeaderPath(), generateConstantsHeader(arch.constants!, index));

    for (const m of arch.modules) {
        add(moduleSourcePath(m.name), generateModuleSource(m, priorities.of.get(m.name)!, index));
        addModuleMakefile(m.name, ['module.c']);
    }

    add(`${ORD_DIR}/module.c`, engineBindingSource('ORD', priorities.ord, 'scheduler', 'schedtypes.h'));
    add(`${ORD_DIR}/schedtypes.h`, schedTypesHeader());
    add(`${ORD_DIR}/schedmessages.h`, schedMessagesHeader());
    add(`${ORD_DIR}/tools.h`, toolsHeader());
    add(`${ORD_DIR}/vocabulary.c`, generateOrdVocabulary(arch, index, priorities));
    addModuleMakefile('ORD', ['module.c', 'vocabulary.c']);

    for (const s of arch.supervisors) {
        const dir = moduleDir(s.name);
        add(`${dir}/module.c`, engineBindingSource(s.name, priorities.of.get(s.name)!, 'supervisor', 'suptypes.h'));
        add(`${dir}/suptypes.h`, supTypesHeader(s.name));
        add(`${dir}/vocabulary.c`, generateSupervisorVocabulary(s, priorities.of.get(s.name)!, index));
        addModuleMakefile(s.name, ['module.c', 'vocabulary.c']);
    }

    const controlled = [...arch.modules.map((m) => ({ name: m.name, kind: `${m.kind} module`, params: m.parameters })), ...arch.supervisors.map((s) => ({ name: s.name, kind: 'supervisor', params: [] }))];
    for (const c of controlled) {
        add(controlSourcePath(c.name), generateControlSource(c.name, c.kind, c.params, index));
        makefiles.push({ path: controlMakefilePath(c.name), own: TOOLS_DIR, sources: [controlSourcePath(c.name)], render: (deps) => generateControlMakefile(c.name, deps) });
    }
    add(architecturePath('tools/Makefile'), generateToolsMakefile(controlled.map((c) => c.name)));

    add(ARCHITECTURE_MAKEFILE, generateArchitectureMakefile(arch, architectureExecutables(arch)));
    files.push(...executableMakefiles(makefiles, files));
    return files;
}
