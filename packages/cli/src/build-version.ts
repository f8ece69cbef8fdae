/**
 * What `contract --version` prints: the package version and, when the build recorded it
 * (dist/build-info.json, written by scripts/write-build-info.mjs after tsc), the commit the build
 * was made from, so that two builds of the same version are told apart (CHANGELOG.md).
 */
import { readFileSync } from 'node:fs';

/** The package folder: both src/ and dist/ are one level below it. */
const PACKAGE_DIR = new URL('..', import.meta.url);

function readJson(url: URL): unknown {
    try {
        return JSON.parse(readFileSync(url, 'utf8'));
    } catch {
        return undefined;
    }
}

/** `0.1.0 (commit 0123456789ab)`, `... with uncommitted changes)`, or the version alone when no commit was recorded. */
export function versionText(packageDir: URL = PACKAGE_DIR): string {
    const pkg = readJson(new URL('package.json', packageDir)) as { version?: unknown } | undefined;
    const version = typeof pkg?.version === 'string' ? pkg.version : 'unknown';
    const info = readJson(new URL('dist/build-info.json', packageDir)) as { commit?: unknown; modified?: unknown } | undefined;
    if (typeof info?.commit !== 'string' || !/^[0-9a-f]{40}$/.test(info.commit)) return version;
    return `${version} (commit ${info.commit.slice(0, 12)}${info.modified === true ? ' with uncommitted changes' : ''})`;
}
