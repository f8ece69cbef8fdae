/**
 * Docker Engine sandbox (dockerode; honours DOCKER_HOST, so a remote engine works): image
 * `contract-gcc` (gcc, make, the runtime at /opt/contract/runtime), NetworkMode none, read-only
 * root, the job's files in a Docker volume at /work (filled through the API with a tar of the
 * host work dir, so nothing needs to be shared with a remote engine; the volume of a project's
 * workspace is kept between its jobs for no-op rebuilds), /tmp a tmpfs with exec and /dev/shm both
 * of tmpMiB, user 1000 (the host's uid 1000 too: docs/sandbox.md "Docker jobs share one uid"),
 * no-new-privileges, all capabilities dropped, Memory (= MemorySwap) and PidsLimit.
 * Limit hits are seen while the job runs, as in bwrap (docker-cgroup.ts): the container's own cgroup,
 * found from its init's /proc/<pid>/cgroup, is polled every 100 ms (an OOM kill or a fork refused by
 * the pids limit ends the job); where this host cannot read it (a remote engine, ...), an OOM kill
 * is taken from the engine's `oom` events and a refused fork from the program's own messages. At
 * the exit, State.OOMKilled is still asked (docker-oom.ts: the flag can come late).
 * Disk: the work volume is a tmpfs of workDiskMiB (local driver options); a tmpfs volume is only
 * kept while some container mounts it, so each workspace volume has a holder container (`sleep`,
 * volume read-only, no network, no capabilities) for its lifetime, which also answers the statfs
 * polls that name a full disk and the work-tree digests (find, no file read).
 * On a local engine the volume's host folder (its Mountpoint), once proven to be the containers'
 * /work (docker-live-root.ts), is where the live trace channel reads the run's logs.
 * Every container and volume is labelled with its owner (this service process) and job
 * (docker-owner.ts); the first use sweeps what dead services left (docker-sweep.ts), close()
 * removes this service's own leftovers.
 */
import { spawn } from 'node:child_process';
import { createHash } from 'node:crypto';
import type { Readable } from 'node:stream';
import { PassThrough } from 'node:stream';
import { createRequire } from 'node:module';
import type Docker from 'dockerode';
import type { ContainerCreateOptions } from 'dockerode';
import type { LimitHit } from '../limits.js';
import { memoryBytes, REALTIME_BOUNDS, tmpBytes, workDiskBytes } from '../limits.js';
import { dockerRealtimeError, dockerRealtimeHostConfig, dockerRealtimeSupport } from './docker-realtime.js';
import { digestFindOutput, workTreeFindArgs } from '../pipeline/work-tree-digest.js';
import { readWorkUsage, workUsageFindArgs, type WorkUsage } from '../pipeline/work-usage.js';
import { SAFE_NAME, type DirListing } from '../pipeline/artifacts.js';
import { firstTarEntry, readTar } from '../util/tar-reader.js';
import { folderListCommand, readFolderList, type FoundEntry, type FoundFolder } from './docker-folder-list.js';
import { currentOwner, ownerLabels, ownerLabelValue, type ServiceOwner } from './docker-owner.js';
import { DEFAULT_SWEEP_POLICY, removeOwnLeftovers, sweepOrphans, type SweepPolicy, type SweepReport } from './docker-sweep.js';
import { proveLiveRoot, type EngineInfo } from './docker-live-root.js';
import type { LiveWorkRoot, Mechanisms, RealtimeSupport, Sandbox, SandboxCommand, SandboxExit, SandboxProbe, SandboxProcess } from './types.js';
import { stopThenKill } from './limit-stop.js';
import { withForkingModule } from './forking-module.js';
import { HOST_PROCESSES } from './host-process.js';
import { engineProcesses } from './docker-top.js';
import { engineSaysOomKilled, KILLED_LINE, looksKilled } from './docker-oom.js';
import { watchContainerLimits, type DockerLimitWatch } from './docker-cgroup.js';
import { terminateNamedOnHost } from './queue-term.js';
import { isWorkDiskFull, workDiskInodes, type WorkDiskState } from './work-disk.js';
import { DOCKER_IMAGE, SANDBOX_GID, SANDBOX_RUNTIME_DIR, SANDBOX_UID, STOP_REASON_CODES, type StopReason } from '@contract-studio/conventions';

export { DOCKER_IMAGE };
export const DOCKER_WORK = '/work';
export const DOCKER_RUNTIME = SANDBOX_RUNTIME_DIR;
const DOCKER_USER = `${SANDBOX_UID}:${SANDBOX_GID}`;
/** statfs of the work volume while a step runs: a job refused a write is stopped within this time. */
const DISK_WATCH_INTERVAL_MS = 1000;
/**
 * terminateNamed inside a container (sh + /proc, in any image; builtins only, no fork per
 * process looked at): SIGTERM to each process whose comm is $1, printing its pid. With a stop
 * reason's code ($2), through $3 (`contract-launch --term-why CODE PID`: the image has no `kill`
 * that queues a value), so that the launcher says why; the shell's plain SIGTERM when that fails
 * (an image whose launcher is older, a container with no room left for a process).
 */
const TERMINATE_NAMED = 'for d in /proc/[0-9]*; do c=; read -r c < "$d/comm" || continue; [ "$c" = "$1" ] || continue; p=${d#/proc/}; if [ -n "$2" ] && "$3" --term-why "$2" "$p"; then echo "$p"; elif kill -TERM "$p"; then echo "$p"; fi; done 2>/dev/null; true';

