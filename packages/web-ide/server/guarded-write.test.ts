/**
 * The guard of generated files over HTTP: the real IDE server on a temp copy of examples/tutorial
 * (with its committed src-gen/ and the generator's manifest), real Generate All, real files.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, readFileSync, writeFileSync, mkdirSync, symlinkSync, existsSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { IdeServer } from './ide-server.js';
import { startTempIdeServer, type TempIdeServer } from './temp-ide-server.test-support.js';

const TUTORIAL = join(fileURLToPath(new URL('../../..', import.meta.url)), 'examples/tutorial');
const MAA = 'src-gen/generated/architecture/modules/MAA_mod/module.c';
const ORD = 'src-gen/generated/architecture/modules/ORD_mod/module.c';
const EXEC = 'ID(protect_exec_MAA) ENABLED START*/';

let base: string;
let ws: string;
let ide: IdeServer;
const disk = (p: string) => readFileSync(join(ws, p), 'utf8');
const put = async (path: string, text: string) => {
  const res = await fetch(`${ide.url}/api/file?path=${encodeURIComponent(path)}`, { method: 'PUT', body: text, headers: { 'x-contract-token': ide.token } });
  return { status: res.status, body: (await res.json()) as Record<string, unknown> };
};

let server: TempIdeServer;
beforeAll(async () => {
  server = await startTempIdeServer('ide-guard-', { workspace: 'tutorial', prepare: (b, w) => {
    base = b;
    ws = w;
    cpSync(TUTORIAL, ws, { recursive: true, filter: (src) => !/[\/]logs$/.test(src) });
    mkdirSync(join(base, 'outside'));
  } });
  ({ base, ws, ide } = server);
});
afterAll(() => server.close());

describe('PUT /api/file on generated files', () => {
  it('writes a save that only changed region content, as given', async () => {
    const text = disk(MAA).replace(EXEC, `${EXEC}\n    /* saved from a tab */`);
    const r = await put(MAA, text);
    expect(r.status).toBe(200);
    expect(r.body.merged).toBeUndefined();
    expect(disk(MAA)).toBe(text);
  });

  it('after Generate All changed the skeleton, a stale save keeps the new skeleton and its regions', async () => {
    const stale = disk(MAA).replace(EXEC, `${EXEC}\n    /* stale tab: é kept */`);
    writeFileSync(join(ws, 'amodule1.contract'), readFileSync(join(ws, 'amodule1.contract'), 'utf8').replace(
      'out :2 string connection_status;', 'out :2 string connection_status;\n        out :3 string added_status;'));
    const gen = await fetch(`${ide.url}/api/generate`, { method: 'POST', headers: { 'content-type': 'application/json', 'x-contract-token': ide.token }, body: '{"project":""}' });
    expect(gen.status).toBe(200);
    expect(((await gen.json()) as { updated: string[] }).updated).toContain('generated/architecture/modules/MAA_mod/module.c');
    const regenerated = disk(MAA);
    expect(regenerated).toContain('added_status');
    expect(regenerated).not.toContain('stale tab');

    const r = await put(MAA, stale);
    expect(r.status).toBe(200);
    expect(r.body).toMatchObject({ path: MAA, merged: true, reason: expect.stringMatching(/changed on disk/) });
    const now = disk(MAA);
    expect(r.body.content).toBe(now);
    expect(now).toBe(regenerated.replace(EXEC, `${EXEC}\n    /* stale tab: é kept */`));
    expect(now).toContain('/* saved from a tab */'); // the region's earlier content, kept by Generate All and by the stale tab
  });

  it('refuses a save holding a region the file no longer has (409, region and line named), writes nothing', async () => {
    const before = disk(MAA);
    const stale = before.replace(/(\/\*PROTECTED REGION ID\(protect_exec_MAA\) ENABLED START\*\/)/, '/*PROTECTED REGION ID(protect_gone_port_MAA) ENABLED START*/mine();/*PROTECTED REGION END*/\n$1');
    const line = stale.split('\n').findIndex((l) => l.includes('protect_gone_port_MAA')) + 1;
    const r = await put(MAA, stale);
    expect(r.status).toBe(409);
    expect(r.body).toMatchObject({ region: 'protect_gone_port_MAA', line, error: expect.stringMatching(/'protect_gone_port_MAA' no longer exists/) });
    expect(disk(MAA)).toBe(before);
  });

  it('refuses a malformed save with its line, writes nothing', async () => {
    const before = disk(MAA);
    const last = 'protect_internal_functions_impl_MAA';
    const broken = before.replace(new RegExp(`(ID\\(${last}\\) ENABLED START\\*\\/[\\s\\S]*?)\\/\\*PROTECTED REGION END\\*\\/`), '$1');
    expect(broken).not.toBe(before);
    const r = await put(MAA, broken);
    expect(r.status).toBe(409);
    expect(r.body.error).toMatch(new RegExp(`module\\.c:\\d+: protected region '${last}' START without END`));
    expect(r.body.line).toBe(before.split('\n').findIndex((l) => l.includes(last)) + 1);
    expect(disk(MAA)).toBe(before);
  });

  it('refuses changes to generated-whole files (ORD module.c, Makefiles), accepts an unchanged save', async () => {
    const ord = disk(ORD);
    const r = await put(ORD, ord.replace('\n', '\n/* hand edit */\n'));
    expect(r.status).toBe(409);
    expect(r.body.error).toMatch(/generated whole: edit the \.contract model instead/);
    expect(disk(ORD)).toBe(ord);
    expect((await put(ORD, ord)).status).toBe(200);
    const mk = 'src-gen/generated/architecture/Makefile';
    expect((await put(mk, `${disk(mk)}\n# mine\n`)).status).toBe(409);
  });

  it('writes files the generator does not own as given: run logs, new files in the tree, models', async () => {
    for (const p of ['src-gen/generated/architecture/logs/MAA_1.csv', 'src-gen/generated/architecture/notes.txt', 'amodule2.contract']) {
      const r = await put(p, 'free text, no region\n');
      expect([p, r.status, r.body.merged]).toEqual([p, 200, undefined]);
      expect(disk(p)).toBe('free text, no region\n');
    }
  });

  it('keeps the path checks: .. and symlinks out of the workspace are refused before any guard', async () => {
    expect((await put('src-gen/generated/../../../outside/x.c', 'x')).status).toBe(403);
    symlinkSync(join(base, 'outside'), join(ws, 'src-gen/generated/architecture/out-link'));
    const r = await put('src-gen/generated/architecture/out-link/module.c', 'x');
    expect(r.status).toBe(403);
    expect(existsSync(join(base, 'outside', 'module.c'))).toBe(false);
  });
});
