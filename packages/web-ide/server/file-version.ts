import { createHash } from 'node:crypto';

/**
 * The version of a workspace file: the SHA-256 of its bytes (hex). GET /api/file and the snapshot
 * hand it out; every IDE save names the version it edits (`If-Match`), so the server can tell a
 * save made on the text now on disk from one made on an older text (docs/ide.md, "Saves, versions
 * and merges").
 */
export function fileVersion(bytes: Buffer): string {
  return createHash('sha256').update(bytes).digest('hex');
}

/**
 * The version a request says it edits: `If-Match: "<hex>"` (a weak `W/` prefix is ignored).
 * Absent → undefined (a blind write: programs that do not track versions). Anything else that is
 * not one SHA-256 in hex is a client error (never compared, never thrown at the server).
 */
export function baseVersionOf(header: string | string[] | undefined): string | undefined | 'invalid' {
  if (header === undefined) return undefined;
  if (Array.isArray(header) || header.length > 100) return 'invalid';
  const v = header.trim().replace(/^W\//, '').replace(/^"(.*)"$/, '$1');
  return /^[0-9a-f]{64}$/.test(v) ? v : 'invalid';
}
