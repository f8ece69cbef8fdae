/**
 * A Docker job's memory and process limit hits, seen while it runs as bwrap's are (docs/sandbox.md
 * "Memory and process limits in Docker"): the engine enforces `Memory` and `PidsLimit` in the
 * container's own cgroup, and the service finds that cgroup from the container's init
 * (`State.Pid` -> `/proc/<pid>/cgroup`) and polls its counters every 100 ms with the readers the
 * bwrap job cgroups use (cgroup.ts, cgroup-v2.ts): an OOM kill (`memory.oom_control` `oom_kill`,
 * v1; `memory.events` `oom_kill`, v2) or a refused fork (`pids.events` `max`) ends the job.
 *
 * Only a cgroup that names the container is used: the last folder of its path must be the
 * container's id (`/docker/<id>`, cgroupfs driver) or `docker-<id>.scope` (systemd driver), so a
 * pid that is not the container's here (a remote engine, another pid namespace, a reused pid)
 * reads as "no cgroup". Everything read is bounded and parsed defensively.
 *
 * When the cgroup cannot be read (a remote engine, the service in a container of its own, rootless
 * Docker in its own pid namespace, no permission), a memory kill is taken from the engine's `oom`
 * events for the container (the API, so a remote engine too) and a refused fork from the
 * program's own messages (docker.ts `noteLine`).
 */
import { join } from 'node:path';
import type { Readable } from 'node:stream';
import type Docker from 'dockerode';
import { readPidsLimitHits, readV1OomKills } from './cgroup.js';
import { readV2OomKills } from './cgroup-v2.js';
import { cgroupPids, readShmemBytes, readSmallFile } from './cgroup-procs.js';

/** Where cgroup v1 controllers are mounted (`<root>/memory`, `<root>/pids`), as cgroup.ts has it. */
export const CGROUP_V1_ROOT = '/sys/fs/cgroup';
/** Where the cgroup v2 hierarchy may be mounted: alone (unified host), or beside v1 (hybrid host). */
export const CGROUP_V2_ROOTS: readonly string[] = ['/sys/fs/cgroup', '/sys/fs/cgroup/unified'];
/** How often the counters are read (as host-process.ts for bwrap). */
export const CGROUP_WATCH_INTERVAL_MS = 100;
/** How often the engine is asked for the container's process count when its cgroup's counters are not read here (a one-shot stats call: 2-8 ms of the engine's). */
export const ENGINE_PIDS_INTERVAL_MS = 250;

/** /proc/<pid>/cgroup is read up to this many bytes; lines, paths and lines kept are bounded too. */
const PROC_CGROUP_MAX_BYTES = 16 * 1024;
const MAX_LINES = 64;
const MAX_PATH_CHARS = 1024;
/** A Docker container id: 64 lowercase hex digits. */
const CONTAINER_ID = /^[0-9a-f]{64}$/;

/** The entries of a /proc/<pid>/cgroup text: v1 controller -> path, and the v2 (`0::`) path. */
export interface ProcCgroupEntries {
  v1: Map<string, string>;
  unified: string | null;
}

/**
 * Parses /proc/<pid>/cgroup (`hierarchy-ID:controller-list:path` per line; `0::path` for v2).
 * A line that is not of that shape, or whose path is not a plain absolute path (no `.`/`..`
 * folder, no control character, at most 1024 characters), is left out; the first entry of a
 * controller wins.
 */
export function parseProcCgroup(text: string): ProcCgroupEntries {
  const out: ProcCgroupEntries = { v1: new Map(), unified: null };
  const lines = text.slice(0, PROC_CGROUP_MAX_BYTES).split('\n').slice(0, MAX_LINES);
  for (const line of lines) {
    const first = line.indexOf(':');
    const second = first < 0 ? -1 : line.indexOf(':', first + 1);
    if (second < 0) continue;
    const id = line.slice(0, first);
    const controllers = line.slice(first + 1, second);
    const path = line.slice(second + 1);
    if (!/^\d{1,6}$/.test(id) || !isPlainCgroupPath(path)) continue;
    if (id === '0' && controllers === '') {
      out.unified ??= path;
      continue;
    }
    for (const c of controllers.split(',')) {
      if (/^[a-z_=0-9]{1,32}$/.test(c) && !out.v1.has(c)) out.v1.set(c, path);
    }
  }
  return out;
}

