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

export default function setup(): void {
  ensureFrontendBuilt();
}
