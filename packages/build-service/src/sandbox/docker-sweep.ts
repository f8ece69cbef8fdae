/**
 * Sweeps the Docker containers and volumes that dead build services left behind (kill -9, crash,
 * machine sleep while a job ran: the container keeps running, the volume stays), and removes a
 * service's own leftovers when it closes.
 *
 * What is removed, what is kept (docs/sandbox.md, "Orphaned containers and volumes"):
 *   - owner on this host, boot and pid namespace, and dead (pid gone or start time differs):
 *     container removed (forced, with its anonymous volumes), volume removed;
 *   - owner alive, or on another host / pid namespace: left alone, silently;
 *   - no owner label (made by a service older than owner labels): a container that is not running
 *     and was created more than `legacyContainerAgeSeconds` ago is removed; a volume no container
 *     mounts, created more than `legacyVolumeAgeSeconds` ago, is removed; anything else is left and
 *     reported (it may belong to an older service still running).
 * planSweep decides (pure: tested without an engine), sweepOrphans acts and logs one line per item.
 */
import type Docker from 'dockerode';
import { judgeOwner, LABEL_JOB, LABEL_KIND, LABEL_OWNER, LABEL_OWNER_INSTANCE, ownerLabelValue, type ServiceOwner } from './docker-owner.js';
import { processStartTime } from './process-owner.js';

export interface SweepPolicy {
  /** An unowned container that is not running is removed once it is this old. Default 600 (10 min). */
  legacyContainerAgeSeconds: number;
  /** An unowned volume no container mounts is removed once it is this old. Default 86400 (1 day). */
  legacyVolumeAgeSeconds: number;
}

export const DEFAULT_SWEEP_POLICY: SweepPolicy = { legacyContainerAgeSeconds: 600, legacyVolumeAgeSeconds: 86_400 };

export interface SeenContainer {
  id: string;
  name: string;
  /** running | created | exited | paused | restarting | removing | dead */
  state: string;
  /** Unix seconds. */
  created: number;
  labels: Record<string, string>;
  /** Names of the volumes it mounts. */
  volumes: string[];
}

export interface SeenVolume {
  name: string;
  /** Unix seconds (NaN when the engine does not say). */
  created: number;
  labels: Record<string, string>;
}

export interface SweepStep {
  kind: 'container' | 'volume';
  /** Container id or volume name. */
  id: string;
  /** How the item is named in the log: "container 3f2a9c81d0e2 (contract-j-12-run) of job j-12". */
  what: string;
  action: 'remove' | 'report';
  /** Why, in words: "its service pid 4242 is gone". */
  why: string;
}

export interface SweepReport {
  removedContainers: string[];
  removedVolumes: string[];
  /** Items left and reported (legacy ones, removals the engine refused). */
  left: string[];
  lines: string[];
}

function age(seconds: number): string {
  if (seconds < 120) return `${Math.max(0, Math.round(seconds))} s`;
  if (seconds < 7200) return `${Math.round(seconds / 60)} min`;
  if (seconds < 172_800) return `${Math.round(seconds / 3600)} h`;
  return `${Math.round(seconds / 86_400)} days`;
}

function describe(kind: 'container' | 'volume', id: string, name: string, labels: Record<string, string>): string {
  const shown = kind === 'container' ? `container ${id.slice(0, 12)}${name ? ` (${name})` : ''}` : `volume ${id}`;
  const job = labels[LABEL_JOB];
  return job ? `${shown} of job ${job}` : shown;
}

/** Decides what to do with each labelled container and volume (containers first, then volumes). */
export function planSweep(
  containers: SeenContainer[],
  volumes: SeenVolume[],
  self: ServiceOwner,
  nowSeconds: number,
  policy: SweepPolicy = DEFAULT_SWEEP_POLICY,
  startTimeOf: (pid: number) => string | null = processStartTime,
): SweepStep[] {
  const steps: SweepStep[] = [];
  const removed = new Set<string>();
  for (const c of containers) {
    if (c.labels[LABEL_KIND] !== 'job') continue;
    const what = describe('container', c.id, c.name, c.labels);
    const verdict = judgeOwner(c.labels, self, startTimeOf);
    if (verdict.state === 'dead') {
      steps.push({ kind: 'container', id: c.id, what, action: 'remove', why: verdict.why });
      removed.add(c.id);
    } else if (verdict.state === 'unowned') {
      const old = nowSeconds - c.created;
      if (c.state === 'running' || c.state === 'restarting' || c.state === 'paused') {
        steps.push({ kind: 'container', id: c.id, what, action: 'report', why: `no owner label (made before owner labels), ${c.state}: it may belong to an older service still running; remove it with "docker rm -f ${c.id.slice(0, 12)}" once that is gone` });
      } else if (old >= policy.legacyContainerAgeSeconds) {
        steps.push({ kind: 'container', id: c.id, what, action: 'remove', why: `no owner label, ${c.state}, created ${age(old)} ago` });
        removed.add(c.id);
      } else {
        steps.push({ kind: 'container', id: c.id, what, action: 'report', why: `no owner label, ${c.state}, created ${age(old)} ago: may belong to an older service still running` });
      }
    }
  }
  const mounted = new Set(containers.filter((c) => !removed.has(c.id)).flatMap((c) => c.volumes));
  for (const v of volumes) {
    if (v.labels[LABEL_KIND] !== 'workspace') continue;
    const what = describe('volume', v.name, '', v.labels);
    const verdict = judgeOwner(v.labels, self, startTimeOf);
    if (verdict.state === 'dead') {
      steps.push({ kind: 'volume', id: v.name, what, action: 'remove', why: verdict.why });
    } else if (verdict.state === 'unowned') {
      const old = nowSeconds - v.created;
      if (mounted.has(v.name)) {
        steps.push({ kind: 'volume', id: v.name, what, action: 'report', why: 'no owner label, mounted by a container that stays' });
      } else if (old >= policy.legacyVolumeAgeSeconds) {
        steps.push({ kind: 'volume', id: v.name, what, action: 'remove', why: `no owner label, unused, created ${age(old)} ago` });
      } else {
        const when = Number.isFinite(old) ? `created ${age(old)} ago` : 'creation time unknown';
        steps.push({ kind: 'volume', id: v.name, what, action: 'report', why: `no owner label, ${when}: may be the workspace of an older service still running` });
      }
    }
  }
  return steps;
}

