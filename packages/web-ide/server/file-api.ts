import type { IncomingMessage, ServerResponse } from 'node:http';
import { readFile, stat, mkdir, rename, rm, writeFile, lstat } from 'node:fs/promises';
import { dirname } from 'node:path';
import { WorkspacePaths } from './workspace-paths.js';
import { listTree } from './file-tree.js';
import { HttpError } from './http-error.js';
import { readBodyBytes, readJson, sendJson } from './http-util.js';
import { saveWorkspaceFile } from './guarded-write.js';
import { GeneratedTreeLock } from './generated-tree-lock.js';

/**
 * The workspace file API (all paths workspace-relative, '/' separators):
 *   GET    /api/tree                      -> {root, entries}
 *   GET    /api/file?path=P               -> {path, content, mtimeMs}
 *   PUT    /api/file?path=P   body=text   -> {path, mtimeMs}   (atomic write; creates parents)
 *          a generated file (src-gen/generated/**, listed in the generator's manifest) is guarded:
 *          -> {path, mtimeMs, merged: true, reason, content} when its generated code differed from
 *          the disk's (the incoming regions were written into the disk text), 409 when it cannot be
 *          merged (unknown region, malformed text, a region-less file changed); see guarded-write.ts
 *   POST   /api/create  {path, type}      -> 201 {path}        (409 if it exists)
 *   POST   /api/rename  {from, to}        -> {from, to}        (409 if `to` exists)
 *   DELETE /api/file?path=P               -> {path}            (files and folders)
 * Returns false when the request is not for this API.
 */
export async function handleFileApi(
  paths: WorkspacePaths, req: IncomingMessage, res: ServerResponse, url: URL, treeLock = new GeneratedTreeLock(),
): Promise<boolean> {
  const route = `${req.method} ${url.pathname}`;
  switch (route) {
    case 'GET /api/tree':
      sendJson(res, 200, { root: paths.root, entries: await listTree(paths.root) });
      return true;
    case 'GET /api/file': {
      const abs = paths.resolveEntry(url.searchParams.get('path'));
      const st = await stat(abs);
      if (st.isDirectory()) throw new HttpError(400, 'is a folder');
      if (st.size > 8 * 1024 * 1024) throw new HttpError(413, 'file larger than 8 MiB');
      sendJson(res, 200, { path: paths.toRelative(abs), content: await readFile(abs, 'utf8'), mtimeMs: st.mtimeMs });
      return true;
    }
    case 'PUT /api/file': {
      const abs = paths.resolveEntry(url.searchParams.get('path'));
      const body = await readBodyBytes(req);
      const existing = await lstat(abs).catch(() => undefined);
      if (existing?.isDirectory()) throw new HttpError(409, 'a folder has that name');
      sendJson(res, 200, await saveWorkspaceFile(paths, abs, body, treeLock));
      return true;
    }
    case 'POST /api/create': {
      const body = await readJson(req);
      const abs = paths.resolveEntry(body.path);
      if (await lstat(abs).catch(() => undefined)) throw new HttpError(409, `already exists: ${paths.toRelative(abs)}`);
      if (body.type === 'dir') await mkdir(abs, { recursive: true });
      else {
        await mkdir(dirname(abs), { recursive: true });
        await writeFile(abs, typeof body.content === 'string' ? body.content : '', { flag: 'wx' });
      }
      sendJson(res, 201, { path: paths.toRelative(abs) });
      return true;
    }
    case 'POST /api/rename': {
      const body = await readJson(req);
      const from = paths.resolveEntry(body.from);
      const to = paths.resolveEntry(body.to);
      await lstat(from);
      if (await lstat(to).catch(() => undefined)) throw new HttpError(409, `already exists: ${paths.toRelative(to)}`);
      if (to.startsWith(from + '/')) throw new HttpError(400, 'cannot move a folder into itself');
      await mkdir(dirname(to), { recursive: true });
      await rename(from, to);
      sendJson(res, 200, { from: paths.toRelative(from), to: paths.toRelative(to) });
      return true;
    }
    case 'DELETE /api/file': {
      const abs = paths.resolveEntry(url.searchParams.get('path'));
      await lstat(abs);
      await rm(abs, { recursive: true });
      sendJson(res, 200, { path: paths.toRelative(abs) });
      return true;
    }
    default:
      return false;
  }
}
