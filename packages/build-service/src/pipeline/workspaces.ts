/**
 * Job workspaces. Each has two folders:
 *   stage/ — trusted: the service's copy of the project and the generated tree; never mounted in
 *            a sandbox, so reading it (Cactal loading, protected-region scan) cannot be tricked;
 *   work/  — the sandbox's only writable folder, owned by the workspace's own non-root uid, filled
 *            from stage/ with no-follow writes that keep unchanged files (and their mtimes) as they are.
 *            For the host sandboxes (bwrap, none) work/ is a tmpfs of `workDiskMiB` when the service
 *            is root (sandbox/work-disk.ts): the job's disk bound.
 * Jobs naming a project folder reuse that project's workspace (so a second build is a no-op make),
 * one job at a time; inline-file jobs get a fresh workspace, removed when the job ends. A reused
 * work/ is only trusted as the last build left it (`acceptedOutputs`, docs/sandbox.md "Build
 * products between jobs"); `reset()` empties it otherwise.
 * Every workspace is removed, without following links, when the service closes — except the
 * persistent ones (`persistentDir`, the shared build cache of docs/getting-started.md "The build
 * cache"): those keep their stage/ and work/ across processes, with their uid and accepted digest
 * in state.json (cache/workspace-state.ts), and one command at a time per project across
 * processes (cache/project-lock.ts). Each also names its project folder (FOLDER_FILE). The first
 * persistent workspace a process acquires first sweeps the others: it removes the entries whose
 * folder is gone (a deleted or temporary project) and the least recently used beyond
 * `keptProjectWorkspaces` (limits.ts; last use = state.json's time), each under its lock taken
 * without waiting, so that their work trees — a tmpfs in memory when the service is root — do not
 * stay until `contract cache clear`.
 */
import { createHash } from 'node:crypto';
import { existsSync, promises as fsp } from 'node:fs';
import { dirname, join } from 'node:path';
import { canMountWorkDisk, mountWorkDisk, resizeWorkDisk, unmountWorkDisk, workDiskState } from '../sandbox/work-disk.js';
import type { Owner } from '../util/safe-fs.js';
import { removeTreeNoFollow } from '../util/safe-fs.js';
import { assertCacheEntry, CacheRefusedError, checkCacheEntry } from '../cache/cache-dir.js';
import { acquireProjectLock, tryProjectLock } from '../cache/project-lock.js';
import { readWorkspaceState, STATE_FILE, writeWorkspaceState, type WorkspaceState } from '../cache/workspace-state.js';
import { SERVICE_BOUNDS } from '../limits.js';
import { removeDeadServiceFolders } from './dead-service-folders.js';

export interface Workspace {
  readonly root: string;
  readonly stageDir: string;
  readonly workDir: string;
  readonly owner: Owner;
  /** True when an earlier job already used it (incremental build). */
  readonly reused: boolean;
  /**
   * Digest of work/ as the last build step that ended by itself left it (work-tree-digest.ts);
   * null when no build ended since work/ was last emptied. Set by the job.
   */
  acceptedOutputs: string | null;
  /** Empties work/ (and drops the sandbox's copy of it): the next build starts from scratch. */
  reset(): Promise<void>;
  release(): Promise<void>;
}

/** What a job waiting for its project's workspace is told, and how it stops waiting. */
export interface AcquireHooks {
  /** Another command (maybe another process) holds the project: called once, with who. */
  onWait?: (holder: string) => void;
  cancelled?: Promise<void>;
}

/** Size of the work tmpfs per acquire (bwrap, none); undefined: no tmpfs (docker bounds its volume). */
export type WorkDiskBytes = number | undefined;

interface Keyed {
  root: string;
  owner: Owner;
  used: boolean;
  acceptedOutputs: string | null;
  lock: Promise<void>;
  /** The folders' creation, registered before it runs so that two first jobs on a project make them once. */
  created?: Promise<void>;
}

/** In a persistent workspace: the project folder it is for (its real path), to find entries whose folder is gone. */
const FOLDER_FILE = 'folder';
const UID_BASE = 100_000;
const UID_SPAN = 60_000;

export interface WorkspaceManagerOptions {
  /** Called before a workspace folder is deleted (docker removes the workspace's volume). */
  onRemove?: (workDir: string) => Promise<void>;
  /** Project workspaces live here and outlive the service (the shared build cache); undefined: removed at close. */
  persistentDir?: string;
  /** How many of them the sweep keeps (the most recently used); default SERVICE_BOUNDS.keptProjectWorkspaces. */
  keptProjects?: number;
  /** baseDir is one service's folder (dead-service-folders.ts): remove dead services' beside it. */
  sweepDeadSiblings?: boolean;
}