export interface DockerOptions {
  image?: string;
  /** dockerode options; default: from DOCKER_HOST (or the local socket). */
  connection?: Docker.DockerOptions;
  /** Where the sweep and shutdown lines go. Default: stderr, prefixed "[build-service] ". */
  log?: (line: string) => void;
  /** When containers and volumes without an owner label are removed (docker-sweep.ts). */
  sweepPolicy?: Partial<SweepPolicy>;
  /**
   * How a job's memory and process limit hits are seen while it runs (docker-cgroup.ts): `auto`
   * (default) the container's cgroup when this host can read it, else the engine's oom events;
   * `engine` the engine's events only (what a remote engine gives; tests).
   */
  limitWatch?: DockerLimitWatch;
}

/** The service's own log lines when nobody gave a log function. */
export function stderrLog(line: string): void {
  process.stderr.write(`[build-service] ${line}\n`);
}

const EMPTY_SWEEP: SweepReport = { removedContainers: [], removedVolumes: [], left: [], lines: [] };
/** An unresponsive engine must not hold a job or the service's close() for ever. */
const ENGINE_DEADLINE_MS = 15_000;

function withDeadline<T>(p: Promise<T>, ms: number, what: string): Promise<T> {
  let timer: NodeJS.Timeout | undefined;
  const late = new Promise<never>((_, reject) => {
    timer = setTimeout(() => reject(new Error(`${what}: no answer from the engine within ${ms / 1000} s`)), ms);
  });
  return Promise.race([p, late]).finally(() => clearTimeout(timer));
}

/** The tar of a work dir that the Docker sandbox copies into the job's volume. */
export function tarOf(dir: string): Promise<Buffer> {
  return new Promise((resolve, reject) => {
    // pax format: mtimes to the nanosecond (GNU tar's default format keeps whole seconds, so a
    // source saved in the same second as the last build ended looked older than its object and
    // make did not rebuild it); atime/ctime left out and a fixed extended-header name, so the same tree gives the same
    // bytes (the digest that skips a no-op sync)
    const child = spawn('tar', ['-C', dir, '--format=posix', '--pax-option=exthdr.name=%d/PaxHeaders/%f,delete=atime,delete=ctime', `--owner=${SANDBOX_UID}`, `--group=${SANDBOX_GID}`, '--numeric-owner', '-cf', '-', '.'], {
      stdio: ['ignore', 'pipe', 'pipe'],
    });
    const chunks: Buffer[] = [];
    let err = '';
    child.stdout.on('data', (c: Buffer) => chunks.push(c));
    child.stderr.on('data', (c: Buffer) => (err += c.toString()));
    child.on('error', reject);
    child.on('close', (code) => (code === 0 ? resolve(Buffer.concat(chunks)) : reject(new Error(`tar failed: ${err.trim()}`))));
  });
}

export class DockerSandbox implements Sandbox {
  readonly name = 'docker' as const;
  readonly needsHostRuntime = false;
  readonly unenforced: readonly string[] = [];
  private engine: Docker | null = null;
  private readonly connection: Docker.DockerOptions | undefined;
  private readonly image: string;
  private readonly volumes = new Map<string, string>();
  private readonly createdVolumes = new Set<string>();
  /** Digest of the last work-dir archive copied into each volume. */
  private readonly syncedTar = new Map<string, string>();
  /** The holder container of each tmpfs work volume, and the volume's size. */
  private readonly holders = new Map<string, Docker.Container>();
  private readonly volumeBytes = new Map<string, number>();
  /** Whether each work volume's Mountpoint is proven to be the containers' /work here (docker-live-root.ts). */
  private readonly liveRoots = new Map<string, Promise<LiveWorkRoot>>();
  private engineInfo: Promise<EngineInfo> | null = null;
  /** The job that last used each work dir (labels of the containers that read it). */
  private readonly jobOfWorkDir = new Map<string, string>();
  /** This service process, written on everything it creates. */
  readonly owner: ServiceOwner;
  private readonly log: (line: string) => void;
  private readonly sweepPolicy: SweepPolicy;
  private readonly limitWatch: DockerLimitWatch;
  /** The reason the containers' cgroups cannot be read here, once logged (one line per service). */
  private limitWatchNoted = false;
  private sweeping: Promise<SweepReport> | null = null;
  /** Set once the engine answered this service (close() then looks for leftovers). */
  private engineSeen = false;

  /**
   * The engine client, loaded on first use: dockerode takes about 0.3 s to load, which a
   * `contract build` in bwrap should not pay (docs/getting-started.md "The build cache").
   */
  private get docker(): Docker {
    if (!this.engine) {
      const Dockerode = createRequire(import.meta.url)('dockerode') as typeof Docker;
      this.engine = new Dockerode(this.connection);
    }
    return this.engine;
  }

  constructor(options: DockerOptions = {}) {
    this.connection = options.connection;
    this.image = options.image ?? DOCKER_IMAGE;
    this.owner = currentOwner();
    this.log = options.log ?? stderrLog;
    this.sweepPolicy = { ...DEFAULT_SWEEP_POLICY, ...options.sweepPolicy };
    this.limitWatch = options.limitWatch ?? 'auto';
  }

