/**
 * Sandbox selection with a Docker engine (docs/sandbox.md): `auto` falls back to docker when
 * bwrap is missing. The engine is started for it (test-support/docker-env.ts); where Docker
 * cannot work, the test is skipped loudly, saying why.
 */
import { afterAll, expect, test } from 'vitest';
import { SandboxRegistry } from './select.js';
import { dockerUp } from '../test-support/docker-env.js';

const docker = dockerUp();
afterAll(() => docker.stop());

if (!docker.available) test.skip(`docker: SKIPPED — ${docker.reason}`, () => {});

test.skipIf(!docker.available)('auto falls back to docker when bwrap is missing and an engine answers', async () => {
  const reg = new SandboxRegistry({ bwrap: { bwrapPath: '/nonexistent/bwrap' } });
  const { sandbox, note } = await reg.resolve('auto');
  expect(sandbox.name).toBe('docker');
  expect(note).toMatch(/^sandbox auto: picked docker \(engine at .*image contract-gcc/);
});
