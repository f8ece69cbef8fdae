/**
 * The launcher's lines file of a logs folder (`contract-launch.log`: build-service
 * trace/launcher-lines-file.ts), read for `contract trace LOGDIR`: a regular file only, never
 * through a link, its first MAX_LAUNCHER_LINES_BYTES read; none there is no problem (a run's logs
 * of an older launcher, or of `contract-launch` run without `--log-dir`).
 */
import { constants, promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { LAUNCHER_LINES_FILE, MAX_LAUNCHER_LINES_BYTES, launcherLinesOfFile, type LauncherFileLine } from '@contract-studio/build-service/trace';

/** The end lines of `dir`'s launcher lines file, in time order; `problems` gets a line when one is there and is not read, or is read in part. */
export async function readLauncherLines(dir: string, problems: string[]): Promise<LauncherFileLine[]> {
    let fh: fsp.FileHandle;
    try {
        fh = await fsp.open(join(dir, LAUNCHER_LINES_FILE), constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
    } catch (e) {
        const code = (e as NodeJS.ErrnoException).code;
        if (code === 'ENOENT') return [];
        problems.push(`${LAUNCHER_LINES_FILE}: ${code === 'ELOOP' ? 'a symbolic link' : (e as Error).message}, not read (the launcher's lines: how each module ended)`);
        return [];
    }
    try {
        const st = await fh.stat();
        if (!st.isFile()) {
            problems.push(`${LAUNCHER_LINES_FILE}: not a regular file, not read (the launcher's lines: how each module ended)`);
            return [];
        }
        const buf = Buffer.alloc(MAX_LAUNCHER_LINES_BYTES);
        const { bytesRead } = await fh.read(buf, 0, MAX_LAUNCHER_LINES_BYTES, 0);
        if (st.size > MAX_LAUNCHER_LINES_BYTES) problems.push(`${LAUNCHER_LINES_FILE}: only its first ${MAX_LAUNCHER_LINES_BYTES} of ${st.size} bytes read (the launcher writes ${MAX_LAUNCHER_LINES_BYTES} at most)`);
        return launcherLinesOfFile(buf.subarray(0, bytesRead).toString('utf8'));
    } catch (e) {
        problems.push(`${LAUNCHER_LINES_FILE}: ${(e as Error).message}, not read`);
        return [];
    } finally {
        await fh.close().catch(() => undefined);
    }
}
