/**
 * Where `contract run` writes the run's CSV logs (docs/watching-a-run.md, "One run per logs
 * folder"): the default DIR/logs is refused when it is a link (a name in an untrusted project
 * folder); the previous run's logs are moved aside to `OUT/previous/run-<time>/` (never deleted);
 * each log is written on its own (O_NOFOLLOW|O_NONBLOCK through the opened folder), a name taken by
 * a link, a FIFO or a folder refused and said, the others written. One run saves into a folder at a
 * time (two projects run with one --logs OUT and ending together): the folder's `.contract-lock`
 * (codegen's tree lock) across processes, a queue within one.
 */
import { constants, promises as fsp } from 'node:fs';
import { dirname, join } from 'node:path';
import { Readable } from 'node:stream';
import { pipeline } from 'node:stream/promises';
import { createGunzip } from 'node:zlib';
import type { Artifact, RunArtifacts } from '@contract-studio/build-service';
import { safeName } from '../terminal-text.js';
import { isLogFileName, LAUNCHER_LINES_FILE } from '@contract-studio/build-service/trace';
import { crashFileModule } from '@contract-studio/build-service/crash-files';

/**
 * A file of a run's logs folder: a module's CSV log, the crash file of a module that crashed
 * (`<MODULE>.crash`, docs/runtime-api.md "Crash file"), or the launcher's own lines
 * (`contract-launch.log`: how each module ended, read by `contract trace OUT`).
 */
const isRunLogFile = (name: string) => isLogFileName(name) || crashFileModule(name) !== undefined || name === LAUNCHER_LINES_FILE;

/**
 * Why the default logs folder (DIR/logs) cannot be written, or null. It is a name in the project
 * folder, which is not trusted (a cloned repository can hold any symlink): a link there would have
 * the run's CSV files written wherever it points. A folder the user names with --logs is theirs to
 * choose, link or not.
 */
export async function refusedDefaultLogs(logsDir: string): Promise<string | null> {
    const st = await fsp.lstat(logsDir).catch(() => null);
    if (!st || st.isDirectory()) return null;
    if (st.isSymbolicLink()) {
        const target = await fsp.readlink(logsDir).catch(() => '?');
        return `${safeName(logsDir)} is a symbolic link (to ${safeName(target)}): the CSV logs are not written through a link found in the project folder; remove it, or name a folder with --logs OUT`;
    }
    return `${safeName(logsDir)} is not a folder: remove it, or name a folder with --logs OUT`;
}

/**
 * Why a folder the user named with `--logs OUT` cannot take the run's logs, said before the run
 * (a file there, or a file on its way: the logs could not be written once the run ended), or null.
 * A link the user named is followed: it is theirs.
 */
export async function refusedLogsOut(logsDir: string): Promise<string | null> {
    const st = await fsp.stat(logsDir).catch((e: NodeJS.ErrnoException) => e);
    if (!(st instanceof Error)) return st.isDirectory() ? null : `${safeName(logsDir)} is not a folder: the CSV logs are written to a folder; name one with --logs OUT`;
    if (st.code !== 'ENOENT' && st.code !== 'ENOTDIR') return `${safeName(logsDir)} cannot be used for the CSV logs (${st.code ?? st.message})`;
    // made when the run ends: the nearest existing folder on its way must be one
    for (let up = dirname(logsDir); ; up = dirname(up)) {
        const a = await fsp.stat(up).catch(() => null);
        if (a) return a.isDirectory() ? null : `${safeName(logsDir)} cannot be made: ${safeName(up)} is not a folder; name a folder with --logs OUT`;
        if (dirname(up) === up) return null;
    }
}

/** Where the previous run's logs are moved, inside the logs folder. */
export const PREVIOUS_DIR = 'previous';

