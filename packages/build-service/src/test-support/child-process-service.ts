/** Test helper: the compiled build service (test-support/child-service.ts) in a child process. */
import { spawn, spawnSync, type ChildProcess } from 'node:child_process';
import { dirname, join } from 'node:path';
import { fileURLToPath } from 'node:url';

const pkg = join(dirname(fileURLToPath(import.meta.url)), '..', '..');

/** Brings dist/ up to date (what `contract serve` runs), starts the service, resolves with its URL. */
export async function startChildService(cacheDir: string): Promise<{ url: string; child: ChildProcess }> {
  const tsc = spawnSync('npx', ['tsc', '-b'], { cwd: pkg, encoding: 'utf8' });
  if (tsc.status !== 0) throw new Error(`tsc -b failed: ${tsc.stdout}${tsc.stderr}`);
  const child = spawn(process.execPath, [join(pkg, 'dist', 'test-support', 'child-service.js'), cacheDir], { stdio: ['ignore', 'pipe', 'inherit'] });
  const url = await new Promise<string>((resolve, reject) => {
    let out = '';
    child.stdout!.on('data', (c: Buffer) => {
      out += c.toString();
      const m = /^URL (\S+)$/m.exec(out);
      if (m) resolve(m[1]!);
    });
    child.on('exit', (code) => reject(new Error(`the service exited (${code}) before it listened`)));
  });
  return { url, child };
}
