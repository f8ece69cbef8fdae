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
import { writeFileAtomic as writeInFolder } from '@contract-studio/codegen/atomic-write';

export { isAtomicTempFile } from '@contract-studio/codegen/atomic-write';

/** Writes `data` to `target` atomically, creating its parent folders. */
export async function writeFileAtomic(target: string, data: string | Uint8Array): Promise<void> {
  const dir = dirname(target);
  await mkdir(dir, { recursive: true });
  writeInFolder(dir, basename(target), typeof data === 'string' ? Buffer.from(data) : data);
}
