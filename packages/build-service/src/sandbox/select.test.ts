import { describe, expect, test } from 'vitest';
import { SandboxRegistry, SandboxUnavailableError } from './select.js';

const noDocker = { connection: { socketPath: '/nonexistent/docker.sock' } };

describe('sandbox selection', () => {
  test('auto picks bwrap when it works here and says so', async () => {
    const { sandbox, note } = await new SandboxRegistry({ docker: noDocker }).resolve('auto');
    expect(sandbox.name).toBe('bwrap');
    expect(note).toMatch(/^sandbox auto: picked bwrap \(bubblewrap \d/);
  });

  test('auto with neither bwrap nor an engine fails, saying how to install bubblewrap', async () => {
    const reg = new SandboxRegistry({ bwrap: { bwrapPath: '/nonexistent/bwrap' }, docker: noDocker });
    const err = await reg.resolve('auto').catch((e: unknown) => e);
    expect(err).toBeInstanceOf(SandboxUnavailableError);
    expect((err as Error).message).toMatch(/apt-get install bubblewrap/);
    expect((err as Error).message).toMatch(/no Docker engine answers/);
  });

  test('an explicitly named unavailable sandbox is refused with its reason', async () => {
    const reg = new SandboxRegistry({ docker: noDocker });
    await expect(reg.resolve('docker')).rejects.toThrow(/sandbox docker unavailable: no Docker engine answers/);
  });

  test('none is only what it says: a warning naming every unenforced limit', async () => {
    const { sandbox, warnings } = await new SandboxRegistry({ docker: noDocker }).resolve('none');
    expect(sandbox.name).toBe('none');
    expect(warnings).toHaveLength(1);
    for (const w of ['network isolation', 'read-only root', 'memory limit', 'process limit']) {
      expect(warnings[0]).toContain(w);
    }
    // as root the processes at least drop to the workspace's own uid
    const asRoot = process.getuid?.() === 0;
    expect(warnings[0].includes('non-root user')).toBe(!asRoot);
  });
});
