/**
 * `contract rename DIR OLD NEW [-o OUT]`: renames a module, supervisor, schema, datatype,
 * enumeration, function, port or parameter (`MODULE:port`), enumeration member (`ENUM.MEMBER`),
 * supervision function (`SUP.function`) or a parameter, local or rule label of one
 * (`SUP.function.NAME`) in the `.contract`
 * files with the language server's rename, carries the generated tree over for entities that name
 * generated files (codegen's renameInGeneratedTree, as the IDE's rename does: paths and region IDs
 * move, user code is kept byte for byte, a default MODULE_DESCRIPTION follows), rewrites the C
 * names of the entity in the protected regions' code (a port's or parameter's variable in its
 * module's regions; a datatype's, an enumeration's or a function's C names, an enumeration's
 * constants `Mode_AUTO` in every region; whole C identifiers in code: codegen's
 * renameIdentifiersInGeneratedTree), renames the entity in the project's `.scenario`
 * files (language's rename-scenarios.ts), then generates and lists the protected regions that still mention
 * the old name (file:line). docs/getting-started.md, "Renaming"; docs/codegen.md, "Renames".
 * Exit 1 with a message when the entity is unknown, the name invalid or taken, or the model has
 * errors (a rename needs every reference resolved); nothing is changed then. Exit 1 too, after
 * the rename, when the code of a protected region still uses the old name (the build would fail).
 */
import { lstatSync, readFileSync } from 'node:fs';
import { stat } from 'node:fs/promises';
import { basename, dirname, join, relative, resolve, sep } from 'node:path';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';
import { formatText, summarize } from '../diagnostic-format.js';
import { safeName } from '../terminal-text.js';
import { MENTIONED_KINDS, printRegionMentions } from '../region-mentions-text.js';
import { holdTreeLock } from '../tree-lock-hold.js';
import { printReport } from './generate.js';
import { RENAME_JOURNAL_NAME, SRC_GEN_DIR } from '@contract-studio/conventions';

