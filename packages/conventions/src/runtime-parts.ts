/**
 * What of the C runtime's folder a user's build needs: what the packed CLI carries, what
 * `contract runtime-source` copies, and all the build cache's runtime key hashes (its tests,
 * benchmarks and image scripts stay in the repository and change no build). One list, so the CLI
 * run from a checkout and the packed CLI key the same runtime alike (docs/getting-started.md
 * "The build cache").
 */
export const RUNTIME_SOURCE_PARTS = ['Makefile', 'build-config.mk', 'installed.mk', 'engines.mk', 'README.md', 'include', 'src', 'launcher', 'sim'] as const;

/** True when `rel` (a `/`-separated path inside the runtime's folder) is one of RUNTIME_SOURCE_PARTS or inside one. */
export function isRuntimeSourcePart(rel: string): boolean {
    const top = rel.split('/')[0];
    return (RUNTIME_SOURCE_PARTS as readonly string[]).includes(top ?? '');
}