  /**
   * Removes the containers and volumes of dead services on this host (docker-sweep.ts), once per
   * service: the first call sweeps, later ones return its report. Never throws: a failure is a log
   * line (and the next call tries again).
   */
  sweep(): Promise<SweepReport> {
    this.sweeping ??= withDeadline(sweepOrphans(this.docker, this.owner, this.log, this.sweepPolicy), ENGINE_DEADLINE_MS, 'sweep').then((report) => {
      this.engineSeen = true;
      return report;
    }, (e: unknown) => {
      this.log(`docker: the sweep of orphaned containers failed: ${(e as Error).message.split('\n')[0]}`);
      this.sweeping = null;
      return EMPTY_SWEEP;
    });
    return this.sweeping;
  }

  /**
   * At shutdown, after the jobs ended: releases the work volumes kept between jobs (and their
   * holders) as usual, without a line, then removes any container or volume still labelled with
   * this service instance (a removal that failed during a cancel, a step started while closing),
   * each named in a line.
   */
  async close(): Promise<SweepReport> {
    if (this.sweeping) await this.sweeping;
    if (!this.engineSeen) return EMPTY_SWEEP;
    for (const workDir of [...this.volumes.keys()]) {
      await withDeadline(this.release(workDir), ENGINE_DEADLINE_MS, 'work volume release').catch(() => undefined);
    }
    try {
      return await withDeadline(removeOwnLeftovers(this.docker, this.owner, this.log), ENGINE_DEADLINE_MS, 'shutdown clean-up');
    } catch (e) {
      this.log(`docker: could not remove this service's containers at shutdown: ${(e as Error).message.split('\n')[0]}`);
      return EMPTY_SWEEP;
    }
  }

  workPath(): string {
    return DOCKER_WORK;
  }

  runtimePath(): string {
    return DOCKER_RUNTIME;
  }

  private where(): string {
    const c = this.connection;
    if (c?.socketPath) return `unix://${c.socketPath}`;
    if (c?.host) return `${c.protocol ?? 'http'}://${c.host}${c.port ? `:${c.port}` : ''}`;
    return process.env.DOCKER_HOST ?? 'unix:///var/run/docker.sock';
  }

  async probe(): Promise<SandboxProbe> {
    try {
      await Promise.race([
        this.docker.ping(),
        new Promise((_, reject) => setTimeout(() => reject(new Error('no answer within 3 s')), 3000)),
      ]);
    } catch (e) {
      return { available: false, detail: `no Docker engine answers at ${this.where()} (${(e as Error).message.split('\n')[0]}); start one with scripts/docker-up.sh` };
    }
    try {
      const info = await this.docker.getImage(this.image).inspect();
      return { available: true, detail: `engine at ${this.where()}, image ${this.image} ${info.Id.slice(7, 19)}` };
    } catch {
      return { available: false, detail: `engine at ${this.where()} has no image "${this.image}"; build it with scripts/docker-up.sh` };
    }
  }

  private volumeFor(workDir: string): string {
    let v = this.volumes.get(workDir);
    if (!v) {
      // the owner is in the name: a volume is never shared with (or inherited from) another service
      v = `contract-ws-${createHash('sha256').update(`${ownerLabelValue(this.owner)}:${this.owner.instance}\0${workDir}`).digest('hex').slice(0, 16)}`;
      this.volumes.set(workDir, v);
    }
    return v;
  }

  async realtimeSupport(): Promise<RealtimeSupport> {
    const rt = await dockerRealtimeSupport(this.docker, REALTIME_BOUNDS);
    return rt.ok && rt.cgroupBudget ? { ...rt, budget: { runtimeUs: REALTIME_BOUNDS.cpuRuntimeUs, periodUs: REALTIME_BOUNDS.cpuPeriodUs } } : rt;
  }


