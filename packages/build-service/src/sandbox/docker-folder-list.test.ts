import { spawn } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { PassThrough } from 'node:stream';
import { afterAll, describe, expect, test } from 'vitest';
import { folderListCommand, readFolderList } from './docker-folder-list.js';

const root = mkdtempSync(join(tmpdir(), 'folder-list-'));
afterAll(() => rmSync(root, { recursive: true, force: true }));

/** find (GNU, as in the sandbox image) run here with the arguments the holder runs it with. */
function listWithFind(dir: string, maxEntries: number) {
  const [cmd, ...args] = folderListCommand(dir);
  const child = spawn(cmd!, args, { stdio: ['ignore', 'pipe', 'ignore'] });
  return readFolderList(child.stdout, maxEntries, () => child.kill());
}

const of = (text: string) => {
  const s = new PassThrough();
  s.end(Buffer.from(text, 'latin1'));
  return s;
};

describe('a work folder listed by find before anything is read', () => {
  test('names, kinds and sizes, odd names whole, links and FIFOs as what they are', async () => {
    const logs = join(root, 'logs');
    mkdirSync(logs);
    writeFileSync(join(logs, 'A.csv'), 'abc');
    writeFileSync(join(logs, 'odd name\nwith a newline.csv'), 'x');
    symlinkSync('/etc/passwd', join(logs, 'X.csv'));
    spawn('mkfifo', [join(logs, 'F.csv')]);
    await new Promise((r) => setTimeout(r, 200));
    const found = await listWithFind(logs, 100);
    expect(found && 'entries' in found && [...found.entries].sort((a, b) => a.name.localeCompare(b.name))).toEqual([
      { name: 'A.csv', kind: 'file', size: 3 },
      { name: 'F.csv', kind: 'other', size: 0 },
      { name: 'odd name\nwith a newline.csv', kind: 'file', size: 1 },
      { name: 'X.csv', kind: 'symlink', size: 11 },
    ]);
    expect(found).toMatchObject({ more: false });
  });

  test('a link in place of the folder is not entered; a missing folder is none', async () => {
    symlinkSync('/etc', join(root, 'linked'));
    expect(await listWithFind(join(root, 'linked'), 100)).toEqual({ notDirectory: 'symlink' });
    expect(await listWithFind(join(root, 'missing'), 100)).toBeNull();
  });

  test('stops at the entry bound and says there were more', async () => {
    const many = join(root, 'many');
    mkdirSync(many);
    for (let i = 0; i < 50; i++) writeFileSync(join(many, `M${i}.csv`), '');
    const found = await listWithFind(many, 10);
    expect(found).toMatchObject({ more: true });
    expect(found && 'entries' in found && found.entries.length).toBe(10);
  });

  test("the runtime's logs come first: 1500 files a program left beside them do not push them out of the entries looked at", async () => {
    const logs = join(root, 'crowded');
    mkdirSync(logs);
    writeFileSync(join(logs, 'CTL_7-Dec-2026-03h00m00s.csv'), 'x\n');
    writeFileSync(join(logs, 'ORD_17-Dec-2026-23h59m59s.csv'), 'y\n');
    for (let i = 0; i < 1500; i++) writeFileSync(join(logs, `F_${i}.csv`), '');
    const found = await listWithFind(logs, 1024);
    expect(found).toMatchObject({ more: true });
    const names = found && 'entries' in found ? found.entries.map((e) => e.name) : [];
    expect(names).toHaveLength(1024);
    expect(names.slice(0, 2).sort()).toEqual(['CTL_7-Dec-2026-03h00m00s.csv', 'ORD_17-Dec-2026-23h59m59s.csv']);
  });

  test('output that is not find\'s ends the listing where it stops making sense, never a throw', async () => {
    expect(await readFolderList(of('d 4096 \0f 3 A.csv\0garbage\0f 1 B.csv\0'), 10, () => {})).toEqual({ entries: [{ name: 'A.csv', kind: 'file', size: 3 }], more: true });
    expect(await readFolderList(of('d 4096 \0f 3 a/b.csv\0'), 10, () => {})).toEqual({ entries: [], more: true });
    expect(await readFolderList(of(`d 4096 \0f 3 ${'y'.repeat(10_000)}`), 10, () => {})).toEqual({ entries: [], more: true });
    expect(await readFolderList(of(''), 10, () => {})).toBeNull();
  });
});
