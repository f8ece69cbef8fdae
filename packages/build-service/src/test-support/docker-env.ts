/**
 * Docker for the tests (this package's and the cli's e2e, through the package export
 * `@contract-studio/build-service/test-support/docker-env`): runs scripts/docker-up.sh (starts
 * dockerd, builds the contract-gcc image when missing or stale) with a lease on the engine held
 * by this process, released by `stop()`: a daemon docker-up started is stopped when its last lease
 * is released or its last holder process is gone (a test file run alone stops the engine it
 * started, also when it is killed; `make test`'s run holds a lease for all its files, so that no
 * file stops the engine under the others). When Docker cannot be made to work here, `reason`
 * says why and the docker tests are skipped LOUDLY.
 */
import { spawnSync } from 'node:child_process';
import { randomBytes } from 'node:crypto';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const repo = join(dirname(fileURLToPath(import.meta.url)), '..', '..', '..', '..');
const script = join(repo, 'scripts', 'docker-up.sh');

export interface DockerEnv {
  available: boolean;
  reason: string;
  stop(): void;
}

export interface DockerUpOptions {
  /** Make sure the image exists (default); false: the engine only (`docker-up.sh --daemon`). */
  image?: boolean;
}

export function dockerUp(options: DockerUpOptions = {}): DockerEnv {
  const lease = `${process.pid}-${randomBytes(4).toString('hex')}`;
  // an image rebuild (debootstrap, runtime built and tested inside) takes minutes
  const r = spawnSync('bash', [script, ...(options.image === false ? ['--daemon'] : []), '--lease', lease], { encoding: 'utf8', timeout: 300_000 });
  let released = false;
  const stop = (): void => {
    if (released) return;
    released = true;
    spawnSync('bash', [script, '--release', lease], { stdio: 'inherit' });
  };
  if (r.status !== 0) {
    const reason = `scripts/docker-up.sh failed (exit ${r.status}): ${(r.stderr ?? '').trim().split('\n').slice(-3).join(' | ')}`;
    console.warn(`\n${'!'.repeat(70)}\n!! DOCKER TESTS SKIPPED: ${reason}\n${'!'.repeat(70)}\n`);
    return { available: false, reason, stop };
  }
  return { available: true, reason: '', stop };
}
