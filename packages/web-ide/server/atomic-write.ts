/**
 * The IDE's saves go through codegen's writeFileAtomic (@contract-studio/codegen/atomic-write: a
 * temporary file created with O_EXCL|O_NOFOLLOW, fsync'ed, renamed over the target, the folder
 * fsync'ed), the one atomic write the generator uses too. Readers see either the old or the new
 * content, never a mix; on any failure the old file is untouched and the temp removed.
 * The workspace file API passes `target` as /proc/self/fd/N/name of a folder it opened without
 * following links (workspace-fs.ts): the temp file and the rename then stay in that folder.
 */
import { mkdir } from 'node:fs/promises';
import { basename, dirname } from 'node:path';
import { readdirSync, statSync, type Dirent } from 'node:fs';
import { isAtomicTempFile, writeFileAtomic as writeInFolder } from '@contract-studio/codegen/atomic-write';
import { removeStaleTemps } from '@contract-studio/codegen/stale-temp';

export { isAtomicTempFile };

/**
 * Folder (dev:ino) and file names whose leftover temp files this process already looked for: a
 * temp file is left only by a writer killed mid-save, so one look per file and process is
 * enough, not a listing of the folder at every save. Bounded: forgotten (looked again) past it.
 */
const swept = new Set<string>();
const SWEPT_MAX = 10_000;

/** The temp file of `name` a killed server (or generator) left in `dir`, removed once it is stale (stale-temp.ts: its writer gone). */
function removeStaleTempOf(dir: string, name: string): void {
  let key: string;
  try {
    const st = statSync(dir);
    key = `${st.dev}:${st.ino}/${name}`;
  } catch {
    return;
  }
  if (swept.has(key)) return;
  if (swept.size >= SWEPT_MAX) swept.clear();
  swept.add(key);
  const prefix = `.${name}.tmp-`;
  let own: Dirent[];
  try {
    own = readdirSync(dir, { withFileTypes: true }).filter((e) => e.name.startsWith(prefix) && isAtomicTempFile(e.name));
  } catch {
    return;
  }
  if (own.length) removeStaleTemps(dir, own);
}

/**
 * Writes `data` to `target` atomically, creating its parent folders; a temp file of the same
 * target that a server killed mid-save left there is removed first (it stayed, hidden, for ever).
 */
export async function writeFileAtomic(target: string, data: string | Uint8Array): Promise<void> {
  const dir = dirname(target);
  await mkdir(dir, { recursive: true });
  removeStaleTempOf(dir, basename(target));
  writeInFolder(dir, basename(target), typeof data === 'string' ? Buffer.from(data) : data);
}
