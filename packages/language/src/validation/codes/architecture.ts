import { DEFAULT_PROCESS_LIMIT, LAUNCHER_MAX_MODULES, RUN_OVERHEAD_PROCESSES, THREADS_PER_MODULE } from '@contract-studio/conventions';
import { defineCodes } from './code-table.js';

/**
 * docs/language-reference.md §7: what a run of the whole architecture needs — one process per
 * module and supervisor, and ORD (packages/conventions/src/run-bounds.ts gives the numbers).
 */
export const { area: architectureArea, codes: ArchitectureCodes } = defineCodes('Architecture size', 'language-reference.md §7', {
    'architecture-too-many-processes': {
        severity: 'error',
        description: `The architecture has more module processes (its modules, its supervisors and ORD) than contract-launch starts in one run (${LAUNCHER_MAX_MODULES}): its run would be refused after the build. Reported once, on the first module or supervisor past the bound (files in path order); the diagnostic data holds \`processes\` and \`max\`.`,
        example: '// 250 modules and 7 supervisors: 258 processes with ORD'
    },
    'architecture-over-process-limit': {
        severity: 'warning',
        description: `The architecture's processes and their threads (${THREADS_PER_MODULE} per module process, its own and its log writer's, and ${RUN_OVERHEAD_PROCESSES} for make, its shell, contract-launch and the sandbox) are more than the build service's default process limit (${DEFAULT_PROCESS_LIMIT}): its run would fail to start them all (\`fork: Resource temporarily unavailable\`). Raise the limit (\`contract run --limit processes=N\`, \`contract build\`, \`contract serve\` likewise) or make the architecture smaller; a job whose own process limit fits the architecture (\`contract run --limit processes=512\`) does not repeat it among its prepare problems. Reported once, on the first module or supervisor past the limit (files in path order); the diagnostic data holds \`processes\`, \`threads\`, \`limit\` and \`suggested\`.`,
        example: '// 120 modules and 7 supervisors: 128 processes with ORD, 260 processes and threads'
    }
});
