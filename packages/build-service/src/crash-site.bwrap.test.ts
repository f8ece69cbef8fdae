/**
 * The crash site in the bwrap sandbox (test-support/crash-site-suite.ts).
 */
import { useBuildServer } from './test-support/build-server.js';
import { crashSiteSuite } from './test-support/crash-site-suite.js';

crashSiteSuite('bwrap', useBuildServer({ concurrency: 1, sandbox: 'bwrap' }, { timeoutMs: 240_000 }));
