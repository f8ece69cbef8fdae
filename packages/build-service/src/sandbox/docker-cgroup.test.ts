/**
 * Finding a Docker container's cgroup from its init's /proc/<pid>/cgroup and reading its counters
 * (docker-cgroup.ts), on fixture texts and fake /proc + /sys trees: cgroup v1 (this machine), a
 * hybrid host (an empty v2 hierarchy at /sys/fs/cgroup/unified), cgroup v2 with the systemd and the
 * cgroupfs drivers, rootless Docker; hostile or foreign texts read as "no cgroup". The v2 path is
 * not exercised against the kernel here (this machine's memory and pids are bound to v1).
 */
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { atPidsLimit, findContainerCgroup, isOomEvent, namesContainer, parseProcCgroup, planContainerCgroup, shmemOfStats } from './docker-cgroup.js';
import { terminateNamedOnHost } from './queue-term.js';

const ID = '679a5f64faf5c7262d8e2534c61cb54143aff5392a16cec3168df7af66aa2338';
const OTHER = 'b'.repeat(64);

/** /proc/<pid>/cgroup of a container's init on this machine (Debian 12, Docker 20.10, cgroupfs driver, v1 + empty v2). */
const V1_HYBRID = `9:name=systemd:/docker/${ID}
8:pids:/docker/${ID}
7:blkio:/docker/${ID}
6:freezer:/docker/${ID}
5:devices:/docker/${ID}
4:memory:/docker/${ID}
3:cpuset:/docker/${ID}
2:cpuacct:/docker/${ID}
1:cpu:/docker/${ID}
0::/docker/${ID}
`;
/** cgroup v2 only, systemd driver (Ubuntu 22.04+, Fedora, Debian 12 default). */
const V2_SYSTEMD = `0::/system.slice/docker-${ID}.scope\n`;
/** cgroup v2 only, cgroupfs driver. */
const V2_CGROUPFS = `0::/docker/${ID}\n`;
/** Rootless Docker (systemd driver) under the user's delegated subtree. */
const V2_ROOTLESS = `0::/user.slice/user-1000.slice/user@1000.service/user.slice/docker-${ID}.scope\n`;

const scratch = mkdtempSync(join(tmpdir(), 'docker-cgroup-test-'));
afterAll(() => rmSync(scratch, { recursive: true, force: true }));
let n = 0;

/** A fake machine: /proc/<pid>/cgroup and the given counter files under its /sys/fs/cgroup. */
function fakeMachine(procText: string, files: Record<string, string>): { procRoot: string; roots: { v1: string; v2: string[] }; sys: string } {
  const root = join(scratch, `m${n++}`);
  const sys = join(root, 'sys', 'fs', 'cgroup');
  mkdirSync(join(root, 'proc', '4242'), { recursive: true });
  writeFileSync(join(root, 'proc', '4242', 'cgroup'), procText);
  for (const [rel, text] of Object.entries(files)) {
    const f = join(sys, rel);
    mkdirSync(join(f, '..'), { recursive: true });
    writeFileSync(f, text);
  }
  return { procRoot: join(root, 'proc'), roots: { v1: sys, v2: [sys, join(sys, 'unified')] }, sys };
}

const running = (id = ID) => ({ Id: id, State: { Pid: 4242, Running: true } });

