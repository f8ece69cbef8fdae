/**
 * One runtime build for a whole test run. Most test files make a fresh build cache and build
 * projects in it, and each such cache would compile the same runtime again (about 11 s of CPU, about
 * fifteen times a run on a two-CPU machine whose tests are CPU-bound). `make test`
 * (scripts/run-tests.mjs) names a folder of its own in CONTRACT_TEST_RUNTIME_SEED; `seedRuntime`
 * builds the repository's runtime there once (the first test file to ask; two at once both build,
 * the first rename wins, as in any cache) and copies it into a test's fresh cache, where the service
 * finds it built (`runtime <key> ... already built`), as a user's second project finds it.
 *
 * Nothing is seeded when the variable is unset (a test file run alone: each cache builds its own, as
 * a user's first build does), nor for another runtime than the repository's (a test's edited copy
 * has another key), nor into a cache that has that runtime already. Tests of building the runtime
 * itself, of a cold cache, or of an installed CLI's first build do not call it.
 */
import { cpSync, existsSync, mkdirSync } from 'node:fs';
import { join } from 'node:path';
import { DEFAULT_RUNTIME_SOURCE } from '../job-service.js';
import { RuntimeCache } from '../pipeline/runtime-cache.js';

/** The variable that names the run's seed folder. */
export const SEED_VARIABLE = 'CONTRACT_TEST_RUNTIME_SEED';

/** The seed's built runtime folder (`<seed>/runtime/runtime-<key>`), built once per process. */
let seeded: Promise<{ key: string; dir: string } | undefined> | undefined;

function seedFolder(): Promise<{ key: string; dir: string } | undefined> {
  const seed = process.env[SEED_VARIABLE];
  if (!seed) return Promise.resolve(undefined);
  seeded ??= (async () => {
    mkdirSync(seed, { recursive: true, mode: 0o711 });
    const cache = new RuntimeCache(DEFAULT_RUNTIME_SOURCE, join(seed, 'runtime'));
    const sources = await cache.sources();
    const dir = await cache.ensureBuilt(sources, () => {});
    return { key: sources.key, dir };
  })();
  return seeded;
}

/**
 * Puts the run's built runtime into `cacheDir` (a build cache: `<cacheDir>/runtime/runtime-<key>`)
 * when the runtime at `runtimeSource` (default: the repository's) is the seed's; returns whether it
 * did. The copy keeps modes and times (readable by the job uids, writable by none, stamped built).
 */
export async function seedRuntime(cacheDir: string, runtimeSource = DEFAULT_RUNTIME_SOURCE): Promise<boolean> {
  const seed = await seedFolder();
  if (!seed) return false;
  if (runtimeSource !== DEFAULT_RUNTIME_SOURCE && (await new RuntimeCache(runtimeSource, cacheDir).sources()).key !== seed.key) return false;
  const target = join(cacheDir, 'runtime', `runtime-${seed.key}`);
  if (existsSync(target)) return false;
  mkdirSync(join(cacheDir, 'runtime'), { recursive: true, mode: 0o711 });
  cpSync(seed.dir, target, { recursive: true, preserveTimestamps: true, verbatimSymlinks: true });
  return true;
}
