/**
 * The C runtime, built once on the host for the bwrap and none sandboxes (the docker image carries
 * its own at /opt/contract/runtime). The runtime sources are copied to
 * `<cacheDir>/runtime-<hash of the sources>/` and `make` is run there; jobs bind that folder
 * read-only and pass it as CONTRACT_RUNTIME. A change of the sources gives a new hash, a new build.
 */
import { spawn } from 'node:child_process';
import { createHash } from 'node:crypto';
import { existsSync, promises as fsp } from 'node:fs';
import { join } from 'node:path';
import { listFilesNoFollow, readFileNoFollow, removeTreeNoFollow, syncFileNoFollow } from '../util/safe-fs.js';

/** The runtime's sources: what make needs (test outputs, CSV logs, objects are left out). */
const SOURCE = /(\.(c|h|mk|def|S|sh)|(^|\/)Makefile)$/;
const SKIP_DIRS = /^(build|logs|run)$|(^|\/)\.git$/;

export class RuntimeCache {
  private readonly builds = new Map<string, Promise<string>>();

  constructor(
    private readonly sourceDir: string,
    private readonly cacheDir: string,
  ) {}

  get source(): string {
    return this.sourceDir;
  }

  /** Returns the host folder of the built runtime, building it first when needed. */
  ensure(onLine: (line: string, stream: 'stdout' | 'stderr') => void): Promise<string> {
    return (async () => {
      if (!existsSync(join(this.sourceDir, 'Makefile'))) {
        throw new Error(`no runtime at ${this.sourceDir} (expected a Makefile producing build/libmodule.a and build/contract-launch)`);
      }
      const files = await listFilesNoFollow(this.sourceDir, (rel, isDir) => (isDir ? !SKIP_DIRS.test(rel) : SOURCE.test(rel)));
      const hash = createHash('sha256');
      const contents = new Map<string, Buffer>();
      for (const f of files) {
        const data = await readFileNoFollow(this.sourceDir, f);
        if (!data) continue;
        contents.set(f, data);
        hash.update(f).update('\0').update(data).update('\0');
      }
      const key = hash.digest('hex').slice(0, 16);
      let build = this.builds.get(key);
      if (!build) {
        build = this.build(key, contents, onLine);
        this.builds.set(key, build);
        build.catch(() => this.builds.delete(key));
      } else {
        onLine(`runtime ${key} already built`, 'stdout');
      }
      return build;
    })();
  }

  private async build(key: string, contents: Map<string, Buffer>, onLine: (line: string, stream: 'stdout' | 'stderr') => void): Promise<string> {
    const dir = join(this.cacheDir, `runtime-${key}`);
    const stamp = join(dir, '.contract-built');
    if (existsSync(stamp)) return dir;
    await removeTreeNoFollow(dir);
    await fsp.mkdir(dir, { recursive: true, mode: 0o755 });
    for (const [rel, data] of contents) await syncFileNoFollow(dir, rel, data, undefined, /\.(sh)$/.test(rel) ? 0o755 : 0o644);
    onLine(`building the runtime (make -C ${this.sourceDir} copy) ...`, 'stdout');
    await new Promise<void>((resolve, reject) => {
      const child = spawn('make', ['-s', '-C', dir], { stdio: ['ignore', 'pipe', 'pipe'] });
      const forward = (stream: 'stdout' | 'stderr') => (chunk: Buffer) => {
        for (const line of chunk.toString('utf8').split('\n')) if (line) onLine(line, stream);
      };
      child.stdout.on('data', forward('stdout'));
      child.stderr.on('data', forward('stderr'));
      child.on('error', reject);
      child.on('close', (code) => (code === 0 ? resolve() : reject(new Error(`runtime build failed (make exit ${code})`))));
    });
    for (const needed of ['build/libmodule.a', 'build/contract-launch']) {
      if (!existsSync(join(dir, needed))) onLine(`warning: the runtime build did not produce ${needed}`, 'stderr');
    }
    await fsp.writeFile(stamp, new Date().toISOString());
    // readable by every job uid, writable by none
    await fsp.chmod(dir, 0o755);
    return dir;
  }
}