export class WorkspaceManager {
  private readonly keyed = new Map<string, Keyed>();
  private readonly fresh = new Set<string>();
  /** The sweep of persistent entries (folder gone, or beyond the kept number): once per process. */
  private swept: Promise<void> | undefined;
  /** The removal of dead services' folders beside baseDir (dead-service-folders.ts): once. */
  private deadSwept: Promise<unknown> | undefined;
  /** Random start: two services on one machine rarely hand out the same uids. */
  private uidCounter = Math.floor(Math.random() * UID_SPAN);

  private readonly onRemove: (workDir: string) => Promise<void>;
  private readonly persistentDir: string | undefined;
  private readonly keptProjects: number;
  private readonly sweepDeadSiblings: boolean;

  constructor(
    private readonly baseDir: string,
    options: WorkspaceManagerOptions = {},
  ) {
    this.onRemove = options.onRemove ?? (async () => {});
    this.persistentDir = options.persistentDir;
    this.keptProjects = options.keptProjects ?? SERVICE_BOUNDS.keptProjectWorkspaces;
    this.sweepDeadSiblings = options.sweepDeadSiblings ?? false;
  }

  private nextOwner(): Owner {
    const isRoot = process.getuid?.() === 0;
    if (!isRoot) return { uid: process.getuid?.() ?? 0, gid: process.getgid?.() ?? 0 };
    const uid = UID_BASE + (this.uidCounter++ % UID_SPAN);
    return { uid, gid: uid };
  }

  /** A persistent workspace's uid: the same whichever process creates it (root: one of the job uids). */
  private ownerFor(id: string): Owner {
    if (process.getuid?.() !== 0) return this.nextOwner();
    const uid = UID_BASE + (parseInt(id.slice(0, 8), 16) % UID_SPAN);
    return { uid, gid: uid };
  }

  private async create(root: string, owner: Owner, disk: WorkDiskBytes): Promise<void> {
    if (this.sweepDeadSiblings) this.deadSwept ??= removeDeadServiceFolders(dirname(this.baseDir));
    await this.deadSwept;
    await fsp.mkdir(this.baseDir, { recursive: true, mode: 0o711 });
    await fsp.mkdir(root, { mode: 0o711 });
    await fsp.mkdir(join(root, 'stage'), { mode: 0o700 });
    await this.createWork(root, owner, disk);
  }

  private async createWork(root: string, owner: Owner, disk: WorkDiskBytes): Promise<void> {
    const work = join(root, 'work');
    await fsp.mkdir(work, { mode: 0o755 });
    await fsp.lchown(work, owner.uid, owner.gid);
    if (disk !== undefined && canMountWorkDisk()) await mountWorkDisk(work, disk, owner);
  }

  /** Unmounts work/ (the kernel drops its tree) and removes the rest without following links. */
  private async removeRoot(root: string): Promise<void> {
    await unmountWorkDisk(join(root, 'work'));
    await removeTreeNoFollow(root);
  }

  private async resetWork(root: string, owner: Owner, disk: WorkDiskBytes): Promise<void> {
    const work = join(root, 'work');
    await this.onRemove(work).catch(() => {});
    await unmountWorkDisk(work);
    await removeTreeNoFollow(work);
    await this.createWork(root, owner, disk);
  }