function isPlainCgroupPath(path: string): boolean {
  if (!path.startsWith('/') || path.length > MAX_PATH_CHARS) return false;
  // eslint-disable-next-line no-control-regex
  if (/[\x00-\x1f\x7f]/.test(path)) return false;
  return path.split('/').every((seg) => seg !== '.' && seg !== '..');
}

/** Whether a cgroup path is the container's own: its last folder is `<id>` or `docker-<id>.scope`. */
export function namesContainer(path: string, containerId: string): boolean {
  if (!CONTAINER_ID.test(containerId)) return false;
  const last = path.slice(path.lastIndexOf('/') + 1);
  return last === containerId || last === `docker-${containerId}.scope`;
}

export type CgroupKind = 'cgroup-v1' | 'cgroup-v2';

/** Where one counter of the container is read. */
export interface CounterSource {
  kind: CgroupKind;
  dir: string;
}

/** Where the container's memory and process counters are read; null for what this host cannot read. */
export interface ContainerCgroupPlan {
  memory: CounterSource | null;
  pids: CounterSource | null;
}

export interface CgroupRoots {
  v1: string;
  v2: readonly string[];
}

/** Each controller's candidate folders, best first, with the counter file that proves one readable. */
function candidates(entries: ProcCgroupEntries, containerId: string, roots: CgroupRoots): Record<'memory' | 'pids', (CounterSource & { file: string })[]> {
  const list = (controller: 'memory' | 'pids', v1File: string, v2File: string): (CounterSource & { file: string })[] => {
    const out: (CounterSource & { file: string })[] = [];
    const v1 = entries.v1.get(controller);
    if (v1 !== undefined && namesContainer(v1, containerId)) {
      const dir = join(roots.v1, controller, v1);
      out.push({ kind: 'cgroup-v1', dir, file: join(dir, v1File) });
    }
    const v2 = entries.unified;
    if (v2 !== null && namesContainer(v2, containerId)) {
      for (const root of roots.v2) {
        const dir = join(root, v2);
        out.push({ kind: 'cgroup-v2', dir, file: join(dir, v2File) });
      }
    }
    return out;
  };
  return { memory: list('memory', 'memory.oom_control', 'memory.events'), pids: list('pids', 'pids.events', 'pids.events') };
}

/**
 * Where to read a container's counters (pure: `exists` says which files this host has). A
 * controller's v1 folder first (`<v1>/memory<path>/memory.oom_control`, `<v1>/pids<path>/pids.events`),
 * else the v2 folder (`<v2 root><path>/memory.events`, `.../pids.events`) under the first root that
 * has it: on a hybrid host the empty v2 hierarchy has the container's folder but no counters.
 */
export function planContainerCgroup(
  entries: ProcCgroupEntries,
  containerId: string,
  exists: (file: string) => boolean,
  roots: CgroupRoots = { v1: CGROUP_V1_ROOT, v2: CGROUP_V2_ROOTS },
): ContainerCgroupPlan {
  const c = candidates(entries, containerId, roots);
  const first = (l: (CounterSource & { file: string })[]): CounterSource | null => {
    const found = l.find((s) => exists(s.file));
    return found ? { kind: found.kind, dir: found.dir } : null;
  };
  return { memory: first(c.memory), pids: first(c.pids) };
}

/** One line for the service's log: what is read where, or why nothing is. */
export function describePlan(plan: ContainerCgroupPlan): string {
  const one = (s: CounterSource | null, what: string): string => (s ? `${what} from ${s.dir} (${s.kind})` : `no ${what} counter`);
  return `${one(plan.memory, 'OOM kills')}, ${one(plan.pids, 'refused forks')}`;
}

/** The counters of a container's cgroup, read with the bwrap job cgroups' readers. */
export class ContainerCgroup {
  constructor(readonly plan: ContainerCgroupPlan) {}

  oomKills(): Promise<number> {
    const m = this.plan.memory;
    if (!m) return Promise.resolve(0);
    return m.kind === 'cgroup-v1' ? readV1OomKills(m.dir) : readV2OomKills(m.dir);
  }

  pidsLimitHits(): Promise<number> {
    return this.plan.pids ? readPidsLimitHits(this.plan.pids.dir) : Promise.resolve(0);
  }

  /** Bytes of the container's memory its tmpfs files held (memory.stat shmem), null when not read here. */
  memoryFiles(): Promise<number | null> {
    return this.plan.memory ? readShmemBytes(this.plan.memory.dir) : Promise.resolve(null);
  }

