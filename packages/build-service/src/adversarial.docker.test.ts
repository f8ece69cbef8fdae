/**
 * Adversarial jobs in the Docker sandbox (see test-support/adversarial-suite.ts); starts dockerd
 * and bootstraps the image when needed, or says SKIPPED loudly with the reason.
 */
import Docker from 'dockerode';
import { afterAll, describe, expect, test } from 'vitest';
import { adversarialSuite } from './test-support/adversarial-suite.js';
import { dockerUp } from './test-support/docker-env.js';

const env = dockerUp();
/** Only what this file's jobs made counts: another service on the machine may keep its project volumes. */
const since = Math.floor(Date.now() / 1000) - 1;
afterAll(() => env.stop());

if (env.available) {
  adversarialSuite('docker', 'docker', async () => {
    const docker = new Docker();
    const containers = await docker.listContainers({ all: true, filters: { label: ['contract-studio=job'] } });
    expect(containers.filter((c) => c.Created >= since)).toEqual([]);
    const { Volumes } = await docker.listVolumes({ filters: { label: ['contract-studio=workspace'] } });
    const created = (v: { CreatedAt?: string }): number => Math.floor(Date.parse(v.CreatedAt ?? '') / 1000);
    expect((Volumes ?? []).filter((v) => !(created(v as { CreatedAt?: string }) < since))).toEqual([]);
  });
} else {
  describe('docker sandbox', () => {
    test.skip(`SKIPPED: ${env.reason}`, () => {});
  });
}
