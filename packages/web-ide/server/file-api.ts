import type { IncomingMessage, ServerResponse } from 'node:http';
import { constants } from 'node:fs';
import { mkdir, open, rename } from 'node:fs/promises';
import { WorkspacePaths } from './workspace-paths.js';
import { flattenFiles, listFolder, listTree, listingCut } from './file-tree.js';
import { HttpError } from './http-error.js';
import { readBodyBytes, readJson, sendJson } from './http-util.js';
import { saveWorkspaceFile } from './guarded-write.js';
import { GeneratedTreeLock } from './generated-tree-lock.js';
import { WorkspaceFs } from './workspace-fs.js';
import { FileLocks } from './file-locks.js';
import { baseVersionOf, fileVersion } from './file-version.js';
import { undecodableLine } from './undecodable.js';
import { generatedUserCode, userCodeInFolder } from './generated-files.js';
import type { FolderContents } from './api-types.js';

/** A workspace file the editor opens, saves or creates: 8 MiB at most (GET and PUT /api/file, POST /api/create). */
const MAX_FILE_BYTES = 8 * 1024 * 1024;

const { O_WRONLY, O_CREAT, O_EXCL, O_NOFOLLOW } = constants;

/**
 * The workspace file API (all paths workspace-relative, '/' separators):
 *   GET    /api/tree                      -> {root, entries}
 *   GET    /api/file?path=P               -> {path, content, mtimeMs, version, undecodableLine?}   (version: file-version.ts;
 *          undecodableLine: the first line holding a byte that is not UTF-8, undecodable.ts)
 *   PUT    /api/file?path=P   body=text   -> {path, mtimeMs, version}   (atomic write; creates parents)
 *          header If-Match: "<version>" = the version the text was edited from: when the disk no
 *          longer has it -> 409 {stale: true, content, version} of the disk, nothing written
 *          (compare and write run in the file's queue, FileLocks); without the header: blind write
 *          a generated file (src-gen/generated/**, listed in the generator's manifest) is guarded:
 *          -> {path, mtimeMs, merged: true, reason, content} when its generated code differed from
 *          the disk's (the incoming regions were written into the disk text), 409 when it cannot be
 *          merged (unknown region, malformed text, a region-less file changed); see guarded-write.ts
 *   POST   /api/create  {path, type}      -> 201 {path}        (409 if it exists)
 *   POST   /api/rename  {from, to}        -> {from, to}        (409 if `to` exists)
 *   DELETE /api/file?path=P               -> {path}            (files and folders)
 *   GET    /api/user-code?path=P          -> {regions, restorable}   a generated file's protected regions holding user code
 *          (recorded first, as a build records them), and whether the next generation restores them if it is deleted
 *   GET    /api/folder-contents?path=F    -> {files, cut, userCode}   what deleting folder F deletes: how many files
 *          (as the tree lists them; `cut`: at its bounds) and its generated files holding user code, as /api/user-code says them
 * Returns false when the request is not for this API.
 */