  async start(cmd: SandboxCommand): Promise<SandboxProcess> {
    await this.sweep();
    const jobId = cmd.jobId ?? cmd.name;
    const diskBytes = workDiskBytes(cmd.limits);
    // a job with another workDiskMiB than the volume's gets a new volume (and a full build)
    const existing = this.volumes.get(cmd.workDir);
    if (existing && this.createdVolumes.has(existing) && this.volumeBytes.get(existing) !== diskBytes) await this.release(cmd.workDir);
    this.jobOfWorkDir.set(cmd.workDir, jobId);
    const volume = this.volumeFor(cmd.workDir);
    this.engineSeen = true;
    if (!this.createdVolumes.has(volume)) {
      await this.docker.createVolume({
        Name: volume,
        Labels: ownerLabels(this.owner, 'workspace', jobId),
        DriverOpts: { type: 'tmpfs', device: 'tmpfs', o: `size=${diskBytes},nr_inodes=${workDiskInodes(diskBytes)},uid=${SANDBOX_UID},gid=${SANDBOX_GID},mode=0755,nosuid,nodev` },
      });
      this.createdVolumes.add(volume);
      this.liveRoots.delete(volume);
      this.volumeBytes.set(volume, diskBytes);
      this.syncedTar.delete(volume);
      await this.startHolder(volume, cmd.name, jobId);
    }
    // the job's files, with their mtimes (make sees unchanged sources as unchanged); skipped
    // when the work dir is byte-for-byte what the volume last received (no-op rebuilds)
    const tar = await tarOf(cmd.workDir);
    const digest = createHash('sha256').update(tar).digest('hex');
    if (this.syncedTar.get(volume) !== digest) {
      this.syncedTar.delete(volume);
      await this.fillVolume(volume, tar, cmd.name, jobId);
      this.syncedTar.set(volume, digest);
    }
    const bytes = memoryBytes(cmd.limits);
    const realtime = cmd.realtime ? await dockerRealtimeSupport(this.docker, REALTIME_BOUNDS) : null;
    if (realtime && !realtime.ok) throw new Error(`real-time mode refused: ${realtime.reason}`);
    const container = await this.docker.createContainer({
      name: `contract-${cmd.name}`,
      Image: this.image,
      Cmd: cmd.argv,
      WorkingDir: cmd.cwd ? `${DOCKER_WORK}/${cmd.cwd}` : DOCKER_WORK,
      User: DOCKER_USER,
      Env: Object.entries({ PATH: '/usr/local/bin:/usr/bin:/bin', HOME: DOCKER_WORK, TMPDIR: '/tmp', LANG: 'C.UTF-8', ...cmd.env }).map(
        ([k, v]) => `${k}=${v}`,
      ),
      NetworkDisabled: true,
      Labels: ownerLabels(this.owner, 'job', jobId),
      AttachStdout: true,
      AttachStderr: true,
      HostConfig: {
        NetworkMode: 'none',
        ReadonlyRootfs: true,
        Mounts: [{ Type: 'volume', Source: volume, Target: DOCKER_WORK }],
        Tmpfs: { '/tmp': `rw,exec,nosuid,nodev,size=${tmpBytes(cmd.limits)}` },
        // /dev/shm the size of /tmp, as in bwrap (Docker's default is 64 MiB whatever tmpMiB says)
        ShmSize: tmpBytes(cmd.limits),
        SecurityOpt: ['no-new-privileges'],
        CapDrop: ['ALL'],
        Memory: bytes,
        MemorySwap: bytes,
        PidsLimit: cmd.limits.processes,
        Init: true,
        ...(realtime?.ok ? dockerRealtimeHostConfig(REALTIME_BOUNDS, realtime.cgroupBudget) : {}),
      },
    }).catch((e: Error) => {
      throw realtime ? dockerRealtimeError(e, REALTIME_BOUNDS) : e;
    });
    const removeContainer = async (): Promise<void> => {
      await container.remove({ force: true }).catch(() => {});
    };
    try {
      const stream = await container.attach({ stream: true, stdout: true, stderr: true });
      const stdout = new PassThrough();
      const stderr = new PassThrough();
      this.docker.modem.demuxStream(stream, stdout, stderr);
      let markEnded!: () => void;
      const streamEnded = new Promise<void>((r) => (markEnded = r));
      stream.on('end', markEnded);
      stream.on('close', markEnded);
      await container.start();
      const mechanisms: Mechanisms = {
        memory: 'docker',
        processes: 'docker',
        network: 'docker-network-none',
        filesystem: 'docker-readonly-rootfs',
        user: `docker user ${DOCKER_USER}`,
        time: 'service-timer',
        output: 'service-counter',
        disk: 'docker-tmpfs-volume',
        ...(realtime?.ok ? { realtime: realtime.detail } : {}),
      };
      let limitHit: LimitHit | null = null;
      let sawKilled = false;
      const memoryHit: LimitHit = { name: 'memory', value: bytes, unit: 'bytes', mechanism: 'docker' };
      const processHit: LimitHit = { name: 'processes', value: cmd.limits.processes, unit: 'count', mechanism: 'docker' };
      let markExited!: () => void;
      const exited = new Promise<void>((r) => (markExited = r));
      /**
       * A limit hit ends the job as in bwrap (host-process.ts): a run's launcher is first asked to
       * stop the modules (stopOnLimit: SIGTERM, then the kill after its grace), a build is killed at once.
       */
      const hitLimit = (h: LimitHit): void => {
        if (limitHit) return;
        limitHit = h;
        void (cmd.stopOnLimit ? stopThenKill(cmd.stopOnLimit, h, { terminateNamed, exited, kill }) : kill());
      };
      // an OOM kill or a refused fork ends the job, as in bwrap (docker-cgroup.ts)
      const watch = watchContainerLimits({
        docker: this.docker,
        container,
        mode: this.limitWatch,
        onHit: (kind) => (kind === 'memory' ? void memoryHitNow().then(hitLimit) : hitProcessLimit()),
        onFallback: (reason) => {
          if (this.limitWatchNoted || this.limitWatch === 'engine') return;
          this.limitWatchNoted = true;
          this.log(`docker: the containers' cgroups cannot be read here (${reason}): a memory limit hit is taken from the engine's oom events, a process limit hit from the engine's process count and the program's messages (docs/sandbox.md "Memory and process limits in Docker")`);
        },
      });
      /** The memory limit, with what of it the job's tmpfs files held, read before the kill (as bwrap's: host-process.ts). */
      const memoryHitNow = async (): Promise<LimitHit> => {
        const files = await watch.memoryFiles().catch(() => null);
        return files !== null ? { ...memoryHit, memoryFilesBytes: files } : memoryHit;
      };
      /** The process limit, with the module whose code forks, named while its processes are there (forking-module.ts). */
      let namingForks = false; // one look at the processes (a fork loop's error lines come by thousands)
      const hitProcessLimit = (): void => {
        if (namingForks || limitHit) return;
        namingForks = true;
        // the processes from the container's cgroup and this host's /proc; without the cgroup, as the engine lists them
        void watch.ready.then(() => watch.pids()).then(async (pids) => {
          if (pids !== null) return withForkingModule(processHit, pids, HOST_PROCESSES);
          const listed = await engineProcesses(container);
          return withForkingModule(processHit, listed.pids, listed.table);
        }, () => processHit).catch(() => processHit).then(hitLimit);
      };
      const diskHit = async (): Promise<LimitHit | null> => {
        const state = await this.volumeState(volume);
        return state && isWorkDiskFull(state) ? { name: 'workDiskMiB', value: diskBytes, unit: 'bytes', mechanism: 'docker-tmpfs-volume' } : null;
      };
      const diskWatch = setInterval(() => {
        void diskHit().then((h) => {
          if (h) hitLimit(h);
        }, () => {});
      }, DISK_WATCH_INTERVAL_MS);
      let killing: Promise<void> | null = null;
      const kill = (): Promise<void> => {
        killing ??= container.kill().catch(() => {}).then(() => undefined);
        return killing.then(() => done.then(() => undefined));
      };
      const done: Promise<SandboxExit> = (async () => {
        const waited = (await container.wait().catch(() => ({ StatusCode: null }))) as { StatusCode: number | null };
        markExited();
        clearInterval(diskWatch);
        // the last counters, when the cgroup is still there (a kill just before the exit)
        if (!limitHit && !killing) {
          const last = await watch.finalLook();
          if (last) limitHit = last === 'memory' ? await memoryHitNow() : processHit;
        }
        watch.stop();
        // the attach stream delivers the last bytes after the container ended: drain it first (a
        // shell's or make's "Killed" line, read below, is among them)
        await Promise.race([streamEnded, new Promise((r) => setTimeout(r, 1000))]);
        if (!limitHit && (await engineSaysOomKilled(() => container.inspect(), !killing && looksKilled(waited.StatusCode, sawKilled)))) {
          limitHit = await memoryHitNow();
        }
        // a job that was refused a write and gave up is reported too; not one the service stopped
        // itself (run time limit, cancel): its reason is known, and the look into the volume (an exec
        // in its holder, 0.2-0.4 s, more on a loaded engine) would only delay the kill's report
        if (!limitHit && !killing) limitHit = await diskHit().catch(() => null);
        stdout.end();
        stderr.end();
        await removeContainer();
        return { exitCode: waited.StatusCode, signal: null, limitHit };
      })();
      const noteLine = (line: string): void => {
        if (KILLED_LINE.test(line)) sawKilled = true;
        if (limitHit) return;
        if (/Resource temporarily unavailable|cannot fork|fork failed/i.test(line)) hitProcessLimit();
      };
      const terminateNamed = async (name: string, reason?: StopReason): Promise<boolean> => {
        if (killing) return false;
        const comm = name.slice(0, 15);
        // from this host, when the container's cgroup is read here and the service may signal its
        // processes: no process to start in a container that may have no room for one (its pids limit)
        const pids = await watch.pids().catch(() => null);
        if (pids) {
          const asked = await terminateNamedOnHost(pids, comm, '/proc', reason);
          if (asked !== null) return asked;
        }
        // the engine lists the container's processes without starting one in it (most runs that
        // are stopped by the time limit are no architecture, and a fork bomb leaves no room to exec)
        const listed = (await container.top({ ps_args: '-o pid,comm' }).catch(() => null)) as { Titles?: string[]; Processes?: string[][] } | null;
        const at = listed?.Titles?.indexOf('COMMAND') ?? -1;
        if (listed?.Processes && at >= 0 && !listed.Processes.some((p) => p[at] === comm)) return false;
        // inside the container, as its user: the container's own processes are all it sees
        const out = new PassThrough();
        let text = '';
        out.on('data', (c: Buffer) => (text += c.toString()));
        const code = reason !== undefined ? String(STOP_REASON_CODES[reason]) : '';
        await this.execIn(container, ['sh', '-c', TERMINATE_NAMED, 'contract-terminate', comm, code, `${DOCKER_RUNTIME}/build/contract-launch`], out).catch(() => null);
        // a pid per process asked, as soon as it is: an architecture that stops at once ends the
        // container, and this exec with it, before the loop is done
        return /^\d+$/m.test(text);
      };
      const proc: SandboxProcess = { stdout, stderr, mechanisms, done, kill, terminateNamed, noteLine };
      return proc;
    } catch (e) {
      await removeContainer();
      throw realtime ? dockerRealtimeError(e as Error, REALTIME_BOUNDS) : e;
    }
  }