/**
 * What the engine holds: containers (all states; every one of them, so that volumes mounted by
 * containers without our labels count as in use) and workspace volumes; with `only`, just those
 * labelled with that service instance.
 */
export async function listSeen(docker: Docker, only?: ServiceOwner): Promise<{ containers: SeenContainer[]; volumes: SeenVolume[] }> {
  const mine = only ? [`${LABEL_OWNER}=${ownerLabelValue(only)}`, `${LABEL_OWNER_INSTANCE}=${only.instance}`] : null;
  const owned = mine ? { filters: { label: mine } } : {};
  const list = await docker.listContainers({ all: true, ...owned });
  const containers = list.map((c) => ({
    id: c.Id,
    name: (c.Names?.[0] ?? '').replace(/^\//, ''),
    state: c.State ?? 'unknown',
    created: c.Created,
    labels: c.Labels ?? {},
    volumes: (c.Mounts ?? []).filter((m) => m.Type === 'volume' && m.Name).map((m) => m.Name as string),
  }));
  const { Volumes } = await docker.listVolumes({ filters: { label: mine ?? [`${LABEL_KIND}=workspace`] } });
  const volumes = (Volumes ?? []).map((v) => ({
    name: v.Name,
    created: Date.parse((v as { CreatedAt?: string }).CreatedAt ?? '') / 1000,
    labels: v.Labels ?? {},
  }));
  return { containers, volumes };
}

function firstLine(e: unknown): string {
  return ((e as Error).message ?? String(e)).split('\n')[0]!;
}

/** Carries out the steps, one log line per item; removals the engine refuses are reported. */
export async function applySweep(docker: Docker, steps: SweepStep[], log: (line: string) => void): Promise<SweepReport> {
  const report: SweepReport = { removedContainers: [], removedVolumes: [], left: [], lines: [] };
  const say = (line: string): void => {
    report.lines.push(line);
    log(line);
  };
  for (const s of steps) {
    if (s.action === 'report') {
      report.left.push(s.id);
      say(`docker: left ${s.what} (${s.why})`);
      continue;
    }
    try {
      if (s.kind === 'container') await docker.getContainer(s.id).remove({ force: true, v: true });
      else await docker.getVolume(s.id).remove();
    } catch (e) {
      if ((e as { statusCode?: number }).statusCode === 404) continue; // someone else removed it meanwhile
      report.left.push(s.id);
      say(`docker: could not remove ${s.what} (${s.why}): ${firstLine(e)}`);
      continue;
    }
    (s.kind === 'container' ? report.removedContainers : report.removedVolumes).push(s.id);
    say(`docker: removed ${s.what} (${s.why})`);
  }
  return report;
}

/** Removes what dead services left (see the header); `self` is never judged dead. */
export async function sweepOrphans(
  docker: Docker,
  self: ServiceOwner,
  log: (line: string) => void,
  policy: SweepPolicy = DEFAULT_SWEEP_POLICY,
): Promise<SweepReport> {
  const { containers, volumes } = await listSeen(docker);
  return applySweep(docker, planSweep(containers, volumes, self, Date.now() / 1000, policy), log);
}

/** At shutdown: removes every container and volume still labelled with this service instance. */
export async function removeOwnLeftovers(docker: Docker, self: ServiceOwner, log: (line: string) => void): Promise<SweepReport> {
  const { containers, volumes } = await listSeen(docker, self);
  const steps: SweepStep[] = [
    ...containers.map((c) => ({ kind: 'container' as const, id: c.id, what: describe('container', c.id, c.name, c.labels), action: 'remove' as const, why: `left by this service at shutdown, ${c.state}` })),
    ...volumes.map((v) => ({ kind: 'volume' as const, id: v.name, what: describe('volume', v.name, '', v.labels), action: 'remove' as const, why: 'left by this service at shutdown' })),
  ];
  return applySweep(docker, steps, log);
}
