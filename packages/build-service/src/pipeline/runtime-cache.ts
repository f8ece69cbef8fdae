/**
 * The C runtime, built once on the host for the bwrap and none sandboxes (the docker image carries
 * its own at /opt/contract/runtime). The runtime sources are copied to
 * `<cacheDir>/runtime-<key>/` and `make` is run there; jobs bind that folder read-only and pass it
 * as CONTRACT_RUNTIME. The key hashes the sources and the toolchain (`gcc -dumpfullversion`, the
 * machine, `uname -m`): a change of either gives a new key, a new build. With a persistent cache
 * folder (docs/getting-started.md "The build cache") the build is shared by every project, the CLI
 * and the IDE server: it is made in a private temporary folder and renamed into place only once
 * complete, so two processes never see half a runtime, and a killed build leaves only a temporary
 * folder that no key names.
 */
import { execFileSync, spawn, type ChildProcess } from 'node:child_process';
import { createHash, randomBytes } from 'node:crypto';
import { existsSync, promises as fsp } from 'node:fs';
import { availableParallelism, machine } from 'node:os';
import { join } from 'node:path';
import { isRuntimeSourcePart } from '@contract-studio/conventions';
import { removeAbandonedBuilds } from '../cache/abandoned-builds.js';
import { markUsed, removeLeastRecentlyUsed } from '../cache/least-recently-used.js';
import { SERVICE_BOUNDS } from '../limits.js';
import { assertCacheEntry, CACHE_ENTRY_NAMES } from '../cache/cache-dir.js';
import { listFilesNoFollow, readFileNoFollow, removeTreeNoFollow, syncFileNoFollow } from '../util/safe-fs.js';
import { RuntimeBuildLines, type RuntimeLineListener } from './runtime-build-lines.js';

let toolchainCache: string | undefined;

/** make jobs for a runtime build: the machine's CPUs, at most 8 (each gcc takes memory). */
const RUNTIME_BUILD_JOBS = Math.max(1, Math.min(8, availableParallelism()));

/** What the runtime's build products depend on besides its sources. */
export function toolchainIdentity(): string {
  if (toolchainCache === undefined) {
    let gcc = 'no gcc';
    for (const cc of ['gcc', 'cc']) {
      try {
        gcc = `${cc} ${execFileSync(cc, ['-dumpfullversion', '-dumpversion'], { encoding: 'utf8', timeout: 5000 }).trim()}`;
        break;
      } catch {
        /* next */
      }
    }
    toolchainCache = `${gcc}; ${machine()}`;
  }
  return toolchainCache;
}

/**
 * Why `dir` cannot be built as a runtime: it is an installed one (`make install PREFIX=...`: its
 * include/ and build/ products, a Makefile that builds nothing, no src/), whose products the cache
 * would take as built from nothing; undefined for a source folder. `named` says where the folder
 * came from (`CONTRACT_RUNTIME=/opt/contract/runtime`, `--runtime ...`).
 */
export function installedRuntimeProblem(dir: string, named: string): string | undefined {
  if (existsSync(join(dir, 'src')) || !existsSync(join(dir, 'build', 'libmodule.a'))) return undefined;
  return `${named} names an installed runtime, which has no sources (no src/ beside its build/): contract build builds the runtime from its sources, for the compiler it uses; unset it, or name a runtime source folder (the runtime/ of ContrACT Studio, or one that contract runtime-source DIR copies)`;
}

/**
 * The runtime's sources: what make needs, in the parts a user's build takes (RUNTIME_SOURCE_PARTS:
 * a checkout's runtime/ and the packed CLI's give the same key; tests, benchmarks, test outputs,
 * CSV logs, objects are left out).
 */
const SOURCE = /(\.(c|h|mk|def|S|sh)|(^|\/)Makefile)$/;
const SKIP_DIRS = /^(build|logs|run)$|(^|\/)\.git$/;
const isRuntimeSource = (rel: string, isDir: boolean): boolean => isRuntimeSourcePart(rel) && (isDir ? !SKIP_DIRS.test(rel) : SOURCE.test(rel));