export const renameCommand: Command = {
    name: 'rename',
    summary: 'rename an entity in the .contract files and carry its generated code over, then generate',
    usage: [
        'usage: contract rename DIR OLD NEW [-o OUT] [--verbose]',
        '  OLD: a module, supervisor, schema, datatype, enumeration or function name; MODULE:port (a port or',
        '       parameter, by name, or by index when only one has it); ENUM.MEMBER (an enumeration member);',
        '       SUPERVISOR.function (a supervision function); SUPERVISOR.function.NAME (a parameter, local or',
        '       rule label of that function)',
        '  NEW: the new name (same rules as the editor\'s rename: modules and supervisors are three upper-case letters)',
        '  OUT: the generated tree (default DIR/src-gen): files and protected-region IDs named after OLD move to NEW',
        'User code in protected regions is kept byte for byte; the uses of a renamed port or parameter in its module\'s',
        'protected regions follow, as do those of a datatype, enumeration (and its constants ENUM_MEMBER), enumeration',
        'member or function in every region (whole C identifiers in code; not in comments or strings); the .scenario files follow;',
        'the tree is then regenerated, and the protected regions that still mention the old name are listed (file:line).',
        'exit status: 1 unknown entity, invalid or taken name, model errors (nothing renamed), generation errors, or',
        '  protected-region code still using the old name (renamed, but the build would fail); 0 otherwise, 2 on bad usage',
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const { positionals, options } = parseArgs(args, ['o', 'output'], ['verbose']);
        if (positionals.length !== 3) throw new UsageError(`expected DIR OLD NEW, got ${positionals.length} argument(s)`);
        const [dirArg, oldSpec, newName] = positionals as [string, string, string];
        const dir = resolve(io.cwd, dirArg);
        if (!(await stat(dir).catch(() => undefined))?.isDirectory()) throw new UsageError(`${safeName(dirArg)} is not a directory`);
        const outOption = options.get('o') ?? options.get('output');
        const out = typeof outOption === 'string' ? resolve(io.cwd, outOption) : join(dir, SRC_GEN_DIR);
        const outLabel = typeof outOption === 'string' ? outOption : join(dirArg, SRC_GEN_DIR);

        // the tree's write lock for the whole rename (carry-over, .contract files, generation): a
        // generate in another terminal or the IDE reads the model and the tree after it, whole
        const { release } = await holdTreeLock(out, outLabel, io, { dir, label: dirArg });
        const renameHeld = async (): Promise<number> => {
            // a journal still there was refused (said above): it may be the only record of a killed
            // rename, so this rename neither goes past it nor replaces it
            if (lstatSync(join(out, RENAME_JOURNAL_NAME), { throwIfNoEntry: false })) {
                io.err(`contract rename: ${safeName(join(outLabel, RENAME_JOURNAL_NAME))} (an interrupted rename) could not be finished (said above): nothing was renamed; once it is dealt with (remove it to go on), rename again\n`);
                return EXIT_FAILURE;
            }
            // loaded when the command runs: `contract build`/`run` never pay for the language server (docs/getting-started.md "The build cache")
            const { loadWorkspace, planRename, RenameError, projectScenarios, renameInScenarios } = await import('@contract-studio/language/node');
            const { generateArchitecture, runJournaledRename, RenameStepError, carryRefusedMessage, identifierRenames, findRegionMentions, mentionMatcher, writeFileAtomic, sha256, realOrSelf } = await import('@contract-studio/codegen');
            const workspace = await loadWorkspace(dir);
            // a rename needs the text parsed and every reference resolved; other errors (a reserved
            // name, a bad value...) do not stop it: renaming is often how they are fixed
            const unresolved = workspace.documents.some((d) => d.document.references.some((r) => r.error !== undefined));
            const errors = workspace.diagnostics.filter((d) => d.severity === 'error');
            if (unresolved || errors.some((d) => blocksRename(d.code))) {
                io.err(formatText(errors, (file) => join(dirArg, file)));
                io.err(`${summarize(errors)}: fix these first (a rename needs the files parsed and every reference resolved); nothing was renamed\n`);
                return EXIT_FAILURE;
            }
            let plan;
            try {
                plan = planRename(workspace, oldSpec, newName);
            } catch (e) {
                if (!(e instanceof RenameError)) throw e;
                // (the editor's messages are sentences: no '.;' before the CLI's end)
                io.err(`contract rename: ${e.message.replace(/\.$/, '')}; nothing was renamed\n`);
                return EXIT_FAILURE;
            }
            const owner = plan.owner;
            const variable = (plan.kind === 'port' || plan.kind === 'parameter') && owner !== undefined;
            // an enumeration's constants are named after it and its members (Mode_AUTO), a member's after its enumeration
            const enumeration = { ...(plan.members ? { members: plan.members } : {}), ...(plan.kind === 'enumeration member' && owner !== undefined ? { enumeration: owner } : {}) };
            const identifiers = identifierRenames(plan.kind, plan.oldName, plan.newName, enumeration);
            const scenarioChanges = renameInScenarios(dir, projectScenarios(dir, [out]), {
                kind: plan.kind, oldName: plan.oldName, newName: plan.newName, owner,
            });
            // the journal first (codegen rename-journal.ts): killed from here on, the next generate or
            // rename finishes this one instead of orphaning the renamed code. Only for the project's
            // own src-gen, which is there (-o OUT: docs/codegen.md "A rename killed half-way")
            const files = [...plan.files.map((f) => ({ path: f.path, text: f.text })), ...scenarioChanges.map((c) => ({ path: c.path, text: c.text }))];
            const inProject = files.every((f) => !relative(dir, f.path).startsWith('..'));
            const own = out === join(dir, SRC_GEN_DIR);
            const journaled = inProject && (await stat(out).catch(() => undefined))?.isDirectory() === true;
            const journal = {
                version: 1 as const, kind: plan.kind, oldName: plan.oldName, newName: plan.newName, generatedNames: plan.generatedNames,
                identifiers: [...identifiers], ...(variable ? { identifierOwner: owner } : {}), ...(own ? {} : { project: realOrSelf(dir) }),
                files: journaled ? files.map((f) => ({ path: relative(dir, f.path).split(sep).join('/'), before: sha256(readFileSync(f.path)), after: f.text })) : [],
            };
            const inTree = (file: string) => safeName(`${outLabel.replace(/\/+$/, '')}/${file}`);
            // journal, generated tree, project files, journal removed (codegen journaled-rename.ts): if a
            // target path is taken in the tree, the .contract files stay as they were
            let carried;
            try {
                ({ carried } = await runJournaledRename(out, journal, {
                    journaled,
                    writeFiles: () => {
                        for (const f of files) writeFileAtomic(dirname(f.path), basename(f.path), Buffer.from(f.text, 'utf8'));
                    },
                }));
            } catch (e) {
                if (!(e instanceof RenameStepError)) throw e;
                io.err(e.step === 'journal'
                    ? `contract rename: cannot write its journal in ${safeName(outLabel)}: ${e.message}; nothing was renamed\n`
                    : e.step === 'carry-over'
                        ? `contract rename: ${e.message}; the .contract files were not changed\n`
                        : `contract rename: writing the renamed files failed: ${e.message}; ${journaled ? `the next contract generate finishes the rename (its journal ${safeName(join(outLabel, RENAME_JOURNAL_NAME))} is kept)` : 'some may be renamed and others not'}\n`);
                return EXIT_FAILURE;
            }
            if (carried.moved) {
                io.out(`${safeName(outLabel)}: ${carried.moved.movedPaths.length} path(s) moved, ${carried.moved.regionIds.length} protected region ID(s) rewritten\n`);
                for (const m of carried.moved.movedPaths) io.out(`  ${safeName(m.from)} -> ${safeName(m.to)}\n`);
                for (const d of carried.moved.descriptions) io.out(`${inTree(d.file)}:${d.line}: default description ${safeName(d.from)} -> ${safeName(d.to)}\n`);
            }
            // the user code: a port or parameter is a variable of its module's module.c, a datatype, an
            // enumeration (its constants too) or a function a C name of every file: their uses in the
            // protected regions followed (whole C identifiers in code only; a module's name is in
            // strings, if anywhere: listed below)
            if (carried.code) {
                for (const r of carried.code.rewritten) {
                    io.out(`${inTree(r.file)}:${r.line}: protected region ${safeName(r.id)}: ${r.occurrences} use(s) of ${[...identifiers.keys()][0]}${identifiers.size > 1 ? ` (or its ${plan.kind === 'enumeration' ? 'functions and constants' : 'functions'})` : ''} renamed\n`);
                }
                const taken = carried.code.refused;
                if (taken) io.err(`warning: ${safeName(carryRefusedMessage(taken, [...identifiers.keys()], `${outLabel.replace(/\/+$/, '')}/${taken.file}:${taken.line}`))}\n`);
            }
            const count = plan.files.reduce((n, f) => n + f.occurrences, 0);
            io.out(`renamed ${plan.kind} ${plan.oldName} -> ${plan.newName}: ${count} occurrence(s) in ${plan.files.length} file(s)\n`);
            for (const f of plan.files) io.out(`  ${safeName(join(dirArg, f.file))} (${f.occurrences})\n`);
            for (const change of scenarioChanges) {
                for (const e of change.edits) io.out(`${safeName(join(dirArg, e.file))}:${e.line}: ${safeName(e.before.trim())}  ->  ${safeName(e.after.trim())}\n`);
            }

            const renamed = await loadWorkspace(dir);
            const after = renamed.diagnostics.filter((d) => d.severity === 'error');
            if (after.length > 0) {
                io.err(formatText(after, (file) => join(dirArg, file)));
                io.err(`${summarize(renamed.diagnostics)} after the rename: nothing was generated\n`);
                return EXIT_FAILURE;
            }
            const report = generateArchitecture(renamed.documents, out);
            await printReport(io, report, outLabel, options.get('verbose') === true);
            io.err(`generated ${safeName(outLabel)}: ${report.created.length} created, ${report.updated.length} updated, ${report.unchanged.length} kept, ${report.orphaned.length} orphaned, ${report.errors.length} error(s)\n`);

            // user code the rename did not change: the build needs what is in code changed by hand
            let inCode = 0;
            if (MENTIONED_KINDS.has(plan.kind)) {
                const mentions = findRegionMentions(out, mentionMatcher(plan.kind, plan.oldName, enumeration), variable ? owner : undefined);
                inCode = printRegionMentions(io, mentions, plan.oldName, inTree);
                if (inCode > 0) io.err(`contract rename: ${plan.kind} renamed, but ${inCode} use(s) of ${plan.oldName} in protected-region code were not changed (listed above)\n`);
            }
            return report.errors.length > 0 || inCode > 0 ? EXIT_FAILURE : EXIT_OK;
        };
        try {
            return await renameHeld();
        } finally {
            release();
        }
    },
};

/** Errors that leave the text or the imports unknown (unresolved references are checked on the documents). */
function blocksRename(code: string): boolean {
    return code === 'lexing-error' || code === 'parsing-error' || code === 'linking-error' || code.startsWith('import-');
}
