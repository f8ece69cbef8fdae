/**
 * `contract runtime-source DIR [--force]`: copies the C runtime's sources the CLI carries (the
 * packed runtime of an installed CLI, or a checkout's runtime/: runtime-source.ts) into DIR, with
 * no build product, so that a user with no checkout can build the runtime by hand (a robot, a
 * cross compiler) and point the generated Makefiles at it (docs/getting-started.md §4).
 * Refuses a DIR that is not empty unless --force (which overwrites the runtime's files there and
 * keeps the others).
 */
import { existsSync, mkdirSync, readdirSync, statSync } from 'node:fs';
import { resolve } from 'node:path';
import { parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';
import { safeName } from '../terminal-text.js';
import { copyRuntimeSources, defaultRuntimeSource } from '../runtime-source.js';

export const runtimeSourceCommand: Command = {
    name: 'runtime-source',
    summary: 'copy the C runtime\'s sources (no build products) into a folder, to build it by hand (a robot, a cross gcc)',
    usage: [
        'usage: contract runtime-source DIR [--force]',
        '  copies the sources of the C runtime this CLI carries (Makefile, include/, src/, launcher/, sim/)',
        '  into DIR, without build products. DIR must not exist or be empty, unless --force (the runtime\'s',
        '  files are overwritten, other files kept). Then, on the machine that builds the robot\'s programs:',
        '    make -C DIR                                            # build/libmodule.a, build/contract-launch (CC=... AR=... for a cross gcc)',
        '    make -C DIR install PREFIX=/opt/contract/runtime       # optional: where the generated Makefiles look by default',
        '    make -C src-gen/generated/architecture all CONTRACT_RUNTIME=DIR',
        'exit status: 0 copied, 1 DIR is not empty (without --force) or cannot be written, 2 bad usage',
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const { positionals, options } = parseArgs(args, [], ['force']);
        if (positionals.length !== 1) throw new UsageError(positionals.length ? 'expected exactly one DIR' : 'missing DIR (the folder to copy the runtime\'s sources into)');
        const dirArg = positionals[0]!;
        const dir = resolve(io.cwd, dirArg);
        if (existsSync(dir)) {
            if (!statSync(dir).isDirectory()) {
                io.err(`contract runtime-source: ${safeName(dirArg)} exists and is not a directory; nothing was copied\n`);
                return EXIT_FAILURE;
            }
            if (readdirSync(dir).length > 0 && options.get('force') !== true) {
                io.err(`contract runtime-source: ${safeName(dirArg)} is not empty; nothing was copied (name a new or empty folder, or add --force to overwrite the runtime's files there)\n`);
                return EXIT_FAILURE;
            }
        }
        // loaded when the command runs: the checkout's runtime/ is the build service's default
        const { DEFAULT_RUNTIME_SOURCE } = await import('@contract-studio/build-service');
        const from = defaultRuntimeSource(DEFAULT_RUNTIME_SOURCE);
        if (!existsSync(resolve(from, 'Makefile'))) {
            io.err(`contract runtime-source: this CLI carries no runtime (no Makefile in ${safeName(from)}); nothing was copied\n`);
            return EXIT_FAILURE;
        }
        mkdirSync(dir, { recursive: true });
        const files = copyRuntimeSources(from, dir);
        io.out(`copied the runtime's sources (${files.length} files, no build products) into ${safeName(dirArg)}\n`);
        io.err(`next: make -C ${safeName(dirArg)} (CC=... AR=... for a cross gcc), then make -C <project>/src-gen/generated/architecture all CONTRACT_RUNTIME=${safeName(dir)}\n`);
        return EXIT_OK;
    },
};