describe('parseProcCgroup', () => {
  test('cgroup v1 with an empty v2 hierarchy (this machine): every controller and the unified path', () => {
    const e = parseProcCgroup(V1_HYBRID);
    expect(e.v1.get('memory')).toBe(`/docker/${ID}`);
    expect(e.v1.get('pids')).toBe(`/docker/${ID}`);
    expect(e.v1.get('cpuacct')).toBe(`/docker/${ID}`);
    expect(e.v1.get('name=systemd')).toBe(`/docker/${ID}`);
    expect(e.unified).toBe(`/docker/${ID}`);
  });

  test('cgroup v2 only: the unified path, no v1 controller', () => {
    for (const [text, path] of [
      [V2_SYSTEMD, `/system.slice/docker-${ID}.scope`],
      [V2_CGROUPFS, `/docker/${ID}`],
      [V2_ROOTLESS, `/user.slice/user-1000.slice/user@1000.service/user.slice/docker-${ID}.scope`],
    ] as const) {
      const e = parseProcCgroup(text);
      expect(e.v1.size).toBe(0);
      expect(e.unified).toBe(path);
    }
  });

  test('combined v1 controllers on one line (cpu,cpuacct) and a path with a colon', () => {
    const e = parseProcCgroup(`3:cpu,cpuacct:/docker/${ID}\n4:memory:/odd:name/${ID}\n`);
    expect(e.v1.get('cpu')).toBe(`/docker/${ID}`);
    expect(e.v1.get('cpuacct')).toBe(`/docker/${ID}`);
    expect(e.v1.get('memory')).toBe(`/odd:name/${ID}`);
  });

  test('hostile or odd lines are left out: relative, "..", control characters, too long, no id', () => {
    const e = parseProcCgroup(
      [
        `4:memory:docker/${ID}`,
        `8:pids:/../../docker/${ID}`,
        `0::/docker/./${ID}`,
        `5:devices:/docker/\u0001${ID}`,
        `6:freezer:/${'x'.repeat(2000)}/${ID}`,
        `x:blkio:/docker/${ID}`,
        'garbage',
        '',
      ].join('\n'),
    );
    expect(e.v1.size).toBe(0);
    expect(e.unified).toBeNull();
  });

  test('the first entry of a controller wins; the text and its lines are bounded', () => {
    const e = parseProcCgroup(`4:memory:/docker/${ID}\n4:memory:/docker/${OTHER}\n`);
    expect(e.v1.get('memory')).toBe(`/docker/${ID}`);
    const late = `${'1:cpu:/a\n'.repeat(100)}4:memory:/docker/${ID}\n`;
    expect(parseProcCgroup(late).v1.has('memory')).toBe(false);
    const huge = `${'x'.repeat(20_000)}\n4:memory:/docker/${ID}\n`;
    expect(parseProcCgroup(huge).v1.has('memory')).toBe(false);
  });
});

describe('namesContainer', () => {
  test('the last folder is the id (cgroupfs driver) or docker-<id>.scope (systemd driver)', () => {
    expect(namesContainer(`/docker/${ID}`, ID)).toBe(true);
    expect(namesContainer(`/system.slice/docker-${ID}.scope`, ID)).toBe(true);
    expect(namesContainer(`/docker/${OTHER}`, ID)).toBe(false);
    expect(namesContainer(`/docker/${ID}/sub`, ID)).toBe(false);
    expect(namesContainer(`/system.slice/docker-${ID}.scope/init.scope`, ID)).toBe(false);
    expect(namesContainer('/', ID)).toBe(false);
    expect(namesContainer('/docker/', '')).toBe(false);
    expect(namesContainer(`/docker/${ID.slice(0, 12)}`, ID.slice(0, 12))).toBe(false);
  });
});

