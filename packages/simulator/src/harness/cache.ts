/**
 * Where built simulators are kept (docs/simulation.md §3): the `sim/` folder of the persistent
 * build cache that `contract build`/`run` and the IDE use (docs/getting-started.md "The build
 * cache"), found the same way: `--cache-dir DIR`, else `$CONTRACT_CACHE_DIR`, else
 * `$XDG_CACHE_HOME/contract-studio`, else `~/.cache/contract-studio` (root:
 * `/var/cache/contract-studio`). The simulator executes what it finds there, so the folder is
 * trusted only under the build cache's own rules (a real folder of ours, writable by nobody else,
 * no link planted in place of `sim/`); a refusal is one sentence naming the folder and the fix.
 */
import { mkdirSync } from 'node:fs';
import { join } from 'node:path';
import { checkCacheEntry, prepareCacheDir, resolveCacheDir, type CacheDirChoice } from '@contract-studio/build-service/cache';

/** The cache's subfolder holding the simulators (`sim-<hash>/contract-sim`) and their build lock. */
export const SIM_CACHE_ENTRY = 'sim';

export interface SimCacheDir {
    /** The build cache root and where it came from (option, env, xdg, home, root default). */
    root: CacheDirChoice;
    /** `<root>/sim`. */
    dir: string;
}

/**
 * The simulators' folder under the build cache `explicitRoot` (resolved against `cwd`), else
 * under the default build cache; created when missing. `{ error }` when the cache cannot be trusted.
 */
export function simulatorCacheDir(explicitRoot?: string, env: NodeJS.ProcessEnv = process.env, cwd = process.cwd()): SimCacheDir | { error: string } {
    const root = resolveCacheDir(explicitRoot, env, process.getuid?.(), undefined, cwd);
    const refused = prepareCacheDir(root.dir, false);
    if (refused) return { error: refused };
    const dir = join(root.dir, SIM_CACHE_ENTRY);
    try {
        mkdirSync(dir, { mode: 0o700 });
    } catch (e) {
        if ((e as NodeJS.ErrnoException).code !== 'EEXIST') return { error: `cannot create ${dir}: ${(e as Error).message.split('\n')[0]}` };
    }
    const planted = checkCacheEntry(dir);
    if (planted) return { error: planted };
    return { root, dir };
}
