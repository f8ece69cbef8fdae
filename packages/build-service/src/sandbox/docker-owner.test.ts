import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { hostname, tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, test } from 'vitest';
import { currentOwner, judgeOwner, LABEL_OWNER, LABEL_OWNER_BOOT, LABEL_OWNER_PIDNS, ownerLabels, type ServiceOwner } from './docker-owner.js';
import { isProcessAlive, ownerProcessState, processStartTime } from './process-owner.js';
import { DEFAULT_SWEEP_POLICY, planSweep, type SeenContainer, type SeenVolume } from './docker-sweep.js';

/** A real process that is gone: its pid and the start time it had. */
async function deadProcess(): Promise<{ pid: number; startTime: string }> {
  const child = spawn('sleep', ['60'], { stdio: 'ignore' });
  const pid = child.pid!;
  const startTime = processStartTime(pid)!;
  const exited = new Promise((r) => child.on('exit', r));
  child.kill('SIGKILL');
  await exited;
  return { pid, startTime };
}

describe('owner of a container or volume', () => {
  const self = currentOwner();

  test('this process: host, pid, start time from /proc/self/stat field 22, boot id, pid namespace', () => {
    expect(self.host).toBe(hostname());
    expect(self.pid).toBe(process.pid);
    // field 22 counted by hand: the 20th field after the ")" that ends the command name
    const stat = readFileSync('/proc/self/stat', 'utf8');
    expect(self.startTime).toBe(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[19]);
    expect(self.boot).toBe(readFileSync('/proc/sys/kernel/random/boot_id', 'utf8').trim());
    expect(self.pidns).toMatch(/^pid:\[\d+\]$/);
    expect(self.instance).toMatch(/^[0-9a-f]{12}$/);
    expect(currentOwner().instance).not.toBe(self.instance);
    expect(ownerLabels(self, 'job', 'j-1')).toEqual({
      'contract-studio': 'job',
      'contract-studio.owner': `${self.host}:${self.pid}:${self.startTime}`,
      'contract-studio.owner-boot': self.boot,
      'contract-studio.owner-pidns': self.pidns,
      'contract-studio.owner-instance': self.instance,
      'contract-studio.job': 'j-1',
    });
  });

  test('a command name with spaces and parentheses does not shift the fields', async () => {
    // exec -a sets argv[0]; the kernel's comm is the file name, so use a copy named "a) b"
    const dir = mkdtempSync(join(tmpdir(), 'comm-'));
    const child = spawn('bash', ['-c', `cp /bin/sleep "${dir}/a) b" && exec "${dir}/a) b" 30`], { stdio: 'ignore' });
    try {
      let comm = '';
      for (let i = 0; i < 100 && !comm.includes('a) b'); i++) {
        await new Promise((r) => setTimeout(r, 20));
        comm = readFileSync(`/proc/${child.pid}/comm`, 'utf8');
      }
      expect(comm.trim()).toBe('a) b');
      const start = processStartTime(child.pid!)!;
      expect(start).toMatch(/^\d+$/);
      expect(Number(start)).toBeGreaterThanOrEqual(Number(self.startTime));
    } finally {
      child.kill('SIGKILL');
      rmSync(dir, { recursive: true, force: true });
    }
  });

  test('a process that ended but is not reaped yet (zombie) has no start time: its services are dead', async () => {
    // `sleep 0` ends at once; its parent exec'd into `sleep 30`, which never reaps it
    const parent = spawn('sh', ['-c', 'sleep 0 & exec sleep 30'], { stdio: 'ignore' });
    try {
      let zombie = 0;
      for (let i = 0; i < 100 && !zombie; i++) {
        await new Promise((r) => setTimeout(r, 20));
        const kids = readFileSync(`/proc/${parent.pid}/task/${parent.pid}/children`, 'utf8').trim().split(' ').filter(Boolean).map(Number);
        zombie = kids.find((k) => / Z /.test(readFileSync(`/proc/${k}/stat`, 'utf8'))) ?? 0;
      }
      expect(zombie).toBeGreaterThan(0);
      expect(processStartTime(zombie)).toBeNull();
      expect(processStartTime(parent.pid!)).toMatch(/^\d+$/);
    } finally {
      parent.kill('SIGKILL');
    }
  });

  test('the live owner is alive; a dead pid is dead; a recycled pid (other start time) is dead', async () => {
    expect(judgeOwner(ownerLabels(self, 'job', 'j'), self)).toEqual({ state: 'alive' });
    const gone = await deadProcess();
    expect(processStartTime(gone.pid)).toBeNull();
    const dead: ServiceOwner = { ...self, pid: gone.pid, startTime: gone.startTime };
    expect(judgeOwner(ownerLabels(dead, 'job', 'j'), self)).toEqual({ state: 'dead', why: `its service pid ${gone.pid} is gone` });
    // our own pid with another start time: the pid was reused by a newer process
    const recycled: ServiceOwner = { ...self, startTime: String(Number(self.startTime) - 1) };
    expect(judgeOwner(ownerLabels(recycled, 'job', 'j'), self)).toMatchObject({ state: 'dead', why: expect.stringMatching(/newer process/) });
    // the same check judges a job cgroup's or a work folder's owner tag (process-owner.ts)
    expect([ownerProcessState(self.pid, self.startTime), ownerProcessState(gone.pid, gone.startTime), ownerProcessState(self.pid, recycled.startTime)])
      .toEqual(['alive', 'gone', 'reused']);
    expect([isProcessAlive(self.pid, self.startTime), isProcessAlive(gone.pid, gone.startTime), isProcessAlive(self.pid, recycled.startTime)]).toEqual([true, false, false]);
  });

  test('another boot is dead; another host or pid namespace cannot be judged; no label is unowned', () => {
    const labels = ownerLabels(self, 'job', 'j');
    expect(judgeOwner({ ...labels, [LABEL_OWNER_BOOT]: 'other-boot' }, self)).toMatchObject({ state: 'dead', why: expect.stringMatching(/rebooted/) });
    expect(judgeOwner({ ...labels, [LABEL_OWNER]: `elsewhere:${self.pid}:${self.startTime}` }, self)).toMatchObject({ state: 'elsewhere' });
    expect(judgeOwner({ ...labels, [LABEL_OWNER_PIDNS]: 'pid:[1]' }, self)).toMatchObject({ state: 'elsewhere' });
    expect(judgeOwner({ ...labels, [LABEL_OWNER]: 'garbage' }, self)).toMatchObject({ state: 'elsewhere', why: expect.stringMatching(/not host:pid:start/) });
    expect(judgeOwner({ 'contract-studio': 'job' }, self)).toEqual({ state: 'unowned' });
  });
});

