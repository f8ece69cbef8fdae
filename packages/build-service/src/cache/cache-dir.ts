/**
 * Where the persistent build cache lives (docs/getting-started.md "The build cache"): the built
 * runtime per toolchain and one work tree per project, shared by `contract build`/`run` and the
 * IDE server. Order: an explicit folder (`--cache-dir`), `$CONTRACT_CACHE_DIR`,
 * `$XDG_CACHE_HOME/contract-studio`, `~/.cache/contract-studio`. A root service hands each
 * workspace its own uid, which must traverse every folder above the work trees; root's home is
 * 0700, so root's default (without XDG_CACHE_HOME) is `/var/cache/contract-studio`.
 *
 * The folder is trusted by the host (docs/sandbox.md "Workspaces and host safety"): it must be a
 * real folder (not a link) owned by the service's user and writable by nobody else; a link planted
 * in place of one of its known entries is refused. Each refusal is a sentence saying how to fix it.
 */
import { lstatSync, mkdirSync, chmodSync } from 'node:fs';
import { homedir } from 'node:os';
import { dirname, isAbsolute, join, resolve } from 'node:path';

export const CACHE_DIR_ENV = 'CONTRACT_CACHE_DIR';

/** Entries of the cache folder the service and the simulator (`sim/`) make (each checked: a real folder, ours). */
export const CACHE_ENTRIES = ['runtime', 'projects', 'generated', 'sim'] as const;

/**
 * The names of the kept entries inside those folders (a built runtime, a generated tree, a built
 * simulator): what the cache's bound counts and removes (least-recently-used.ts) and what
 * `contract cache` counts. Anything else there (a build in progress, a temporary file) is not one.
 */
export const CACHE_ENTRY_NAMES = {
  runtime: /^runtime-[0-9a-f]{16}$/,
  generated: /^[0-9a-f]{32}\.json\.gz$/,
  sim: /^sim-[0-9a-f]{20}$/,
} as const;

export interface CacheDirChoice {
  dir: string;
  /** Where it came from, for --verbose and error messages. */
  source: 'option' | 'env' | 'xdg' | 'home' | 'root default';
}

/** The cache folder to use: `explicit` (an option, resolved against cwd), else the environment, else XDG. */
export function resolveCacheDir(explicit: string | undefined, env: NodeJS.ProcessEnv = process.env, uid = process.getuid?.(), home = homedir(), cwd = process.cwd()): CacheDirChoice {
  if (explicit) return { dir: resolve(cwd, explicit), source: 'option' };
  const fromEnv = env[CACHE_DIR_ENV];
  if (fromEnv) return { dir: resolve(cwd, fromEnv), source: 'env' };
  // XDG Base Directory: a relative XDG_CACHE_HOME is invalid and ignored
  const xdg = env.XDG_CACHE_HOME;
  if (xdg && isAbsolute(xdg)) return { dir: join(xdg, 'contract-studio'), source: 'xdg' };
  if (uid === 0) return { dir: '/var/cache/contract-studio', source: 'root default' };
  return { dir: join(home, '.cache', 'contract-studio'), source: 'home' };
}

const HOW = `choose another folder with --cache-dir DIR or ${CACHE_DIR_ENV}=DIR`;

/**
 * Creates the cache folder when missing and checks it can be trusted; returns null when it can,
 * else the reason (one sentence naming the folder and the fix). `jobUidsMustTraverse`: the service
 * runs jobs under other uids (root), so every folder above it must be searchable by others.
 */
export function prepareCacheDir(dir: string, jobUidsMustTraverse: boolean, uid = process.getuid?.()): string | null {
  try {
    mkdirSync(dir, { recursive: true, mode: 0o711 });
  } catch (e) {
    return `cannot create the cache folder ${dir}: ${(e as Error).message.split('\n')[0]}; ${HOW}`;
  }
  let st;
  try {
    st = lstatSync(dir);
  } catch (e) {
    return `cannot read the cache folder ${dir}: ${(e as Error).message.split('\n')[0]}; ${HOW}`;
  }
  if (st.isSymbolicLink()) return `the cache folder ${dir} is a symbolic link, which the build cache does not follow; ${HOW} (the link's target itself)`;
  if (!st.isDirectory()) return `the cache folder ${dir} is not a folder; ${HOW}`;
  if (uid !== undefined && st.uid !== uid) return `the cache folder ${dir} belongs to uid ${st.uid}, not to you (uid ${uid}): its build products cannot be trusted; ${HOW}`;
  if ((st.mode & 0o022) !== 0) {
    return `the cache folder ${dir} is writable by ${st.mode & 0o002 ? 'every user' : 'its group'} (mode ${(st.mode & 0o777).toString(8)}): its build products cannot be trusted; run "chmod 711 ${dir}" or ${HOW}`;
  }
  for (const name of CACHE_ENTRIES) {
    const problem = checkCacheEntry(join(dir, name), uid);
    if (problem) return problem;
  }
  if (jobUidsMustTraverse) {
    // the sandboxed jobs run under their own uids: they must reach their work tree and the runtime
    try {
      if ((st.mode & 0o001) === 0) chmodSync(dir, (st.mode & 0o777) | 0o011);
    } catch {
      /* checked below */
    }
    for (let up = dir; ; up = dirname(up)) {
      let mode: number;
      try {
        mode = lstatSync(up).mode;
      } catch {
        mode = 0;
      }
      if ((mode & 0o001) === 0) {
        return `the sandboxed builds run under their own uids and cannot reach the cache folder ${dir} (${up} is not searchable by others); ${HOW} under /var/cache, /var/tmp or /tmp`;
      }
      if (up === dirname(up)) break;
    }
  }
  return null;
}

/** A known entry of the cache (or a folder below it): absent, or a real folder of ours not writable by others. */
export function checkCacheEntry(path: string, uid = process.getuid?.()): string | null {
  let st;
  try {
    st = lstatSync(path);
  } catch {
    return null;
  }
  if (st.isSymbolicLink()) return `refusing the build cache: ${path} is a symbolic link (planted?); remove it ("rm ${path}") or ${HOW}`;
  if (!st.isDirectory()) return `refusing the build cache: ${path} is not a folder; remove it or ${HOW}`;
  if (uid !== undefined && st.uid !== uid) return `refusing the build cache: ${path} belongs to uid ${st.uid}, not to you (uid ${uid}); remove it or ${HOW}`;
  if ((st.mode & 0o022) !== 0) return `refusing the build cache: ${path} is writable by others (mode ${(st.mode & 0o777).toString(8)}); remove it or ${HOW}`;
  return null;
}

/** Throws CacheRefusedError when `path` may not be used (see checkCacheEntry). */
export function assertCacheEntry(path: string): void {
  const problem = checkCacheEntry(path);
  if (problem) throw new CacheRefusedError(problem);
}

export class CacheRefusedError extends Error {}
