/**
 * The user's own copy of a generated file in the project's src-gen (a common header whose
 * protected regions the simulator carries over, a file a compile error points into), read as
 * hostile input: a regular file only, bounded, no link followed out of src-gen. Never throws.
 */
import { realpathSync } from 'node:fs';
import { join, sep } from 'node:path';
import { readRegularFile } from '../read-regular-file.js';

export const MAX_USER_FILE_BYTES = 4 * 1024 * 1024;

/** `rel` (relative to `srcGen`) as latin1 text, or undefined (absent, not a regular file, too large, outside src-gen). */
export function readUserFile(srcGen: string, rel: string): string | undefined {
    try {
        const root = realpathSync(srcGen);
        const real = realpathSync(join(srcGen, rel));
        if (!real.startsWith(root + sep)) return undefined;
        const data = readRegularFile(real, MAX_USER_FILE_BYTES);
        return Buffer.isBuffer(data) ? data.toString('latin1') : undefined;
    } catch {
        return undefined;
    }
}
