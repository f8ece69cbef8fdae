/** Shared set-up of the simulator tests: the repository's examples and one cache folder per run. */
import { mkdtempSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { DEFAULT_RUNTIME_DIR, prepareProject, type PreparedProject } from '../src/index.js';

export const REPO = fileURLToPath(new URL('../../../', import.meta.url));
export const TUTORIAL = join(REPO, 'examples', 'tutorial');
export const ROBOT = join(REPO, 'examples', 'mobile-robot');
export const CACHE = mkdtempSync(join(tmpdir(), 'contract-sim-test-'));

export async function prepared(dir: string): Promise<PreparedProject> {
    const p = await prepareProject(dir, { runtimeDir: DEFAULT_RUNTIME_DIR, cacheDir: CACHE });
    if (!('build' in p)) throw new Error(`cannot prepare ${dir}: ${p.buildError ?? p.sandboxError ?? p.modelErrors.map((d) => d.message).join('; ')}`);
    return p;
}
