import { readFile, stat } from 'node:fs/promises';
import type { WorkspacePaths } from './workspace-paths.js';
import { writeFileAtomic } from './atomic-write.js';
import { HttpError } from './http-error.js';
import { isGeneratedFile, splitGeneratedPath } from './generated-files.js';
import { guardGeneratedWrite } from './region-guard.js';
import { loadRegionParser } from './integrations.js';
import type { GeneratedTreeLock } from './generated-tree-lock.js';
import type { FileWriteResponse } from './api-types.js';

async function readIfPresent(abs: string): Promise<Buffer | undefined> {
  try {
    return await readFile(abs);
  } catch (e) {
    if ((e as NodeJS.ErrnoException).code === 'ENOENT') return undefined;
    throw e;
  }
}

async function written(paths: WorkspacePaths, abs: string, extra: Partial<FileWriteResponse> = {}): Promise<FileWriteResponse> {
  return { path: paths.toRelative(abs), mtimeMs: (await stat(abs)).mtimeMs, ...extra };
}

/**
 * The save of PUT /api/file. A file the generator owns (generated-files.ts) is guarded
 * (region-guard.ts): only its protected regions are taken from `body`; the generated code around
 * them stays the disk's (answer `merged`), and a write that cannot be merged is refused with 409.
 * Every other file is written as given. Writes are atomic; guarded ones run under the tree lock,
 * so that Generate All cannot rewrite the file between the read and the write.
 */
export async function saveWorkspaceFile(paths: WorkspacePaths, abs: string, body: Buffer, lock: GeneratedTreeLock): Promise<FileWriteResponse> {
  const rel = paths.toRelative(abs);
  if (!splitGeneratedPath(rel)) {
    await writeFileAtomic(abs, body);
    return written(paths, abs);
  }
  return lock.run(async () => {
    const disk = (await readIfPresent(abs))?.toString('latin1');
    if (disk === undefined || !(await isGeneratedFile(paths.root, rel, disk))) {
      await writeFileAtomic(abs, body);
      return written(paths, abs);
    }
    const decision = guardGeneratedWrite(body.toString('latin1'), disk, rel, await loadRegionParser());
    if (decision.kind === 'refuse') {
      throw new HttpError(409, decision.message, { region: decision.region, line: decision.line, generated: true });
    }
    const bytes = Buffer.from(decision.text, 'latin1');
    if (decision.text !== disk) await writeFileAtomic(abs, bytes);
    if (decision.kind === 'write') return written(paths, abs);
    return written(paths, abs, { merged: true, reason: decision.reason, content: bytes.toString('utf8') });
  });
}
