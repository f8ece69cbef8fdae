/**
 * The crash site in the Docker sandbox (test-support/crash-site-suite.ts): the image's own runtime
 * writes the crash report, addr2line runs in the job's container. Starts dockerd and bootstraps the
 * image when needed, or says SKIPPED loudly with the reason.
 */
import { describe, test } from 'vitest';
import { useBuildServer } from './test-support/build-server.js';
import { crashSiteSuite } from './test-support/crash-site-suite.js';
import { dockerUp } from './test-support/docker-env.js';

const docker = dockerUp();
const served = useBuildServer({ concurrency: 1, sandbox: 'docker', log: () => {} }, { skip: !docker.available, afterClose: () => docker.stop(), timeoutMs: 300_000 });

if (docker.available) crashSiteSuite('docker', served);
else {
  describe('docker sandbox', () => {
    test.skip(`SKIPPED: ${docker.reason}`, () => {});
  });
}
