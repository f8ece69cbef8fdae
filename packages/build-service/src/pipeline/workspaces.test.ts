import { mkdirSync, mkdtempSync, readdirSync, readFileSync, realpathSync, rmSync, utimesSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, expect, test } from 'vitest';
import { WorkspaceManager } from './workspaces.js';

let tmp: string;
beforeEach(() => {
  tmp = realpathSync(mkdtempSync(join(tmpdir(), 'ws-sweep-')));
});
afterEach(() => rmSync(tmp, { recursive: true, force: true }));

/** The project folders the kept workspaces of the cache name. */
const kept = (cache: string): string[] => readdirSync(cache).map((id) => readFileSync(join(cache, id, 'folder'), 'utf8')).sort();

test('the build cache drops the workspace of a project folder that is gone at the next process\'s first acquire, not one a command holds', async () => {
  const cache = join(tmp, 'projects');
  const [p1, p2, p3] = ['p1', 'p2', 'p3'].map((n) => join(tmp, n)) as [string, string, string];
  for (const p of [p1, p2, p3]) mkdirSync(p);
  const first = new WorkspaceManager(join(tmp, 'base1'), { persistentDir: cache });
  for (const p of [p1, p2, p3]) await (await first.acquireForProject(p, 'none')).release();
  expect(kept(cache)).toEqual([p1, p2, p3]);
  // p3's workspace is in use (a command holds it); p1 and p3 are deleted
  const held = await first.acquireForProject(p3, 'none');
  rmSync(p1, { recursive: true });
  rmSync(p3, { recursive: true });
  const second = new WorkspaceManager(join(tmp, 'base2'), { persistentDir: cache }); // another command
  await (await second.acquireForProject(p2, 'none')).release();
  expect(kept(cache)).toEqual([p2, p3]);
  await held.release();
  const third = new WorkspaceManager(join(tmp, 'base3'), { persistentDir: cache });
  await (await third.acquireForProject(p2, 'none')).release();
  expect(kept(cache)).toEqual([p2]);
  // the one left is the same workspace, reused
  const again = await third.acquireForProject(p2, 'none');
  expect(again.reused).toBe(true);
  await again.release();
});

test('the build cache keeps the most recently used project workspaces up to its bound, the one acquired and the held ones besides', async () => {
  const cache = join(tmp, 'projects');
  const [p1, p2, p3, p4, p5] = ['p1', 'p2', 'p3', 'p4', 'p5'].map((n) => join(tmp, n)) as [string, string, string, string, string];
  const first = new WorkspaceManager(join(tmp, 'base1'), { persistentDir: cache, keptProjects: 3 });
  for (const p of [p1, p2, p3, p4, p5]) {
    mkdirSync(p);
    await (await first.acquireForProject(p, 'none')).release();
  }
  // the first process's sweep ran before any entry existed: all five are there
  expect(kept(cache)).toEqual([p1, p2, p3, p4, p5]);
  const held = await first.acquireForProject(p2, 'none'); // a command is using p2
  // used in the order p1 (longest ago) ... p5 (last)
  const now = Date.now() / 1000;
  for (const id of readdirSync(cache)) {
    const n = Number(readFileSync(join(cache, id, 'folder'), 'utf8').slice(-1));
    utimesSync(join(cache, id, 'state.json'), now - 100 + n, now - 100 + n);
  }
  const second = new WorkspaceManager(join(tmp, 'base2'), { persistentDir: cache, keptProjects: 3 });
  // the one acquired (p1, the least recently used) stays, with the two most recent (p5, p4);
  // p3 goes; p2 is held, so it stays too
  await (await second.acquireForProject(p1, 'none')).release();
  expect(kept(cache)).toEqual([p1, p2, p4, p5]);
  await held.release();
});

test('first jobs on one project at once share one workspace, one after the other: none removes the folders another is using', async () => {
  const manager = new WorkspaceManager(join(tmp, 'base'));
  const project = join(tmp, 'p');
  mkdirSync(project);
  const order: string[] = [];
  const jobs = [1, 2, 3].map(async (n) => {
    const ws = await manager.acquireForProject(project, 'none');
    order.push(`start ${n}`);
    // the job leaves a file in its stage; the next one must find it (its folders were not remade)
    writeFileSync(join(ws.stageDir, `job${n}`), 'x');
    await new Promise((r) => setTimeout(r, 30));
    const seen = readdirSync(ws.stageDir).sort();
    order.push(`end ${n}`);
    await ws.release();
    return { root: ws.root, seen, reused: ws.reused };
  });
  const results = await Promise.all(jobs);
  expect(new Set(results.map((r) => r.root)).size).toBe(1);
  expect(order).toEqual(['start 1', 'end 1', 'start 2', 'end 2', 'start 3', 'end 3']);
  expect(results.map((r) => r.seen)).toEqual([['job1'], ['job1', 'job2'], ['job1', 'job2', 'job3']]);
  expect(results.map((r) => r.reused)).toEqual([false, true, true]);
});
