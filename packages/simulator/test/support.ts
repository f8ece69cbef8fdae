/** Shared set-up of the simulator tests: the repository's examples and one cache folder per run. */
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { inject } from 'vitest';
import { DEFAULT_RUNTIME_DIR, prepareProject, type PreparedProject } from '../src/index.js';

export const REPO = fileURLToPath(new URL('../../../', import.meta.url));
export const TUTORIAL = join(REPO, 'examples', 'tutorial');
export const ROBOT = join(REPO, 'examples', 'mobile-robot');
/** The run's build cache (made and removed by cache-folder.global.ts). */
export const CACHE = inject('simulatorCache');

export async function prepared(dir: string): Promise<PreparedProject> {
    const p = await prepareProject(dir, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir: CACHE });
    if (!('build' in p)) throw new Error(`cannot prepare ${dir}: ${p.buildError ?? p.sandboxError ?? p.modelErrors.map((d) => d.message).join('; ')}`);
    return p;
}
