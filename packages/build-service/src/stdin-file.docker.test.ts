/**
 * A module's stdin from a file of the project in the Docker sandbox (test-support/stdin-file-suite.ts):
 * the file staged in the work dir reaches the job's volume. Starts dockerd and bootstraps the image
 * when needed, or says SKIPPED loudly with the reason.
 */
import { describe, test } from 'vitest';
import { useBuildServer } from './test-support/build-server.js';
import { stdinFileSuite } from './test-support/stdin-file-suite.js';
import { dockerUp } from './test-support/docker-env.js';

const docker = dockerUp();
if (docker.available) {
  stdinFileSuite('docker', (projectRoots) => useBuildServer({ concurrency: 1, sandbox: 'docker', projectRoots, log: () => {} }, { afterClose: () => docker.stop(), timeoutMs: 300_000 }));
} else {
  describe('docker sandbox', () => {
    test.skip(`SKIPPED: ${docker.reason}`, () => {});
  });
}
