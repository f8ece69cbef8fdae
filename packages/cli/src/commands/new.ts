/**
 * `contract new DIR`: creates a small complete Cactal project (data types, two modules, a periodic
 * schema, the scheduler configuration, a supervisor) in DIR. The templates are the web IDE's "New
 * project" ones (one place: @contract-studio/language PROJECT_TEMPLATES), and a `.gitignore`
 * (project-gitignore.ts). Never overwrites a file.
 */
import { existsSync, mkdirSync, readdirSync, statSync, writeFileSync } from 'node:fs';
import { join, relative, resolve } from 'node:path';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';
import { safeName } from '../terminal-text.js';
import { PROJECT_GITIGNORE } from '../project-gitignore.js';

export const newCommand: Command = {
    name: 'new',
    summary: 'create a new Cactal project from the template (types, modules, schema, scheduler, supervisor)',
    usage: [
        'usage: contract new DIR',
        '  DIR must not exist or be empty; it gets 6 .contract files that check without errors, and a .gitignore',
        '  (logs/, src-gen/.contract-lock, src-gen/.contract-rename.json: commit the rest, src-gen/orphans/ too).',
        '  next: contract check DIR && contract build DIR && contract run DIR --duration 5s',
        'exit status: 0 created, 1 DIR is not empty or cannot be written, 2 bad usage',
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const { positionals } = parseArgs(args, []);
        if (positionals.length !== 1) throw new UsageError(positionals.length ? 'expected exactly one DIR' : 'missing DIR (the folder to create)');
        const dirArg = positionals[0]!;
        const dir = resolve(io.cwd, dirArg);
        if (existsSync(dir)) {
            if (!statSync(dir).isDirectory()) {
                io.err(`contract new: ${safeName(dirArg)} exists and is not a directory; pick another name\n`);
                return EXIT_FAILURE;
            }
            if (readdirSync(dir).length > 0) {
                io.err(`contract new: ${safeName(dirArg)} is not empty; nothing was written (pick a new or empty folder)\n`);
                return EXIT_FAILURE;
            }
        }
        // loaded when the command runs: `contract build`/`run` never pay for the language server (docs/getting-started.md "The build cache")
        const { PROJECT_TEMPLATES: templates } = await import('@contract-studio/language');
        mkdirSync(dir, { recursive: true });
        for (const [file, text] of [...Object.entries(templates), ['.gitignore', PROJECT_GITIGNORE] as const]) {
            writeFileSync(join(dir, file), text, { flag: 'wx' });
            io.out(`created ${safeName(join(relative(io.cwd, dir) || '.', file))}\n`);
        }
        io.err(`next: contract check ${safeName(dirArg)} && contract run ${safeName(dirArg)} --duration 5s\n`);
        return EXIT_OK;
    },
};
