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
  release(): void;
}

/** Takes the lock at `path` only if nobody holds it now: null when it is held (or flock fails). */
export function tryProjectLock(path: string): Promise<ProjectLock | null> {
  return new Promise<ProjectLock | null>((resolve) => {
    const child = spawn('flock', ['-n', '-E', '75', '-x', path, '-c', 'echo locked; exec cat >/dev/null'], { stdio: ['pipe', 'pipe', 'ignore'] });
    let out = '';
    let locked = false;
    child.stdout!.on('data', (c: Buffer) => {
      out += c.toString('utf8');
      if (!locked && out.includes('locked')) {
        locked = true;
        resolve({ release: () => void child.stdin!.end() });
      }
    });
    child.on('error', () => resolve(null));
    child.on('close', () => {
      if (!locked) resolve(null);
    });
  });
}

/** Acquires the lock at `path` (created if missing); calls `onWait` once when another holder makes it wait. */
export function acquireProjectLock(path: string, onWait: (holder: string) => void, cancelled?: Promise<void>): Promise<ProjectLock> {
  const holderFile = `${path}.holder`;
  return new Promise<ProjectLock>((resolve, reject) => {
    // -E 75 (EX_TEMPFAIL) with -n: tells "busy" apart from a failure of flock itself
    let child: ChildProcess;
    let waiting = false;
    let held = false;
    const start = (blocking: boolean): void => {
      child = spawn('flock', [...(blocking ? [] : ['-n', '-E', '75']), '-x', path, '-c', 'echo locked; exec cat >/dev/null'], {
        stdio: ['pipe', 'pipe', 'ignore'],
      });
      let out = '';
      let locked = false;
      const self = child;
      child.stdout!.on('data', (c: Buffer) => {
        out += c.toString('utf8');
        if (!locked && out.includes('locked')) {
          locked = true;
          held = true;
          try {
            writeFileSync(holderFile, `pid ${process.pid}, started ${new Date().toISOString()}`, { mode: 0o600 });
          } catch {
            /* only for the message of a waiting command */
          }
          resolve({
            release: () => {
              self.stdin!.end();
            },
          });
        }
      });
      child.on('error', (e) => reject(new Error(`cannot lock ${path}: ${e.message} (is util-linux "flock" installed?)`)));
      child.on('close', (code) => {
        if (locked) return;
        if (!blocking && code === 75) {
          if (!waiting) {
            waiting = true;
            let holder = 'another command';
            try {
              holder = readFileSync(holderFile, 'utf8').slice(0, 200).replace(/[^\x20-\x7e]/g, '?');
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
