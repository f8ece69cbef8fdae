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

/**
 * Brings dist/ up to date, starts test-support/orphan-service.ts (a service whose job loops for
 * ever) in `mode`, waits until its job loops, kills it with -9 and waits until it is reaped: what a
 * killed service leaves is then on the host. Resolves with the job's id and the child's pid.
 */
export async function killServiceMidRun(cacheDir: string, mode: 'docker' | 'bwrap-realtime', timeoutMs = 60_000): Promise<{ jobId: string; pid: number }> {
  const tsc = spawnSync('npx', ['tsc', '-b'], { cwd: pkg, encoding: 'utf8' });
  if (tsc.status !== 0) throw new Error(`tsc -b failed: ${tsc.stdout}${tsc.stderr}`);
  const child = spawn(process.execPath, [join(pkg, 'dist', 'test-support', 'orphan-service.js'), cacheDir, mode], { stdio: ['ignore', 'pipe', 'pipe'] });
  let out = '';
  let err = '';
  child.stderr!.on('data', (d: Buffer) => (err += d.toString()));
  try {
    const jobId = await new Promise<string>((resolve, reject) => {
      const timer = setTimeout(() => reject(new Error(`the child's job did not loop within ${timeoutMs / 1000} s; stdout: ${out} stderr: ${err}`)), timeoutMs);
      child.stdout!.on('data', (d: Buffer) => {
        out += d.toString();
        const m = /LOOPING (j-[0-9a-f]+)/.exec(out);
        if (m) {
          clearTimeout(timer);
          resolve(m[1]!);
        }
        if (out.includes('ENDED')) reject(new Error(`the child's job ended: ${out}`));
      });
      child.once('exit', (code) => reject(new Error(`the child exited (${code}) before its job looped; stdout: ${out} stderr: ${err}`)));
    });
    return { jobId, pid: child.pid! };
  } finally {
    if (child.exitCode === null && child.signalCode === null) {
      const exited = new Promise((r) => child.once('exit', r));
      child.kill('SIGKILL');
      await exited; // reaped: /proc/<pid> is gone
    }
  }
}
