/**
 * `contract generate DIR [-o OUT]`: generates the C tree of a Cactal project (default OUT =
 * DIR/src-gen), merging protected regions with what is there. The tree is the same bytes from any
 * folder on any machine: the runtime is given at build time (docs/architecture.md, Seam 3). Prints what was
 * created, updated, kept, orphaned and removed; errors go to stderr. Exit 1 when the model has
 * errors (nothing is generated) or a file could not be merged (left untouched), 2 on bad usage.
 */
import { stat } from 'node:fs/promises';
import { join, resolve } from 'node:path';
import type { FinishedRename, GenerationProblem, GenerationReport } from '@contract-studio/codegen';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';
import { formatText, summarize } from '../diagnostic-format.js';
import { ORPHANS_HOLD, REGION_COPY_NAME, SRC_GEN_DIR, unusedTreeWarning } from '@contract-studio/conventions';
import { gitignoreHint } from '../gitignore-hint.js';
import { safeName } from '../terminal-text.js';
import { MENTIONED_KINDS, printRegionMentions } from '../region-mentions-text.js';
import { holdTreeLock } from '../tree-lock-hold.js';
import { insideProjectRefusal } from '../enclosing-project.js';

function list(io: CliIO, label: string, paths: string[], show = true): void {
    if (paths.length === 0) return;
    io.out(`${label}: ${paths.length}\n`);
    if (show) for (const p of paths) io.out(`  ${safeName(p)}\n`);
}

/** Prints what a generation did (also after `contract rename`). */
export async function printReport(io: CliIO, report: GenerationReport, outLabel: string, verbose: boolean): Promise<void> {
    const { formatProblem } = await import('@contract-studio/codegen');
    list(io, 'created', report.created);
    list(io, 'updated', report.updated);
    list(io, 'kept (unchanged)', report.unchanged, verbose);
    list(io, `copied to orphans/ (${ORPHANS_HOLD})`, report.orphaned);
    list(io, 'removed (no user code)', report.removed);
    // plain concatenation, not path.join: join would normalise the message too (a refused
    // manifest entry such as "../../x" must be shown as it is)
    const inOut = (p: GenerationProblem) => `${safeName(outLabel.replace(/\/+$/, ''))}/${formatProblem({ ...p, file: safeName(p.file) })}`;
    for (const w of report.warnings) io.err(`warning: ${inOut(w)}\n`);
    for (const e of report.errors) io.err(`error: ${e.file.startsWith('(') || e.file.startsWith('/') ? formatProblem({ ...e, file: safeName(e.file) }) : inOut(e)}\n`);
}

export const generateCommand: Command = {
    name: 'generate',
    summary: 'generate the C source tree (src-gen) of a Cactal project',
    usage: [
        'usage: contract generate DIR [-o OUT] [--verbose]',
        '  OUT: output folder (default DIR/src-gen); the tree goes to OUT/generated/architecture',
        '  --verbose: also list the files kept unchanged (otherwise only counted)',
        'DIR is the project\'s root (docs/codegen.md "Where a project is": the outermost folder holding a src-gen/, else the folder of the .contract files): its .contract files may be in a sub-folder (DIR/src/*.contract, tree DIR/src-gen);',
        '  refused when they are all in a sub-folder with its own src-gen/, DIR holds several projects, or DIR is inside a project (a folder above it holds a generated tree: P/src of P/src-gen);',
        '  a second src-gen/ below DIR is said and not used.',
        'User code in protected regions is kept; code whose region or entity disappeared goes to OUT/orphans/.',
        'The runtime is not part of the tree: give it when building (contract build --runtime PATH, or make CONTRACT_RUNTIME=PATH).',
        'exit status: 1 when the model has errors, DIR holds no .contract file, its files are all in a sub-folder with its own src-gen/, DIR holds several projects or is inside a project (nothing generated), or a file could not be merged; 0 otherwise, 2 on bad usage',
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const { positionals, options } = parseArgs(args, ['o', 'output', 'runtime'], ['verbose']);
        // the generated Makefiles take the runtime at build time (docs/architecture.md, Seam 3)
        if (options.has('runtime')) throw new UsageError('generate takes no --runtime: the runtime is given when building (contract build --runtime PATH, or make CONTRACT_RUNTIME=PATH)');
        if (positionals.length !== 1) throw new UsageError(positionals.length ? 'expected exactly one DIR' : 'missing DIR');
        const dirArg = positionals[0]!;
        const dir = resolve(io.cwd, dirArg);
        const info = await stat(dir).catch(() => undefined);
        if (!info?.isDirectory()) throw new UsageError(`${safeName(dirArg)} is not a directory`);
        const outOption = options.get('o') ?? options.get('output');
        const out = typeof outOption === 'string' ? resolve(io.cwd, outOption) : join(dir, SRC_GEN_DIR);
        // a folder inside a project (P/src of P/src-gen) is no project: its tree would be a second, empty one (-o OUT is taken as meant)
        const inside = typeof outOption === 'string' ? null : insideProjectRefusal(dir, dirArg, 'generate', 'generated');
        if (inside) {
            io.err(`contract generate: ${inside}\n`);
            return EXIT_FAILURE;
        }

        // loaded when the command runs: `contract build`/`run` never pay for the language server (docs/getting-started.md "The build cache")
        const { loadWorkspace } = await import('@contract-studio/language/node');
        const { generateArchitecture } = await import('@contract-studio/codegen');
        // the tree's write lock before the model is read (a rename in another terminal or the IDE
        // changes the .contract files and the tree together: seen whole or not at all)
        const { release, finished } = await holdTreeLock(out, typeof outOption === 'string' ? outOption : join(dirArg, SRC_GEN_DIR), io, { dir, label: dirArg });
        try {
            const status = await generateHeld(dir, dirArg, out, outOption, options.get('verbose') === true, io, loadWorkspace, generateArchitecture);
            if (finished) await listFinishedRenameLeftovers(io, finished, out, typeof outOption === 'string' ? outOption : join(dirArg, SRC_GEN_DIR));
            return status;
        } finally {
            release();
        }
    },
};