  /**
   * Copies the work dir into the volume. The engine extracts archives as root, so a service-run
   * container (no user code, no network, only CAP_CHOWN) then hands the tree to the job user:
   * `chown -R` does not follow symlinks, and it only sees the volume.
   */
  private async fillVolume(volume: string, tar: Buffer, name: string, jobId: string): Promise<void> {
    const c = await this.docker.createContainer({
      name: `contract-${name}-sync`,
      Image: this.image,
      Cmd: ['chown', '-R', DOCKER_USER, DOCKER_WORK],
      User: '0:0',
      NetworkDisabled: true,
      Labels: ownerLabels(this.owner, 'job', jobId),
      HostConfig: {
        NetworkMode: 'none',
        ReadonlyRootfs: true,
        Mounts: [{ Type: 'volume', Source: volume, Target: DOCKER_WORK }],
        SecurityOpt: ['no-new-privileges'],
        CapDrop: ['ALL'],
        CapAdd: ['CHOWN'],
      },
    });
    try {
      await c.putArchive(tar, { path: DOCKER_WORK });
      await c.start();
      const r = (await c.wait()) as { StatusCode: number };
      if (r.StatusCode !== 0) throw new Error(`cannot give the work volume to user ${DOCKER_USER} (chown exit ${r.StatusCode})`);
    } finally {
      await c.remove({ force: true }).catch(() => {});
    }
  }

