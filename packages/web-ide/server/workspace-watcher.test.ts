/**
 * The workspace watcher tells every client which paths changed (docs/ide.md "Several tabs"). A
 * folder made by another program and filled at once (a run's logs/ and its first CSV files,
 * within a few ms) is told with what it held when its watcher was set: those files were made
 * before anyone watched that folder, and nothing else would tell them until they changed again.
 */
import { mkdirSync, mkdtempSync, realpathSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, describe, expect, it } from 'vitest';
import type { ServerResponse } from 'node:http';
import { WorkspaceWatcher } from './workspace-watcher.js';

let root: string;
let watcher: WorkspaceWatcher | undefined;
afterEach(() => {
  watcher?.close();
  rmSync(root, { recursive: true, force: true });
});

/** A fake SSE response collecting the paths of `change` events. */
function client(): { res: ServerResponse; paths: Set<string> } {
  const paths = new Set<string>();
  const res = {
    writeHead: () => res,
    write: (chunk: string) => {
      const m = /^event: change\ndata: (.*)\n\n$/s.exec(chunk);
      if (m) for (const p of (JSON.parse(m[1]!) as { paths: string[] }).paths) paths.add(p);
      return true;
    },
    on: () => res,
    end: () => undefined,
  } as unknown as ServerResponse;
  return { res, paths };
}

describe('WorkspaceWatcher', () => {
  it('a folder made and filled at once is told with the files and folders it held when its watcher was set', async () => {
    root = realpathSync(mkdtempSync(join(tmpdir(), 'ide-watch-')));
    mkdirSync(join(root, 'proj'));
    watcher = new WorkspaceWatcher(root);
    const c = client();
    watcher.attach(c.res);
    // a run: logs/ and its first logs, then a sub-folder with a file, all before the first flush (60 ms)
    mkdirSync(join(root, 'proj/logs'));
    writeFileSync(join(root, 'proj/logs/ORD_1.csv'), 'x\n');
    writeFileSync(join(root, 'proj/logs/SUP_1.csv'), 'y\n');
    mkdirSync(join(root, 'proj/logs/previous'));
    writeFileSync(join(root, 'proj/logs/previous/OLD_1.csv'), 'z\n');
    for (let i = 0; i < 100 && !c.paths.has('proj/logs/previous/OLD_1.csv'); i++) await new Promise((r) => setTimeout(r, 20));
    expect([...c.paths].sort()).toEqual(expect.arrayContaining(['proj/logs', 'proj/logs/ORD_1.csv', 'proj/logs/SUP_1.csv', 'proj/logs/previous', 'proj/logs/previous/OLD_1.csv']));
    // the new folders are watched from then on
    c.paths.clear();
    writeFileSync(join(root, 'proj/logs/previous/NEW_2.csv'), 'w\n');
    for (let i = 0; i < 100 && !c.paths.has('proj/logs/previous/NEW_2.csv'); i++) await new Promise((r) => setTimeout(r, 20));
    expect(c.paths.has('proj/logs/previous/NEW_2.csv')).toBe(true);
  });
});