  /**
   * A workspace for a project folder (`key` = its real path), waiting for the previous job on it;
   * its work tmpfs takes this job's size (a refused resize, below what is used, empties it).
   */
  async acquireForProject(key: string, sandbox: string, disk?: WorkDiskBytes, hooks: AcquireHooks = {}): Promise<Workspace> {
    const id = createHash('sha256').update(`${sandbox}\0${key}`).digest('hex').slice(0, 16);
    if (this.persistentDir) return this.acquirePersistent(id, key, disk, hooks);
    let entry = this.keyed.get(id);
    if (!entry) {
      // registered before the first await: a second job on the project arriving meanwhile waits
      // for this one instead of removing and making the same folders under it
      const root = join(this.baseDir, `ws-${id}`);
      const owner = this.nextOwner();
      const created = this.removeRoot(root).then(() => this.create(root, owner, disk));
      const fresh: Keyed = { root, owner, used: false, acceptedOutputs: null, lock: created.then(() => {}, () => {}), created };
      created.catch(() => {
        if (this.keyed.get(id) === fresh) this.keyed.delete(id); // the next job tries again
      });
      entry = fresh;
      this.keyed.set(id, entry);
    }
    const e = entry;
    const previous = e.lock;
    let unlock!: () => void;
    e.lock = new Promise<void>((r) => (unlock = r));
    await previous;
    try {
      await e.created;
    } catch (err) {
      unlock();
      throw err;
    }
    let reused = e.used;
    e.used = true;
    const work = join(e.root, 'work');
    if (disk !== undefined && canMountWorkDisk()) {
      const state = await workDiskState(work);
      if (!state || (state.sizeBytes !== disk && !(await resizeWorkDisk(work, disk, e.owner)))) {
        await this.resetWork(e.root, e.owner, disk);
        e.acceptedOutputs = null;
        reused = false;
      }
    }
    return {
      root: e.root,
      stageDir: join(e.root, 'stage'),
      workDir: work,
      owner: e.owner,
      reused,
      get acceptedOutputs() {
        return e.acceptedOutputs;
      },
      set acceptedOutputs(v: string | null) {
        e.acceptedOutputs = v;
      },
      reset: async () => {
        e.acceptedOutputs = null;
        await this.resetWork(e.root, e.owner, disk);
      },
      release: async () => unlock(),
    };
  }

  /**
   * A persistent project workspace (see the header): waits for this process's previous job on it,
   * then for any other process's (flock), then trusts only what state.json and the checks allow.
   */
  private async acquirePersistent(id: string, folder: string, disk: WorkDiskBytes, hooks: AcquireHooks): Promise<Workspace> {
    const base = this.persistentDir!;
    await fsp.mkdir(base, { recursive: true, mode: 0o711 });
    assertCacheEntry(base);
    this.swept ??= this.sweep(base, id).catch(() => {});
    await this.swept;
    const root = join(base, id);
    await fsp.mkdir(root, { recursive: true, mode: 0o711 });
    assertCacheEntry(root);
    let entry = this.keyed.get(id);
    if (!entry) {
      entry = { root, owner: { uid: 0, gid: 0 }, used: true, acceptedOutputs: null, lock: Promise.resolve() };
      this.keyed.set(id, entry);
    }
    const e = entry;
    const previous = e.lock;
    let unlock!: () => void;
    e.lock = new Promise<void>((r) => (unlock = r));
    let fileLock;
    try {
      await previous;
      fileLock = await acquireProjectLock(join(root, 'lock'), hooks.onWait ?? (() => {}), hooks.cancelled);
    } catch (err) {
      unlock();
      throw err;
    }
    try {
      const work = join(root, 'work');
      const stage = join(root, 'stage');
      for (const p of [stage, work]) {
        const st = await fsp.lstat(p).catch(() => null);
        if (st && (st.isSymbolicLink() || !st.isDirectory())) throw new CacheRefusedError(`refusing the build cache: ${p} is ${st.isSymbolicLink() ? 'a symbolic link (planted?)' : 'not a folder'}; remove ${root} or choose another cache folder`);
      }
      let state: WorkspaceState | null = readWorkspaceState(root);
      let reused = state !== null;
      if (state) {
        await fsp.mkdir(stage, { mode: 0o700 }).catch(() => {});
        assertCacheEntry(stage);
        if (!(await fsp.lstat(work).catch(() => null))) {
          await this.createWork(root, state.owner, disk);
          state = { ...state, acceptedOutputs: null };
        }
      } else {
        // new, or its state was lost or unreadable: nothing in it is trusted
        state = { owner: this.ownerFor(id), acceptedOutputs: null };
        await unmountWorkDisk(work);
        await removeTreeNoFollow(work);
        await removeTreeNoFollow(stage);
        await fsp.mkdir(stage, { mode: 0o700 });
        await this.createWork(root, state.owner, disk);
      }
      const owner = state.owner;
      if (disk !== undefined && canMountWorkDisk()) {
        // not mounted any more (a reboot, a manual umount) or another size: start from an empty tmpfs
        const ds = await workDiskState(work);
        if (!ds || (ds.sizeBytes !== disk && !(await resizeWorkDisk(work, disk, owner)))) {
          await this.resetWork(root, owner, disk);
          state = { ...state, acceptedOutputs: null };
          reused = false;
        }
      }
      let accepted = state.acceptedOutputs;
      writeWorkspaceState(root, { owner, acceptedOutputs: accepted });
      // the id is the folder's hash: once written, the file never changes
      await fsp.writeFile(join(root, FOLDER_FILE), folder, { mode: 0o600, flag: 'wx' }).catch((e: NodeJS.ErrnoException) => {
        if (e.code !== 'EEXIST') throw e;
      });
      const lock = fileLock;
      return {
        root,
        stageDir: stage,
        workDir: work,
        owner,
        reused,
        get acceptedOutputs() {
          return accepted;
        },
        set acceptedOutputs(v: string | null) {
          accepted = v;
          writeWorkspaceState(root, { owner, acceptedOutputs: v });
        },
        reset: async () => {
          accepted = null;
          writeWorkspaceState(root, { owner, acceptedOutputs: null });
          await this.resetWork(root, owner, disk);
        },
        release: async () => {
          await lock.release();
          unlock();
        },
      };
    } catch (err) {
      await fileLock.release();
      unlock();
      throw err;
    }
  }

