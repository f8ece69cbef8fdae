import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { mkdirSync, writeFileSync, readFileSync, symlinkSync, existsSync, rmSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { join } from 'node:path';
import { startIdeServer, type IdeServer } from './ide-server.js';
import { startTempIdeServer, type TempIdeServer } from './temp-ide-server.test-support.js';

let base: string;
let ws: string;
let ide: IdeServer;

let server: TempIdeServer;
beforeAll(async () => {
  server = await startTempIdeServer('ide-api-', { prepare: (b, w) => {
    base = b;
    ws = w;
    mkdirSync(join(ws, 'sub'), { recursive: true });
    mkdirSync(join(base, 'outside'));
    writeFileSync(join(base, 'outside', 'secret.txt'), 'secret');
    writeFileSync(join(ws, 'a.contract'), 'datatype T {int x};');
    symlinkSync(join(base, 'outside'), join(ws, 'out-link'));
  } });
  ({ base, ws, ide } = server);
});
afterAll(() => server.close());

/**
 * fetch, tried again once when the connection it reused was closed by the server meanwhile (its
 * keep-alive timeout ran out while a slow step of the test, a loaded machine's mkdir of 200
 * folders, kept it idle: ECONNRESET before any byte of the answer).
 */
async function fetchOnce(url: string, init: RequestInit): Promise<Response> {
  try {
    return await fetch(url, init);
  } catch (e) {
    if ((e as { cause?: { code?: string } }).cause?.code !== 'ECONNRESET') throw e;
    return fetch(url, init);
  }
}

const call = async (method: string, path: string, body?: unknown, headers: Record<string, string> = {}) => {
  const res = await fetchOnce(ide.url + path, {
    method,
    headers: { 'x-contract-token': ide.token, ...(typeof body === 'object' ? { 'content-type': 'application/json' } : {}), ...headers },
    body: body === undefined ? undefined : typeof body === 'string' ? body : JSON.stringify(body),
  });
  return { status: res.status, body: (await res.json()) as Record<string, unknown> };
};

describe('file API over HTTP', () => {
  it('binds to 127.0.0.1 by default', () => {
    expect(ide.url).toMatch(/^http:\/\/127\.0\.0\.1:\d+$/);
  });

  it('the first snapshot leaves out a .contract too large for it without reading it, and keeps the others', async () => {
    // a hostile project's 400 MB file (sparse: no disk used) was read whole to be dropped, and every file after
    // it was then left out of the snapshot (its budget spent)
    const big = join(ws, 'huge.contract');
    execFileSync('truncate', ['-s', '400M', big]);
    writeFileSync(join(ws, 'z.contract'), 'datatype Z {int z};');
    try {
      const t0 = Date.now();
      const snap = await call('GET', '/api/snapshot');
      expect(snap.status).toBe(200);
      expect(Date.now() - t0).toBeLessThan(5000);
      const files = snap.body.files as Record<string, string>;
      expect(Object.keys(files)).not.toContain('huge.contract');
      expect(files['z.contract']).toBe('datatype Z {int z};');
      expect(files['a.contract']).toBe('datatype T {int x};');
    } finally {
      rmSync(big);
      rmSync(join(ws, 'z.contract'));
    }
  });

  it('past 50,000 entries: a folder\'s own files come before its sub-folders, and what the bound cut is marked truncated (a generated tree of 40,000 files took the root\'s own files, without a word)', async () => {
    // 50,100 generated files listed before the root's own, as readdir may give them
    execFileSync('python3', ['-c', `import os\nos.chdir(${JSON.stringify(ws)})\nos.makedirs('src-gen/a')\nos.makedirs('src-gen/b')\nfor i in range(50100):\n    open('src-gen/a/f%d.c' % i, 'w').close()\nopen('src-gen/b/g.c', 'w').close()`]);
    try {
      const tree = await call('GET', '/api/tree');
      expect(tree.status).toBe(200);
      type Entry = { name: string; path: string; type: string; children?: Entry[]; truncated?: boolean };
      const root = tree.body.entries as Entry[];
      // the root's own files are all there
      expect(root.filter((e) => e.type === 'file').map((e) => e.name)).toEqual(expect.arrayContaining(['a.contract']));
      const gen = root.find((e) => e.name === 'src-gen')!;
      const a = gen.children!.find((e) => e.name === 'a')!;
      expect(a.truncated).toBe(true);
      expect(a.children!.length).toBeGreaterThan(40_000);
      expect(a.children!.length).toBeLessThan(50_100);
      // a folder after the bound: listed, marked, no content
      expect(gen.children!.find((e) => e.name === 'b')).toMatchObject({ type: 'dir', truncated: true, children: [] });
      expect(gen.truncated).toBeUndefined();
    } finally {
      rmSync(join(ws, 'src-gen'), { recursive: true, force: true });
    }
  }, 60_000);

  it('lists a tree of 200 nested folders down to 64 levels, the deeper one marked truncated (one descriptor per level)', async () => {
    execFileSync('python3', ['-c', `import os\nos.chdir(${JSON.stringify(ws)})\nfor i in range(200):\n    os.mkdir('d'); os.chdir('d')\nopen('deep.contract', 'w').write('x')`]);
    try {
      const tree = await call('GET', '/api/tree');
      expect(tree.status).toBe(200);
      type Entry = { name: string; type: string; children?: Entry[]; truncated?: boolean };
      let level = (tree.body.entries as Entry[]).find((e) => e.name === 'd');
      let depth = 1;
      while (level?.children?.length) {
        level = level.children.find((e) => e.name === 'd');
        depth++;
      }
      expect(depth).toBe(64);
      expect(level).toMatchObject({ type: 'dir', truncated: true, children: [] });
      expect((await call('GET', '/api/snapshot')).status).toBe(200);
    } finally {
      rmSync(join(ws, 'd'), { recursive: true, force: true });
    }
  });

  it('lists, reads and atomically writes files', async () => {
    const tree = await call('GET', '/api/tree');
    expect((tree.body.entries as Array<{ path: string }>).map((e) => e.path)).toEqual(['sub', 'a.contract']); // symlinks are not listed
    expect((await call('GET', '/api/file?path=a.contract')).body.content).toBe('datatype T {int x};');
    const put = await call('PUT', '/api/file?path=sub/new.contract', 'datatype U {int y};');
    expect(put.status).toBe(200);
    expect(readFileSync(join(ws, 'sub', 'new.contract'), 'utf8')).toBe('datatype U {int y};');
  });

  it('writes no file the editor could not open again (8 MiB), whether saved or created; the file on disk stays as it was', async () => {
    const big = 'x'.repeat(8 * 1024 * 1024 + 1);
    const put = await call('PUT', '/api/file?path=a.contract', big);
    expect(put.status).toBe(413);
    expect(put.body.error).toMatch(/^file larger than 8 MiB: not saved/);
    expect(readFileSync(join(ws, 'a.contract'), 'utf8')).toBe('datatype T {int x};');
    const created = await call('POST', '/api/create', { path: 'sub/big.contract', type: 'file', content: big });
    expect(created.status).toBe(413);
    expect(existsSync(join(ws, 'sub', 'big.contract'))).toBe(false);
    // 8 MiB exactly is written and read back
    const edge = 'y'.repeat(8 * 1024 * 1024);
    expect((await call('PUT', '/api/file?path=sub/edge.txt', edge)).status).toBe(200);
    expect((await call('GET', '/api/file?path=sub/edge.txt')).body.content).toBe(edge);
    expect((await call('DELETE', '/api/file?path=sub/edge.txt')).status).toBe(200);
  });

  it('a file whose bytes are not UTF-8 (Latin-1) is read with its first such line, and no text is written over it, blind or on its version; its own bytes back are', async () => {
    const latin1 = Buffer.from('/* ok */\nint x; /* caf\xe9 \xff */\nint y;\n', 'latin1');
    writeFileSync(join(ws, 'sub', 'latin1.c'), latin1);
    const read = await call('GET', '/api/file?path=sub/latin1.c');
    expect(read.body.undecodableLine).toBe(2);
    expect(read.body.content).toContain('caf\uFFFD');
    // what the editor would save: its text of the file, one line added
    const edited = `${read.body.content as string}int z;\n`;
    const blindAndOnItsVersion: Array<Record<string, string>> = [{}, { 'if-match': `"${read.body.version as string}"` }];
    for (const headers of blindAndOnItsVersion) {
      const put = await call('PUT', '/api/file?path=sub/latin1.c', edited, headers);
      expect(put.status).toBe(409);
      expect(put.body.error).toMatch(/^sub\/latin1\.c holds bytes that are not UTF-8 \(line 2: Latin-1 or binary\).*nothing was written/);
      expect(put.body.undecodableLine).toBe(2);
      expect(readFileSync(join(ws, 'sub', 'latin1.c')).equals(latin1)).toBe(true);
    }
    // a UTF-8 file reads without the mark
    expect((await call('GET', '/api/file?path=a.contract')).body.undecodableLine).toBeUndefined();
    rmSync(join(ws, 'sub', 'latin1.c'));
  });

  it('refuses to make a name with a bidirectional override or a control character (it shows as another name), or a part over 255 bytes, saying why', async () => {
    const spoof = await call('POST', '/api/create', { path: 'x\u202Etnoc.c', type: 'file' });
    expect(spoof.status).toBe(400);
    expect(spoof.body.error).toBe('a name with the character U+202E is refused: a control or bidirectional character shows a name as another one');
    expect((await call('POST', '/api/create', { path: 'tab\there.contract', type: 'file' })).status).toBe(400);
    const long = await call('POST', '/api/create', { path: `${'n'.repeat(300)}.contract`, type: 'file' });
    expect(long.status, JSON.stringify(long.body)).toBe(400);
    expect(long.body.error).toMatch(/^a name of more than 255 bytes is refused/);
    const renamed = await call('POST', '/api/rename', { from: 'a.contract', to: 'a\u2066.contract' });
    expect(renamed.status, JSON.stringify(renamed.body)).toBe(400);
    expect(existsSync(join(ws, 'a.contract'))).toBe(true);
  });

  it('creates, renames and deletes, with 409 on conflicts', async () => {
    expect((await call('POST', '/api/create', { path: 'sub/b.contract', type: 'file' })).status).toBe(201);
    expect((await call('POST', '/api/create', { path: 'sub/b.contract', type: 'file' })).status).toBe(409);
    expect((await call('POST', '/api/create', { path: 'dir2', type: 'dir' })).status).toBe(201);
    expect((await call('POST', '/api/rename', { from: 'sub/b.contract', to: 'a.contract' })).status).toBe(409);
    expect((await call('POST', '/api/rename', { from: 'sub/b.contract', to: 'dir2/c.contract' })).status).toBe(200);
    expect(existsSync(join(ws, 'dir2', 'c.contract'))).toBe(true);
    expect((await call('POST', '/api/rename', { from: 'dir2', to: 'dir2/inner' })).status).toBe(400);
    expect((await call('DELETE', '/api/file?path=dir2')).status).toBe(200);
    expect(existsSync(join(ws, 'dir2'))).toBe(false);
    expect((await call('DELETE', '/api/file?path=dir2')).status).toBe(404);
  });

  it('refuses paths outside the workspace with clear 4xx errors', async () => {
    const dotdot = await call('GET', '/api/file?path=../outside/secret.txt');
    expect(dotdot.status).toBe(403);
    expect(dotdot.body.error).toMatch(/'\.\.'/);
    expect((await call('GET', `/api/file?path=${encodeURIComponent(join(base, 'outside', 'secret.txt'))}`)).status).toBe(403);
    const link = await call('GET', '/api/file?path=out-link/secret.txt');
    expect(link.status).toBe(403);
    expect(link.body.error).toMatch(/leaves the workspace/);
    expect((await call('PUT', '/api/file?path=out-link/evil.txt', 'x')).status).toBe(403);
    expect(existsSync(join(base, 'outside', 'evil.txt'))).toBe(false);
    expect((await call('POST', '/api/rename', { from: 'a.contract', to: '../a.contract' })).status).toBe(403);
    // a link that stays inside is not followed either (the tree does not list links)
    symlinkSync(join(ws, 'sub'), join(ws, 'in-link'));
    const inside = await call('PUT', '/api/file?path=in-link/x.contract', 'x');
    expect(inside.status).toBe(403);
    expect(inside.body.error).toMatch(/symbolic links are not followed: in-link\/x\.contract/);
    expect(existsSync(join(ws, 'sub', 'x.contract'))).toBe(false);
    expect((await call('GET', '/api/file?path=in-link/new.contract')).status).toBe(403);
    expect((await call('DELETE', '/api/file?path=')).status).toBe(403);
    expect((await call('POST', '/api/create', '{', { 'content-type': 'application/json' })).status).toBe(400);
  });

  it('answers at once for a FIFO in the workspace (400 on read, 409 on write) and leaves it in place', async () => {
    // a hostile folder (an unpacked archive) can hold a FIFO under any name: opening it to read used
    // to wait for a writer for ever, holding one of the server's file threads (four of them: four
    // such requests stopped every file operation of the IDE)
    execFileSync('mkfifo', [join(ws, 'pipe.contract')]);
    try {
      const reads = await Promise.all([1, 2, 3, 4, 5].map(() => call('GET', '/api/file?path=pipe.contract')));
      for (const r of reads) {
        expect(r.status).toBe(400);
        expect(r.body.error).toMatch(/not a regular file/);
      }
      expect((await call('GET', '/api/file?path=a.contract')).status).toBe(200); // the server's file threads are free
      const put = await call('PUT', '/api/file?path=pipe.contract', 'datatype V {int z};');
      expect(put.status).toBe(409);
      expect(put.body.error).toMatch(/not a regular file/);
      expect(execFileSync('stat', ['-c', '%F', join(ws, 'pipe.contract')], { encoding: 'utf8' }).trim()).toBe('fifo');
    } finally {
      rmSync(join(ws, 'pipe.contract'));
    }
  }, 20_000);

  it('refuses DNS-rebinding hosts and cross-site writes', async () => {
    const { request } = await import('node:http');
    const raw = (headers: Record<string, string>, method = 'GET', path = '/api/tree', body = '') =>
      new Promise<number>((resolve, reject) => {
        const r = request(ide.url + path, { method, headers: { 'x-contract-token': ide.token, ...headers } }, (res) => {
          res.resume();
          resolve(res.statusCode ?? 0);
        });
        r.on('error', reject);
        r.end(body);
      });
    expect(await raw({ host: 'evil.example:80' })).toBe(403);
    expect(await raw({ host: `localhost:${new URL(ide.url).port}` })).toBe(200);
    const create = JSON.stringify({ path: 'pwned.contract', type: 'file' });
    expect(await raw({ origin: 'http://evil.example', 'content-type': 'application/json' }, 'POST', '/api/create', create)).toBe(403);
    expect(await raw({ 'content-type': 'text/plain' }, 'POST', '/api/create', create)).toBe(415);
    expect(existsSync(join(ws, 'pwned.contract'))).toBe(false);
    expect(await raw({ origin: ide.url, 'content-type': 'application/json' }, 'POST', '/api/create', create)).toBe(201);
  });

  it('reports a port in use (EADDRINUSE) instead of hanging', async () => {
    const port = Number(new URL(ide.url).port);
    await expect(startIdeServer({ workspace: ws, port, buildService: false })).rejects.toMatchObject({ code: 'EADDRINUSE' });
  });

  it('answers unknown routes and missing front end builds with clear messages', async () => {
    expect((await call('GET', '/api/nope')).status).toBe(404);
    const page = await fetch(ide.url + '/', { headers: { 'x-contract-token': ide.token } });
    expect(page.status).toBe(500);
    expect(await page.text()).toMatch(/npm run build/);
  });
});

describe('the front end files', () => {
  it('serve the built files; an unknown file is 404 (never the page without a session), a malformed escape 400', async () => {
    const dist = join(base, 'dist-static');
    mkdirSync(join(dist, 'assets'), { recursive: true });
    writeFileSync(join(dist, 'index.html'), '<!doctype html><title>IDE</title>');
    writeFileSync(join(dist, 'assets', 'app.js'), 'console.log(1);');
    const server = await startIdeServer({ workspace: ws, port: 0, buildService: false, distDir: dist });
    try {
      const get = async (path: string, headers: Record<string, string> = {}) => {
        const r = await fetch(server.url + path, { headers });
        return { status: r.status, text: await r.text() };
      };
      expect(await get('/assets/app.js')).toEqual({ status: 200, text: 'console.log(1);' });
      expect((await get('/missing.js')).status).toBe(404);
      expect((await get('/deep/path/x.css')).text).not.toContain('<title>IDE</title>');
      expect((await get('/%E0%A4%A.js')).status).toBe(400);
      expect((await get('/some/route')).status).toBe(401);
      expect(await get('/some/route', { 'x-contract-token': server.token })).toEqual({ status: 200, text: '<!doctype html><title>IDE</title>' });
    } finally {
      await server.close();
    }
  });
});
