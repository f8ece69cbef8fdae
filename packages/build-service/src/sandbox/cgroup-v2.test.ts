/**
 * The cgroup v2 decision logic on fake /proc + /sys trees (plain files: this machine's cgroup2
 * hierarchy has no memory or pids controller, they are bound to v1, so the v2 path is not
 * exercised against the kernel here — docs/sandbox.md says so): which hierarchy is chosen, why a
 * v2 subtree is refused (no unified entry, no cgroup2 mount, controllers missing, not delegated,
 * foreign processes), the move into the service's leaf and the controllers enabled, the limits
 * written, and the OOM / pids hits read from memory.events and pids.events.
 */
import { chmodSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { chooseCgroup, createJobCgroup } from './cgroup-choice.js';
import { enableV2Controllers, findDelegatedV2, JobCgroupV2, type CgroupV2Paths } from './cgroup-v2.js';

const scratch = mkdtempSync(join(tmpdir(), 'cgroup-v2-test-'));
afterAll(() => rmSync(scratch, { recursive: true, force: true }));
let n = 0;

/** A fake machine: /proc/self/{cgroup,mounts} and a cgroup2 mount with the service's cgroup. */
function fakeMachine(opts: { cgroupLine?: string; mounts?: string; controllers?: string; procs?: string; subtree?: string } = {}): { paths: CgroupV2Paths; mount: string; own: string } {
  const root = join(scratch, `m${n++}`);
  const mount = join(root, 'sys', 'fs', 'cgroup');
  const own = join(mount, 'user.slice', 'app.scope');
  mkdirSync(own, { recursive: true });
  mkdirSync(join(root, 'proc', 'self'), { recursive: true });
  writeFileSync(join(root, 'proc', 'self', 'cgroup'), opts.cgroupLine ?? '0::/user.slice/app.scope\n');
  writeFileSync(join(root, 'proc', 'self', 'mounts'), opts.mounts ?? `proc /proc proc rw 0 0\ncgroup2 ${mount} cgroup2 rw,nosuid 0 0\n`);
  writeFileSync(join(own, 'cgroup.controllers'), opts.controllers ?? 'cpu io memory pids\n');
  writeFileSync(join(own, 'cgroup.subtree_control'), opts.subtree ?? '');
  writeFileSync(join(own, 'cgroup.procs'), opts.procs ?? '4242\n');
  return { paths: { selfCgroup: join(root, 'proc', 'self', 'cgroup'), selfMounts: join(root, 'proc', 'self', 'mounts'), pid: 4242 }, mount, own };
}

describe('findDelegatedV2', () => {
  test('a delegated unified cgroup with memory and pids is usable', () => {
    const m = fakeMachine();
    expect(findDelegatedV2(m.paths)).toEqual({ ok: true, dir: m.own });
  });

  test('a hybrid host: the cgroup2 mount at /sys/fs/cgroup/unified is found from the mounts', () => {
    const m = fakeMachine({ cgroupLine: '9:memory:/\n8:pids:/\n0::/user.slice/app.scope\n' });
    expect(findDelegatedV2(m.paths)).toEqual({ ok: true, dir: m.own });
  });

  test('refusals say why', () => {
    expect(findDelegatedV2(fakeMachine({ cgroupLine: '9:memory:/\n8:pids:/\n' }).paths)).toEqual({ ok: false, reason: 'no cgroup v2 (unified) entry in /proc/self/cgroup' });
    expect(findDelegatedV2(fakeMachine({ mounts: 'proc /proc proc rw 0 0\n' }).paths)).toEqual({ ok: false, reason: 'no cgroup2 file system mounted' });
    // this machine's case: an empty cgroup2 hierarchy next to cgroup v1
    const empty = findDelegatedV2(fakeMachine({ controllers: '' }).paths);
    expect(empty.ok).toBe(false);
    expect(!empty.ok && empty.reason).toMatch(/does not offer the memory and pids controller\(s\) — on a hybrid host they stay bound to cgroup v1/);
    const onlyCpu = findDelegatedV2(fakeMachine({ controllers: 'cpu pids' }).paths);
    expect(!onlyCpu.ok && onlyCpu.reason).toMatch(/does not offer the memory controller\(s\) \(only cpu pids\)/);
  });

  test.runIf(process.getuid?.() !== 0)('a cgroup that is not writable is not delegated', () => {
    const m = fakeMachine();
    chmodSync(join(m.own, 'cgroup.subtree_control'), 0o444);
    const d = findDelegatedV2(m.paths);
    expect(!d.ok && d.reason).toMatch(/is not delegated to this service \(cgroup.subtree_control is not writable\)/);
  });
});

describe('chooseCgroup', () => {
  test('v1 first, then a delegated v2, else none with both reasons', () => {
    expect(chooseCgroup(null, { ok: true, dir: '/x' })).toEqual({ kind: 'cgroup-v1' });
    expect(chooseCgroup('not root', { ok: true, dir: '/x' })).toEqual({ kind: 'cgroup-v2', dir: '/x' });
    expect(chooseCgroup('cgroup v1 controller "memory" is not mounted', { ok: false, reason: 'no cgroup2 file system mounted' })).toEqual({
      kind: 'none',
      reason: 'cgroup v1: cgroup v1 controller "memory" is not mounted; cgroup v2: no cgroup2 file system mounted',
    });
  });
});

describe('enableV2Controllers and JobCgroupV2', () => {
  test('the service moves into its leaf, memory and pids are enabled for children, the job gets its limits', async () => {
    const m = fakeMachine();
    const cg = await createJobCgroup({ kind: 'cgroup-v2', dir: m.own }, 'contract-j1-build', 512 * 1024 * 1024, 256, m.paths);
    expect(readFileSync(join(m.own, 'contract-service', 'cgroup.procs'), 'utf8')).toBe('4242');
    expect(readFileSync(join(m.own, 'cgroup.subtree_control'), 'utf8')).toBe('+memory +pids');
    const dir = join(m.own, 'contract-j1-build');
    expect(readFileSync(join(dir, 'memory.max'), 'utf8')).toBe(String(512 * 1024 * 1024));
    expect(readFileSync(join(dir, 'memory.swap.max'), 'utf8')).toBe('0');
    expect(readFileSync(join(dir, 'pids.max'), 'utf8')).toBe('256');
    expect(readFileSync(join(dir, 'memory.oom.group'), 'utf8')).toBe('1');
    expect(cg.mechanism).toBe('cgroup-v2');
    expect(cg.procsFiles).toEqual([join(dir, 'cgroup.procs')]);
    // a run's: the kernel kills one process at an OOM, the run's launcher stops the others
    await createJobCgroup({ kind: 'cgroup-v2', dir: m.own }, 'contract-j1-run', 512 * 1024 * 1024, 256, m.paths, false);
    expect(readFileSync(join(m.own, 'contract-j1-run', 'memory.oom.group'), 'utf8')).toBe('0');
  });

  test('controllers already enabled: nothing moves', async () => {
    const m = fakeMachine({ subtree: 'memory pids\n' });
    await enableV2Controllers(m.own, m.paths);
    expect(readFileSync(join(m.own, 'cgroup.subtree_control'), 'utf8')).toBe('memory pids\n');
  });

  test("processes that are not the service's are not moved: refused with the reason", async () => {
    const m = fakeMachine({ procs: '4242\n17\n' });
    await expect(enableV2Controllers(m.own, m.paths)).rejects.toThrow(/also holds processes that are not this service's \(17\)/);
  });

  test('an OOM kill and a refused fork are read from memory.events and pids.events', async () => {
    const m = fakeMachine({ subtree: 'memory pids' });
    const cg = await JobCgroupV2.create(m.own, 'contract-j2-run', 1 << 20, 8);
    const dir = join(m.own, 'contract-j2-run');
    expect(await cg.oomKills()).toBe(0);
    writeFileSync(join(dir, 'memory.events'), 'low 0\nhigh 0\nmax 12\noom 1\noom_kill 1\noom_group_kill 0\n');
    expect(await cg.oomKills()).toBe(1);
    writeFileSync(join(dir, 'memory.events'), 'low 0\nhigh 0\nmax 3\noom 1\noom_kill 0\noom_group_kill 1\n');
    expect(await cg.oomKills()).toBe(1);
    expect(await cg.pidsLimitHits()).toBe(0);
    writeFileSync(join(dir, 'pids.events'), 'max 3\n');
    expect(await cg.pidsLimitHits()).toBe(3);
    writeFileSync(join(dir, 'cgroup.procs'), '');
    expect(await cg.killAll(100)).toBe(true);
  });
});
