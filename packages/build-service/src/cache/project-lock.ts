/**
 * One command at a time per project work tree, across processes (the CLI and the IDE server share
 * the cache): an exclusive flock(2) on `<workspace>/lock`, held by a small `flock` child process
 * whose stdin is a pipe from us. The kernel drops the lock when that child exits, and the child
 * exits when its stdin closes: when we release, and also when we are killed (even with -9), so a
 * killed command never leaves a lock behind and no pid file has to be guessed stale.
 * A second command on the same project waits (with one line saying for whom) until the first ends.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';

export interface ProjectLock {
  /**
   * Lets the lock go. The promise resolves once the kernel has dropped it (the `flock` child has
   * exited): a command that awaits it before it ends leaves the next command of the same process
   * (the IDE's server, the CLI in a script) a free lock, not a wait for itself.
   */
  release(): Promise<void>;
}

/**
 * One `flock` child on `path` (blocking, or -n: exit 75, EX_TEMPFAIL, tells "busy" apart from a
 * failure of flock itself). `held` gets the lock once it is held (and `<path>.holder` names us, for
 * a command that waits); `ended` gets flock's exit code, or its spawn error, when it ended without it.
 */
function lockChild(path: string, blocking: boolean, held: (lock: ProjectLock) => void, ended: (code: number | null, error?: Error) => void): ChildProcess {
  const child = spawn('flock', [...(blocking ? [] : ['-n', '-E', '75']), '-x', path, '-c', 'echo locked; exec cat >/dev/null'], {
    stdio: ['pipe', 'pipe', 'ignore'],
  });
  let out = '';
  let locked = false;
  const closed = new Promise<void>((resolve) => child.on('close', () => resolve()));
  child.stdout!.on('data', (c: Buffer) => {
    out += c.toString('utf8');
    if (!locked && out.includes('locked')) {
      locked = true;
      try {
        writeFileSync(`${path}.holder`, `pid ${process.pid}, started ${new Date().toISOString()}`, { mode: 0o600 });
      } catch {
        /* only for the message of a waiting command */
      }
      held({
        release: () => {
          child.stdin!.end();
          return closed;
        },
      });
    }
  });
  child.on('error', (e) => {
    if (!locked) ended(null, e);
  });
  child.on('close', (code) => {
    if (!locked) ended(code);
  });
  return child;
}

/** Takes the lock at `path` only if nobody holds it now: null when it is held (or flock fails). */
export function tryProjectLock(path: string): Promise<ProjectLock | null> {
  return new Promise<ProjectLock | null>((resolve) => void lockChild(path, false, resolve, () => resolve(null)));
}

/** Acquires the lock at `path` (created if missing); calls `onWait` once when another holder makes it wait. */
export function acquireProjectLock(path: string, onWait: (holder: string) => void, cancelled?: Promise<void>): Promise<ProjectLock> {
  return new Promise<ProjectLock>((resolve, reject) => {
    let child: ChildProcess;
    let waiting = false;
    let held = false;
    const start = (blocking: boolean): void => {
      child = lockChild(path, blocking, (lock) => {
        held = true;
        resolve(lock);
      }, (code, error) => {
        if (error) reject(new Error(`cannot lock ${path}: ${error.message} (is util-linux "flock" installed?)`));
        else if (!blocking && code === 75) {
          if (!waiting) {
            waiting = true;
            let holder = 'another command';
            try {
              holder = readFileSync(`${path}.holder`, 'utf8').slice(0, 200).replace(/[^\x20-\x7e]/g, '?');
            } catch {
              /* unknown holder */
            }
            onWait(holder);
          }
          start(true);
        } else reject(new Error(`cannot lock ${path} (flock exit ${code})`));
      });
    };
    start(false);
    // a cancel stops the waiting only: once held, the lock is released by release() alone, after
    // the job's processes are gone (the next command must not touch a work tree still in use)
    void cancelled?.then(() => {
      if (held) return;
      child.stdin?.end();
      child.kill();
      reject(new Error('cancelled'));
    });
  });
}
