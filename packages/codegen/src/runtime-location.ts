import { existsSync } from 'node:fs';
import { dirname, isAbsolute, join, relative, resolve, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

/** Where the `contract-gcc` image installs the runtime (docs/architecture.md, seam 3). */
export const INSTALLED_RUNTIME = '/opt/contract/runtime';

/** The repository's runtime/ folder when this package runs inside the ContrACT Studio repo. */
export function repoRuntime(): string | undefined {
    const here = dirname(fileURLToPath(import.meta.url)); // packages/codegen/{src,dist}
    const candidate = resolve(here, '..', '..', '..', 'runtime');
    return existsSync(join(candidate, 'include', 'libmodule', 'libmodule.h')) ? candidate : undefined;
}

/**
 * The CONTRACT_RUNTIME default written in the architecture Makefile: `runtime` if given (an
 * absolute path becomes relative to the architecture folder, a relative one is taken as already
 * relative to it), else the repo's runtime, else the installed one.
 */
export function runtimeFromArchitecture(architectureDir: string, runtime?: string): string {
    if (runtime !== undefined && !isAbsolute(runtime)) return runtime.split(sep).join('/');
    const target = runtime ?? repoRuntime();
    if (!target) return INSTALLED_RUNTIME;
    if (target === INSTALLED_RUNTIME) return target;
    return relative(resolve(architectureDir), resolve(target)).split(sep).join('/') || '.';
}