describe('planContainerCgroup', () => {
  const roots = { v1: '/sys/fs/cgroup', v2: ['/sys/fs/cgroup', '/sys/fs/cgroup/unified'] };

  test('v1 on a hybrid host: memory and pids from v1, the empty v2 hierarchy not used', () => {
    const has = new Set([`/sys/fs/cgroup/memory/docker/${ID}/memory.oom_control`, `/sys/fs/cgroup/pids/docker/${ID}/pids.events`]);
    expect(planContainerCgroup(parseProcCgroup(V1_HYBRID), ID, (f) => has.has(f), roots)).toEqual({
      memory: { kind: 'cgroup-v1', dir: `/sys/fs/cgroup/memory/docker/${ID}` },
      pids: { kind: 'cgroup-v1', dir: `/sys/fs/cgroup/pids/docker/${ID}` },
    });
  });

  test('v2 only (systemd driver): both counters from the unified folder under /sys/fs/cgroup', () => {
    const dir = `/sys/fs/cgroup/system.slice/docker-${ID}.scope`;
    const has = new Set([`${dir}/memory.events`, `${dir}/pids.events`]);
    expect(planContainerCgroup(parseProcCgroup(V2_SYSTEMD), ID, (f) => has.has(f), roots)).toEqual({
      memory: { kind: 'cgroup-v2', dir },
      pids: { kind: 'cgroup-v2', dir },
    });
  });

  test('v2 mounted at /sys/fs/cgroup/unified (hybrid host with the controllers on v2)', () => {
    const dir = `/sys/fs/cgroup/unified/docker/${ID}`;
    const has = new Set([`${dir}/memory.events`, `${dir}/pids.events`]);
    expect(planContainerCgroup(parseProcCgroup(V2_CGROUPFS), ID, (f) => has.has(f), roots)).toEqual({
      memory: { kind: 'cgroup-v2', dir },
      pids: { kind: 'cgroup-v2', dir },
    });
  });

  test('a cgroup of another container, or none readable: nothing to read', () => {
    expect(planContainerCgroup(parseProcCgroup(V1_HYBRID), OTHER, () => true, roots)).toEqual({ memory: null, pids: null });
    expect(planContainerCgroup(parseProcCgroup(V2_SYSTEMD), ID, () => false, roots)).toEqual({ memory: null, pids: null });
  });
});

