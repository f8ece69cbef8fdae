/**
 * The sweep of what dead build services left in the Docker engine, with the real engine: planted
 * containers and volumes owned by a dead process, by this live process and by nobody; a real
 * service child killed with -9 while its job loops for ever; the shutdown clean-up of close().
 * Starts dockerd when needed (scripts/docker-up.sh), or says SKIPPED loudly with the reason.
 */
import { spawn } from 'node:child_process';
import { randomBytes } from 'node:crypto';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import Docker from 'dockerode';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { JobService } from './job-service.js';
import { DOCKER_IMAGE, DockerSandbox } from './sandbox/docker.js';
import { currentOwner, LABEL_JOB, ownerLabels, type ServiceOwner } from './sandbox/docker-owner.js';
import { processStartTime } from './sandbox/process-owner.js';
import type { SweepReport } from './sandbox/docker-sweep.js';
import { honestProgram, infiniteLoop, makeProject } from './test-support/c-projects.js';
import { killServiceMidRun } from './test-support/child-process-service.js';
import { dockerUp } from './test-support/docker-env.js';

const env = dockerUp();
const docker = new Docker();
const planted = { containers: new Set<string>(), volumes: new Set<string>() };
const childJobs: string[] = [];
/** A child service was started (and killed: killServiceMidRun): its leftovers are a dead service's. */
let orphanSpawned = false;
const tempDirs: string[] = [];
const services: JobService[] = [];

/** A container running `sleep 600` in the job image, with a volume, both labelled as given. */
async function plant(containerLabels: Record<string, string>, volumeLabels: Record<string, string>): Promise<{ container: string; name: string; volume: string }> {
  const tag = randomBytes(4).toString('hex');
  const volume = `contract-test-sweep-${tag}`;
  await docker.createVolume({ Name: volume, Labels: volumeLabels });
  planted.volumes.add(volume);
  const name = `contract-test-sweep-${tag}`;
  const c = await docker.createContainer({
    name,
    Image: DOCKER_IMAGE,
    Cmd: ['sleep', '600'],
    Labels: containerLabels,
    NetworkDisabled: true,
    HostConfig: { NetworkMode: 'none', Init: true, Mounts: [{ Type: 'volume', Source: volume, Target: '/work' }] },
  });
  planted.containers.add(c.id);
  await c.start();
  return { container: c.id, name, volume };
}

async function exists(kind: 'container' | 'volume', id: string): Promise<boolean> {
  try {
    if (kind === 'container') await docker.getContainer(id).inspect();
    else await docker.getVolume(id).inspect();
    return true;
  } catch (e) {
    if ((e as { statusCode?: number }).statusCode === 404) return false;
    throw e;
  }
}

async function isRunning(id: string): Promise<boolean> {
  return (await docker.getContainer(id).inspect()).State.Running;
}

/** An owner that existed and is gone: a real process, its start time read, then killed and reaped. */
async function deadOwner(): Promise<ServiceOwner> {
  const child = spawn('sleep', ['60'], { stdio: 'ignore' });
  const startTime = processStartTime(child.pid!)!;
  const exited = new Promise((r) => child.once('exit', r));
  child.kill('SIGKILL');
  await exited;
  return { ...currentOwner(), pid: child.pid!, startTime };
}

function collectingService(options: ConstructorParameters<typeof JobService>[0]): { service: JobService; lines: string[] } {
  const lines: string[] = [];
  const cacheDir = mkdtempSync(join(tmpdir(), 'contract-sweep-cache-'));
  tempDirs.push(cacheDir);
  const service = new JobService({ concurrency: 1, cacheDir, ...options, log: (l) => lines.push(l) });
  services.push(service);
  return { service, lines };
}

afterAll(async () => {
  try {
    for (const s of services) await s.close().catch(() => {});
    if (env.available) {
      // a child killed before it said its job id: its leftovers are those of a dead service
      if (orphanSpawned) await new DockerSandbox({ log: () => {} }).sweep();
      for (const job of childJobs) {
        for (const c of await docker.listContainers({ all: true, filters: { label: [`${LABEL_JOB}=${job}`] } })) planted.containers.add(c.Id);
        const { Volumes } = await docker.listVolumes({ filters: { label: [`${LABEL_JOB}=${job}`] } });
        for (const v of Volumes ?? []) planted.volumes.add(v.Name);
      }
      for (const id of planted.containers) await docker.getContainer(id).remove({ force: true, v: true }).catch(() => {});
      for (const v of planted.volumes) await docker.getVolume(v).remove().catch(() => {});
    }
    for (const d of tempDirs) rmSync(d, { recursive: true, force: true });
  } finally {
    env.stop();
  }
}, 60_000);