  /**
   * Lists work-dir folders of the volume with `find` in its holder (docker-folder-list.ts: names,
   * kinds and sizes, no link followed, at most maxEntries entries, the runtime's logs first), then
   * reads the regular files the collector takes, by name: those of at most BATCHED_FILE_BYTES
   * together by one tar in the holder (readSmallFiles), each bigger one through the holder's archive
   * API (the engine resolves the path inside the container and its tar reports a link as a link),
   * only as far as the collector asks and never past the size find gave. A folder is never archived whole: its archive
   * streams every byte of every file in it (a sparse file of a terabyte, thousands of files past
   * the entries looked at), so its cost would be the program's choice. A folder find cannot list
   * is an error (the collection's warning line), not a reason to read it another way.
   */
  async readWorkDirs(workDir: string, rels: string[], _maxBytes: number, maxEntries: number): Promise<Map<string, DirListing>> {
    const out = new Map<string, DirListing>();
    const volume = this.volumes.get(workDir);
    if (!volume || !this.createdVolumes.has(volume)) {
      for (const rel of rels) out.set(rel, null);
      return out;
    }
    for (const rel of rels) {
      const found = await this.listFolder(volume, rel, maxEntries);
      if (found === undefined) throw new Error(`the work volume's ${rel}/ could not be listed (find in its holder failed)`);
      if (found === null || 'notDirectory' in found) {
        out.set(rel, found);
        continue;
      }
      // the small files in one tar of the holder, the first time one of them is asked for (an
      // archive call per file takes about 80 ms: 256 files of a flooded logs/ took 22 s)
      const small = found.entries.filter((e) => e.kind === 'file' && e.size <= BATCHED_FILE_BYTES && SAFE_NAME.test(e.name));
      let batch: Promise<Map<string, Buffer>> | null = null;
      out.set(rel, {
        ...(found.more ? { more: true } : {}),
        entries: found.entries.map((e) => ({
          ...e,
          read: async (max: number, signal?: AbortSignal) => {
            if (e.kind !== 'file') return null;
            if (small.includes(e)) {
              batch ??= this.readSmallFiles(volume, `${DOCKER_WORK}/${rel}`, small, signal);
              const data = (await batch).get(e.name);
              if (data) return data.subarray(0, max);
            }
            return this.readFilePrefix(volume, `${DOCKER_WORK}/${rel}/${e.name}`, Math.min(max, e.size), signal);
          },
        })),
      });
    }
    return out;
  }

  /**
   * The work volume's folder on this host, once proven to be the containers' /work (a local engine
   * that mounts its volumes where this process sees them; docker-live-root.ts): the live trace
   * channel reads the run's logs there. Proven once per volume; never throws.
   */
  async liveWorkRoot(workDir: string): Promise<LiveWorkRoot> {
    const volume = this.volumes.get(workDir);
    if (!volume || !this.createdVolumes.has(volume)) return { ok: false, reason: 'the job has no work volume yet' };
    let answer = this.liveRoots.get(volume);
    if (!answer) {
      const jobId = this.jobOfWorkDir.get(workDir) ?? 'proof';
      answer = proveLiveRoot({
        docker: this.docker,
        address: this.where(),
        info: () => (this.engineInfo ??= (this.docker.info() as Promise<EngineInfo>).catch((e: unknown) => {
          this.engineInfo = null;
          throw e;
        })),
        volume,
        holder: this.holders.get(volume),
        writer: (name, cmd) => {
          const spec = this.volumeReader(name, cmd, volume, jobId);
          return { ...spec, HostConfig: { ...spec.HostConfig, Mounts: [{ Type: 'volume', Source: volume, Target: DOCKER_WORK }] } };
        },
        uid: SANDBOX_UID,
        gid: SANDBOX_GID,
        mountedAt: DOCKER_WORK,
        deadline: (p, what) => withDeadline(p, ENGINE_DEADLINE_MS, what),
      });
      this.liveRoots.set(volume, answer);
    }
    return answer;
  }

  /** Removes the volume of a workspace that is being deleted (its holder first). */
  async release(workDir: string): Promise<void> {
    const v = this.volumes.get(workDir);
    if (!v) return;
    this.volumes.delete(workDir);
    this.jobOfWorkDir.delete(workDir);
    this.createdVolumes.delete(v);
    this.syncedTar.delete(v);
    this.liveRoots.delete(v);
    this.volumeBytes.delete(v);
    const holder = this.holders.get(v);
    this.holders.delete(v);
    await holder?.remove({ force: true }).catch(() => {});
    await this.docker.getVolume(v).remove({ force: true }).catch(() => {});
  }

