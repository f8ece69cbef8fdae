/**
 * Reads a file the simulator is handed (a scenario, a user header of src-gen) as hostile input:
 * opened without following a link, a regular file only, at most `maxBytes`. Never throws.
 */
import { closeSync, constants, fstatSync, openSync, readSync } from 'node:fs';

export function readRegularFile(path: string, maxBytes: number): Buffer | { error: string } {
    let fd: number | undefined;
    try {
        // O_NONBLOCK: a FIFO named like a scenario or a header must not wait for a writer for ever (fstat refuses it next)
        fd = openSync(path, constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
        const st = fstatSync(fd);
        if (!st.isFile()) return { error: 'not a regular file' };
        if (st.size > maxBytes) return { error: `larger than ${maxBytes} bytes` };
        const buf = Buffer.alloc(st.size);
        let got = 0;
        while (got < st.size) {
            const n = readSync(fd, buf, got, st.size - got, got);
            if (n <= 0) break;
            got += n;
        }
        return buf.subarray(0, got);
    } catch (e) {
        return { error: (e as NodeJS.ErrnoException).code === 'ELOOP' ? 'a symbolic link (not followed)' : (e as Error).message };
    } finally {
        if (fd !== undefined) closeSync(fd);
    }
}
