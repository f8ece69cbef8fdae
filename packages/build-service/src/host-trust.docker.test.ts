/**
 * The host trust boundary in Docker (test-support/host-trust-suite.ts); starts dockerd and
 * bootstraps the image when needed, or says SKIPPED loudly with the reason.
 */
import { afterAll, describe, test } from 'vitest';
import { dockerUp } from './test-support/docker-env.js';
import { hostTrustSuite } from './test-support/host-trust-suite.js';

const env = dockerUp();
afterAll(() => env.stop());

if (env.available) hostTrustSuite('docker');
else {
  describe('docker sandbox', () => {
    test.skip(`SKIPPED: ${env.reason}`, () => {});
  });
}
