/**
 * Saves name the version they edit (If-Match): the real IDE server over HTTP on a temp workspace.
 * A save on a stale base is refused with the disk's text; concurrent saves of one file never
 * interleave (exactly one of N saves on the same base is written). docs/ide.md, "Saves, versions
 * and merges".
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { existsSync, mkdirSync, writeFileSync, readFileSync } from 'node:fs';
import { createHash } from 'node:crypto';
import { join } from 'node:path';
import type { IdeServer } from './ide-server.js';
import { startTempIdeServer, type TempIdeServer } from './temp-ide-server.test-support.js';

let ws: string;
let ide: IdeServer;
const sha = (t: string) => createHash('sha256').update(Buffer.from(t, 'utf8')).digest('hex');
const disk = (p: string) => readFileSync(join(ws, p), 'utf8');

let server: TempIdeServer;
beforeAll(async () => {
  server = await startTempIdeServer('ide-versions-');
  ({ ws, ide } = server);
});
afterAll(() => server.close());

const get = async (path: string) => {
  const res = await fetch(`${ide.url}/api/file?path=${encodeURIComponent(path)}`, { headers: { 'x-contract-token': ide.token } });
  return (await res.json()) as { content: string; version: string };
};
const put = async (path: string, text: string, baseVersion?: string) => {
  const headers: Record<string, string> = { 'x-contract-token': ide.token, 'content-type': 'text/plain; charset=utf-8' };
  if (baseVersion !== undefined) headers['if-match'] = `"${baseVersion}"`;
  const res = await fetch(`${ide.url}/api/file?path=${encodeURIComponent(path)}`, { method: 'PUT', body: text, headers });
  return { status: res.status, body: (await res.json()) as Record<string, unknown> };
};

describe('PUT /api/file with a base version', () => {
  it('GET gives the version of the bytes on disk; a save on that version is written and answers the new version', async () => {
    writeFileSync(join(ws, 'a.contract'), 'MSA;\nMSB;\n');
    const r = await get('a.contract');
    expect(r.version).toBe(sha('MSA;\nMSB;\n'));
    const w = await put('a.contract', 'MSA; // mine\nMSB;\n', r.version);
    expect(w.status).toBe(200);
    expect(w.body.version).toBe(sha('MSA; // mine\nMSB;\n'));
    expect(disk('a.contract')).toBe('MSA; // mine\nMSB;\n');
  });

  it('a save on a stale base is refused with 409, the disk text and its version; nothing is written', async () => {
    writeFileSync(join(ws, 'b.contract'), 'one\n');
    const { version: v0 } = await get('b.contract');
    writeFileSync(join(ws, 'b.contract'), 'one\ntwo (another program)\n');
    const w = await put('b.contract', 'one (this tab)\n', v0);
    expect(w.status).toBe(409);
    expect(w.body).toMatchObject({ stale: true, content: 'one\ntwo (another program)\n', version: sha('one\ntwo (another program)\n') });
    expect(disk('b.contract')).toBe('one\ntwo (another program)\n');
    // on the version it was given, the same client's merged text goes through
    expect((await put('b.contract', 'one (this tab)\ntwo (another program)\n', w.body.version as string)).status).toBe(200);
  });

  it('without If-Match the write is blind (programs); a malformed If-Match is a 400', async () => {
    writeFileSync(join(ws, 'c.txt'), 'x');
    expect((await put('c.txt', 'y')).status).toBe(200);
    expect(disk('c.txt')).toBe('y');
    const bad = await fetch(`${ide.url}/api/file?path=c.txt`, { method: 'PUT', body: 'z', headers: { 'x-contract-token': ide.token, 'if-match': '"not-a-version"' } });
    expect(bad.status).toBe(400);
    expect(disk('c.txt')).toBe('y');
  });

  it('a save whose file was deleted meanwhile recreates it (nothing on disk to lose); not a generated file whose module was renamed away (a stale copy outside the build)', async () => {
    const w = await put('gone.contract', 'kept\n', sha('before\n'));
    expect(w.status).toBe(200);
    expect(disk('gone.contract')).toBe('kept\n');
    mkdirSync(join(ws, 'src-gen', 'generated', 'architecture', 'modules'), { recursive: true });
    const renamed = await put('src-gen/generated/architecture/modules/MSC_mod/module.c', '/* typed during a rename */\n', sha('before\n'));
    expect(renamed.status).toBe(409);
    expect(renamed.body).toMatchObject({ gone: true });
    expect(String(renamed.body.error)).toMatch(/^src-gen\/generated\/architecture\/modules\/MSC_mod\/module\.c no longer exists \(its module was renamed or removed since this text was loaded\): not recreated/);
    expect(existsSync(join(ws, 'src-gen', 'generated', 'architecture', 'modules', 'MSC_mod'))).toBe(false);
  });

  it('concurrent saves of one file on the same base never interleave: exactly one is written, the others get 409 with its text', async () => {
    writeFileSync(join(ws, 'race.contract'), 'base\n');
    const { version } = await get('race.contract');
    const texts = Array.from({ length: 24 }, (_, i) => `base\nwriter ${i}\n`.repeat(200));
    const answers = await Promise.all(texts.map((t) => put('race.contract', t, version)));
    const ok = answers.filter((a) => a.status === 200);
    const refused = answers.filter((a) => a.status === 409);
    expect(ok).toHaveLength(1);
    expect(refused).toHaveLength(texts.length - 1);
    const winner = texts[answers.indexOf(ok[0]!)]!;
    expect(disk('race.contract')).toBe(winner);
    for (const r of refused) expect(r.body).toMatchObject({ stale: true, content: winner, version: sha(winner) });
  });

  it('chained saves, each on the version the previous one answered, all land in order', async () => {
    writeFileSync(join(ws, 'chain.contract'), '');
    let { version } = await get('chain.contract');
    let text = '';
    for (let i = 0; i < 20; i++) {
      text += `line ${i}\n`;
      const w = await put('chain.contract', text, version);
      expect(w.status).toBe(200);
      version = w.body.version as string;
    }
    expect(disk('chain.contract')).toBe(text);
  });
});