describe('sweep plan', () => {
  const self = currentOwner();
  const now = 1_800_000_000;
  const deadOwner: ServiceOwner = { ...self, pid: 999_999_999, startTime: '1' }; // above pid_max: never a process
  const container = (id: string, state: string, labels: Record<string, string>, ageSeconds: number, volumes: string[] = []): SeenContainer => ({
    id: id.padEnd(64, '0'),
    name: `contract-${id}`,
    state,
    created: now - ageSeconds,
    labels,
    volumes,
  });
  const volume = (name: string, labels: Record<string, string>, ageSeconds: number): SeenVolume => ({ name, created: now - ageSeconds, labels });

  test('dead owners: containers (any state) and volumes removed; live owners and other hosts untouched, unlisted', () => {
    const steps = planSweep(
      [
        container('dead1', 'running', ownerLabels(deadOwner, 'job', 'j-dead'), 5),
        container('dead2', 'exited', ownerLabels(deadOwner, 'job', 'j-dead'), 5),
        container('live', 'running', ownerLabels(self, 'job', 'j-live'), 5),
        container('remote', 'running', { ...ownerLabels(self, 'job', 'j-r'), [LABEL_OWNER]: 'far:1:1' }, 99_999),
        container('notours', 'exited', { other: 'x' }, 99_999),
      ],
      [volume('v-dead', ownerLabels(deadOwner, 'workspace', 'j-dead'), 5), volume('v-live', ownerLabels(self, 'workspace', 'j-live'), 5)],
      self,
      now,
    );
    expect(steps.map((s) => [s.kind, s.id.slice(0, 5), s.action])).toEqual([
      ['container', 'dead1', 'remove'],
      ['container', 'dead2', 'remove'],
      ['volume', 'v-dea', 'remove'],
    ]);
    expect(steps[0]!.what).toBe('container dead10000000 (contract-dead1) of job j-dead');
    expect(steps[0]!.why).toBe('its service pid 999999999 is gone');
    expect(steps[2]!.what).toBe('volume v-dead of job j-dead');
  });

  test('no owner label: old stopped containers and old unused volumes removed; running, young or mounted ones reported', () => {
    const legacy = { 'contract-studio': 'job' };
    const legacyVolume = { 'contract-studio': 'workspace' };
    const steps = planSweep(
      [
        container('oldexit', 'exited', legacy, DEFAULT_SWEEP_POLICY.legacyContainerAgeSeconds + 1),
        container('youngex', 'created', legacy, 30),
        container('oldrun', 'running', legacy, 99_999, ['v-mounted']),
      ],
      [
        volume('v-old', legacyVolume, DEFAULT_SWEEP_POLICY.legacyVolumeAgeSeconds + 1),
        volume('v-young', legacyVolume, 60),
        volume('v-mounted', legacyVolume, 99_999),
        volume('v-nodate', legacyVolume, Number.NaN),
      ],
      self,
      now,
    );
    expect(steps.map((s) => [s.id.slice(0, 7), s.action])).toEqual([
      ['oldexit', 'remove'],
      ['youngex', 'report'],
      ['oldrun0', 'report'],
      ['v-old', 'remove'],
      ['v-young', 'report'],
      ['v-mount', 'report'],
      ['v-nodat', 'report'],
    ]);
    expect(steps[0]!.why).toBe('no owner label, exited, created 10 min ago');
    expect(steps[2]!.why).toMatch(/^no owner label \(made before owner labels\), running: .*docker rm -f oldrun000000/);
    expect(steps[5]!.why).toBe('no owner label, mounted by a container that stays');
  });

  test('a volume whose dead container is removed in the same sweep is not "mounted"', () => {
    const legacy = { 'contract-studio': 'job' };
    const steps = planSweep(
      [container('oldexit', 'exited', legacy, 9_999, ['v-legacy'])],
      [volume('v-legacy', { 'contract-studio': 'workspace' }, 999_999)],
      self,
      now,
    );
    expect(steps.map((s) => s.action)).toEqual(['remove', 'remove']);
  });
});
