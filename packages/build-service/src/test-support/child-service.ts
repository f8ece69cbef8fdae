/**
 * Child process of http/body-limits.test.ts and sandbox-output.bwrap.test.ts (run compiled: `node
 * dist/test-support/child-service.js CACHE_DIR`): a build service (bwrap) on a free loopback port,
 * in its own process as `contract serve` runs it; prints `URL <url>`, then serves until killed.
 * The tests read its peak memory (VmHWM), or that it is still alive after a hostile job.
 */
import { createBuildServer } from '../server.js';

const cacheDir = process.argv[2];
if (!cacheDir) {
  process.stderr.write('usage: child-service.js CACHE_DIR\n');
  process.exit(2);
}
const server = createBuildServer({ token: false, port: 0, cacheDir, sandbox: 'bwrap', log: () => {} });
const { url } = await server.listen();
process.stdout.write(`URL ${url}\n`);
