/**
 * Generate All, the rename carry-over and the guard's manifest read on hostile project folders
 * (docs/codegen.md, "What generate refuses"): the real IDE server, real files and symlinks.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, readFileSync, readdirSync, writeFileSync, mkdirSync, symlinkSync, lstatSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { IdeServer } from './ide-server.js';
import { startTempIdeServer, type TempIdeServer } from './temp-ide-server.test-support.js';
import { isGeneratedFile } from './generated-files.js';

const TUTORIAL = join(fileURLToPath(new URL('../../..', import.meta.url)), 'examples/tutorial');

let base: string;
let ws: string;
let outside: string;
let victim: string;
let ide: IdeServer;
const VICTIM_TEXT = 'precious\n';

/** ws/<name> holding the tutorial's Cactal sources (no src-gen). */
function project(name: string): string {
  const dir = join(ws, name);
  mkdirSync(dir);
  for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) cpSync(join(TUTORIAL, f), join(dir, f));
  return dir;
}

async function post(route: string, body: unknown): Promise<{ status: number; body: Record<string, unknown> }> {
  const res = await fetch(`${ide.url}${route}`, { method: 'POST', headers: { 'content-type': 'application/json', 'x-contract-token': ide.token }, body: JSON.stringify(body) });
  return { status: res.status, body: (await res.json()) as Record<string, unknown> };
}

let server: TempIdeServer;
beforeAll(async () => {
  server = await startTempIdeServer('ide-hostile-', { prepare: (b, w) => {
    base = b;
    ws = w;
    outside = join(base, 'outside');
    mkdirSync(outside);
    mkdirSync(join(base, 'victim'));
    victim = join(base, 'victim', 'important.txt');
    writeFileSync(victim, VICTIM_TEXT);
  } });
  ({ base, ws, ide } = server);
});
afterAll(() => server.close());

describe('Generate All on a hostile project folder', () => {
  it('refuses a src-gen symlinked out of the workspace, writing nothing there', async () => {
    const p = project('p2');
    symlinkSync(outside, join(p, 'src-gen'));
    const r = await post('/api/generate', { project: 'p2' });
    expect(r.status).toBe(200);
    expect(r.body.created).toEqual([]);
    expect(r.body.errors).toEqual([{ file: '(output)', message: expect.stringMatching(/p2\/src-gen is a symbolic link \(-> .*outside\): refused/) }]);
    expect(readdirSync(outside)).toEqual([]);
  });

  it('refuses a folder inside src-gen symlinked elsewhere (src-gen/generated -> outside)', async () => {
    const p = project('p3');
    mkdirSync(join(p, 'src-gen'));
    symlinkSync(outside, join(p, 'src-gen', 'generated'));
    const r = await post('/api/generate', { project: 'p3' });
    expect(r.body.errors).toEqual([{ file: 'generated', message: expect.stringMatching(/^generated is a symbolic link .*; 52 file\(s\) not read, written or deleted/) }]);
    expect(readdirSync(outside)).toEqual([]);
  });

  it('drops manifest entries naming host files (never deleted), with a warning', async () => {
    const p = project('p4');
    expect((await post('/api/generate', { project: 'p4' })).body.errors).toEqual([]);
    const manifestFile = join(p, 'src-gen', '.contract-manifest.json');
    const manifest = JSON.parse(readFileSync(manifestFile, 'utf8')) as { files: Record<string, unknown> };
    const entry = '../'.repeat(16) + victim.slice(1);
    manifest.files[entry] = {};
    writeFileSync(manifestFile, JSON.stringify(manifest));
    const r = await post('/api/generate', { project: 'p4' });
    expect(r.body.removed).toEqual([]);
    expect(r.body.warnings).toEqual([{ file: '.contract-manifest.json', message: expect.stringContaining(`entry ${JSON.stringify(entry)} dropped`) }]);
    expect(readFileSync(victim, 'utf8')).toBe(VICTIM_TEXT);
  });
});

describe('rename carry-over and the guard on hostile src-gen folders', () => {
  it('refuses to carry a rename over in a symlinked src-gen, or one holding a link, changing nothing', async () => {
    const p = project('p5');
    mkdirSync(join(outside, 'MAA_mod'));
    symlinkSync(outside, join(p, 'src-gen'));
    const r = await post('/api/rename-entity', { project: 'p5', from: 'MAA', to: 'MAZ' });
    expect(r.status).toBe(409);
    expect(r.body.error).toMatch(/cannot carry MAA -> MAZ over: .*p5\/src-gen is a symbolic link/);
    expect(readdirSync(outside)).toEqual(['MAA_mod']);

    const q = project('p6');
    mkdirSync(join(q, 'src-gen', 'generated', 'MAA_mod'), { recursive: true });
    symlinkSync(outside, join(q, 'src-gen', 'generated', 'link'));
    const s = await post('/api/rename-entity', { project: 'p6', from: 'MAA', to: 'MAZ' });
    expect(s.status).toBe(409);
    expect(s.body.error).toMatch(/src-gen\/generated\/link is a symbolic link/);
    expect(lstatSync(join(q, 'src-gen', 'generated', 'MAA_mod')).isDirectory()).toBe(true);
    expect(readdirSync(outside)).toEqual(['MAA_mod']);
  });

  it('does not read a symlinked manifest to decide whether a file is generated', async () => {
    const p = project('p7');
    mkdirSync(join(p, 'src-gen', 'generated'), { recursive: true });
    const elsewhere = join(base, 'elsewhere.json');
    writeFileSync(elsewhere, JSON.stringify({ version: 1, files: { 'generated/x.c': {} } }));
    symlinkSync(elsewhere, join(p, 'src-gen', '.contract-manifest.json'));
    // through the link, the manifest would list x.c (generated); refused, x.c has no markers: not generated
    expect(await isGeneratedFile(ws, 'p7/src-gen/generated/x.c', 'int x;\n')).toBe(false);
  });
});