/** Why OUT/previous cannot take the previous run's logs (a link or a file there), or null. */
export async function refusedPrevious(logsDir: string): Promise<string | null> {
    const st = await fsp.lstat(join(logsDir, PREVIOUS_DIR)).catch(() => null);
    if (!st || st.isDirectory()) return null;
    return `${safeName(join(logsDir, PREVIOUS_DIR))} is ${st.isSymbolicLink() ? 'a symbolic link' : 'not a folder'}: the previous run's logs are moved there (never through a link); remove it, or name another folder with --logs OUT`;
}

export interface SavedLogs {
    /** The logs written, by name. */
    saved: string[];
    /** Logs not written, `NAME: why` (a link or another file of that name in the folder). */
    refused: string[];
    /** Where the previous run's logs were moved (OUT/previous/run-...), and how many. */
    movedAside: { folder: string; files: number } | null;
}

/** `run-2026-12-03T02-05-31` from a time (local, as the logs' own names). */
function runStamp(ms: number): string {
    const d = new Date(ms);
    const two = (n: number) => String(n).padStart(2, '0');
    return `run-${d.getFullYear()}-${two(d.getMonth() + 1)}-${two(d.getDate())}T${two(d.getHours())}-${two(d.getMinutes())}-${two(d.getSeconds())}`;
}

/** Opens (creating it) the folder `name` inside the folder open as `parent`, never through a link. */
async function openSubfolder(parent: fsp.FileHandle, name: string, exclusive: boolean): Promise<fsp.FileHandle> {
    const path = `/proc/self/fd/${parent.fd}/${name}`;
    await fsp.mkdir(path, { mode: 0o755 }).catch((e: NodeJS.ErrnoException) => {
        if (exclusive || e.code !== 'EEXIST') throw e;
    });
    return fsp.open(path, constants.O_RDONLY | constants.O_DIRECTORY | constants.O_NOFOLLOW);
}

/**
 * One run per logs folder: the CSV logs, crash files and launcher lines (regular `*.csv`, `<MODULE>.crash` and `contract-launch.log` files) already in the
 * folder open as `dir` — the previous run's — are moved into `previous/run-<time of the newest>/`
 * (never deleted; a link or anything else there is left alone). Returns that folder and the
 * number moved, or null when there was none.
 */
async function moveAsidePrevious(dir: fsp.FileHandle, to: string): Promise<SavedLogs['movedAside']> {
    const here = `/proc/self/fd/${dir.fd}`;
    const old: { name: string; mtime: number }[] = [];
    for (const name of await fsp.readdir(here)) {
        if (!isRunLogFile(name)) continue;
        const st = await fsp.lstat(`${here}/${name}`).catch(() => null);
        if (st?.isFile()) old.push({ name, mtime: st.mtimeMs });
    }
    if (!old.length) return null;
    const previous = await openSubfolder(dir, PREVIOUS_DIR, false);
    try {
        const stamp = runStamp(Math.max(...old.map((o) => o.mtime)));
        let run: fsp.FileHandle | undefined;
        let folder = stamp;
        for (let i = 2; !run; i++) {
            try {
                run = await openSubfolder(previous, folder, true);
            } catch (e) {
                if ((e as NodeJS.ErrnoException).code !== 'EEXIST' || i > 1000) throw e;
                folder = `${stamp}-${i}`;
            }
        }
        try {
            for (const o of old) await fsp.rename(`${here}/${o.name}`, `/proc/self/fd/${run.fd}/${o.name}`);
        } finally {
            await run.close().catch(() => {});
        }
        // the logs counted (the launcher's lines file goes with them, uncounted: `N file(s) moved` are logs)
        return { folder: join(to, PREVIOUS_DIR, folder), files: old.filter((o) => o.name !== LAUNCHER_LINES_FILE).length };
    } finally {
        await previous.close().catch(() => {});
    }
}

/** Who takes a logs folder's lock, as its error names the holder. */
const LOGS_WRITERS = 'a contract run saving its logs';

/** The saves of this process, by logs folder (device:inode): the tree lock is re-entrant within a process. */
const saving = new Map<string, Promise<unknown>>();