  /**
   * A service-side container that only reads a work volume (artifact collection, the volume's
   * holder): the volume read-only, no network, read-only root, no capabilities, no new privileges,
   * owner-labelled like the job's own containers so that the sweep finds it.
   */
  private volumeReader(name: string, cmd: string[], volume: string, jobId: string): ContainerCreateOptions {
    return {
      name,
      Image: this.image,
      Cmd: cmd,
      User: DOCKER_USER,
      NetworkDisabled: true,
      Labels: ownerLabels(this.owner, 'job', jobId),
      HostConfig: {
        NetworkMode: 'none',
        ReadonlyRootfs: true,
        Mounts: [{ Type: 'volume', Source: volume, Target: DOCKER_WORK, ReadOnly: true }],
        SecurityOpt: ['no-new-privileges'],
        CapDrop: ['ALL'],
      },
    };
  }

  /**
   * Starts the container that keeps a tmpfs work volume mounted between a workspace's steps and
   * jobs (the local driver unmounts it, contents gone, when no container uses it).
   */
  private async startHolder(volume: string, name: string, jobId: string): Promise<void> {
    const spec = this.volumeReader(`contract-${name}-hold`, ['sleep', 'infinity'], volume, jobId);
    // the volume writable, for the service's own exec that removes what earlier runs left (removeRunOutputs)
    const Mounts = [{ Type: 'volume' as const, Source: volume, Target: DOCKER_WORK, ReadOnly: false }];
    const c = await this.docker.createContainer({ ...spec, HostConfig: { ...spec.HostConfig, Mounts, Memory: 64 * 1024 * 1024, PidsLimit: 16, Init: true } });
    this.holders.set(volume, c);
    await c.start();
  }

  /** One folder of a work volume as `find` in its holder sees it; undefined without a holder or on a failure. */
  private async listFolder(volume: string, rel: string, maxEntries: number): Promise<FoundFolder | undefined> {
    if (!this.holders.has(volume)) return undefined;
    const out = new PassThrough();
    out.on('error', () => {});
    const exited = this.execInHolder(volume, folderListCommand(`${DOCKER_WORK}/${rel}`), out).catch(() => undefined);
    const found = await readFolderList(out, maxEntries, () => out.destroy());
    return (await exited) === undefined ? undefined : found;
  }

  /**
   * The first `bytes` bytes of a regular file of a work volume (a bounded read of its one-file
   * archive, through the holder); null when it cannot be read or the signal aborted the read.
   */
  private async readFilePrefix(volume: string, path: string, bytes: number, signal?: AbortSignal): Promise<Buffer | null> {
    const holder = this.holders.get(volume);
    if (!holder || signal?.aborted) return null;
    try {
      const stream = (await holder.getArchive({ path })) as unknown as Readable;
      const entry = firstTarEntry(await readBounded(stream, bytes + TAR_HEADER_ROOM, signal));
      return entry?.kind === 'file' && entry.data && entry.data.length >= bytes ? entry.data.subarray(0, bytes) : null;
    } catch {
      return null;
    }
  }

  /**
   * The listed regular files of `dir` (each at most BATCHED_FILE_BYTES), read together by one `tar`
   * in the holder (no link followed: tar archives a link as a link), read no further than their
   * listed sizes allow; a file that is not there as listed (a regular file of that size) is left
   * out of the answer (its own read then tries). Never throws.
   */
  private async readSmallFiles(volume: string, dir: string, files: readonly FoundEntry[], signal?: AbortSignal): Promise<Map<string, Buffer>> {
    const got = new Map<string, Buffer>();
    if (files.length === 0 || signal?.aborted) return got;
    const out = new PassThrough();
    out.on('error', () => {});
    // a header block, a PAX header and its block for a long name, the data in blocks; two end blocks and tar's record padding
    const bound = files.reduce((sum, e) => sum + 3 * 512 + Math.ceil(e.size / 512) * 512, 0) + 20 * 512;
    const exited = this.execInHolder(volume, ['tar', '-C', dir, '--no-recursion', '-cf', '-', ...files.map((e) => `./${e.name}`)], out).catch(() => null);
    try {
      const listed = new Map(files.map((e) => [e.name, e.size]));
      for (const entry of readTar(await readBounded(out, bound, signal))) {
        if (entry.kind === 'file' && entry.data && entry.data.length === listed.get(entry.name)) got.set(entry.name, entry.data);
      }
    } catch {
      /* cancelled, or the tar failed: each file is read on its own */
    }
    out.destroy();
    await exited;
    return got;
  }

  /** Runs a command in a volume's holder; stdout to `out`, resolves with the exit code. */
  private async execInHolder(volume: string, cmd: string[], out: PassThrough): Promise<number | null> {
    const holder = this.holders.get(volume);
    if (!holder) {
      out.end();
      return null;
    }
    return this.execIn(holder, cmd, out);
  }

  /** Runs a command in a running container, as the jobs' user; stdout to `out`, resolves with the exit code. */
  private async execIn(container: Docker.Container, cmd: string[], out: PassThrough): Promise<number | null> {
    const exec = await container.exec({ Cmd: cmd, AttachStdout: true, AttachStderr: true, User: DOCKER_USER });
    const stream = (await exec.start({ hijack: true, stdin: false })) as unknown as Readable;
    const err = new PassThrough();
    err.resume();
    this.docker.modem.demuxStream(stream, out, err);
    await new Promise<void>((resolve) => {
      stream.on('end', resolve);
      stream.on('close', resolve);
      stream.on('error', () => resolve());
    });
    out.end();
    const info = await exec.inspect();
    return info.ExitCode ?? null;
  }