describe('a project folder swapped for a link while Generate All runs', () => {
  it('generates into the folder it opened, never through the link (0 files outside)', async () => {
    const p = project('p8');
    const elsewhere = join(base, 'elsewhere-project');
    mkdirSync(elsewhere);
    for (const f of readdirSync(p)) cpSync(join(p, f), join(elsewhere, f));
    symlinkSync(elsewhere, join(ws, 'p8_link'));
    // p8 and the link trade places as fast as a process can rename, for the whole test
    const { spawn } = await import('node:child_process');
    const swapper = spawn('python3', ['-c', [
      'import os, time', `os.chdir(${JSON.stringify(ws)})`, 'end = time.time() + 6',
      'while time.time() < end:',
      "    os.rename('p8', 'p8_tmp'); os.rename('p8_link', 'p8'); os.rename('p8', 'p8_link'); os.rename('p8_tmp', 'p8')",
    ].join('\n')], { stdio: 'ignore' });
    let exited = false;
    const done = new Promise<void>((r) => swapper.on('exit', () => { exited = true; r(); }));
    let generated = 0;
    while (!exited) {
      const r = await post('/api/generate', { project: 'p8' });
      if (r.status === 200 && Array.isArray(r.body.created) && (r.body.created.length || (r.body.unchanged as string[]).length)) generated++;
    }
    await done;
    expect(readdirSync(elsewhere).filter((n) => n === 'src-gen')).toEqual([]);
    expect(generated).toBeGreaterThan(0); // requests got through between swaps
    expect(lstatSync(join(ws, 'p8', 'src-gen')).isDirectory()).toBe(true);
  }, 30_000);
});

describe('a model too large to load', () => {
  it('Generate All and Simulate answer 413 naming the size and the limit, before parsing anything', async () => {
    const p = project('p9');
    // 1.1 MiB in one file (a comment: cheap to write, and never parsed)
    writeFileSync(join(p, 'huge.contract'), `// ${'x'.repeat(1100 * 1024)}\n`);
    const t0 = Date.now();
    const g = await post('/api/generate', { project: 'p9' });
    expect(g.status).toBe(413);
    expect(g.body.error).toMatch(/the project's \.contract files hold \d+ bytes, over the limit of 1048576 bytes/);
    expect(Date.now() - t0).toBeLessThan(5_000);
    expect(readdirSync(p)).not.toContain('src-gen');
    const s = await post('/api/simulate', { project: 'p9', scenario: 'start SUP.action()\n' });
    expect(s.status).toBe(413);
    expect(s.body.error).toMatch(/over the limit of 1048576 bytes/);
  });
});

describe('a terminal rename killed half-way (its journal in src-gen)', () => {
  it('Generate All finishes it before reading the model, says so in its warnings, and orphans nothing', async () => {
    const p = project('p10');
    expect((await post('/api/generate', { project: 'p10' })).status).toBe(200);
    const codegen = await import('@contract-studio/codegen');
    const file = join(p, 'src-gen/generated/architecture/modules/MSC_mod/module.c');
    writeFileSync(file, readFileSync(file, 'latin1').replace('/*PROTECTED REGION ID(protect_init_MSC) ENABLED START*/', '/*PROTECTED REGION ID(protect_init_MSC) ENABLED START*/\n    int ide_marker = 1; (void)ide_marker;'), 'latin1');
    // the rename's journal (each .contract file's text after MSC -> MSK), then its tree carry-over: killed there
    const files = readdirSync(p).filter((f) => f.endsWith('.contract')).flatMap((f) => {
      const text = readFileSync(join(p, f), 'utf8');
      const after = text.replace(/\bMSC\b/g, 'MSK');
      return after === text ? [] : [{ path: f, before: codegen.sha256(Buffer.from(text, 'utf8')), after }];
    });
    codegen.writeRenameJournal(join(p, 'src-gen'), { version: 1, kind: 'module', oldName: 'MSC', newName: 'MSK', generatedNames: true, identifiers: [], files });
    await codegen.renameInGeneratedTree(join(p, 'src-gen'), 'MSC', 'MSK');
    const r = await post('/api/generate', { project: 'p10' });
    expect(r.status).toBe(200);
    expect(r.body.errors, JSON.stringify(r.body.warnings)).toEqual([]);
    // one entry for the rename, naming the files it wrote (not one warning per file)
    const fromJournal = (r.body.warnings as Array<{ file: string; message: string }>).filter((w) => w.file === '.contract-rename.json');
    expect(fromJournal).toHaveLength(1);
    expect(fromJournal[0]!.message).toMatch(new RegExp(`^finished the rename of module MSC -> MSK that was interrupted \\(its journal src-gen/\\.contract-rename\\.json\\): ${files.length} file\\(s\\) written, 0 already renamed \\(p10/[^)]*\\.contract\\)$`));
    expect(r.body.orphaned).toEqual([]);
    expect(readFileSync(join(p, 'src-gen/generated/architecture/modules/MSK_mod/module.c'), 'latin1')).toContain('int ide_marker = 1;');
    expect(lstatSync(join(p, 'src-gen/.contract-rename.json'), { throwIfNoEntry: false })).toBeUndefined();
  });
});
