/**
 * terminateNamed of a host process tree (the bwrap and none sandboxes): SIGTERM reaches the
 * command's own processes of that name, never a process of the same name outside the command.
 */
import { spawn } from 'node:child_process';
import { copyFileSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, expect, test } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import { startHostProcess } from './host-process.js';
import type { Mechanisms } from './types.js';

const dir = mkdtempSync(join(tmpdir(), 'host-process-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));
// a program whose kernel name (comm) is the launcher's: a copy of sleep under that file name
const named = join(dir, 'contract-launch');
copyFileSync('/bin/sleep', named);

const mechanisms = { memory: 'none', processes: 'none', network: 'none', filesystem: 'none', user: 'none', time: 'service-timer', output: 'service-counter', disk: 'none' } as unknown as Mechanisms;

test('SIGTERM to the command\'s processes of that name only; none of that name: false', async () => {
  const outside = spawn(named, ['30'], { stdio: 'ignore' });
  const outsideEnded = new Promise<string | null>((r) => outside.on('exit', (_c, sig) => r(sig)));
  // the command: a shell that runs the named program as a grandchild, and says when it got SIGTERM
  const proc = startHostProcess({
    argv: ['/bin/sh', '-c', `"${named}" 30 & wait $!; echo "inner ended: $?"; sleep 30`],
    cwd: dir,
    env: { PATH: '/usr/bin:/bin' },
    limits: DEFAULT_LIMITS,
    mechanisms,
    cgroup: null,
    guessLimitsFromOutput: false,
  });
  let out = '';
  proc.stdout.on('data', (d: Buffer) => (out += d.toString()));
  await new Promise((r) => setTimeout(r, 300));
  expect(await proc.terminateNamed('no-such-name')).toBe(false);
  expect(await proc.terminateNamed('contract-launch')).toBe(true);
  for (let i = 0; i < 50 && !out.includes('inner ended'); i++) await new Promise((r) => setTimeout(r, 50));
  expect(out).toContain('inner ended: 143'); // 128 + SIGTERM
  expect(outside.exitCode).toBeNull(); // the process of the same name outside the command runs on
  expect(outside.signalCode).toBeNull();
  await proc.kill();
  outside.kill('SIGKILL');
  expect(await outsideEnded).toBe('SIGKILL');
});