  /**
   * Removes the persistent entries whose project folder is gone, and the least recently used
   * beyond `keptProjects` (`current`, the entry being acquired, counts as the newest and stays).
   * Each under its lock taken without waiting: an entry a command holds stays (and counts). Entries
   * that are not the cache's own (a link, another owner) are never touched.
   */
  private async sweep(base: string, current: string): Promise<void> {
    const entries: Array<{ root: string; gone: boolean; usedAt: number }> = [];
    for (const id of await fsp.readdir(base).catch(() => [] as string[])) {
      if (!/^[0-9a-f]{16}$/.test(id) || id === current) continue;
      const root = join(base, id);
      if (checkCacheEntry(root)) continue;
      // an entry of an earlier version names no folder: only the kept number bounds it
      const folder = await fsp.readFile(join(root, FOLDER_FILE), 'utf8').then((t) => t.slice(0, 8192), () => null);
      const gone = folder !== null && folder.startsWith('/') && !existsSync(folder);
      const used = (await fsp.lstat(join(root, STATE_FILE)).catch(() => null)) ?? (await fsp.lstat(root).catch(() => null));
      entries.push({ root, gone, usedAt: used?.mtimeMs ?? 0 });
    }
    entries.sort((a, b) => b.usedAt - a.usedAt);
    let kept = 1; // the entry being acquired
    for (const e of entries) {
      if (!e.gone && kept < this.keptProjects) {
        kept++;
        continue;
      }
      if (!(await this.removeUnheld(e.root))) kept++;
    }
  }

  /** Removes a persistent entry unless a command holds its lock. True when removed. */
  private async removeUnheld(root: string): Promise<boolean> {
    const lock = await tryProjectLock(join(root, 'lock'));
    if (!lock) return false;
    try {
      await this.onRemove(join(root, 'work')).catch(() => {});
      await this.removeRoot(root);
      return true;
    } catch {
      return false; /* left for clear */
    } finally {
      await lock.release();
    }
  }

  /** A fresh workspace, removed on release. */
  async acquireFresh(jobId: string, disk?: WorkDiskBytes): Promise<Workspace> {
    const root = join(this.baseDir, `job-${jobId}`);
    const owner = this.nextOwner();
    await this.removeRoot(root);
    await this.create(root, owner, disk);
    this.fresh.add(root);
    let accepted: string | null = null;
    return {
      root,
      stageDir: join(root, 'stage'),
      workDir: join(root, 'work'),
      owner,
      reused: false,
      get acceptedOutputs() {
        return accepted;
      },
      set acceptedOutputs(v: string | null) {
        accepted = v;
      },
      reset: async () => {
        accepted = null;
        await this.resetWork(root, owner, disk);
      },
      release: async () => {
        this.fresh.delete(root);
        await this.onRemove(join(root, 'work')).catch(() => {});
        await this.removeRoot(root);
      },
    };
  }

  /** Removes every workspace (call when no job runs any more). */
  async removeAll(): Promise<void> {
    for (const root of this.fresh) {
      await this.onRemove(join(root, 'work')).catch(() => {});
      await this.removeRoot(root);
    }
    this.fresh.clear();
    for (const e of this.keyed.values()) {
      await e.lock;
      if (this.persistentDir) continue; // the build cache outlives the service
      await this.onRemove(join(e.root, 'work')).catch(() => {});
      await this.removeRoot(e.root);
    }
    this.keyed.clear();
  }
}
