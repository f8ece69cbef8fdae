import { existsSync, statSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { execFileSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';

const pkg = fileURLToPath(new URL('../..', import.meta.url));

function newestMtime(dir: string): number {
  let newest = 0;
  for (const e of readdirSync(dir, { withFileTypes: true })) {
    const p = join(dir, e.name);
    newest = Math.max(newest, e.isDirectory() ? newestMtime(p) : statSync(p).mtimeMs);
  }
  return newest;
}

/** The built packages the front end bundles (the language worker, the shared conventions, the service's types). */
const BUNDLED = ['language', 'conventions', 'build-service'].map((p) => join(pkg, '..', p, 'dist'));

/**
 * Builds the production front end when dist/ is missing or older than src/ or than the built
 * packages it bundles (the e2e tests use it).
 */
export function ensureFrontendBuilt(): void {
  const index = join(pkg, 'dist', 'index.html');
  const inputs = [newestMtime(join(pkg, 'src')), statSync(join(pkg, 'index.html')).mtimeMs, ...BUNDLED.filter(existsSync).map(newestMtime)];
  const stale = !existsSync(index) || statSync(index).mtimeMs < Math.max(...inputs);
  if (stale) execFileSync(process.execPath, [join(pkg, '../../node_modules/vite/bin/vite.js'), 'build', '--logLevel', 'warn'], { cwd: pkg, stdio: 'inherit' });
}

/** vitest options whose value is the next word of the command line (not a file filter). */
const VALUED = new Set(['-t', '--testNamePattern', '--exclude', '--reporter', '--outputFile', '-c', '--config', '-r', '--root', '--dir',
  '--project', '--pool', '--shard', '--bail', '--retry', '--maxWorkers', '--testTimeout', '--hookTimeout', '--environment', '--mode']);

/**
 * The file filters of the vitest command line (`npx vitest run src/monitor/x.test.ts -t name`:
 * `src/monitor/x.test.ts`).
 */
export function fileFilters(argv: readonly string[]): string[] {
  const words = argv.slice(2);
  const out: string[] = [];
  for (let i = 0; i < words.length; i++) {
    const w = words[i]!;
    if (VALUED.has(w)) i++;
    else if (!w.startsWith('-') && !(i === 0 && ['run', 'watch', 'dev', 'related', 'list'].includes(w))) out.push(w);
  }
  return out;
}

/**
 * Only the browser tests (test/e2e/) load the built front end (the unit tests of src/ and server/
 * serve no page, or a folder of their own): a run whose every file filter is a path under src/ or
 * server/ does not build it (~20 s saved); any other run (every file, an e2e file, a bare name that
 * may match one) builds it when stale.
 */
export default function setup(): void {
  const filters = fileFilters(process.argv);
  if (filters.length && filters.every((f) => /^(\.\/)?((src|server)\/|test\/[^/]+\.test\.ts$)/.test(f))) return;
  ensureFrontendBuilt();
}
