import type { Architecture } from '../model/architecture.js';
import { ArchitectureIndex } from '../model/lookup.js';
import { computePriorities } from '../model/priorities.js';
import type { GeneratedFile } from '../writer/write-tree.js';
import { ARCHITECTURE_MAKEFILE, generateArchitectureMakefile } from './architecture-makefile.js';
import { controlMakefilePath, controlSourcePath, generateControlMakefile, generateControlSource, generateToolsMakefile } from './control-tool.js';
import { generateModuleMakefile, moduleMakefilePath } from './module-makefile.js';
import { generateModuleSource, moduleSourcePath } from './module-source.js';
import { engineBindingSource, ORD_DIR, schedMessagesHeader, schedTypesHeader, toolsHeader } from './ord-module.js';
import { generateSharedFunctionHeader, sharedFunctionPath } from './shared-function-header.js';
import { generateSharedTypeHeader, sharedTypePath } from './shared-type-header.js';
import { generateSharedEnumHeader, sharedEnumPath } from './shared-enum-header.js';
import { constantsHeaderPath, generateConstantsHeader } from './constants-header.js';
import { supTypesHeader } from './supervisor-module.js';
import { generateOrdVocabulary } from './vocabulary/ord-vocabulary.js';
import { generateSupervisorVocabulary } from './vocabulary/supervisor-vocabulary.js';
import { architecturePath } from '@contract-studio/conventions';

/** Every file of the generated tree (docs/codegen.md "The tree") for an architecture (paths relative to the output folder). */
export function generateFiles(arch: Architecture): GeneratedFile[] {
    const index = new ArchitectureIndex(arch);
    const priorities = computePriorities(arch);
    const files: GeneratedFile[] = [];
    const add = (path: string, content: string) => files.push({ path, content });

    for (const e of arch.enums ?? []) add(sharedEnumPath(e.name), generateSharedEnumHeader(e));
    for (const t of arch.datatypes) add(sharedTypePath(t.name), generateSharedTypeHeader(t));
    for (const f of arch.functions) add(sharedFunctionPath(f.name), generateSharedFunctionHeader(f));
    if ((arch.constants ?? []).length > 0) add(constantsHeaderPath(), generateConstantsHeader(arch.constants!, index));

    for (const m of arch.modules) {
        add(moduleSourcePath(m.name), generateModuleSource(m, priorities.of.get(m.name)!, index));
        add(moduleMakefilePath(m.name), generateModuleMakefile(m.name, ['module.c']));
    }

    add(`${ORD_DIR}/module.c`, engineBindingSource('ORD', priorities.ord, 'scheduler', 'schedtypes.h'));
    add(`${ORD_DIR}/schedtypes.h`, schedTypesHeader());
    add(`${ORD_DIR}/schedmessages.h`, schedMessagesHeader());
    add(`${ORD_DIR}/tools.h`, toolsHeader());
    add(`${ORD_DIR}/vocabulary.c`, generateOrdVocabulary(arch, index, priorities));
    add(moduleMakefilePath('ORD'), generateModuleMakefile('ORD', ['module.c', 'vocabulary.c']));

    for (const s of arch.supervisors) {
        const dir = architecturePath(`modules/${s.name}_mod`);
        add(`${dir}/module.c`, engineBindingSource(s.name, priorities.of.get(s.name)!, 'supervisor', 'suptypes.h'));
        add(`${dir}/suptypes.h`, supTypesHeader(s.name));
        add(`${dir}/vocabulary.c`, generateSupervisorVocabulary(s, priorities.of.get(s.name)!, index));
        add(moduleMakefilePath(s.name), generateModuleMakefile(s.name, ['module.c', 'vocabulary.c']));
    }

    const controlled = [...arch.modules.map((m) => ({ name: m.name, kind: `${m.kind} module`, params: m.parameters })), ...arch.supervisors.map((s) => ({ name: s.name, kind: 'supervisor', params: [] }))];
    for (const c of controlled) {
        add(controlSourcePath(c.name), generateControlSource(c.name, c.kind, c.params, index));
        add(controlMakefilePath(c.name), generateControlMakefile(c.name));
    }
    add(architecturePath('tools/Makefile'), generateToolsMakefile(controlled.map((c) => c.name)));

    const executables = ['ORD', ...arch.modules.map((m) => m.name), ...arch.supervisors.map((s) => s.name)];
    add(ARCHITECTURE_MAKEFILE, generateArchitectureMakefile(arch, executables));
    return files;
}
