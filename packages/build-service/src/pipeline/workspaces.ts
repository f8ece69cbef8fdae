/**
 * Job workspaces. Each has two folders:
 *   stage/ — trusted: the service's copy of the project and the generated tree; never mounted in
 *            a sandbox, so reading it (Cactal loading, protected-region scan) cannot be tricked;
 *   work/  — the sandbox's only writable folder, owned by the workspace's own non-root uid, filled
 *            from stage/ with no-follow writes that keep unchanged files (and their mtimes) as they are.
 * Jobs naming a project folder reuse that project's workspace (so a second build is a no-op make),
 * one job at a time; inline-file jobs get a fresh workspace, removed when the job ends.
 * Every workspace is removed, without following links, when the service closes.
 */
import { createHash } from 'node:crypto';
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';
import type { Owner } from '../util/safe-fs.js';
import { removeTreeNoFollow } from '../util/safe-fs.js';

export interface Workspace {
  readonly root: string;
  readonly stageDir: string;
  readonly workDir: string;
  readonly owner: Owner;
  /** True when an earlier job already used it (incremental build). */
  readonly reused: boolean;
  release(): Promise<void>;
}

interface Keyed {
  root: string;
  owner: Owner;
  used: boolean;
  lock: Promise<void>;
}

const UID_BASE = 100_000;
const UID_SPAN = 60_000;

export class WorkspaceManager {
  private readonly keyed = new Map<string, Keyed>();
  private readonly fresh = new Set<string>();
  /** Random start: two services on one machine rarely hand out the same uids. */
  private uidCounter = Math.floor(Math.random() * UID_SPAN);

  constructor(
    private readonly baseDir: string,
    /** Called before a workspace folder is deleted (docker removes the workspace's volume). */
    private readonly onRemove: (workDir: string) => Promise<void> = async () => {},
  ) {}

  private nextOwner(): Owner {
    const isRoot = process.getuid?.() === 0;
    if (!isRoot) return { uid: process.getuid?.() ?? 0, gid: process.getgid?.() ?? 0 };
    const uid = UID_BASE + (this.uidCounter++ % UID_SPAN);
    return { uid, gid: uid };
  }

  private async create(root: string, owner: Owner): Promise<void> {
    await fsp.mkdir(this.baseDir, { recursive: true, mode: 0o711 });
    await fsp.mkdir(root, { mode: 0o711 });
    await fsp.mkdir(join(root, 'stage'), { mode: 0o700 });
    await fsp.mkdir(join(root, 'work'), { mode: 0o755 });
    await fsp.lchown(join(root, 'work'), owner.uid, owner.gid);
  }

  /** A workspace for a project folder (`key` = its real path), waiting for the previous job on it. */
  async acquireForProject(key: string, sandbox: string): Promise<Workspace> {
    const id = createHash('sha256').update(`${sandbox}\0${key}`).digest('hex').slice(0, 16);
    let entry = this.keyed.get(id);
    if (!entry) {
      const root = join(this.baseDir, `ws-${id}`);
      const owner = this.nextOwner();
      await removeTreeNoFollow(root);
      await this.create(root, owner);
      entry = { root, owner, used: false, lock: Promise.resolve() };
      this.keyed.set(id, entry);
    }
    const e = entry;
    const previous = e.lock;
    let unlock!: () => void;
    e.lock = new Promise<void>((r) => (unlock = r));
    await previous;
    const reused = e.used;
    e.used = true;
    return {
      root: e.root,
      stageDir: join(e.root, 'stage'),
      workDir: join(e.root, 'work'),
      owner: e.owner,
      reused,
      release: async () => unlock(),
    };
  }

  /** A fresh workspace, removed on release. */
  async acquireFresh(jobId: string): Promise<Workspace> {
    const root = join(this.baseDir, `job-${jobId}`);
    const owner = this.nextOwner();
    await removeTreeNoFollow(root);
    await this.create(root, owner);
    this.fresh.add(root);
    return {
      root,
      stageDir: join(root, 'stage'),
      workDir: join(root, 'work'),
      owner,
      reused: false,
      release: async () => {
        this.fresh.delete(root);
        await this.onRemove(join(root, 'work')).catch(() => {});
        await removeTreeNoFollow(root);
      },
    };
  }

  /** Removes every workspace (call when no job runs any more). */
  async removeAll(): Promise<void> {
    for (const root of this.fresh) {
      await this.onRemove(join(root, 'work')).catch(() => {});
      await removeTreeNoFollow(root);
    }
    this.fresh.clear();
    for (const e of this.keyed.values()) {
      await e.lock;
      await this.onRemove(join(e.root, 'work')).catch(() => {});
      await removeTreeNoFollow(e.root);
    }
    this.keyed.clear();
  }
}