/** generate's work, the tree's write lock held. */
async function generateHeld(
    dir: string, dirArg: string, out: string, outOption: unknown, verbose: boolean, io: CliIO,
    loadWorkspace: typeof import('@contract-studio/language/node').loadWorkspace,
    generateArchitecture: typeof import('@contract-studio/codegen').generateArchitecture,
): Promise<number> {
        const workspace = await loadWorkspace(dir);
        // where the project's root is (conventions' project-root.ts): DIR, unless its files are all in a
        // sub-folder with its own src-gen/ or DIR holds several projects (-o OUT is taken as meant)
        if (typeof outOption !== 'string' && workspace.documents.length > 0) {
            const { roots, unusedTrees } = workspace.layout;
            if (roots.length > 1) {
                io.err(`${safeName(dirArg)} holds several projects (${roots.map((r) => safeName(`${r}/`)).join(', ')}): generate one of them (contract generate ${safeName(join(dirArg, roots[0]!))}), or name the output with -o OUT; nothing was generated\n`);
                return EXIT_FAILURE;
            }
            const nested = roots[0] ?? '';
            if (nested !== '') {
                io.err(`the .contract files of ${safeName(dirArg)} are all in ${safeName(nested)}/, which has its own ${SRC_GEN_DIR}/ (its generated code and yours): generate ${safeName(join(dirArg, nested))} instead (or name the output with -o OUT); nothing was generated\n`);
                return EXIT_FAILURE;
            }
            for (const u of unusedTrees) io.err(`warning: ${unusedTreeWarning(safeName(join(dirArg, u)), safeName(dirArg))}\n`);
        }
        const errors = workspace.diagnostics.filter((d) => d.severity === 'error');
        if (errors.length > 0) {
            io.err(formatText(errors, (file) => join(dirArg, file)));
            io.err(`${summarize(workspace.diagnostics)}: the model has errors, nothing was generated\n`);
            return EXIT_FAILURE;
        }
        if (workspace.documents.length === 0) {
            io.err(`no .contract file in ${safeName(dirArg)}: nothing was generated (a project is the folder of its .contract files)\n`);
            return EXIT_FAILURE;
        }
        // the last generation's copy of the regions' code: created by this generation in a project of
        // an older `contract new` (no .gitignore), said once (gitignore-hint.ts)
        const regionCopy = join(out, REGION_COPY_NAME);
        const copyBefore = typeof outOption !== 'string' && (await stat(regionCopy).catch(() => undefined)) !== undefined;
        const report = generateArchitecture(workspace.documents, out);
        const outLabel = typeof outOption === 'string' ? outOption : join(dirArg, SRC_GEN_DIR);
        await printReport(io, report, outLabel, verbose);
        io.err(`generated ${safeName(outLabel)}: ${report.created.length} created, ${report.updated.length} updated, ${report.unchanged.length} kept, ${report.orphaned.length} orphaned, ${report.errors.length} error(s)\n`);
        if (typeof outOption !== 'string' && !copyBefore && (await stat(regionCopy).catch(() => undefined)) !== undefined) {
            const hint = await gitignoreHint(dir, safeName(dirArg), [`${SRC_GEN_DIR}/${REGION_COPY_NAME}`]);
            if (hint) io.err(hint);
        }
        return report.errors.length > 0 ? EXIT_FAILURE : EXIT_OK;
}

/**
 * After finishing a rename killed half-way (and generating): the protected regions that still
 * mention its old name, listed as `contract rename` lists them (region-mentions-text.ts), with a
 * summary line when code uses it (the build fails until it is changed by hand).
 */
async function listFinishedRenameLeftovers(io: CliIO, finished: FinishedRename, out: string, outLabel: string): Promise<void> {
    if (!MENTIONED_KINDS.has(finished.kind)) return;
    const { findRegionMentions, oldNamesMatcher } = await import('@contract-studio/codegen');
    const mentions = findRegionMentions(out, oldNamesMatcher(finished.kind, finished.oldName, finished.identifiers.map(([from]) => from)), finished.identifierOwner);
    const inCode = printRegionMentions(io, mentions, finished.oldName, (f) => safeName(`${outLabel.replace(/\/+$/, '')}/${f}`));
    if (inCode > 0) io.err(`contract generate: the rename of ${finished.kind} ${finished.oldName} -> ${finished.newName} is finished, but ${inCode} use(s) of ${finished.oldName} in protected-region code were not changed (listed above)\n`);
}
