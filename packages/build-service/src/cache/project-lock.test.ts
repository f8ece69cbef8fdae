import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { acquireProjectLock, tryProjectLock } from './project-lock.js';

const dir = mkdtempSync(join(tmpdir(), 'project-lock-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('project lock (flock child)', () => {
  it('a released lock is free at once: the next command of the same process does not wait for the one before', async () => {
    const path = join(dir, 'lock-a');
    for (let i = 0; i < 20; i++) {
      const waited: string[] = [];
      const lock = await acquireProjectLock(path, (holder) => waited.push(holder));
      expect(waited).toEqual([]);
      await lock.release();
      const next = await tryProjectLock(path);
      expect(next, `try ${i}: the lock was still held after release() resolved`).not.toBeNull();
      await next!.release();
    }
  });

  it('a second command waits, says for whom, and gets the lock once the first lets it go', async () => {
    const path = join(dir, 'lock-b');
    const first = await acquireProjectLock(path, () => {});
    expect(await tryProjectLock(path)).toBeNull();
    const waited: string[] = [];
    let got = false;
    const second = acquireProjectLock(path, (holder) => waited.push(holder)).then((l) => ((got = true), l));
    await new Promise((r) => setTimeout(r, 200));
    expect(got).toBe(false);
    expect(waited).toHaveLength(1);
    expect(waited[0]).toMatch(new RegExp(`^pid ${process.pid}, started \\d{4}-`));
    await first.release();
    await (await second).release();
    expect(got).toBe(true);
  });
});
