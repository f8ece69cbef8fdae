/**
 * `contract cache [clear] [--cache-dir DIR]`: where the build cache is (the built runtime, one work
 * tree per project, the simulators of `simulate`; shared by `build`, `run`, `simulate` and the IDE), and how to empty it. Clearing waits for
 * a build still using a project, and unmounts the work trees a root service keeps mounted
 * (docs/getting-started.md "The build cache").
 */
import { existsSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { folderOption, parseArgs } from '../args.js';
import { EXIT_FAILURE, EXIT_OK, UsageError, type CliIO, type Command } from '../command.js';

export const cacheCommand: Command = {
    name: 'cache',
    summary: 'show or clear the build cache (built runtime, one work tree per project, simulators)',
    usage: [
        'usage: contract cache [clear] [--cache-dir DIR]',
        '  prints the cache folder and what it holds; `clear` removes it (the next build starts cold)',
        '  --cache-dir: the cache folder (default: $CONTRACT_CACHE_DIR, else $XDG_CACHE_HOME/contract-studio,',
        '               else ~/.cache/contract-studio; root: /var/cache/contract-studio)',
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        const { positionals, options } = parseArgs(args, ['cache-dir'], []);
        if (positionals.length > 1 || (positionals[0] !== undefined && positionals[0] !== 'clear')) throw new UsageError(`unknown cache action '${positionals.join(' ')}' (expected nothing or clear)`);
        const { resolveCacheDir, clearCache, CACHE_DIR_ENV, CACHE_ENTRY_NAMES } = await import('@contract-studio/build-service');
        const cache = resolveCacheDir(folderOption(options, 'cache-dir', io.cwd), process.env, process.getuid?.(), undefined, io.cwd);
        if (positionals[0] === 'clear') {
            if (!existsSync(cache.dir)) {
                io.err(`${cache.dir}: no build cache there, nothing to clear\n`);
                return EXIT_OK;
            }
            try {
                await clearCache(cache.dir, (holder) => io.err(`waiting for the build using a project (${holder}) ...\n`));
            } catch (e) {
                io.err(`contract cache: ${(e as Error).message}\n`);
                return EXIT_FAILURE;
            }
            io.err(`cleared ${cache.dir}\n`);
            return EXIT_OK;
        }
        const count = (sub: string, filter: (n: string) => boolean = () => true): number => {
            try {
                return readdirSync(join(cache.dir, sub)).filter(filter).length;
            } catch {
                return 0;
            }
        };
        io.out(`${cache.dir}\n`);
        io.err(`build cache (${cache.source}; move it with --cache-dir or ${CACHE_DIR_ENV}): ${count('runtime', (n) => CACHE_ENTRY_NAMES.runtime.test(n))} runtime build(s), ${count('projects')} project work tree(s), ${count('sim', (n) => CACHE_ENTRY_NAMES.sim.test(n))} simulator(s), ${count('generated', (n) => CACHE_ENTRY_NAMES.generated.test(n))} generated tree(s); \`contract cache clear\` empties it\n`);
        return EXIT_OK;
    },
};
