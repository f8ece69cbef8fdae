/**
 * What a persistent project workspace remembers between processes (`<workspace>/state.json`, in
 * the trusted part of the cache, never mounted in a sandbox): the uid its work tree belongs to,
 * and the digest of the work tree as the last build step that ended by itself left it
 * (docs/sandbox.md "Build products between jobs"). It is written atomically (temporary file +
 * rename) and set to "no accepted digest" before a build starts, so a command killed mid-build
 * leaves a workspace the next command empties instead of trusting. A file that does not parse
 * as exactly this shape counts as absent: the workspace starts from scratch.
 */
import { readFileSync, renameSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import type { Owner } from '../util/safe-fs.js';

export interface WorkspaceState {
  owner: Owner;
  acceptedOutputs: string | null;
}

/** The file's name in the workspace (its modification time is the workspace's last use). */
export const STATE_FILE = 'state.json';
const MAX_BYTES = 4096;

function isId(v: unknown): v is number {
  return typeof v === 'number' && Number.isInteger(v) && v >= 0 && v < 2 ** 31;
}

export function readWorkspaceState(root: string): WorkspaceState | null {
  let text: string;
  try {
    text = readFileSync(join(root, STATE_FILE), 'utf8');
  } catch {
    return null;
  }
  if (text.length > MAX_BYTES) return null;
  try {
    const v = JSON.parse(text) as { version?: unknown; owner?: { uid?: unknown; gid?: unknown }; acceptedOutputs?: unknown };
    if (v.version !== 1 || !v.owner || !isId(v.owner.uid) || !isId(v.owner.gid)) return null;
    const accepted = v.acceptedOutputs;
    if (accepted !== null && !(typeof accepted === 'string' && /^[0-9a-f]{64}$/.test(accepted))) return null;
    return { owner: { uid: v.owner.uid, gid: v.owner.gid }, acceptedOutputs: accepted };
  } catch {
    return null;
  }
}

export function writeWorkspaceState(root: string, state: WorkspaceState): void {
  const tmp = join(root, `${STATE_FILE}.${process.pid}.tmp`);
  writeFileSync(tmp, JSON.stringify({ version: 1, owner: state.owner, acceptedOutputs: state.acceptedOutputs }), { mode: 0o600 });
  renameSync(tmp, join(root, STATE_FILE));
}
