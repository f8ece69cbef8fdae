/**
 * Removes a test's scratch folder. A root `contract build` keeps each project's work tree mounted
 * (a tmpfs, the disk limit) in its build cache between commands, which plain `rm -rf` cannot
 * remove (EBUSY): every mount below the folder is unmounted first.
 */
import { execFileSync } from 'node:child_process';
import { chmodSync, mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { seedRuntime } from '@contract-studio/build-service/test-support/runtime-seed';

export function removeScratch(root: string): void {
    const mounts = readFileSync('/proc/self/mounts', 'utf8')
        .split('\n')
        .map((l) => l.split(' ')[1] ?? '')
        .filter((p) => p.startsWith(`${root}/`))
        .sort((a, b) => b.length - a.length);
    for (const m of mounts) {
        try {
            execFileSync('umount', ['-l', m]);
        } catch {
            /* gone already */
        }
    }
    rmSync(root, { recursive: true, force: true });
}

/**
 * A test file's scratch folder, its build cache (`CONTRACT_CACHE_DIR`, set for the file) seeded
 * with the test run's built runtime: no test builds the runtime again.
 */
export async function makeSeededScratch(prefix: string): Promise<string> {
    const root = mkdtempSync(join(tmpdir(), prefix));
    chmodSync(root, 0o711); // the sandbox's own uid must reach the cache folder inside
    process.env.CONTRACT_CACHE_DIR = join(root, 'cache');
    await seedRuntime(join(root, 'cache'));
    return root;
}

/** Removes what makeSeededScratch made, and its CONTRACT_CACHE_DIR. */
export function removeSeededScratch(root: string): void {
    delete process.env.CONTRACT_CACHE_DIR;
    removeScratch(root);
}