  /** The host pids of the container's processes (its cgroup.procs), as this host sees them. */
  pids(): Promise<number[]> {
    const dir = this.plan.pids?.dir ?? this.plan.memory?.dir;
    return dir ? cgroupPids(dir) : Promise.resolve([]);
  }
}

/** What `container.inspect()` gives that the watch needs. */
export interface InspectedContainer {
  Id?: string;
  State?: { Pid?: number; Running?: boolean; StartedAt?: string };
  HostConfig?: { PidsLimit?: number | null };
}

export interface FindOptions {
  /** /proc by default. */
  procRoot?: string;
  roots?: CgroupRoots;
}

/**
 * The cgroup of a running container as this host sees it, or why it cannot be read. The pid
 * and the id come from the engine; /proc/<pid>/cgroup must name that id.
 */
export async function findContainerCgroup(info: InspectedContainer, options: FindOptions = {}): Promise<{ ok: true; cgroup: ContainerCgroup } | { ok: false; reason: string }> {
  const id = info.Id ?? '';
  const pid = info.State?.Pid ?? 0;
  if (!CONTAINER_ID.test(id)) return { ok: false, reason: 'the engine gave no container id' };
  if (!Number.isSafeInteger(pid) || pid <= 0) return { ok: false, reason: 'the container is not running (no init pid)' };
  const file = join(options.procRoot ?? '/proc', String(pid), 'cgroup');
  const text = await readSmallFile(file, PROC_CGROUP_MAX_BYTES);
  if (!text) return { ok: false, reason: `cannot read ${file} (a remote engine, another pid namespace, or no permission)` };
  const entries = parseProcCgroup(text);
  const names = [...entries.v1.values(), ...(entries.unified !== null ? [entries.unified] : [])];
  if (!names.some((p) => namesContainer(p, id))) return { ok: false, reason: `${file} does not name container ${id.slice(0, 12)} (a remote engine, or another pid namespace)` };
  // each candidate counter file is read once (bounded): the plan takes those that answer
  const roots = options.roots ?? { v1: CGROUP_V1_ROOT, v2: CGROUP_V2_ROOTS };
  const c = candidates(entries, id, roots);
  const readable = new Set<string>();
  for (const s of [...c.memory, ...c.pids]) if (!readable.has(s.file) && (await readSmallFile(s.file, 512)) !== '') readable.add(s.file);
  const plan = planContainerCgroup(entries, id, (f) => readable.has(f), roots);
  if (!plan.memory && !plan.pids) return { ok: false, reason: `no memory or pids counters of container ${id.slice(0, 12)} are readable here` };
  return { ok: true, cgroup: new ContainerCgroup(plan) };
}

/** Whether one line of the engine's event stream is an `oom` event of the container. */
export function isOomEvent(line: string, containerId: string): boolean {
  if (line.length > 64 * 1024) return false;
  let e: unknown;
  try {
    e = JSON.parse(line);
  } catch {
    return false;
  }
  if (!e || typeof e !== 'object') return false;
  const ev = e as { status?: unknown; Action?: unknown; id?: unknown; Actor?: { ID?: unknown } };
  const action = typeof ev.Action === 'string' ? ev.Action : ev.status;
  const id = typeof ev.Actor?.ID === 'string' ? ev.Actor.ID : ev.id;
  return action === 'oom' && id === containerId;
}

/**
 * Follows the engine's `oom` events of a container from `sinceSeconds` (the engine's clock: the
 * container's StartedAt, so nothing since its start is missed); calls `onOom` at the first.
 * `stop()` ends the stream. Resolves once subscribed; rejects when the engine refuses.
 */
export async function followEngineOom(docker: Docker, containerId: string, sinceSeconds: number, onOom: () => void): Promise<{ stop(): void }> {
  const abort = new AbortController();
  const stream = (await docker.getEvents({
    since: sinceSeconds,
    filters: { container: [containerId], event: ['oom'] },
    abortSignal: abort.signal,
  } as Parameters<Docker['getEvents']>[0])) as unknown as Readable;
  let pending = '';
  let fired = false;
  stream.on('data', (chunk: Buffer) => {
    if (fired) return;
    pending += chunk.toString('utf8');
    const lines = pending.split('\n');
    pending = lines.pop() ?? '';
    if (pending.length > 64 * 1024) pending = '';
    for (const l of lines) {
      if (isOomEvent(l.trim(), containerId)) {
        fired = true;
        onOom();
        return;
      }
    }
  });
  stream.on('error', () => {});
  return {
    stop: () => {
      abort.abort();
      stream.destroy();
    },
  };
}

