/**
 * The job cgroups a killed service leaves behind (sandbox/cgroup-sweep.ts, docs/sandbox.md "Cgroups
 * left by a killed service"): the decision on fake answers, then the defect it fixes, for real: two
 * services killed with -9 during a real-time bwrap run kept their cpu cgroups and with them 2 × 40 ms
 * of the kernel's 95 ms real-time budget per 100 ms, so every later real-time run was refused
 * ("no real-time budget left") until the machine rebooted; their work tmpfs stayed mounted too
 * (memory), and made the next service sharing the cache folder fail to close. Each service now
 * removes a dead one's cgroups and work folders before it makes its first own.
 */
import { spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, rmSync, rmdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { JobService } from './job-service.js';
import { BwrapSandbox } from './sandbox/bwrap.js';
import { forgetSweptParents, jobCgroupName, LEGACY_AGE_MS, planCgroupSweep, sweepStaleCgroups } from './sandbox/cgroup-sweep.js';
import type { ProcessOwner } from './sandbox/process-owner.js';
import { processStartTime } from './sandbox/process-owner.js';
import { readRealtimeFacts } from './sandbox/realtime.js';
import { honestProgram, makeProject } from './test-support/c-projects.js';
import { killServiceMidRun } from './test-support/child-process-service.js';

const ID = 'j-0123456789abcdef0123456789abcdef';
const self: ProcessOwner = { pid: 100, startTime: '5000', pidns: '4026531836' };

describe('planCgroupSweep', () => {
  const alive = (pid: number, start: string) => pid === 100 || (pid === 200 && start === '7000');
  const seen = (name: string, ageMs = 0, processes = 0) => ({ name, ageMs, processes });

  test('a dead owner in our pid namespace: removed (its processes killed); a live one kept', () => {
    const plan = planCgroupSweep([
      seen(`contract-${ID}-run.o300-1-4026531836`, 0, 3), // pid 300 gone
      seen(`contract-rt-${ID}-run.o200-6999-4026531836`), // pid 200 reused: started at another time
      seen(`contract-${ID}-build.o200-7000-4026531836`, 0, 2), // pid 200 alive
      seen(`contract-${ID}-run.o100-5000-4026531836`), // ourselves
    ], self, alive);
    expect([...plan]).toEqual([
      [`contract-${ID}-run.o300-1-4026531836`, 'remove'],
      [`contract-rt-${ID}-run.o200-6999-4026531836`, 'remove'],
      [`contract-${ID}-build.o200-7000-4026531836`, 'keep'],
      [`contract-${ID}-run.o100-5000-4026531836`, 'keep'],
    ]);
  });

  test('an owner in another pid namespace is not judged; a name without owner goes only when empty and old; other names untouched', () => {
    const plan = planCgroupSweep([
      seen(`contract-${ID}-run.o300-1-4026532000`),
      seen(`contract-${ID}-run`, LEGACY_AGE_MS, 0),
      seen(`contract-rt-${ID}-run`, LEGACY_AGE_MS - 1, 0),
      seen(`contract-${ID}-build`, LEGACY_AGE_MS * 10, 1),
      seen('contract-service'),
      seen(`contract-${ID}-run.o300-1-4026531836.x`),
      seen(`contract-j-0123-run.o300-1-4026531836`),
      seen('user.slice'),
    ], self, () => false);
    expect([...plan]).toEqual([
      [`contract-${ID}-run.o300-1-4026532000`, 'keep'],
      [`contract-${ID}-run`, 'remove-if-empty'],
      [`contract-rt-${ID}-run`, 'keep'],
      [`contract-${ID}-build`, 'keep'],
    ]);
  });

  test('without its own pid namespace known, no owner is judged', () => {
    const plan = planCgroupSweep([seen(`contract-${ID}-run.o300-1-0`)], { ...self, pidns: '0' }, () => false);
    expect(plan.get(`contract-${ID}-run.o300-1-0`)).toBe('keep');
  });
});

// A real cgroup folder: the pids hierarchy (cgroup v1, root), where a folder costs nothing.
const PIDS = '/sys/fs/cgroup/pids';
const pidsWritable = process.getuid?.() === 0 && existsSync(join(PIDS, 'cgroup.procs'));

describe.skipIf(!pidsWritable)('sweepStaleCgroups on a real cgroup v1 hierarchy', () => {
  test('removes the folder of a dead owner, keeps a live owner\'s and a stranger\'s, once per parent', async () => {
    const parent = join(PIDS, `contract-sweep-test-${process.pid}`);
    mkdirSync(parent);
    try {
      const dead = spawnSync('true'); // a pid that has exited: its owner is gone
      const deadOwner = { pid: dead.pid!, startTime: '1', pidns: '' };
      const me = { pid: process.pid, startTime: processStartTime(process.pid)!, pidns: '' };
      const own = jobCgroupName(`contract-${ID}-run`);
      const pidns = own.slice(own.lastIndexOf('-') + 1);
      const names = {
        dead: jobCgroupName(`contract-rt-${ID}-run`, { ...deadOwner, pidns }),
        live: jobCgroupName(`contract-${ID}-build`, { ...me, pidns }),
        stranger: 'contract-other-tool',
      };
      for (const n of Object.values(names)) mkdirSync(join(parent, n));
      forgetSweptParents();
      expect(await sweepStaleCgroups(parent)).toEqual([names.dead]);
      expect(readdirSync(parent).filter((n) => n.startsWith('contract-')).sort()).toEqual([names.live, names.stranger].sort());
      mkdirSync(join(parent, names.dead));
      expect(await sweepStaleCgroups(parent)).toEqual([]); // once per process and parent
      rmdirSync(join(parent, names.dead));
      for (const n of [names.live, names.stranger]) rmdirSync(join(parent, n));
    } finally {
      spawnSync('sh', ['-c', `rmdir ${parent}/* ${parent} 2>/dev/null`]);
    }
  });
});

const facts = readRealtimeFacts();
const budgetCgroups = facts.cpuCgroupDir !== null && facts.cpuCgroupRtRuntimeUs !== null && facts.cpuCgroupWritable && process.getuid?.() === 0;
const support = budgetCgroups ? await new BwrapSandbox().realtimeSupport() : { ok: false };

describe.skipIf(!support.ok || !budgetCgroups)('a service killed with -9 during a real-time run (bwrap, cgroup v1 real-time budget)', () => {
  const dirs: string[] = [];
  afterAll(() => {
    for (const d of dirs) rmSync(d, { recursive: true, force: true });
  });

  /** A child service whose real-time run loops, killed with -9 once it loops: its job's id. */
  const killedMidRun = async (cacheDir: string): Promise<string> => (await killServiceMidRun(cacheDir, 'bwrap-realtime')).jobId;

  const leftovers = (jobId: string) => readdirSync(facts.cpuCgroupDir!).filter((n) => n.startsWith(`contract-rt-${jobId}-`));
  /** The work tmpfs mounts of the job (its fresh workspace under the service's folder of ws/). */
  const mounts = (jobId: string) => readFileSync('/proc/self/mounts', 'utf8').split('\n').filter((l) => l.includes(`/job-${jobId}/work `));

  test('its cpu cgroup keeps the budget; the next service removes it and its real-time run is granted', async () => {
    const cacheDir = mkdtempSync(join(tmpdir(), 'contract-rt-orphan-'));
    dirs.push(cacheDir);
    // what the bug was: a killed run's budget stays with its cgroup (bwrap's processes are gone)
    // and its work tmpfs stays mounted (memory)
    const first = await killedMidRun(cacheDir);
    expect(leftovers(first), `the cpu cgroup of ${first}`).toHaveLength(1);
    expect(mounts(first), `the work tmpfs of ${first}`).toHaveLength(1);
    // the next service (killed too) removed both before making its own
    const second = await killedMidRun(cacheDir);
    expect(leftovers(first), `the cpu cgroup of ${first}`).toEqual([]);
    expect(mounts(first), `the work tmpfs of ${first}`).toEqual([]);
    expect(leftovers(second), `the cpu cgroup of ${second}`).toHaveLength(1);
    expect(mounts(second), `the work tmpfs of ${second}`).toHaveLength(1);

    forgetSweptParents(); // as a new process: this one may have swept already (one module graph)
    const service = new JobService({ sandbox: 'bwrap', concurrency: 1, cacheDir });
    try {
      const job = await service.submit({ action: 'run', kind: 'make', realtime: true, project: { files: makeProject(honestProgram(1)) } });
      await job.finished;
      expect(job.status, JSON.stringify(job.result)).toBe('succeeded');
      expect(job.result?.mechanisms?.realtime).toMatch(/cgroup-v1-rt/);
    } finally {
      await service.close(); // it threw before: a dead service's mount in the shared ws/ (EBUSY)
    }
    expect(leftovers(second), `the cpu cgroup of ${second}`).toEqual([]);
    expect(mounts(second), `the work tmpfs of ${second}`).toEqual([]);
    expect(existsSync(join(cacheDir, 'ws')), 'ws/ of the shared cache folder, emptied').toBe(false);
  }, 180_000);
});
