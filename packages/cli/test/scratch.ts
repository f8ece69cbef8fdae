/**
 * Removes a test's scratch folder. A root `contract build` keeps each project's work tree mounted
 * (a tmpfs, the disk limit) in its build cache between commands, which plain `rm -rf` cannot
 * remove (EBUSY): every mount below the folder is unmounted first.
 */
import { execFileSync } from 'node:child_process';
import { readFileSync, rmSync } from 'node:fs';

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
