/**
 * docs/language-reference.md §7: whether a run of the whole architecture can start every process
 * it has — ORD, one per module, one per supervisor (the generated Makefile's EXECUTABLES) — under
 * contract-launch's bound and the build service's default process limit, told before any build
 * (packages/conventions/src/run-bounds.ts: the numbers the launcher and the sandbox use).
 */
import { AstUtils, WorkspaceCache, type AstNode, type ValidationAcceptor, type ValidationChecks } from 'langium';
import {
    DEFAULT_PROCESS_LIMIT, LAUNCHER_MAX_MODULES, modulesUnderProcessLimit, runThreads, THREADS_PER_MODULE
} from '@contract-studio/conventions';
import { isModel, isModule, isSupervisor, type CactalAstType, type Module, type Supervisor } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { ArchitectureCodes } from './codes/architecture.js';
import { report } from './report.js';

interface Census {
    /** Every module and supervisor of the project, files in path order, each file's in its order. */
    processes: Array<Module | Supervisor>;
    /** Each one's place in `processes`. */
    index: Map<Module | Supervisor, number>;
    modules: number;
    supervisors: number;
}

export function architectureChecks(services: CactalServices): ValidationChecks<CactalAstType> {
    const cache = new WorkspaceCache<string, Census>(services.shared);
    const projects = services.projects.Projects;
    const census = (node: AstNode): Census => cache.get(projects.keyOf(AstUtils.getDocument(node).uri), () => {
        const docs = projects.documentsOf(AstUtils.getDocument(node).uri).sort((a, b) => a.uri.toString() < b.uri.toString() ? -1 : a.uri.toString() > b.uri.toString() ? 1 : 0);
        const processes: Array<Module | Supervisor> = [];
        let modules = 0, supervisors = 0;
        for (const doc of docs) {
            const root = doc.parseResult?.value;
            if (!isModel(root)) continue;
            for (const element of root.elements) {
                if (isModule(element)) { modules++; processes.push(element); }
                else if (isSupervisor(element)) { supervisors++; processes.push(element); }
            }
        }
        return { processes, index: new Map(processes.map((p, i) => [p, i])), modules, supervisors };
    });
    const check = (node: Module | Supervisor, accept: ValidationAcceptor) => checkProcesses(node, census(node), accept);
    return { Module: check, Supervisor: check };
}

/** The number of processes of a run, said with what they are. */
function describe(c: Census): string {
    const total = c.modules + c.supervisors + 1;
    return `${total} processes (${c.modules} module${c.modules === 1 ? '' : 's'}, ${c.supervisors} supervisor${c.supervisors === 1 ? '' : 's'} and ORD)`;
}

function checkProcesses(node: AstNode & (Module | Supervisor), c: Census, accept: ValidationAcceptor): void {
    const total = c.modules + c.supervisors + 1;
    // ORD is the first process of a run: the module or supervisor at index i is process i + 2
    const position = (c.index.get(node) ?? -2) + 2;
    if (total > LAUNCHER_MAX_MODULES) {
        if (position !== LAUNCHER_MAX_MODULES + 1) return;
        report(accept, ArchitectureCodes['architecture-too-many-processes'],
            `This architecture runs ${describe(c)}: contract-launch starts at most ${LAUNCHER_MAX_MODULES} in one run (ORD and the supervisors count), so its run would be refused after the build. ${node.name} is process ${position}: make the architecture smaller, or split it into architectures run apart.`,
            { node, property: 'name', data: { processes: total, max: LAUNCHER_MAX_MODULES } });
        return;
    }
    const threads = runThreads(total);
    if (threads <= DEFAULT_PROCESS_LIMIT) return;
    const fit = modulesUnderProcessLimit(DEFAULT_PROCESS_LIMIT);
    if (position !== fit + 1) return;
    const suggested = Math.ceil(threads / 64) * 64;
    report(accept, ArchitectureCodes['architecture-over-process-limit'],
        `This architecture runs ${describe(c)}, ${THREADS_PER_MODULE} threads each: with make and the launcher, ${threads} processes and threads, more than the build service's default process limit of ${DEFAULT_PROCESS_LIMIT} (${fit} module processes fit), so its run would fail to start them all. ${node.name} is process ${position}. Raise the limit: \`contract run --limit processes=${suggested}\` (\`contract build\` and \`contract serve\` take --limit too), or make the architecture smaller.`,
        { node, property: 'name', data: { processes: total, threads, limit: DEFAULT_PROCESS_LIMIT, suggested } });
}