  /** statfs of a work volume (through its holder), null when it cannot be read. */
  private async volumeState(volume: string): Promise<WorkDiskState | null> {
    const out = new PassThrough();
    let text = '';
    out.on('data', (c: Buffer) => (text += c.toString()));
    // %b blocks, %a blocks free to users, %d free inodes (not %f: free blocks), %S block size
    const code = await this.execInHolder(volume, ['stat', '-f', '-c', '%b %a %d %S', DOCKER_WORK], out);
    const m = /^(\d+) (\d+) (\d+) (\d+)/.exec(text.trim());
    if (code !== 0 || !m) return null;
    const [blocks, avail, freeInodes, bsize] = m.slice(1).map(Number) as [number, number, number, number];
    return { sizeBytes: blocks * bsize, freeBytes: avail * bsize, freeInodes };
  }

  /** The biggest files of a workspace's volume (pipeline/work-usage.ts), found by its holder. */
  async workUsage(workDir: string): Promise<WorkUsage | null> {
    const volume = this.volumes.get(workDir);
    if (!volume || !this.holders.has(volume)) return null;
    const out = new PassThrough();
    const exited = this.execInHolder(volume, ['find', ...workUsageFindArgs(DOCKER_WORK)], out);
    const usage = await readWorkUsage(out, () => out.destroy());
    return (await exited) === 0 || usage.partial ? usage : null;
  }

  /**
   * Removes what earlier runs left in a workspace's volume (logs/, run/: a run's logs, a link a
   * module planted there as `logs/previous`), by its holder as the jobs' user, never following a
   * link: a folder a module made unreadable is first made the user's again (find -P, before it is
   * entered). True when both are gone (or there is no volume yet); false otherwise: the caller
   * then empties the work dir.
   */
  async removeRunOutputs(workDir: string): Promise<boolean> {
    const volume = this.volumes.get(workDir);
    if (!volume || !this.createdVolumes.has(volume)) return true;
    const out = new PassThrough();
    out.resume();
    const code = await this.execInHolder(volume, ['sh', '-c', REMOVE_RUN_OUTPUTS], out).catch(() => null);
    return code === 0;
  }

  /** The work-tree digest of a workspace's volume (pipeline/work-tree-digest.ts), found by its holder. */
  async workTreeDigest(workDir: string): Promise<string | null> {
    const volume = this.volumes.get(workDir);
    if (!volume || !this.holders.has(volume)) return null;
    const out = new PassThrough();
    const exited = this.execInHolder(volume, ['find', ...workTreeFindArgs(DOCKER_WORK)], out);
    return digestFindOutput(out, exited);
  }
}

/** removeRunOutputs' shell: each folder made enterable before find enters it, links never followed, then both removed and checked gone. */
const REMOVE_RUN_OUTPUTS = `for d in ${DOCKER_WORK}/logs ${DOCKER_WORK}/run; do if [ -d "$d" ] && [ ! -L "$d" ]; then find -P "$d" -xdev -type d -exec chmod u+rwx {} \\; 2>/dev/null; fi; done; rm -rf --one-file-system ${DOCKER_WORK}/logs ${DOCKER_WORK}/run; ! [ -e ${DOCKER_WORK}/logs ] && ! [ -L ${DOCKER_WORK}/logs ] && ! [ -e ${DOCKER_WORK}/run ] && ! [ -L ${DOCKER_WORK}/run ]`;

/** Files of logs/ at most this big are read together (readSmallFiles), the bigger ones each on its own. */
const BATCHED_FILE_BYTES = 64 * 1024;

/** Room for a one-file archive's headers before the file's bytes (a PAX header with a long name). */
const TAR_HEADER_ROOM = 64 * 1024;

/**
 * Reads a stream up to `limit` bytes (then stops reading it), into one buffer of that size, made
 * first (the callers' limit is what find said the file holds, at most the collector's file bound:
 * no chunk list copied at the end, a 256 MiB read costs 256 MiB). An abort of `signal` stops the
 * read and rejects.
 */
export function readBounded(stream: Readable, limit: number, signal?: AbortSignal): Promise<Buffer> {
  return new Promise((resolve, reject) => {
    const buf = Buffer.allocUnsafe(limit);
    let size = 0;
    let settled = false;
    const settle = (f: () => void): void => {
      if (settled) return;
      settled = true;
      signal?.removeEventListener('abort', onAbort);
      f();
    };
    const finish = (): void => settle(() => resolve(buf.subarray(0, size)));
    const onAbort = (): void => {
      stream.destroy();
      settle(() => reject(new Error('the read was cancelled')));
    };
    if (signal?.aborted) return onAbort();
    signal?.addEventListener('abort', onAbort, { once: true });
    stream.on('data', (c: Buffer) => {
      if (settled) return;
      const take = Math.min(c.length, limit - size);
      c.copy(buf, size, 0, take);
      size += take;
      if (size >= limit) {
        stream.destroy();
        finish();
      }
    });
    stream.on('end', finish);
    stream.on('close', finish);
    stream.on('error', (e) => (size >= limit ? finish() : settle(() => reject(e))));
  });
}
