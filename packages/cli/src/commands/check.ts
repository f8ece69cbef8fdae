/**
 * `contract check DIR [--format text|json|sarif]`: loads every `.contract` file under DIR, builds the
 * workspace and prints its diagnostics. Exit 1 when there is an error, 0 otherwise, 2 on bad usage.
 * A DIR of several projects (docs/codegen.md "Where a project is": `examples/`) is checked project
 * by project, each as if alone (its names, its scheduler configuration), as `contract serve DIR`
 * shows it; the summary names the projects. (`generate` refuses such a DIR: it writes one tree.)
 */
import { stat } from 'node:fs/promises';
import { join, resolve } from 'node:path';
import type { WorkspaceDiagnostic } from '@contract-studio/language/node';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';
import { formatJson, formatSarif, formatText, summarize } from '../diagnostic-format.js';
import { safeName } from '../terminal-text.js';

const FORMATS = ['text', 'json', 'sarif'] as const;
type Format = (typeof FORMATS)[number];

export const checkCommand: Command = {
    name: 'check',
    summary: 'check a Cactal project and print its diagnostics',
    usage: [
        'usage: contract check DIR [--format text|json|sarif]',
        '  text (default): one line per diagnostic, `DIR/file:line:col severity code message`',
        '  json: {"diagnostics":[{"file","line","column","severity","code","message"}]} (file relative to DIR)',
        '  sarif: SARIF 2.1.0 log',
        'a DIR holding several projects (each a first-level folder, or the folders holding a src-gen/) is checked project by project, each as if alone',
        'exit status: 1 when there is an error or no .contract file in DIR, 0 otherwise (warnings and hints do not fail), 2 on bad usage'
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const { positionals, options } = parseArgs(args, ['format']);
        if (positionals.length !== 1) throw new UsageError(positionals.length ? 'expected exactly one DIR' : 'missing DIR');
        const format = (options.get('format') ?? 'text') as Format;
        if (!FORMATS.includes(format)) throw new UsageError(`unknown format '${String(format)}' (expected text, json or sarif)`);
        const dirArg = positionals[0]!;
        const dir = resolve(io.cwd, dirArg);
        const info = await stat(dir).catch(() => undefined);
        if (!info?.isDirectory()) throw new UsageError(`${safeName(dirArg)} is not a directory`);

        // loaded when the command runs: `contract build`/`run` never pay for the language server (docs/getting-started.md "The build cache")
        const { loadWorkspace } = await import('@contract-studio/language/node');
        const workspace = await loadWorkspace(dir);
        const diagnostics: WorkspaceDiagnostic[] = workspace.diagnostics;
        if (format === 'json') io.out(formatJson(diagnostics));
        else if (format === 'sarif') io.out(formatSarif(diagnostics, dir, (await import('@contract-studio/language')).findCode));
        else {
            const text = formatText(diagnostics, (file) => join(dirArg, file));
            if (text) io.out(text);
            const { roots } = workspace.layout;
            const projects = roots.length > 1 ? ` of ${roots.length} projects (${roots.map((r) => safeName(`${r}/`)).join(', ')}), each checked alone` : '';
            io.err(`${summarize(diagnostics)} in ${workspace.documents.length} file${workspace.documents.length === 1 ? '' : 's'}${projects}\n`);
        }
        if (workspace.documents.length === 0 && !diagnostics.some((d) => d.code === 'source-too-large')) {
            // nothing checked is no green light (a CI step given the wrong folder)
            io.err(`no .contract file in ${safeName(dirArg)}: nothing was checked (a project is the folder of its .contract files)\n`);
            return EXIT_FAILURE;
        }
        return diagnostics.some((d) => d.severity === 'error') ? EXIT_FAILURE : EXIT_OK;
    }
};