if (!env.available) {
  describe('docker sweep', () => {
    test.skip(`SKIPPED: ${env.reason}`, () => {});
  });
} else {
  describe('start-up sweep (default sandbox docker): planted containers and volumes', () => {
    let dead: ServiceOwner;
    let orphan: { container: string; name: string; volume: string };
    let live: { container: string; name: string; volume: string };
    let legacy: { container: string; name: string; volume: string };
    let service: JobService;
    let lines: string[];
    let report: SweepReport;

    beforeAll(async () => {
      dead = await deadOwner();
      orphan = await plant(ownerLabels(dead, 'job', 'j-test-dead'), ownerLabels(dead, 'workspace', 'j-test-dead'));
      const self = currentOwner(); // this live process, another service instance
      live = await plant(ownerLabels(self, 'job', 'j-test-live'), ownerLabels(self, 'workspace', 'j-test-live'));
      // made before owner labels: running, and its volume mounted
      legacy = await plant({ 'contract-studio': 'job' }, { 'contract-studio': 'workspace' });
      expect(await isRunning(orphan.container)).toBe(true);
      ({ service, lines } = collectingService({ sandbox: 'docker' }));
      report = await service.sweepDocker();
    }, 60_000);

    test('the container and the volume of a dead service are removed, one log line each', async () => {
      expect(await exists('container', orphan.container)).toBe(false);
      expect(await exists('volume', orphan.volume)).toBe(false);
      expect(report.removedContainers).toContain(orphan.container);
      expect(report.removedVolumes).toContain(orphan.volume);
      expect(lines).toContain(`docker: removed container ${orphan.container.slice(0, 12)} (${orphan.name}) of job j-test-dead (its service pid ${dead.pid} is gone)`);
      expect(lines).toContain(`docker: removed volume ${orphan.volume} of job j-test-dead (its service pid ${dead.pid} is gone)`);
    });

    test('the container and volume of a live service (this process) are untouched and not logged', async () => {
      expect(await isRunning(live.container)).toBe(true);
      expect(await exists('volume', live.volume)).toBe(true);
      expect(lines.filter((l) => l.includes(live.container.slice(0, 12)) || l.includes(live.volume))).toEqual([]);
    });

    test('a running container without owner label is left and reported once, its mounted volume too', async () => {
      expect(await isRunning(legacy.container)).toBe(true);
      expect(await exists('volume', legacy.volume)).toBe(true);
      const about = lines.filter((l) => l.includes(legacy.container.slice(0, 12)));
      expect(about).toHaveLength(1);
      expect(about[0]).toMatch(new RegExp(`^docker: left container ${legacy.container.slice(0, 12)} \\(${legacy.name}\\) \\(no owner label \\(made before owner labels\\), running: .*docker rm -f`));
      expect(lines).toContain(`docker: left volume ${legacy.volume} (no owner label, mounted by a container that stays)`);
    });

    test('the sweep runs once per service: a second call returns the same report', async () => {
      const n = lines.length;
      expect(await service.sweepDocker()).toBe(report);
      expect(lines).toHaveLength(n);
    });

    test('close() removes what this service instance still owns, and nothing of another instance', async () => {
      const own = service.sandboxes.docker.owner;
      const leftover = await plant(ownerLabels(own, 'job', 'j-test-own'), ownerLabels(own, 'workspace', 'j-test-own'));
      await service.close();
      expect(await exists('container', leftover.container)).toBe(false);
      expect(await exists('volume', leftover.volume)).toBe(false);
      expect(lines).toContain(`docker: removed container ${leftover.container.slice(0, 12)} (${leftover.name}) of job j-test-own (left by this service at shutdown, running)`);
      expect(lines).toContain(`docker: removed volume ${leftover.volume} of job j-test-own (left by this service at shutdown)`);
      expect(await isRunning(live.container)).toBe(true);
    });
  });

  describe('clean shutdown mid-run', () => {
    test('close() while a docker job loops removes its container and volume', async () => {
      const { service } = collectingService({ sandbox: 'docker' });
      const job = await service.submit({ action: 'run', kind: 'make', project: { files: makeProject(infiniteLoop) } });
      childJobs.push(job.id); // cleaned up after the tests should this one fail
      await new Promise<void>((resolve, reject) => {
        const timer = setTimeout(() => reject(new Error('the job did not loop within 40 s')), 40_000);
        job.events.subscribe(0, (e) => {
          if (e.type === 'line' && e.line === 'looping') {
            clearTimeout(timer);
            resolve();
          }
        });
      });
      const [running] = await docker.listContainers({ filters: { label: [`${LABEL_JOB}=${job.id}`] } });
      expect(running?.Names[0]).toBe(`/contract-${job.id}-run`);
      await service.close();
      expect(job.status).toBe('cancelled');
      expect(await exists('container', running!.Id)).toBe(false);
      const { Volumes } = await docker.listVolumes({ filters: { label: [`${LABEL_JOB}=${job.id}`] } });
      expect(Volumes ?? []).toEqual([]);
    }, 60_000);
  });

  describe('clean shutdown after a job', () => {
    test('close() releases the kept work volume and its holder without naming them as leftovers', async () => {
      // a project folder (not inline files): its workspace, and so its volume, is kept between jobs
      const dir = mkdtempSync(join(tmpdir(), 'contract-sweep-project-'));
      tempDirs.push(dir);
      for (const [rel, text] of Object.entries(makeProject(honestProgram(3)))) writeFileSync(join(dir, rel), text);
      const { service, lines } = collectingService({ sandbox: 'docker', projectRoots: [dir], persistentWorkspaces: true }); // as the CLI: the work tree outlives the service, the volume cannot
      const job = await service.submit({ action: 'run', kind: 'make', project: { dir } });
      childJobs.push(job.id);
      await job.finished;
      expect(job.status).toBe('succeeded');
      // between jobs the work volume stays, with its holder, for the next (incremental) build
      const kept = await docker.listVolumes({ filters: { label: [`${LABEL_JOB}=${job.id}`] } });
      expect((kept.Volumes ?? []).length).toBe(1);
      await service.close();
      const { Volumes } = await docker.listVolumes({ filters: { label: [`${LABEL_JOB}=${job.id}`] } });
      expect(Volumes ?? []).toEqual([]);
      expect(await docker.listContainers({ all: true, filters: { label: [`${LABEL_JOB}=${job.id}`] } })).toEqual([]);
      expect(lines.filter((l) => l.includes('left by this service'))).toEqual([]);
    }, 60_000);
  });

  describe('a service killed with -9 mid-run', () => {
    test('its looping container keeps running; the next service sweeps it at its first docker job', async () => {
      const cacheDir = mkdtempSync(join(tmpdir(), 'contract-orphan-cache-'));
      tempDirs.push(cacheDir);
      orphanSpawned = true;
      const child = await killServiceMidRun(cacheDir, 'docker', 40_000);
      const jobId = child.jobId;
      childJobs.push(jobId);
      const [orphan] = await docker.listContainers({ all: true, filters: { label: [`${LABEL_JOB}=${jobId}`] } });
      expect(orphan, 'the run container of the killed service').toBeDefined();
      expect(orphan!.Names[0]).toBe(`/contract-${jobId}-run`);
      await new Promise((r) => setTimeout(r, 500));
      expect(await isRunning(orphan!.Id)).toBe(true); // nobody stops it: it would loop for ever
      const { Volumes } = await docker.listVolumes({ filters: { label: [`${LABEL_JOB}=${jobId}`] } });
      expect(Volumes).toHaveLength(1);
      const volume = Volumes![0]!.Name;

      // a new service whose default is bwrap: its first docker job sweeps before its own container
      const { service, lines } = collectingService({ sandbox: 'bwrap' });
      const job = await service.submit({ action: 'build', kind: 'make', sandbox: 'docker', project: { files: makeProject(honestProgram(1)) } });
      await job.finished;
      expect(job.status, JSON.stringify(job.result)).toBe('succeeded');
      expect(await exists('container', orphan!.Id)).toBe(false);
      expect(await exists('volume', volume)).toBe(false);
      expect(lines).toContain(`docker: removed container ${orphan!.Id.slice(0, 12)} (contract-${jobId}-run) of job ${jobId} (its service pid ${child.pid} is gone)`);
      expect(lines).toContain(`docker: removed volume ${volume} of job ${jobId} (its service pid ${child.pid} is gone)`);
    }, 60_000);
  });
}
