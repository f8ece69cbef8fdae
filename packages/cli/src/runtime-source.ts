/**
 * Where the C runtime's sources are when neither --runtime nor CONTRACT_RUNTIME names them: inside
 * the installed CLI (the packed tarball carries them under runtime/: scripts/pack.mjs), else the
 * repository's runtime/ (a checkout). The build service builds them into the build cache on first
 * use; they are never built in place by `build` or `run`. `contract runtime-source DIR` copies
 * them out, for a build by hand (a robot, a cross compiler).
 */
import { cpSync, existsSync, lstatSync } from 'node:fs';
import { dirname, join, relative, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';
import { RUNTIME_SOURCE_PARTS } from '@contract-studio/conventions';

/** The runtime folder packed with the CLI (present in an installed tarball, absent in a checkout). */
export const PACKED_RUNTIME = resolve(dirname(fileURLToPath(import.meta.url)), '..', 'runtime');

/** What of runtime/ a user's build needs: what the tarball carries and `contract runtime-source` copies (its tests and benchmarks stay in the repository); the build cache keys the runtime by these alone. */
export const RUNTIME_PARTS = RUNTIME_SOURCE_PARTS;

/** The packed runtime when there is one, else `checkoutDefault` (the package's own default: the repository's runtime/). */
export function defaultRuntimeSource(checkoutDefault: string): string {
    return existsSync(join(PACKED_RUNTIME, 'Makefile')) ? PACKED_RUNTIME : checkoutDefault;
}

/**
 * Copies the runtime's sources (RUNTIME_PARTS of `from`) into `to`, never a build product (no
 * `build/` folder, no object, library or program); files already in `to` are overwritten, others
 * kept. Returns the relative paths of the files copied.
 */
export function copyRuntimeSources(from: string, to: string): string[] {
    const copied: string[] = [];
    const isBuildProduct = (rel: string): boolean => rel.split(sep).includes('build') || /\.(o|a|so)$/.test(rel);
    for (const part of RUNTIME_PARTS) {
        if (!existsSync(join(from, part))) continue;
        cpSync(join(from, part), join(to, part), {
            recursive: true,
            filter: (src) => {
                const rel = relative(from, src);
                if (isBuildProduct(rel)) return false;
                if (lstatSync(src).isFile()) copied.push(rel);
                return true;
            },
        });
    }
    return copied;
}
