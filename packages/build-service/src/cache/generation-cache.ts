/**
 * Generated trees by their inputs (docs/getting-started.md "The build cache"): generation is a
 * function of the project's files (.contract sources and the src-gen with its user code, as
 * prepare reads them) and of the generator (docs/architecture.md Seam 3: one model generates the
 * same bytes from any folder). So a project copied to a new folder, or built by the IDE after the
 * CLI, takes the generated src-gen from `<cache>/generated/<key>.json.gz` instead of loading the
 * model again (about 1.5 s for the tutorial). The key hashes the prepare digest of the inputs and
 * the generator's identity (every file of the language and codegen packages' dist/ folders:
 * their paths inside dist/ and bytes), so a rebuilt generator never serves an old tree.
 *
 * Only trees generated on a stage that had no src-gen before the project was staged are stored
 * (what any fresh workspace would generate). The entries are written by the service alone, in the
 * trusted cache folder, atomically; an entry that does not read back as exactly this shape, or
 * names a path leaving src-gen, is ignored (generation runs). Each hit marks its entry used; each
 * new entry first removes those beyond `keptGeneratedTrees` (least recently used first,
 * least-recently-used.ts) and the temporary files of writers killed before their rename.
 */
import { createHash, randomBytes } from 'node:crypto';
import { promises as fsp, readdirSync, readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { basename, dirname, join, relative } from 'node:path';
import { removeStaleTemps } from '@contract-studio/codegen/stale-temp';
import { SERVICE_BOUNDS } from '../limits.js';
import { gunzipSync, gzipSync } from 'node:zlib';
import type { CactalProblem } from '../pipeline/cactal-adapter.js';
import { checkRelativePath } from '../util/safe-fs.js';
import { assertCacheEntry, CACHE_ENTRY_NAMES } from './cache-dir.js';
import { markUsed, removeLeastRecentlyUsed } from './least-recently-used.js';

export interface GeneratedTree {
  problems: CactalProblem[];
  written: number;
  unchanged: number;
  /** src-gen's files after generation: path relative to src-gen -> bytes, executable bit. */
  files: Map<string, { data: Buffer; executable: boolean }>;
}

/** Entries above this size (compressed) are neither stored nor read. */
const MAX_ENTRY_BYTES = 32 * 1024 * 1024;

let identity: string | undefined;

/**
 * The generator's identity: the path inside dist/ and the bytes of every file of the two packages'
 * dist/ (not where they are nor their times: the CLI run from a checkout and the packed one share
 * the generated trees; about 10 ms, once per process).
 */
export function generatorIdentity(): string {
  if (identity !== undefined) return identity;
  const hash = createHash('sha256');
  const require = createRequire(import.meta.url);
  for (const spec of ['@contract-studio/language/node', '@contract-studio/codegen']) {
    let dir: string;
    try {
      dir = dirname(require.resolve(spec));
    } catch {
      hash.update(`${spec}: absent\0`);
      continue;
    }
    // from dist/node/index.js or dist/index.js up to dist/
    while (!dir.endsWith('/dist') && dirname(dir) !== dir) dir = dirname(dir);
    const walk = (d: string): void => {
      for (const e of readdirSync(d, { withFileTypes: true }).sort((a, b) => (a.name < b.name ? -1 : 1))) {
        const p = join(d, e.name);
        if (e.isDirectory()) walk(p);
        else if (e.isFile() && !e.name.endsWith('.map')) {
          hash.update(`${spec}/${relative(dir, p)}\0`).update(readFileSync(p)).update('\0');
        }
      }
    };
    walk(dir);
  }
  identity = hash.digest('hex');
  return identity;
}

export class GenerationCache {
  constructor(private readonly dir: string) {}

  private file(inputsDigest: string): string {
    const key = createHash('sha256').update(generatorIdentity()).update('\0').update(inputsDigest).digest('hex').slice(0, 32);
    return join(this.dir, `${key}.json.gz`);
  }

  async get(inputsDigest: string): Promise<GeneratedTree | null> {
    try {
      assertCacheEntry(this.dir);
      const path = this.file(inputsDigest);
      const st = await fsp.lstat(path);
      if (!st.isFile() || st.size > MAX_ENTRY_BYTES) return null;
      await markUsed(path);
      const v = JSON.parse(gunzipSync(await fsp.readFile(path), { maxOutputLength: 8 * MAX_ENTRY_BYTES }).toString('utf8')) as {
        version?: unknown;
        problems?: unknown;
        written?: unknown;
        unchanged?: unknown;
        files?: unknown;
      };
      if (v.version !== 1 || !Array.isArray(v.problems) || typeof v.written !== 'number' || typeof v.unchanged !== 'number' || !Array.isArray(v.files)) return null;
      const files = new Map<string, { data: Buffer; executable: boolean }>();
      for (const f of v.files as unknown[]) {
        const { path: rel, data, executable } = (f ?? {}) as { path?: unknown; data?: unknown; executable?: unknown };
        if (typeof rel !== 'string' || typeof data !== 'string' || typeof executable !== 'boolean') return null;
        files.set(checkRelativePath(rel), { data: Buffer.from(data, 'base64'), executable });
      }
      return { problems: v.problems as CactalProblem[], written: v.written, unchanged: v.unchanged, files };
    } catch {
      return null;
    }
  }

  async put(inputsDigest: string, tree: GeneratedTree): Promise<void> {
    await fsp.mkdir(this.dir, { recursive: true, mode: 0o700 });
    assertCacheEntry(this.dir);
    const body = gzipSync(
      JSON.stringify({
        version: 1,
        problems: tree.problems,
        written: tree.written,
        unchanged: tree.unchanged,
        files: [...tree.files].map(([path, f]) => ({ path, data: f.data.toString('base64'), executable: f.executable })),
      }),
    );
    if (body.length > MAX_ENTRY_BYTES) return;
    // the entries beyond the bound, and the temporary files of writers killed before their rename
    removeStaleTemps(this.dir);
    await removeLeastRecentlyUsed(this.dir, CACHE_ENTRY_NAMES.generated, SERVICE_BOUNDS.keptGeneratedTrees - 1);
    const path = this.file(inputsDigest);
    const tmp = join(this.dir, `.${basename(path)}.${randomBytes(4).toString('hex')}.tmp-${process.pid}`);
    await fsp.writeFile(tmp, body, { mode: 0o600 });
    await fsp.rename(tmp, path);
  }
}
