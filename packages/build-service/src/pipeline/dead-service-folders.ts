/**
 * The per-job work folders that dead services left (docs/sandbox.md "What a killed service leaves").
 * Each service keeps its fresh workspaces under `<cacheDir>/ws/s<owner tag>` (process-owner.ts),
 * and removes that folder when it closes. A service killed with -9 cannot: its folders stay, and
 * with them their work tmpfs (memory, up to `workDiskMiB` each, until a reboot). Before a service
 * makes its first workspace there, it removes its dead siblings' folders: each work tmpfs
 * unmounted first (the kernel drops its tree), then the rest removed without following links.
 * Folders of live services, of services in another pid namespace, and any other name are left.
 */
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { currentProcessOwner, isProcessAlive, judgeOwnerTag, OWNER_TAG, ownerTag, type ProcessOwner } from '../sandbox/process-owner.js';
import { unmountWorkDisk } from '../sandbox/work-disk.js';
import { removeTreeNoFollow } from '../util/safe-fs.js';

const SERVICE_FOLDER = new RegExp(`^s${OWNER_TAG}$`);

/** The folder of `owner`'s fresh workspaces under `wsDir`. */
export function serviceFolder(wsDir: string, owner: ProcessOwner = currentProcessOwner()): string {
  return join(wsDir, `s${ownerTag(owner)}`);
}

/** Removes the folders of dead services under `wsDir`; returns their names. Never throws. */
export async function removeDeadServiceFolders(
  wsDir: string,
  self: ProcessOwner = currentProcessOwner(),
  alive: (pid: number, startTime: string) => boolean = isProcessAlive,
): Promise<string[]> {
  const removed: string[] = [];
  const entries = await fsp.readdir(wsDir, { withFileTypes: true }).catch(() => []);
  for (const e of entries) {
    const m = SERVICE_FOLDER.exec(e.name);
    if (!m || !e.isDirectory() || judgeOwnerTag(m[1]!, m[2]!, m[3]!, self, alive) !== 'dead') continue;
    const folder = join(wsDir, e.name);
    try {
      for (const w of await fsp.readdir(folder, { withFileTypes: true })) {
        if (w.isDirectory()) await unmountWorkDisk(join(folder, w.name, 'work'));
      }
      await removeTreeNoFollow(folder);
      removed.push(e.name);
    } catch {
      /* left as it is: a later service tries again */
    }
  }
  return removed;
}