/** A runtime's sources read once: their key, the name of their folder in the cache, the files. */
export interface RuntimeSources {
  key: string;
  /** `runtime-<key>`: the folder's name in the cache. */
  name: string;
  contents: Map<string, Buffer>;
}

/** One runtime build of this cache: its end, its lines (told to the jobs waiting for it), whether it ended. */
interface SharedBuild {
  done: Promise<string>;
  lines: RuntimeBuildLines;
  settled: boolean;
}

export class RuntimeCache {
  private readonly builds = new Map<string, SharedBuild>();
  /** The runtime builds' make processes running now (close() stops them). */
  private readonly makes = new Set<ChildProcess>();
  private closed = false;

  constructor(
    private readonly sourceDir: string,
    private readonly cacheDir: string,
  ) {}

  get source(): string {
    return this.sourceDir;
  }

  /** Returns the host folder of the built runtime, building it first when needed. */
  ensure(onLine: RuntimeLineListener, until?: Promise<unknown>): Promise<string> {
    return this.sources().then((s) => this.ensureBuilt(s, onLine, until));
  }

  /**
   * The runtime's sources as they are now and their key (their hash with the toolchain's), without
   * building anything: a job knows which runtime it will link against (`runtime-<key>`, the name
   * of its folder) before it decides whether its work tree's build products can be kept.
   */
  async sources(): Promise<RuntimeSources> {
    if (!existsSync(join(this.sourceDir, 'Makefile'))) {
      throw new Error(`no runtime at ${this.sourceDir} (expected a Makefile producing build/libmodule.a and build/contract-launch)`);
    }
    const installed = installedRuntimeProblem(this.sourceDir, `the runtime folder ${this.sourceDir}`);
    if (installed) throw new Error(installed);
    const files = await listFilesNoFollow(this.sourceDir, isRuntimeSource);
    const hash = createHash('sha256').update(toolchainIdentity()).update('\0');
    const contents = new Map<string, Buffer>();
    for (const f of files) {
      const data = await readFileNoFollow(this.sourceDir, f);
      if (!data) continue;
      contents.set(f, data);
      hash.update(f).update('\0').update(data).update('\0');
    }
    const key = hash.digest('hex').slice(0, 16);
    return { key, name: `runtime-${key}`, contents };
  }

  /**
   * Stops the builds in progress (a job cancelled during the first build no longer waits for it:
   * it goes on for the service's other and later jobs until the service closes) and waits for
   * them to have removed their temporary folders. No build starts afterwards.
   */
  async close(): Promise<void> {
    this.closed = true;
    // GNU make passes a SIGTERM on to the compilers it runs and waits for them
    for (const child of this.makes) child.kill('SIGTERM');
    await Promise.all([...this.builds.values()].map((b) => b.done.catch(() => undefined)));
  }

  /**
   * The host folder of the runtime of `s` (sources()), building it first when needed. `onLine`
   * gets the build's lines (those so far too, for a build already in progress) until `until`
   * settles (the job stopped waiting: cancelled) or the build ends (runtime-build-lines.ts).
   */
  ensureBuilt(s: RuntimeSources, onLine: RuntimeLineListener, until?: Promise<unknown>): Promise<string> {
    let build = this.builds.get(s.key);
    if (this.closed) return Promise.reject(new Error('the build service is closing: the runtime is not built'));
    if (!build) {
      const lines = new RuntimeBuildLines();
      lines.follow(onLine, until);
      const shared: SharedBuild = { done: this.build(s.key, s.contents, (l, st) => lines.line(l, st)), lines, settled: false };
      build = shared;
      this.builds.set(s.key, shared);
      shared.done.catch(() => this.builds.delete(s.key)).finally(() => {
        shared.settled = true;
        lines.end();
      });
    } else if (build.settled) {
      onLine(`runtime ${s.key} already built`, 'stdout');
    } else {
      // another job's build in progress: its lines so far, then the later ones
      onLine(`runtime ${s.key} is being built for another job: its lines follow`, 'stdout');
      build.lines.follow(onLine, until);
    }
    // each job marks the runtime it links against as used (the cache's bound keeps it)
    return build.done.then(async (dir) => {
      await markUsed(dir);
      return dir;
    });
  }

