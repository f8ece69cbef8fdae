/**
 * Real-time mode in the Docker sandbox (docs/sandbox.md, "Real-time mode"): the container's user
 * (1000, no capabilities) takes SCHED_FIFO through RLIMIT_RTPRIO (`--ulimit rtprio`), RLIMIT_RTTIME
 * stops a process that runs too long without blocking (`--ulimit rttime`), and on cgroup v1 the
 * container's cpu cgroup gets a real-time budget (`--cpu-rt-runtime` / `--cpu-rt-period`), which
 * the daemon can only hand out when it was started with its own `--cpu-rt-runtime`.
 */
import { readFileSync } from 'node:fs';
import type Docker from 'dockerode';
import type { HostConfig } from 'dockerode';
import type { RealtimeBounds } from '../limits.js';

export type DockerRealtimeSupport = { ok: true; detail: string; cgroupBudget: boolean } | { ok: false; reason: string };

/** The HostConfig fields of a real-time run. */
export function dockerRealtimeHostConfig(bounds: RealtimeBounds, cgroupBudget: boolean): Partial<HostConfig> {
  return {
    Ulimits: [
      { Name: 'rtprio', Soft: bounds.priorityCeiling, Hard: bounds.priorityCeiling },
      { Name: 'rttime', Soft: bounds.cpuWithoutBlockingSoftUs, Hard: bounds.cpuWithoutBlockingHardUs },
    ],
    ...(cgroupBudget ? { CpuRtPeriod: bounds.cpuPeriodUs, CpuRtRuntime: bounds.cpuRuntimeUs } : {}),
  };
}

/**
 * What the engine can grant. cgroup v1 (where Docker supports a real-time budget): the daemon's
 * parent cgroup must have one; it is read where the engine is local (/sys/fs/cgroup/cpu/docker),
 * a remote engine answers at container creation. cgroup v2: no per-container budget exists; the
 * bound is RLIMIT_RTTIME and the kernel's global throttling.
 */
export async function dockerRealtimeSupport(docker: Docker, bounds: RealtimeBounds, parentRuntimeFile = '/sys/fs/cgroup/cpu/docker/cpu.rt_runtime_us'): Promise<DockerRealtimeSupport> {
  const info = (await docker.info()) as { CgroupVersion?: string };
  const limits = `SCHED_FIFO up to ${bounds.priorityCeiling} (ulimit rtprio); RLIMIT_RTTIME ${bounds.cpuWithoutBlockingSoftUs / 1e6} s / ${bounds.cpuWithoutBlockingHardUs / 1e6} s (ulimit rttime)`;
  if (info.CgroupVersion === '2') {
    return { ok: true, cgroupBudget: false, detail: `${limits}; no per-container budget on cgroup v2: kernel.sched_rt_runtime_us (global-rt-throttling)` };
  }
  if (!process.env.DOCKER_HOST) {
    let parent: number | null = null;
    try {
      parent = Number(readFileSync(parentRuntimeFile, 'utf8').trim());
    } catch {
      parent = null; // no such cgroup yet (no container ran) or no CONFIG_RT_GROUP_SCHED: the engine answers
    }
    if (parent === 0) {
      return {
        ok: false,
        reason:
          'the Docker daemon gives its containers no real-time budget (its cgroup\'s cpu.rt_runtime_us is 0): ' +
          `start dockerd with --cpu-rt-runtime=<µs per second> (at least ${bounds.cpuRuntimeUs * (1_000_000 / bounds.cpuPeriodUs)}: the budget all its containers share)`,
      };
    }
  }
  return { ok: true, cgroupBudget: true, detail: `${limits}; cpu.rt_runtime_us ${bounds.cpuRuntimeUs} per ${bounds.cpuPeriodUs} (--cpu-rt-runtime)` };
}

/** An engine error while creating or starting a real-time container, with what the engine needs. */
export function dockerRealtimeError(e: Error, bounds: RealtimeBounds): Error {
  const cause = e.message.split('\n')[0]!.replace(/^\(HTTP code \d+\)[^-]*-\s*/, '').trim();
  return new Error(
    `real-time mode refused by the Docker engine: ${cause} — it needs a real-time budget for its containers ` +
      `(dockerd --cpu-rt-runtime=${bounds.cpuRuntimeUs * (1_000_000 / bounds.cpuPeriodUs)} or more) and may have to raise RLIMIT_RTPRIO (CAP_SYS_RESOURCE); docs/sandbox.md "Real-time mode"`,
  );
}
