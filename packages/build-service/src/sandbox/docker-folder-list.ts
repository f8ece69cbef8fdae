/**
 * Lists one folder of a Docker work volume with `find` run in the volume's holder, before anything
 * of it is read: names, kinds and sizes, no link followed, at most a bounded number of entries.
 * The artifact collector (docker.ts readWorkDirs) needs the sizes first: the archive API streams a
 * file's every byte, and a sandboxed program can leave a sparse file of a terabyte in logs/.
 */
import type { Readable } from 'node:stream';
import type { TarEntryKind } from '../util/tar-reader.js';
import { LOG_NAME_GLOB } from '../trace/parse.js';

export interface FoundEntry {
  name: string;
  kind: TarEntryKind;
  size: number;
}

/** A folder as find saw it: its entries (`more` when there were others), not a folder, or none (null). */
export type FoundFolder = { entries: FoundEntry[]; more: boolean } | { notDirectory: TarEntryKind } | null;

/** One entry as find prints it: `type size name\0`. */
const PRINTF = '%y %s %P\\0';

/**
 * The command that lists `dir`: the folder itself first (depth 0, an empty name), then its entries
 * named as the runtime names its logs (LOG_NAME_GLOB), then the others, `type size name\0` each.
 * The runtime's logs come first so that the entries looked at (a bound) hold them even when the
 * program left thousands of files of its own beside them (artifacts.ts collectionRank takes them
 * first too); find never follows a link (-P), the folder itself included.
 */
export function folderListCommand(dir: string): string[] {
  const find = (what: string): string => `find -P "$1" ${what} -printf '${PRINTF}'`;
  const script = `${find('-maxdepth 0')} && ${find('-mindepth 1 -maxdepth 1 -name "$2"')} && ${find('-mindepth 1 -maxdepth 1 ! -name "$2"')}`;
  return ['sh', '-c', script, 'folder-list', dir, LOG_NAME_GLOB];
}

/** A name longer than this is not one a file system gives (255 bytes): the output is not find's. */
const MAX_RECORD = 4096;

const kindOf = (y: string): TarEntryKind => (y === 'f' ? 'file' : y === 'd' ? 'dir' : y === 'l' ? 'symlink' : 'other');

/**
 * Reads find's output (folderListCommand) up to `maxEntries` entries, then calls `stop`. Never
 * throws: output it cannot read ends the listing there.
 */
export function readFolderList(stdout: Readable, maxEntries: number, stop: () => void): Promise<FoundFolder> {
  return new Promise((resolve) => {
    let buf: Buffer = Buffer.alloc(0);
    let self: { kind: TarEntryKind } | null = null;
    const entries: FoundEntry[] = [];
    let done = false;
    const finish = (more: boolean): void => {
      if (done) return;
      done = true;
      stdout.removeAllListeners('data');
      if (more) stop();
      if (!self) resolve(null);
      else if (self.kind !== 'dir') resolve({ notDirectory: self.kind });
      else resolve({ entries, more });
    };
    stdout.on('data', (chunk: Buffer) => {
      if (done) return;
      buf = buf.length ? Buffer.concat([buf, chunk]) : chunk;
      let nul: number;
      while ((nul = buf.indexOf(0)) >= 0) {
        const m = /^([a-zA-Z]) (\d+) ([^]*)$/.exec(buf.toString('utf8', 0, nul));
        buf = buf.subarray(nul + 1);
        if (!m) return finish(true);
        if (!self) {
          self = { kind: kindOf(m[1]!) };
          if (self.kind !== 'dir') return finish(true);
          continue;
        }
        if (entries.length >= maxEntries) return finish(true);
        if (m[3] === '' || m[3]!.includes('/')) return finish(true);
        entries.push({ name: m[3]!, kind: kindOf(m[1]!), size: Number(m[2]) });
      }
      if (buf.length > MAX_RECORD) finish(true);
    });
    stdout.on('end', () => finish(false));
    stdout.on('close', () => finish(false));
    stdout.on('error', () => finish(false));
  });
}
