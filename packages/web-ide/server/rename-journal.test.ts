/**
 * An IDE rename (POST /api/rename-entity with the `.contract` files the editor's rename changed) is
 * journaled as `contract rename` is (codegen rename-journal.ts): stopped half-way, after its
 * journal and the generated tree's carry-over and before the project's files were written (a
 * crash, simulated by rename-api.ts's step hook), the next Generate All finishes it, and the
 * project ends byte for byte as after the same rename run whole, the module's user code carried over
 * (not moved to orphans/). Real server, real codegen, copies of the tutorial with its user code.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { cpSync, existsSync, readFileSync, readdirSync } from 'node:fs';
import { createHash } from 'node:crypto';
import { join, relative } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { GenerateResponse, RenameEntityResponse } from './api-types.js';
import { FileLocks } from './file-locks.js';
import { GeneratedTreeLock } from './generated-tree-lock.js';
import { renameEntity, type RenamedFile } from './rename-api.js';
import { startTempIdeServer, type TempIdeServer } from './temp-ide-server.test-support.js';
import { WorkspacePaths } from './workspace-paths.js';

const TUTORIAL = join(fileURLToPath(new URL('../../..', import.meta.url)), 'examples/tutorial');

let server: TempIdeServer;
beforeAll(async () => {
  server = await startTempIdeServer('ide-rename-journal-', {
    prepare: (_base, ws) => {
      for (const p of ['whole', 'stopped']) cpSync(TUTORIAL, join(ws, p), { recursive: true, filter: (src) => !/\/logs$/.test(src) });
    },
  });
});
afterAll(() => server.close());

/** POST /api/generate (its answer a GenerateResponse) or /api/rename-entity (a RenameEntityResponse). */
async function post<Answer extends GenerateResponse | RenameEntityResponse>(path: string, body: unknown): Promise<{ status: number; body: Answer }> {
  const res = await fetch(`${server.ide.url}${path}`, { method: 'POST', headers: { 'content-type': 'application/json', 'x-contract-token': server.ide.token }, body: JSON.stringify(body) });
  return { status: res.status, body: (await res.json()) as Answer };
}

/** The `.contract` files of `project` that name MSC, as the editor's rename to MSK leaves them, on the version on disk. */
function renamedFiles(project: string): RenamedFile[] {
  const dir = join(server.ws, project);
  return readdirSync(dir).filter((f) => f.endsWith('.contract')).sort().flatMap((f) => {
    const bytes = readFileSync(join(dir, f));
    const after = bytes.toString('utf8').replace(/\bMSC\b/g, 'MSK');
    return after === bytes.toString('utf8') ? [] : [{ path: `${project}/${f}`, text: after, base: createHash('sha256').update(bytes).digest('hex') }];
  });
}

/** Every file of the project folder (relative path -> bytes as hex digest), the tree's lock file aside. */
function snapshot(dir: string): Map<string, string> {
  const out = new Map<string, string>();
  const walk = (d: string) => {
    for (const e of readdirSync(d, { withFileTypes: true })) {
      const p = join(d, e.name);
      if (e.isDirectory()) walk(p);
      else if (!/\.lock$/.test(e.name)) out.set(relative(dir, p), createHash('sha256').update(readFileSync(p)).digest('hex'));
    }
  };
  walk(dir);
  return out;
}

const body = (project: string) => ({ project, from: 'MSC', to: 'MSK', kind: 'module', files: renamedFiles(project) });

describe('an IDE rename stopped half-way is finished by the next Generate All', () => {
  it('stopped after its journal and the tree carry-over: Generate All writes the renamed files, the project as after the whole rename', async () => {
    const ws = server.ws;
    for (const p of ['whole', 'stopped']) expect((await post<GenerateResponse>('/api/generate', { project: p })).status).toBe(200);

    const wholeAsked = body('whole');
    expect(wholeAsked.files.length).toBeGreaterThan(1);
    const whole = await post<RenameEntityResponse>('/api/rename-entity', wholeAsked);
    expect(whole.status).toBe(200);
    expect(whole.body.written.map((w) => w.file)).toEqual(wholeAsked.files.map((f) => f.path));
    for (const f of wholeAsked.files) expect(readFileSync(join(ws, f.path), 'utf8')).toBe(f.text);
    expect(existsSync(join(ws, 'whole/src-gen/.contract-rename.json'))).toBe(false);
    expect((await post<GenerateResponse>('/api/generate', { project: 'whole' })).status).toBe(200);

    // the same rename, the server "killed" once the generated tree is carried over
    const asked = body('stopped');
    const crash = new Error('killed');
    await expect(renameEntity(new WorkspacePaths(ws), new GeneratedTreeLock(), new FileLocks(), asked, (at) => { if (at === 'tree carried over') throw crash; })).rejects.toThrow();
    expect(existsSync(join(ws, 'stopped/src-gen/.contract-rename.json'))).toBe(true);
    expect(existsSync(join(ws, 'stopped/src-gen/generated/architecture/modules/MSK_mod/module.c'))).toBe(true); // the tree renamed...
    for (const f of asked.files) expect(readFileSync(join(ws, f.path), 'utf8')).toMatch(/\bMSC\b/); // ...the model not

    const generated = await post<GenerateResponse>('/api/generate', { project: 'stopped' });
    expect(generated.status).toBe(200);
    expect(generated.body.warnings.map((w) => w.message)).toContainEqual(expect.stringMatching(/^finished the rename of module MSC -> MSK that was interrupted .*: \d+ file\(s\) written, 0 already renamed/));
    expect(existsSync(join(ws, 'stopped/src-gen/.contract-rename.json'))).toBe(false);

    const a = snapshot(join(ws, 'whole'));
    const b = snapshot(join(ws, 'stopped'));
    expect([...b.keys()].filter((k) => k.includes('orphans')), 'nothing orphaned').toEqual([...a.keys()].filter((k) => k.includes('orphans')));
    expect(b).toEqual(a);
  }, 120_000);
});