/** The process count of a container's stats (`pids_stats`), as the engine gives it. */
export interface PidsStats {
  current?: number;
  limit?: number;
}

/**
 * Whether a stats sample shows the container at its process limit (`limit`: its PidsLimit, when
 * the sample lacks it): then a fork is refused, whatever the program says of it. The engine gives
 * no count of refused forks (`pids.events`), only the count now: a limit reached between two
 * samples and left before the next is not seen.
 */
export function atPidsLimit(stats: PidsStats | undefined, limit?: number): boolean {
  const max = typeof stats?.limit === 'number' && stats.limit > 0 ? stats.limit : limit;
  return typeof stats?.current === 'number' && typeof max === 'number' && max > 0 && stats.current >= max;
}

/**
 * Asks the engine for the container's process count every ENGINE_PIDS_INTERVAL_MS (stats, one
 * shot); calls `onHit` at the first sample at its limit (atPidsLimit), `onStats` with each sample.
 * For a container whose cgroup is not read here (a remote engine): a program that hides its
 * refused forks is still seen.
 */
export function followEnginePids(container: Docker.Container, limit: number | undefined, onHit: () => void, onStats?: (stats: EngineMemoryStats) => void): { stop(): void } {
  let stopped = false;
  let busy = false;
  const timer = setInterval(() => {
    if (busy || stopped) return;
    busy = true;
    container.stats({ stream: false, 'one-shot': true })
      .then((s) => {
        if (!stopped) onStats?.(s as EngineMemoryStats);
        if (!stopped && atPidsLimit(s?.pids_stats, limit)) {
          stopped = true;
          clearInterval(timer);
          onHit();
        }
      }, () => {})
      .finally(() => (busy = false));
  }, ENGINE_PIDS_INTERVAL_MS);
  return {
    stop: () => {
      stopped = true;
      clearInterval(timer);
    },
  };
}

/** How a Docker job's limit hits are seen while it runs: `auto` the cgroup when readable, else the engine; `engine` the engine only. */
export type DockerLimitWatch = 'auto' | 'engine';

export interface LimitWatchOptions {
  docker: Docker;
  container: Docker.Container;
  mode: DockerLimitWatch;
  /** Called at the first hit seen: an OOM kill, or a fork refused by the pids limit. */
  onHit(kind: 'memory' | 'processes'): void;
  /** Called once the watch knows the cgroup cannot be read (with the reason), before the engine's events are followed. */
  onFallback?(reason: string): void;
}

export interface LimitWatch {
  /** Ends the polls and the event stream (idempotent). */
  stop(): void;
  /** One last read of the counters (the kernel may have killed a process just before the exit): the hit, if any. */
  finalLook(): Promise<'memory' | 'processes' | null>;
  /** The container's host pids from its cgroup; null when the cgroup is not read here. */
  pids(): Promise<number[] | null>;
  /**
   * Bytes of the container's memory its tmpfs files held (the work dir, /tmp, /dev/shm: memory.stat
   * `shmem`), from its cgroup, else from the engine's stats (a remote engine too): the more of a
   * read now and the watch's last sample (read with its counters: at an OOM kill of the container's
   * init the container ends and its tmpfs mounts are freed while the hit is being told); null when
   * neither says.
   */
  memoryFiles(): Promise<number | null>;
  /** Resolves once the watch is in place (the cgroup found, or the event stream open, or neither). */
  readonly ready: Promise<void>;
}

function sinceOf(info: InspectedContainer): number {
  const started = Date.parse(info.State?.StartedAt ?? '');
  // the engine's own clock (a remote engine's may differ from ours), a second before the start
  return Number.isFinite(started) && started > 0 ? Math.floor(started / 1000) - 1 : Math.floor(Date.now() / 1000) - 60;
}

/**
 * Watches a started container's limits: its cgroup's counters every 100 ms, else the engine's oom
 * events. Never throws; a failure to set up either leaves the checks at the exit (docker.ts).
 */
