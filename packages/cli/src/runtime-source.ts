/**
 * Where the C runtime's sources are when neither --runtime nor CONTRACT_RUNTIME names them: inside
 * the installed CLI (the packed tarball carries them under runtime/: scripts/pack.mjs), else the
 * repository's runtime/ (a checkout). The build service builds them into the build cache on first
 * use; they are never built in place by `build` or `run`.
 */
import { existsSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

/** The runtime folder packed with the CLI (present in an installed tarball, absent in a checkout). */
export const PACKED_RUNTIME = resolve(dirname(fileURLToPath(import.meta.url)), '..', 'runtime');

/** The packed runtime when there is one, else `checkoutDefault` (the package's own default: the repository's runtime/). */
export function defaultRuntimeSource(checkoutDefault: string): string {
    return existsSync(join(PACKED_RUNTIME, 'Makefile')) ? PACKED_RUNTIME : checkoutDefault;
}
