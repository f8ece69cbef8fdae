/**
 * Adversarial jobs in the Docker sandbox (see test-support/adversarial-suite.ts); starts dockerd
 * and bootstraps the image when needed, or says SKIPPED loudly with the reason.
 */
import Docker from 'dockerode';
import { hostname } from 'node:os';
import { afterAll, describe, expect, test } from 'vitest';
import { adversarialSuite } from './test-support/adversarial-suite.js';
import { dockerUp } from './test-support/docker-env.js';

const env = dockerUp();
/**
 * Only what this file's jobs made counts: another service on the machine (another test file of the
 * same run) may have jobs running and keep its project volumes: its own service's labels, and made
 * since this file began.
 */
const since = Math.floor(Date.now() / 1000) - 1;
const ownedHere = (labels: Record<string, string> | undefined): boolean =>
  (labels?.['contract-studio.owner'] ?? '').startsWith(`${hostname()}:${process.pid}:`);
afterAll(() => env.stop());

if (env.available) {
  adversarialSuite('docker', 'docker', async () => {
    const docker = new Docker();
    const containers = await docker.listContainers({ all: true, filters: { label: ['contract-studio=job'] } });
    expect(containers.filter((c) => c.Created >= since && ownedHere(c.Labels))).toEqual([]);
    const { Volumes } = await docker.listVolumes({ filters: { label: ['contract-studio=workspace'] } });
    const created = (v: { CreatedAt?: string }): number => Math.floor(Date.parse(v.CreatedAt ?? '') / 1000);
    expect((Volumes ?? []).filter((v) => !(created(v as { CreatedAt?: string }) < since) && ownedHere(v.Labels ?? undefined))).toEqual([]);
  });
} else {
  describe('docker sandbox', () => {
    test.skip(`SKIPPED: ${env.reason}`, () => {});
  });
}