export function watchContainerLimits(opts: LimitWatchOptions): LimitWatch {
  let stopped = false;
  let timer: NodeJS.Timeout | null = null;
  let events: { stop(): void } | null = null;
  let enginePids: { stop(): void } | null = null;
  let cgroup: ContainerCgroup | null = null;
  let fired = false;
  /** The tmpfs files' bytes at the last sample (cgroup or engine stats), null before one. */
  let filesSampled: number | null = null;
  const sampleFiles = (bytes: number | null): void => {
    if (bytes !== null && !fired) filesSampled = bytes;
  };
  const fire = (kind: 'memory' | 'processes'): void => {
    if (fired || stopped) return;
    fired = true;
    opts.onHit(kind);
  };
  const look = async (cg: ContainerCgroup): Promise<'memory' | 'processes' | null> => {
    if ((await cg.oomKills()) > 0) return 'memory';
    if ((await cg.pidsLimitHits()) > 0) return 'processes';
    return null;
  };
  const ready = (async () => {
    const info = (await opts.container.inspect().catch(() => null)) as InspectedContainer | null;
    if (!info || stopped) return;
    /** The process limit from the engine's process count, when the cgroup's pids counter is not read here (started once). */
    const followPidsByEngine = (): void =>
      void (enginePids ??= followEnginePids(opts.container, info.HostConfig?.PidsLimit ?? undefined, () => fire('processes'), (s) => {
        if (!cgroup?.plan.memory) sampleFiles(shmemOfStats(s));
      }));
    let reason = 'the limits are watched through the engine (limitWatch: engine)';
    if (opts.mode === 'auto') {
      const found = await findContainerCgroup(info);
      if (stopped) return;
      if (found.ok) {
        cgroup = found.cgroup;
        let busy = false;
        timer = setInterval(() => {
          if (busy) return;
          busy = true;
          // the files' sample only when no hit is seen: at the hit the container may be ending, its tmpfs freed
          look(found.cgroup)
            .then((h) => (h ? fire(h) : found.cgroup.memoryFiles().then(sampleFiles)))
            .catch(() => {})
            .finally(() => (busy = false));
        }, CGROUP_WATCH_INTERVAL_MS);
        if (!found.cgroup.plan.pids) followPidsByEngine();
        if (found.cgroup.plan.memory) return;
        reason = `no memory counter of the container is readable here (${describePlan(found.cgroup.plan)})`;
      } else {
        // a container that already ended has no cgroup: its exit is looked at as before
        if (info.State?.Pid === 0 || info.State?.Running === false) return;
        reason = found.reason;
      }
    }
    opts.onFallback?.(reason);
    if (!stopped) followPidsByEngine();
    const id = info.Id ?? '';
    if (!CONTAINER_ID.test(id)) return;
    const sub = await followEngineOom(opts.docker, id, sinceOf(info), () => fire('memory')).catch(() => null);
    if (stopped) sub?.stop();
    else events = sub;
  })().catch(() => {});
  return {
    ready,
    stop: () => {
      stopped = true;
      if (timer) clearInterval(timer);
      events?.stop();
      enginePids?.stop();
    },
    finalLook: async () => (cgroup ? look(cgroup).catch(() => null) : null),
    pids: async () => (cgroup ? cgroup.pids() : null),
    memoryFiles: async () => {
      const now = await (cgroup?.plan.memory ? cgroup.memoryFiles() : engineMemoryFiles(opts.container)).catch(() => null);
      return now === null ? filesSampled : filesSampled === null ? now : Math.max(now, filesSampled);
    },
  };
}

/** What the engine's stats say of a container's memory (`memory_stats.stats`: cgroup v1's or v2's memory.stat). */
export interface EngineMemoryStats {
  memory_stats?: { stats?: Record<string, unknown> };
}

/**
 * The bytes of tmpfs and shared memory a container's stats count: `shmem` (cgroup v2), else, as the
 * engine gives no shmem under cgroup v1, its page cache (`total_cache`, `cache`): at an OOM kill, the
 * page cache the kernel could not reclaim is that of the tmpfs files; null when they do not say or
 * say no whole number.
 */
export function shmemOfStats(stats: EngineMemoryStats | null | undefined): number | null {
  const s = stats?.memory_stats?.stats;
  if (!s || typeof s !== 'object') return null;
  for (const key of ['total_shmem', 'shmem', 'total_cache', 'cache']) {
    const v = s[key];
    if (typeof v === 'number' && Number.isSafeInteger(v) && v >= 0) return v;
  }
  return null;
}

/** The container's shmem bytes from one stats call of the engine (2-8 ms), null when it cannot say. */
async function engineMemoryFiles(container: Docker.Container): Promise<number | null> {
  const stats = (await container.stats({ stream: false, 'one-shot': true }).catch(() => null)) as EngineMemoryStats | null;
  return shmemOfStats(stats);
}
