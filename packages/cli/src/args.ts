/** Minimal argument parsing: positionals and `--name value` / `--name=value` options. */
import { resolve } from 'node:path';
import { UsageError } from './command.js';

export interface ParsedArgs {
    positionals: string[];
    options: Map<string, string | true>;
    /** The values of each repeatable option, in order (`--limit a=1 --limit b=2`). */
    repeated: Map<string, string[]>;
}

/**
 * `valued` lists options that take a value, `flags` those that do not, `repeatable` valued options
 * that may be given more than once (ParsedArgs.repeated); anything else is a usage error.
 */
export function parseArgs(args: string[], valued: string[], flags: string[] = [], repeatable: string[] = []): ParsedArgs {
    const positionals: string[] = [];
    const options = new Map<string, string | true>();
    const repeated = new Map<string, string[]>();
    for (let i = 0; i < args.length; i++) {
        const arg = args[i]!;
        if (arg === '--') { positionals.push(...args.slice(i + 1)); break; }
        if (arg.startsWith('-') && arg !== '-') {
            const eq = arg.indexOf('=');
            const name = (eq >= 0 ? arg.slice(0, eq) : arg).replace(/^--?/, '');
            if (repeatable.includes(name)) {
                const value = eq >= 0 ? arg.slice(eq + 1) : args[++i];
                if (value === undefined) throw new UsageError(`option --${name} needs a value`);
                repeated.set(name, [...(repeated.get(name) ?? []), value]);
            } else if (valued.includes(name)) {
                const value = eq >= 0 ? arg.slice(eq + 1) : args[++i];
                if (value === undefined) throw new UsageError(`option --${name} needs a value`);
                options.set(name, value);
            } else if (flags.includes(name) && eq < 0) {
                options.set(name, true);
            } else {
                throw new UsageError(`unknown option ${arg}`);
            }
        } else {
            positionals.push(arg);
        }
    }
    return { positionals, options, repeated };
}

/**
 * The folder a path option names (`--cache-dir DIR`), resolved against `cwd`; undefined when the
 * option is not given. An empty value is refused: resolved, it would name the current folder, and
 * `contract cache clear --cache-dir "$UNSET"` would then empty it.
 */
export function folderOption(options: Map<string, string | true>, name: string, cwd: string): string | undefined {
    const value = options.get(name);
    if (typeof value !== 'string') return undefined;
    if (value.trim() === '') throw new UsageError(`--${name} was given an empty value (an unset variable in the command?): name a folder, or leave the option out`);
    return resolve(cwd, value);
}
