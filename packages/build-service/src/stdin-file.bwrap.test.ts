/**
 * A module's stdin from a file of the project in the bwrap sandbox (test-support/stdin-file-suite.ts).
 */
import { useBuildServer } from './test-support/build-server.js';
import { stdinFileSuite } from './test-support/stdin-file-suite.js';

stdinFileSuite('bwrap', (projectRoots) => useBuildServer({ concurrency: 1, sandbox: 'bwrap', projectRoots, log: () => {} }, { timeoutMs: 240_000 }));