export async function handleFileApi(
  paths: WorkspacePaths, req: IncomingMessage, res: ServerResponse, url: URL, treeLock = new GeneratedTreeLock(),
  fileLocks = new FileLocks(),
): Promise<boolean> {
  const route = `${req.method} ${url.pathname}`;
  // paths.entry gives the clear 400/403 answers ('..', absolute, a symlink leaving); every access
  // then goes through WorkspaceFs, folder by folder from the root, never following a symlink.
  const fs = paths.fs;
  switch (route) {
    case 'GET /api/tree':
      sendJson(res, 200, { root: paths.root, entries: await listTree(fs) });
      return true;
    case 'GET /api/file': {
      const rel = paths.entry(url.searchParams.get('path'));
      const answer = await fs.withParent(rel, false, async (dir, name) => {
        const { handle, stats: st } = await WorkspaceFs.openFile(dir, name, rel);
        try {
          if (st.isDirectory()) throw new HttpError(400, 'is a folder');
          if (st.size > MAX_FILE_BYTES) throw new HttpError(413, 'file larger than 8 MiB');
          const bytes = await handle.readFile();
          const line = undecodableLine(bytes);
          return { path: rel, content: bytes.toString('utf8'), mtimeMs: st.mtimeMs, version: fileVersion(bytes), ...(line !== undefined ? { undecodableLine: line } : {}) };
        } finally {
          await handle.close();
        }
      });
      sendJson(res, 200, answer);
      return true;
    }
    case 'PUT /api/file': {
      const rel = paths.entry(url.searchParams.get('path'));
      const base = baseVersionOf(req.headers['if-match']);
      if (base === 'invalid') throw new HttpError(400, 'If-Match must be one quoted SHA-256 version, as GET /api/file gives it');
      const body = await readBodyBytes(req);
      // what GET /api/file reads back: a file saved larger could not be opened again
      if (body.length > MAX_FILE_BYTES) throw new HttpError(413, 'file larger than 8 MiB: not saved (the editor opens files of 8 MiB at most)');
      sendJson(res, 200, await saveWorkspaceFile(paths, rel, body, treeLock, { base, fileLocks }));
      return true;
    }
    case 'POST /api/create': {
      const body = await readJson(req);
      checkNewName(body.path);
      const rel = paths.entry(body.path);
      if (typeof body.content === 'string' && Buffer.byteLength(body.content) > MAX_FILE_BYTES) throw new HttpError(413, 'file larger than 8 MiB: not created (the editor opens files of 8 MiB at most)');
      await fs.withParent(rel, true, async (dir, name) => {
        if (await WorkspaceFs.entry(dir, name)) throw new HttpError(409, `already exists: ${rel}`);
        if (body.type === 'dir') return mkdir(dir.at(name));
        // O_EXCL: never opens an existing entry, nor a symlink planted since the check
        const handle = await open(dir.at(name), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW, 0o644);
        try {
          await handle.writeFile(typeof body.content === 'string' ? body.content : '');
        } finally {
          await handle.close();
        }
      });
      sendJson(res, 201, { path: rel });
      return true;
    }
    case 'POST /api/rename': {
      const body = await readJson(req);
      const from = paths.entry(body.from);
      checkNewName(body.to);
      const to = paths.entry(body.to);
      if (to.startsWith(from + '/')) throw new HttpError(400, 'cannot move a folder into itself');
      await fs.withParent(from, false, (fromDir, fromName) =>
        fs.withParent(to, true, async (toDir, toName) => {
          if (!(await WorkspaceFs.entry(fromDir, fromName))) throw new HttpError(404, `not found: ${from}`);
          if (await WorkspaceFs.entry(toDir, toName)) throw new HttpError(409, `already exists: ${to}`);
          // rename(2) moves the entry itself: a symlink is moved as a link, never followed
          await rename(fromDir.at(fromName), toDir.at(toName));
        }),
      );
      sendJson(res, 200, { from, to });
      return true;
    }
    case 'GET /api/user-code': {
      const rel = paths.entry(url.searchParams.get('path'));
      sendJson(res, 200, await treeLock.run(() => generatedUserCode(paths.root, rel)));
      return true;
    }
    case 'GET /api/folder-contents': {
      const rel = paths.entry(url.searchParams.get('path'));
      const kind = await fs.withParent(rel, false, (dir, name) => WorkspaceFs.entry(dir, name));
      if (!kind) throw new HttpError(404, `not found: ${rel}`);
      if (!kind.isDirectory()) throw new HttpError(400, `not a folder: ${rel}`);
      const entries = await listFolder(fs, rel);
      const files = flattenFiles(entries);
      const contents: FolderContents = { files: files.length, cut: listingCut(entries), userCode: await treeLock.run(() => userCodeInFolder(paths.root, rel, files)) };
      sendJson(res, 200, contents);
      return true;
    }
    case 'DELETE /api/file': {
      const rel = paths.entry(url.searchParams.get('path'));
      await fs.withParent(rel, false, async (dir, name) => {
        if (!(await WorkspaceFs.entry(dir, name))) throw new HttpError(404, `not found: ${rel}`);
        await WorkspaceFs.remove(dir, name);
      });
      sendJson(res, 200, { path: rel });
      return true;
    }
    default:
      return false;
  }
}

/**
 * A name the IDE makes (a new file or folder, a rename's target): no control character, and no
 * bidirectional override, which shows a name as another (`x\u202Etnoc.c` reads `xc.contract`);
 * a part longer than the file system takes is said as such (it was a raw ENAMETOOLONG).
 */
function checkNewName(rel: unknown): void {
  if (typeof rel !== 'string') return; // the path's own checks say what is wrong
  // eslint-disable-next-line no-control-regex
  const bad = /[\u0000-\u001f\u007f\u200e\u200f\u202a-\u202e\u2066-\u2069]/.exec(rel);
  if (bad) throw new HttpError(400, `a name with the character U+${bad[0].charCodeAt(0).toString(16).toUpperCase().padStart(4, '0')} is refused: a control or bidirectional character shows a name as another one`);
  const long = rel.split(/[\\/]/).find((part) => Buffer.byteLength(part) > 255);
  if (long) throw new HttpError(400, `a name of more than 255 bytes is refused (the file system's bound): ${long.slice(0, 40)}…`);
}
