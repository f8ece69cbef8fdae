import { mkdirSync, renameSync, rmSync, writeFileSync } from 'node:fs';
import { basename, dirname, join } from 'node:path';

/**
 * Writes `data` to `file` through a temporary file in the same folder and a rename: readers never
 * see half a file. `knownDirs` remembers folders already created during one tree write.
 */
export function writeFileAtomic(file: string, data: Buffer, knownDirs?: Set<string>): void {
    const dir = dirname(file);
    if (!knownDirs?.has(dir)) {
        mkdirSync(dir, { recursive: true });
        knownDirs?.add(dir);
    }
    const tmp = join(dir, `.${basename(file)}.tmp-${process.pid}`);
    try {
        writeFileSync(tmp, data);
        renameSync(tmp, file);
    } catch (e) {
        rmSync(tmp, { force: true });
        throw e;
    }
}
