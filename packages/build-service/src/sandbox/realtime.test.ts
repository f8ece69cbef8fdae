/** The decision of how real-time mode is granted and bounded (realtime.ts), on every kind of host. */
import { describe, expect, test } from 'vitest';
import { REALTIME_BOUNDS } from '../limits.js';
import { describeRealtime, planRealtime, readRealtimeFacts, realtimePrefix, type RealtimeFacts } from './realtime.js';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import type Docker from 'dockerode';
import { dockerRealtimeError, dockerRealtimeHostConfig, dockerRealtimeSupport } from './docker-realtime.js';

/** A root service on a cgroup v1 host with CONFIG_RT_GROUP_SCHED (what most root services see). */
const rootV1: RealtimeFacts = {
  capSysNice: true,
  capSysResource: true,
  rtprioHard: 0,
  cpuCgroupDir: '/sys/fs/cgroup/cpu/',
  cpuCgroupRtRuntimeUs: 950_000,
  cpuCgroupWritable: true,
  globalRtRuntimeUs: 950_000,
};

describe('planRealtime', () => {
  test('root with CAP_SYS_RESOURCE: RLIMIT_RTPRIO raised, a per-job rt budget in the cpu cgroup', () => {
    expect(planRealtime(rootV1, REALTIME_BOUNDS)).toEqual({ ok: true, grant: 'rlimit-rtprio', budget: 'cgroup-v1-rt', cpuCgroupDir: '/sys/fs/cgroup/cpu/' });
  });

  test('a user given rtprio 99 in limits.conf: RLIMIT_RTPRIO, no capability needed', () => {
    const plan = planRealtime({ ...rootV1, capSysNice: false, capSysResource: false, rtprioHard: 99 }, REALTIME_BOUNDS);
    expect(plan).toMatchObject({ ok: true, grant: 'rlimit-rtprio' });
  });

  test('root without CAP_SYS_RESOURCE (a container) but with CAP_SYS_NICE: the run starts at FIFO <ceiling>', () => {
    expect(planRealtime({ ...rootV1, capSysResource: false }, REALTIME_BOUNDS)).toMatchObject({ ok: true, grant: 'inherited-fifo', budget: 'cgroup-v1-rt' });
  });

  test('no way to grant FIFO: refused, saying how to allow it', () => {
    const plan = planRealtime({ ...rootV1, capSysNice: false, capSysResource: false, rtprioHard: 0 }, REALTIME_BOUNDS);
    expect(plan.ok).toBe(false);
    if (plan.ok) return;
    expect(plan.reason).toMatch(/RLIMIT_RTPRIO hard limit is 0 \(below 99\)/);
    expect(plan.reason).toMatch(/run the service as root, or give its user "<user> - rtprio 99" in \/etc\/security\/limits\.d\//i);
  });

  test('RT group scheduling and a cpu cgroup the service may not write: refused', () => {
    const plan = planRealtime({ ...rootV1, cpuCgroupWritable: false }, REALTIME_BOUNDS);
    expect(plan).toEqual({ ok: false, reason: expect.stringMatching(/CONFIG_RT_GROUP_SCHED.*may not create one under \/sys\/fs\/cgroup\/cpu\/: run the service as root/) });
  });

  test('the service itself in a cpu cgroup without rt budget: refused (no FIFO is possible below it)', () => {
    const plan = planRealtime({ ...rootV1, cpuCgroupRtRuntimeUs: 0 }, REALTIME_BOUNDS);
    expect(plan).toEqual({ ok: false, reason: expect.stringMatching(/has no real-time budget \(cpu\.rt_runtime_us = 0\)/) });
  });

  test('no RT group scheduling (cgroup v2, or a kernel without it): the global throttling bounds', () => {
    const plan = planRealtime({ ...rootV1, cpuCgroupDir: null, cpuCgroupRtRuntimeUs: null, cpuCgroupWritable: false }, REALTIME_BOUNDS);
    expect(plan).toEqual({ ok: true, grant: 'rlimit-rtprio', budget: 'global-rt-throttling', cpuCgroupDir: null });
  });

  test('no RT group scheduling and global throttling off: refused, saying the sysctl', () => {
    const plan = planRealtime({ ...rootV1, cpuCgroupDir: null, cpuCgroupRtRuntimeUs: null, globalRtRuntimeUs: -1 }, REALTIME_BOUNDS);
    expect(plan).toEqual({ ok: false, reason: expect.stringMatching(/sysctl kernel\.sched_rt_runtime_us=950000/) });
  });
});

describe('what the sandbox runs', () => {
  test('inherited FIFO: chrt at the ceiling, RLIMIT_RTTIME; RLIMIT_RTPRIO grant: no chrt', () => {
    expect(realtimePrefix('inherited-fifo', REALTIME_BOUNDS)).toEqual({ chrt: ['chrt', '--fifo', '99'], prlimit: ['--rttime=500000:1000000'] });
    expect(realtimePrefix('rlimit-rtprio', REALTIME_BOUNDS)).toEqual({ chrt: [], prlimit: ['--rttime=500000:1000000', '--rtprio=99'] });
  });

  test('the mechanism line names each bound', () => {
    expect(describeRealtime('inherited-fifo', 'cgroup-v1-rt', REALTIME_BOUNDS)).toBe(
      'SCHED_FIFO up to 99 (inherited-fifo); cpu.rt_runtime_us 40000 per 100000 on each CPU (cgroup-v1-rt); RLIMIT_RTTIME 0.5 s / 1 s',
    );
    expect(describeRealtime('rlimit-rtprio', 'global-rt-throttling', REALTIME_BOUNDS, 950000)).toMatch(/kernel\.sched_rt_runtime_us 950000 \(global-rt-throttling\)/);
  });

  test('docker: ulimits rtprio and rttime, and the rt budget where the engine has one', () => {
    expect(dockerRealtimeHostConfig(REALTIME_BOUNDS, true)).toEqual({
      Ulimits: [
        { Name: 'rtprio', Soft: 99, Hard: 99 },
        { Name: 'rttime', Soft: 500000, Hard: 1000000 },
      ],
      CpuRtPeriod: 100000,
      CpuRtRuntime: 40000,
    });
    expect(dockerRealtimeHostConfig(REALTIME_BOUNDS, false)).not.toHaveProperty('CpuRtRuntime');
  });

  test('docker: what the engine can grant, read from its cgroup version and its containers\' parent budget', async () => {
    const dir = mkdtempSync(join(tmpdir(), 'contract-rt-docker-'));
    const engine = (version: string) => ({ info: async () => ({ CgroupVersion: version }) }) as unknown as Docker;
    const saved = process.env.DOCKER_HOST;
    delete process.env.DOCKER_HOST;
    try {
      const parent = join(dir, 'cpu.rt_runtime_us');
      writeFileSync(parent, '0\n');
      expect(await dockerRealtimeSupport(engine('1'), REALTIME_BOUNDS, parent)).toEqual({
        ok: false,
        reason: expect.stringMatching(/no real-time budget \(its cgroup's cpu\.rt_runtime_us is 0\): start dockerd with --cpu-rt-runtime=<µs per second> \(at least 400000/),
      });
      writeFileSync(parent, '400000\n');
      expect(await dockerRealtimeSupport(engine('1'), REALTIME_BOUNDS, parent)).toMatchObject({ ok: true, cgroupBudget: true });
      expect(await dockerRealtimeSupport(engine('1'), REALTIME_BOUNDS, join(dir, 'absent'))).toMatchObject({ ok: true, cgroupBudget: true });
      expect(await dockerRealtimeSupport(engine('2'), REALTIME_BOUNDS, parent)).toMatchObject({ ok: true, cgroupBudget: false, detail: expect.stringMatching(/global-rt-throttling/) });
    } finally {
      if (saved !== undefined) process.env.DOCKER_HOST = saved;
      rmSync(dir, { recursive: true, force: true });
    }
  });

  test('docker: an engine error of a real-time container says what the engine needs', () => {
    const e = dockerRealtimeError(new Error('(HTTP code 500) server error - failed to write 40000 to cpu.rt_runtime_us: invalid argument\nmore'), REALTIME_BOUNDS);
    expect(e.message).toBe(
      'real-time mode refused by the Docker engine: failed to write 40000 to cpu.rt_runtime_us: invalid argument — it needs a real-time budget for its containers ' +
        '(dockerd --cpu-rt-runtime=400000 or more) and may have to raise RLIMIT_RTPRIO (CAP_SYS_RESOURCE); docs/sandbox.md "Real-time mode"',
    );
  });

  test('the bounds leave room: two real-time jobs fit under the kernel default budget (95 %)', () => {
    expect((2 * REALTIME_BOUNDS.cpuRuntimeUs) / REALTIME_BOUNDS.cpuPeriodUs).toBeLessThanOrEqual(0.95);
    expect(REALTIME_BOUNDS.cpuWithoutBlockingSoftUs).toBeLessThan(REALTIME_BOUNDS.cpuWithoutBlockingHardUs);
  });
});

test('this host\'s facts are read without throwing and are consistent', () => {
  const facts = readRealtimeFacts();
  expect(typeof facts.capSysNice).toBe('boolean');
  expect(facts.rtprioHard).toBeGreaterThanOrEqual(0);
  if (facts.cpuCgroupRtRuntimeUs !== null) expect(facts.cpuCgroupDir).not.toBeNull();
});
