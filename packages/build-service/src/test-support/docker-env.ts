/**
 * Docker for the tests (this package's and the cli's e2e, through the package export
 * `@contract-studio/build-service/test-support/docker-env`): runs scripts/docker-up.sh (starts
 * dockerd, builds the contract-gcc image when missing or stale) and stops the daemon afterwards
 * when it started it. When Docker cannot be made to work here, `reason` says why and the docker
 * tests are skipped LOUDLY.
 */
import { spawnSync } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const repo = join(dirname(fileURLToPath(import.meta.url)), '..', '..', '..', '..');
const script = join(repo, 'scripts', 'docker-up.sh');

export interface DockerEnv {
  available: boolean;
  reason: string;
  stop(): void;
}

export function dockerUp(): DockerEnv {
  // an image rebuild (debootstrap, runtime built and tested inside) takes minutes
  const r = spawnSync('bash', [script], { encoding: 'utf8', timeout: 300_000 });
  const started = /dockerd-started (\d+)/.exec(r.stdout ?? '')?.[1];
  const stop = (): void => {
    if (started) spawnSync('bash', [script, '--stop', started], { stdio: 'inherit' });
  };
  if (r.status !== 0) {
    const reason = `scripts/docker-up.sh failed (exit ${r.status}): ${(r.stderr ?? '').trim().split('\n').slice(-3).join(' | ')}`;
    console.warn(`\n${'!'.repeat(70)}\n!! DOCKER TESTS SKIPPED: ${reason}\n${'!'.repeat(70)}\n`);
    return { available: false, reason, stop };
  }
  return { available: true, reason: '', stop };
}
