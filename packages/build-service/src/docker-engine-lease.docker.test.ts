/**
 * Who stops the Docker engine the tests start (scripts/docker-up.sh leases, test-support/docker-env.ts):
 * a docker test file run alone stops the daemon it started, also when its process is killed
 * before its hooks run; a lease released while another is held leaves the engine to the other
 * (`make test`'s run holds one for every file of its lanes). The engine only, no image.
 * Needs an engine that can be started here (root, dockerd): else SKIPPED loudly with the reason.
 * The stopping is checked only when no engine answered before this file (one started by someone
 * else is never stopped, and is left alone).
 */
import { execFileSync, spawn, spawnSync } from 'node:child_process';
import { existsSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, describe, expect, it } from 'vitest';
import { dockerUp } from './test-support/docker-env.js';

const script = join(dirname(fileURLToPath(import.meta.url)), '..', '..', '..', 'scripts', 'docker-up.sh');
const answers = (): boolean => spawnSync('docker', ['info'], { stdio: 'ignore', timeout: 20_000 }).status === 0;
const canStart = spawnSync('bash', ['-c', 'command -v docker && command -v dockerd'], { stdio: 'ignore' }).status === 0 && process.getuid?.() === 0;
const engineBefore = canStart && answers();
if (!canStart) console.warn(`\n${'!'.repeat(70)}\n!! DOCKER ENGINE LEASE TESTS SKIPPED: no docker/dockerd, or not root\n${'!'.repeat(70)}\n`);

/** Daemons a test started: killed at the end if a test failed before they stopped. */
const started: number[] = [];
afterAll(() => {
  if (engineBefore) return;
  const file = join(process.env['TMPDIR'] ?? tmpdir(), 'contract-docker-users', 'started');
  const recorded = existsSync(file) ? Number(readFileSync(file, 'utf8').trim()) : 0;
  for (const pid of [...started, ...(recorded > 0 ? [recorded] : [])]) if (isAlive(pid)) process.kill(pid);
});
const isAlive = (pid: number): boolean => {
  try { process.kill(pid, 0); return true; } catch { return false; }
};
async function until(what: () => boolean, ms: number): Promise<boolean> {
  for (const end = Date.now() + ms; Date.now() < end; await new Promise((r) => setTimeout(r, 250))) if (what()) return true;
  return what();
}

describe.skipIf(!canStart)('the Docker engine the tests start (scripts/docker-up.sh leases)', () => {
  it.runIf(!engineBefore)('a test process killed before its hooks ran: the engine started for it stops within seconds', async () => {
    const holder = spawn(process.execPath, ['-e', 'setInterval(() => {}, 1000)'], { stdio: 'ignore' });
    try {
      const out = execFileSync('bash', [script, '--daemon', '--lease', `${holder.pid}-killed`], { encoding: 'utf8', timeout: 120_000 });
      const pid = Number(/dockerd-started (\d+)/.exec(out)?.[1]);
      expect(pid).toBeGreaterThan(0);
      started.push(pid);
      expect(answers()).toBe(true);
      holder.kill('SIGKILL');
      expect(await until(() => !isAlive(pid), 20_000), `dockerd ${pid} still runs 20 s after its only holder was killed`).toBe(true);
      expect(answers()).toBe(false);
    } finally {
      holder.kill('SIGKILL');
    }
  }, 180_000);

  it('two leases: the first release leaves the engine to the second; the last stops it when it was started for them', async () => {
    const first = dockerUp({ image: false });
    const second = dockerUp({ image: false });
    expect(first.available, first.reason).toBe(true);
    expect(second.available).toBe(true);
    first.stop();
    expect(answers()).toBe(true);
    second.stop();
    // an engine that answered before (someone else's) is left running; one started here stops
    expect(await until(() => answers() === engineBefore, 20_000)).toBe(true);
  }, 180_000);
});