describe('findContainerCgroup on fake /proc + /sys trees', () => {
  test('cgroup v1: the OOM kills and the refused forks are read from the container folders', async () => {
    const m = fakeMachine(V1_HYBRID, {
      [`memory/docker/${ID}/memory.oom_control`]: 'oom_kill_disable 0\nunder_oom 0\noom_kill 0\n',
      [`pids/docker/${ID}/pids.events`]: 'max 0\n',
      [`unified/docker/${ID}/cgroup.procs`]: '4242\n',
    });
    const found = await findContainerCgroup(running(), { procRoot: m.procRoot, roots: m.roots });
    expect(found.ok).toBe(true);
    if (!found.ok) return;
    expect(found.cgroup.plan.memory).toEqual({ kind: 'cgroup-v1', dir: join(m.sys, 'memory', 'docker', ID) });
    expect(await found.cgroup.oomKills()).toBe(0);
    expect(await found.cgroup.pidsLimitHits()).toBe(0);
    writeFileSync(join(m.sys, 'memory', 'docker', ID, 'memory.oom_control'), 'oom_kill_disable 0\nunder_oom 0\noom_kill 1\n');
    writeFileSync(join(m.sys, 'pids', 'docker', ID, 'pids.events'), 'max 1357\n');
    expect(await found.cgroup.oomKills()).toBe(1);
    expect(await found.cgroup.pidsLimitHits()).toBe(1357);
  });

  test('cgroup v2 (systemd driver): memory.events oom_kill / oom_group_kill and pids.events max', async () => {
    const scope = `system.slice/docker-${ID}.scope`;
    const m = fakeMachine(V2_SYSTEMD, {
      [`${scope}/memory.events`]: 'low 0\nhigh 0\nmax 12\noom 0\noom_kill 0\noom_group_kill 0\n',
      [`${scope}/pids.events`]: 'max 0\n',
    });
    const found = await findContainerCgroup(running(), { procRoot: m.procRoot, roots: m.roots });
    expect(found.ok).toBe(true);
    if (!found.ok) return;
    expect(found.cgroup.plan).toEqual({ memory: { kind: 'cgroup-v2', dir: join(m.sys, scope) }, pids: { kind: 'cgroup-v2', dir: join(m.sys, scope) } });
    // `max 12` of memory.events is the limit reached (reclaim), not a kill
    expect(await found.cgroup.oomKills()).toBe(0);
    writeFileSync(join(m.sys, scope, 'memory.events'), 'low 0\nhigh 0\nmax 40\noom 1\noom_kill 1\noom_group_kill 0\n');
    writeFileSync(join(m.sys, scope, 'pids.events'), 'max 3\n');
    expect(await found.cgroup.oomKills()).toBe(1);
    expect(await found.cgroup.pidsLimitHits()).toBe(3);
  });

  test('rootless Docker: the folder in the user subtree', async () => {
    const scope = `user.slice/user-1000.slice/user@1000.service/user.slice/docker-${ID}.scope`;
    const m = fakeMachine(V2_ROOTLESS, { [`${scope}/memory.events`]: 'oom_kill 2\n', [`${scope}/pids.events`]: 'max 0\n' });
    const found = await findContainerCgroup(running(), { procRoot: m.procRoot, roots: m.roots });
    expect(found.ok && (await found.cgroup.oomKills())).toBe(2);
  });

  test('only the memory counter readable: the pids side stays with the fallback', async () => {
    const m = fakeMachine(V2_CGROUPFS, { [`docker/${ID}/memory.events`]: 'oom_kill 0\n' });
    const found = await findContainerCgroup(running(), { procRoot: m.procRoot, roots: m.roots });
    expect(found.ok && found.cgroup.plan).toEqual({ memory: { kind: 'cgroup-v2', dir: join(m.sys, 'docker', ID) }, pids: null });
  });

  test('why no cgroup: no pid, no /proc entry, another container (a reused pid, another namespace), no counters', async () => {
    const m = fakeMachine(V1_HYBRID, {});
    const opts = { procRoot: m.procRoot, roots: m.roots };
    expect(await findContainerCgroup({ Id: ID, State: { Pid: 0, Running: false } }, opts)).toEqual({ ok: false, reason: 'the container is not running (no init pid)' });
    expect(await findContainerCgroup({ Id: 'abc', State: { Pid: 4242 } }, opts)).toEqual({ ok: false, reason: 'the engine gave no container id' });
    expect(await findContainerCgroup({ Id: ID, State: { Pid: 999 } }, opts)).toMatchObject({ ok: false, reason: expect.stringMatching(/^cannot read .*999\/cgroup/) });
    expect(await findContainerCgroup(running(OTHER), opts)).toMatchObject({ ok: false, reason: expect.stringMatching(/does not name container bbbbbbbbbbbb/) });
    expect(await findContainerCgroup(running(), opts)).toMatchObject({ ok: false, reason: expect.stringMatching(/no memory or pids counters/) });
  });

  test('counter files with junk read as no hit', async () => {
    const m = fakeMachine(V1_HYBRID, {
      [`memory/docker/${ID}/memory.oom_control`]: 'oom_kill 99999999999999999999\n',
      [`memory/docker/${ID}/memory.failcnt`]: 'lots\n',
      [`pids/docker/${ID}/pids.events`]: `${'x'.repeat(10_000)}\nmax 5\n`,
    });
    const found = await findContainerCgroup(running(), { procRoot: m.procRoot, roots: m.roots });
    expect(found.ok).toBe(true);
    if (!found.ok) return;
    expect(await found.cgroup.oomKills()).toBe(0);
    // beyond the bounded read: not seen
    expect(await found.cgroup.pidsLimitHits()).toBe(0);
  });
});

