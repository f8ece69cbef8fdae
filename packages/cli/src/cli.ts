/** The `contract` dispatcher: `contract <command> [args]`, `contract --help`, `contract --version`. */
import { EXIT_FAILURE, EXIT_OK, EXIT_USAGE, UsageError, type CliIO, type Command } from './command.js';
import { COMMANDS } from './commands/index.js';
import { makeProcessIO } from './process-io.js';
import { versionText } from './build-version.js';
import { safeName, terminalSafeIO } from './terminal-text.js';
import { closestName } from '@contract-studio/language/near-names';


export function helpText(commands: Command[] = COMMANDS): string {
    const width = Math.max(...commands.map((c) => c.name.length));
    return [
        'usage: contract <command> [arguments]',
        '',
        'commands:',
        ...commands.map((c) => `  ${c.name.padEnd(width)}  ${c.summary}`),
        '',
        'contract <command> --help shows the usage of a command.',
        'exit status: 0 success, 1 failure (e.g. errors found, build failed, a module crashed), 2 bad usage,',
        '3 environment (no usable sandbox, a build cache folder that cannot be trusted),',
        '4 run incomplete (contract run: a limit hit, a module stuck, hung at the stop or ended early, the start request refused, output or logs cut), 130 interrupted.'
    ].join('\n') + '\n';
}

export const processIO: CliIO = makeProcessIO();

/** Runs `contract` with the given arguments; resolves to the exit code. Never throws. */
export async function runCli(argv: string[], rawIO: CliIO = processIO, commands: Command[] = COMMANDS): Promise<number> {
    // sandbox output, gcc messages and project file names are printed: no control character passes
    const io = terminalSafeIO(rawIO);
    const [name, ...rest] = argv;
    if (!name || name === '--help' || name === '-h' || name === 'help') {
        (name ? io.out : io.err)(helpText(commands));
        return name ? EXIT_OK : EXIT_USAGE;
    }
    if (name === '--version' || name === '-v') {
        io.out(`contract ${versionText()}\n`);
        return EXIT_OK;
    }
    const command = commands.find((c) => c.name === name);
    if (!command) {
        const near = closestName(name, commands.map((c) => c.name));
        io.err(`contract: unknown command '${safeName(name)}'${near ? `; did you mean '${near}'?` : ''}\n\n${helpText(commands)}`);
        return EXIT_USAGE;
    }
    if (rest.includes('--help') || rest.includes('-h')) {
        io.out(command.usage + '\n');
        return EXIT_OK;
    }
    try {
        return await command.run(rest, io);
    } catch (err) {
        if (err instanceof UsageError) {
            // the synopsis only: the whole option list (20 lines for run) buried the message
            io.err(`contract ${command.name}: ${err.message}\n${command.usage.split('\n')[0]}\n(contract ${command.name} --help lists every option)\n`);
            return EXIT_USAGE;
        }
        io.err(`contract ${command.name}: ${err instanceof Error ? err.message : String(err)}\n`);
        return EXIT_FAILURE;
    }
}