  private async build(key: string, contents: Map<string, Buffer>, onLine: (line: string, stream: 'stdout' | 'stderr') => void): Promise<string> {
    await fsp.mkdir(this.cacheDir, { recursive: true, mode: 0o711 });
    assertCacheEntry(this.cacheDir);
    const final = join(this.cacheDir, `runtime-${key}`);
    assertCacheEntry(final);
    if (existsSync(join(final, '.contract-built'))) {
      onLine(`runtime ${key} (${toolchainIdentity()}) already built in ${final}`, 'stdout');
      return final;
    }
    // a folder without its stamp is a build that did not finish (older layout): not trusted
    await removeTreeNoFollow(final);
    await removeAbandonedBuilds(this.cacheDir, RUNTIME_BUILDING);
    // a new runtime per ContrACT Studio version or compiler: the least recently used beyond the bound go
    await removeLeastRecentlyUsed(this.cacheDir, CACHE_ENTRY_NAMES.runtime, SERVICE_BOUNDS.keptRuntimes - 1);
    // named as RUNTIME_BUILDING matches: a killed build's folder is removed by a later build
    const dir = join(this.cacheDir, `.building-${key}-${process.pid}-${randomBytes(4).toString('hex')}`);
    await fsp.mkdir(dir, { mode: 0o700 });
    for (const [rel, data] of contents) await syncFileNoFollow(dir, rel, data, undefined, /\.(sh)$/.test(rel) ? 0o755 : 0o644);
    onLine(`building the runtime (make -C ${this.sourceDir} copy, ${toolchainIdentity()}) ...`, 'stdout');
    try {
      await this.make(dir, onLine);
    } catch (e) {
      await removeTreeNoFollow(dir);
      throw e;
    }
    await fsp.writeFile(join(dir, '.contract-built'), new Date().toISOString());
    // readable by every job uid, writable by none
    await fsp.chmod(dir, 0o755);
    try {
      await fsp.rename(dir, final);
    } catch {
      // another process put the same key in place first: use theirs
      await removeTreeNoFollow(dir);
      assertCacheEntry(final);
      if (!existsSync(join(final, '.contract-built'))) throw new Error(`the runtime cache ${final} is incomplete`);
    }
    return final;
  }

  private async make(dir: string, onLine: (line: string, stream: 'stdout' | 'stderr') => void): Promise<void> {
    await new Promise<void>((resolve, reject) => {
      // parallel: the runtime's Makefile is (the same libmodule.a, byte for byte); 10.4 -> 5.7 s on two cores
      if (this.closed) return reject(new Error('the build service is closing: the runtime build was stopped'));
      const child = spawn('make', ['-s', `-j${RUNTIME_BUILD_JOBS}`, '-C', dir], { stdio: ['ignore', 'pipe', 'pipe'] });
      this.makes.add(child);
      child.on('close', () => this.makes.delete(child));
      const forward = (stream: 'stdout' | 'stderr') => (chunk: Buffer) => {
        for (const line of chunk.toString('utf8').split('\n')) if (line) onLine(line, stream);
      };
      child.stdout.on('data', forward('stdout'));
      child.stderr.on('data', forward('stderr'));
      child.on('error', reject);
      child.on('close', (code, signal) => (code === 0 ? resolve() : reject(new Error(this.closed ? 'the build service is closing: the runtime build was stopped' : `runtime build failed (make ${signal ? `killed by ${signal}` : `exit ${code}`})`))));
    });
    // a make that ends well without them (a Makefile that builds nothing) is a failed build: never
    // stamped "built", or every later job would link against nothing
    const missing = ['build/libmodule.a', 'build/contract-launch'].filter((needed) => !existsSync(join(dir, needed)));
    if (missing.length > 0) throw new Error(`runtime build failed: make -C ${this.sourceDir} ended without producing ${missing.join(' and ')} (is it a runtime source folder?)`);
  }
}

/** `.building-<key>-<pid>-<random>`: a runtime build in progress, by process pid. */
export const RUNTIME_BUILDING = /^\.building-[0-9a-f]{16}-(\d{1,10})-[0-9a-f]{8}$/;