describe("the engine's oom events", () => {
  test('an oom event of the container, in the current and the older event shape', () => {
    expect(isOomEvent(JSON.stringify({ Type: 'container', Action: 'oom', Actor: { ID: ID, Attributes: {} }, time: 1 }), ID)).toBe(true);
    expect(isOomEvent(JSON.stringify({ status: 'oom', id: ID, from: 'contract-gcc' }), ID)).toBe(true);
  });

  test('anything else is not', () => {
    expect(isOomEvent(JSON.stringify({ Action: 'oom', Actor: { ID: OTHER } }), ID)).toBe(false);
    expect(isOomEvent(JSON.stringify({ Action: 'die', Actor: { ID: ID } }), ID)).toBe(false);
    expect(isOomEvent('{"Action":"oom"', ID)).toBe(false);
    expect(isOomEvent('null', ID)).toBe(false);
    expect(isOomEvent(`{"Action":"oom","Actor":{"ID":"${ID}"},"x":"${'y'.repeat(70_000)}"}`, ID)).toBe(false);
  });
});

describe('terminateNamedOnHost', () => {
  test("SIGTERM to the container's processes of that name only, from this host", async () => {
    const { spawn } = await import('node:child_process');
    const launcher = spawn('sleep', ['30']);
    const other = spawn('sleep', ['30']);
    const procRoot = join(scratch, `p${n++}`);
    for (const [pid, comm] of [[launcher.pid!, 'contract-launch'], [other.pid!, 'ENC']] as const) {
      mkdirSync(join(procRoot, String(pid)), { recursive: true });
      writeFileSync(join(procRoot, String(pid), 'comm'), `${comm}\n`);
    }
    const ended = new Promise<NodeJS.Signals | null>((r) => launcher.on('exit', (_c, s) => r(s)));
    try {
      expect(await terminateNamedOnHost([launcher.pid!, other.pid!, 999_999_999], 'contract-launch', procRoot)).toBe(true);
      expect(await ended).toBe('SIGTERM');
      expect(other.exitCode).toBeNull();
      expect(await terminateNamedOnHost([other.pid!], 'contract-launch', procRoot)).toBe(false);
      expect(await terminateNamedOnHost([], 'contract-launch', procRoot)).toBe(false);
    } finally {
      launcher.kill('SIGKILL');
      other.kill('SIGKILL');
    }
  });
});

describe('atPidsLimit (the engine\'s stats, when the cgroup is not read here)', () => {
  test('at or past the limit the sample gives, else the PidsLimit given; nothing known is no hit', () => {
    expect(atPidsLimit({ current: 24, limit: 24 })).toBe(true);
    expect(atPidsLimit({ current: 23, limit: 24 })).toBe(false);
    expect(atPidsLimit({ current: 24 }, 24)).toBe(true);
    expect(atPidsLimit({ current: 24, limit: 0 }, 24)).toBe(true);
    expect(atPidsLimit({ current: 24 })).toBe(false);
    expect(atPidsLimit({}, 24)).toBe(false);
    expect(atPidsLimit(undefined, 24)).toBe(false);
    // an engine that gives no limit (0, or a huge "max") and none given: no hit
    expect(atPidsLimit({ current: 5, limit: 0 })).toBe(false);
  });
});

describe('shmemOfStats (the engine\'s stats of a container)', () => {
  test('shmem under cgroup v2, else the page cache (cgroup v1 stats have no shmem); null for anything else', () => {
    expect(shmemOfStats({ memory_stats: { stats: { shmem: 1234, file: 99999 } } })).toBe(1234);
    expect(shmemOfStats({ memory_stats: { stats: { total_cache: 5000, cache: 4000 } } })).toBe(5000);
    expect(shmemOfStats({ memory_stats: { stats: { cache: 4000 } } })).toBe(4000);
    expect(shmemOfStats({ memory_stats: { stats: { shmem: -1 } } })).toBeNull();
    expect(shmemOfStats({ memory_stats: { stats: { shmem: '77' } } })).toBeNull();
    expect(shmemOfStats({ memory_stats: { stats: { shmem: 2 ** 60 } } })).toBeNull();
    expect(shmemOfStats({ memory_stats: {} })).toBeNull();
    expect(shmemOfStats(null)).toBeNull();
  });
});