/**
 * `work` on the logs folder open as `dir`, when no other save of this process or of another holds
 * it: moving the previous run aside and writing this one's is then one step, not interleaved with
 * another run's (whose moves failed on the files this one had moved, and whose logs were mixed).
 */
async function holdingLogsFolder<T>(dir: fsp.FileHandle, shownAs: string, work: () => Promise<T>): Promise<T> {
    const st = await dir.stat();
    const key = `${st.dev}:${st.ino}`;
    const mine = (saving.get(key) ?? Promise.resolve()).catch(() => {}).then(async () => {
        const { lockTree } = await import('@contract-studio/codegen');
        const release = await lockTree(`/proc/self/fd/${dir.fd}`, shownAs, undefined, undefined, LOGS_WRITERS);
        try {
            return await work();
        } finally {
            release();
        }
    });
    const settled = mine.catch(() => {});
    saving.set(key, settled);
    try {
        return await mine;
    } finally {
        if (saving.get(key) === settled) saving.delete(key);
    }
}

/**
 * Writes the run's CSV logs and crash files, as the build service collected them out of the sandbox (any sandbox:
 * `job.artifacts`), into `to`, after moving the previous run's logs there aside (one run per
 * folder: `contract trace OUT` tells this run). Never writes through a link found there (the
 * folder itself, when `noFollowDir`, opened O_NOFOLLOW and written through its descriptor: a link
 * put there during the run is not followed either): a log whose name is taken by a link, a FIFO or
 * anything but a regular file is refused and said, the others are written.
 */
export async function saveLogs(artifacts: RunArtifacts | null, to: string, noFollowDir: boolean): Promise<SavedLogs> {
    const result: SavedLogs = { saved: [], refused: [], movedAside: null };
    // the CSV logs, the crash files (contract trace OUT tells where a module crashed from its crash file)
    // and the launcher's lines (how each module ended: one killed from outside told at its end)
    const files = (artifacts?.files ?? []).filter((f) => /^[\w.-]+\.csv$/.test(f.name) || crashFileModule(f.name) !== undefined || f.name === LAUNCHER_LINES_FILE);
    if (!files.length) return result;
    await fsp.mkdir(to, { recursive: true });
    const dir = await fsp.open(to, constants.O_RDONLY | constants.O_DIRECTORY | (noFollowDir ? constants.O_NOFOLLOW : 0));
    try {
        await holdingLogsFolder(dir, safeName(to), async () => {
            result.movedAside = await moveAsidePrevious(dir, to);
            for (const file of files) {
                const refused = await writeLog(dir, file);
                if (refused) result.refused.push(`${file.name}: ${refused}`);
                else result.saved.push(file.name);
            }
        });
    } finally {
        await dir.close().catch(() => {});
    }
    result.saved.sort();
    return result;
}

/** Writes one collected log into the folder open as `dir`; why it was not, or null. */
async function writeLog(dir: fsp.FileHandle, file: Artifact): Promise<string | null> {
    let handle: fsp.FileHandle;
    try {
        // O_NONBLOCK: a FIFO planted under a log's name fails (ENXIO) rather than wait for a reader
        handle = await fsp.open(`/proc/self/fd/${dir.fd}/${file.name}`, constants.O_WRONLY | constants.O_CREAT | constants.O_NOFOLLOW | constants.O_NONBLOCK, 0o644);
    } catch (e) {
        const code = (e as NodeJS.ErrnoException).code;
        return code === 'ELOOP' ? 'a symbolic link of that name is there (never written through)' : code === 'ENXIO' ? 'a FIFO of that name is there' : `cannot be written (${code ?? (e as Error).message})`;
    }
    try {
        const st = await handle.stat();
        if (!st.isFile()) return `${st.isDirectory() ? 'a folder' : 'something other than a file'} of that name is there`;
        await handle.truncate(0);
        // kept gzip-compressed by the service (an hour of logs is hundreds of MB): inflated as it is written
        await pipeline(Readable.from([file.gzip]), createGunzip(), handle.createWriteStream());
        return null;
    } finally {
        await handle.close().catch(() => {});
    }
}
