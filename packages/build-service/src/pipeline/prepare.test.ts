/**
 * The host-side prepare step on a hostile inline project (POST /api/jobs with files): the manifest
 * of src-gen names host files. Generation runs on the host in stage/ (docs/codegen.md, "What
 * generate refuses"), so the entries must be dropped, never acted on. Real language + codegen.
 */
import { chmodSync, copyFileSync, cpSync, existsSync, mkdirSync, mkdtempSync, readdirSync, readFileSync, renameSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import { prepareWorkspace } from './prepare.js';
import type { Workspace } from './workspaces.js';

const TUTORIAL = fileURLToPath(new URL('../../../../examples/tutorial', import.meta.url));

let base: string;
let victimDir: string;
let victim: string;
const VICTIM_TEXT = 'x\n/*PROTECTED REGION ID(stolen) ENABLED START*/host_secret/*PROTECTED REGION END*/\n';

beforeAll(() => {
  base = mkdtempSync(join(tmpdir(), 'bs-prepare-hostile-'));
  victimDir = join(base, 'victim');
  mkdirSync(victimDir);
  victim = join(victimDir, 'important.txt');
  writeFileSync(victim, VICTIM_TEXT);
});
afterAll(() => rmSync(base, { recursive: true, force: true }));

function workspace(): Workspace {
  const root = mkdtempSync(join(base, 'ws-'));
  mkdirSync(join(root, 'stage'));
  mkdirSync(join(root, 'work'));
  return {
    root,
    stageDir: join(root, 'stage'),
    workDir: join(root, 'work'),
    owner: { uid: process.getuid!(), gid: process.getgid!() },
    reused: false,
    acceptedOutputs: null,
    reset: async () => {},
    release: async () => {},
  };
}

describe('prepareWorkspace with an inline manifest naming host files', () => {
  it('drops the entries with a warning; the host file and its folder stay', async () => {
    const files: Record<string, string> = {};
    for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) files[f] = readFileSync(join(TUTORIAL, f), 'utf8');
    const entries = ['../'.repeat(24) + victim.slice(1), victim, 'generated/../../../../../victim/important.txt'];
    files['src-gen/.contract-manifest.json'] = JSON.stringify({ version: 1, files: Object.fromEntries(entries.map((e) => [e, {}])) });
    const log: string[] = [];
    const out = await prepareWorkspace(workspace(), { files }, 'cactal', { ...DEFAULT_LIMITS }, (l: string) => log.push(l));
    expect(out.ok, log.join('\n')).toBe(true);
    expect(readFileSync(victim, 'utf8')).toBe(VICTIM_TEXT);
    for (const e of entries) {
      expect(out.problems).toContainEqual(expect.objectContaining({
        file: '.contract-manifest.json',
        severity: 'warning',
        message: expect.stringContaining(`entry ${JSON.stringify(e)} dropped (`),
      }));
    }
    expect(out.problems.filter((p) => p.severity === 'error')).toEqual([]);
  }, 120_000);
});

describe('prepareWorkspace on a workspace prepared before', () => {
  const tutorial = (): Record<string, string> => {
    const files: Record<string, string> = {};
    for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) files[f] = readFileSync(join(TUTORIAL, f), 'utf8');
    return files;
  };
  it('skips generation for the same inputs and generator, and generates again when the generator changed (an upgrade)', async () => {
    const ws = workspace();
    const run = async () => {
      const log: string[] = [];
      const out = await prepareWorkspace(ws, { files: tutorial() }, 'cactal', { ...DEFAULT_LIMITS }, (l: string) => log.push(l));
      expect(out.ok, log.join('\n')).toBe(true);
      return log;
    };
    expect((await run()).some((l) => l.startsWith('generated src-gen/'))).toBe(true);
    expect(await run()).toContain('project unchanged since the last build: generation skipped');
    // the stamp an older version wrote: the inputs' digest alone, no generator
    const stampFile = join(ws.stageDir, 'inputs.sha256');
    const stamp = readFileSync(stampFile, 'utf8');
    expect(stamp).toMatch(/^[0-9a-f]{64} generator=[0-9a-f]{64}$/);
    writeFileSync(stampFile, stamp.split(' ')[0]!);
    const again = await run();
    expect(again).not.toContain('project unchanged since the last build: generation skipped');
    expect(again.some((l) => l.startsWith('generated src-gen/'))).toBe(true);
  }, 60_000);
});

describe('prepareWorkspace on a project folder: what of it is read', () => {
  const MSC_C = 'src-gen/generated/architecture/modules/MSC_mod/module.c';
  const project = (): string => {
    const dir = mkdtempSync(join(base, 'project-'));
    cpSync(TUTORIAL, dir, { recursive: true });
    // the user's code, in a protected region of MSC
    const text = readFileSync(join(dir, MSC_C), 'utf8');
    const id = '/*PROTECTED REGION ID(protect_init_MSC) ENABLED START*/';
    writeFileSync(join(dir, MSC_C), text.replace(id, `${id}\n    /* the user's marker */`));
    return dir;
  };
  const prepare = async (dir: string) => {
    const ws = workspace();
    const log: string[] = [];
    const out = await prepareWorkspace(ws, { dir }, 'cactal', { ...DEFAULT_LIMITS }, (l: string) => log.push(l));
    expect(out.ok, log.join('\n')).toBe(true);
    return ws;
  };

  it('reads a source with an executable bit (a FAT or WSL mount, an unzip) and leaves out only the programs a local build made', async () => {
    const dir = project();
    chmodSync(join(dir, MSC_C), 0o755);
    mkdirSync(join(dir, 'src-gen/generated/architecture/bin'), { recursive: true });
    copyFileSync(process.execPath, join(dir, 'src-gen/generated/architecture/bin/MSC')); // an ELF program, as make leaves it
    const ws = await prepare(dir);
    expect(readFileSync(join(ws.workDir, MSC_C), 'utf8')).toContain("the user's marker");
    expect(existsSync(join(ws.workDir, 'src-gen/generated/architecture/bin/MSC'))).toBe(false);
  }, 120_000);

  it('refuses, naming it, a source that is a link (the file, the tree, a .contract), never building without it; a link elsewhere is no source', async () => {
    const cases: Array<[string, (dir: string) => void]> = [
      [`${MSC_C} (a symbolic link)`, (dir) => {
        renameSync(join(dir, MSC_C), join(dir, 'elsewhere.c'));
        symlinkSync(join(dir, 'elsewhere.c'), join(dir, MSC_C));
      }],
      ['src-gen (a symbolic link)', (dir) => {
        renameSync(join(dir, 'src-gen'), join(dir, 'tree'));
        symlinkSync(join(dir, 'tree'), join(dir, 'src-gen'));
      }],
      ['smodule3.contract (a symbolic link)', (dir) => {
        renameSync(join(dir, 'smodule3.contract'), join(dir, 'keep.txt'));
        symlinkSync(join(dir, 'keep.txt'), join(dir, 'smodule3.contract'));
      }],
    ];
    for (const [named, make] of cases) {
      const dir = project();
      make(dir);
      const err = await prepareWorkspace(workspace(), { dir }, 'cactal', { ...DEFAULT_LIMITS }, () => {}).then(() => null, (e: Error) => e);
      expect(err?.message, named).toMatch(new RegExp(`^${named.replace(/[.()]/g, '\\$&')}: the build service never reads a project's source through a link .*nothing was built$`));
    }
    const dir = project();
    symlinkSync('/etc', join(dir, 'notes'));
    const ws = await prepare(dir);
    expect(readFileSync(join(ws.workDir, MSC_C), 'utf8')).toContain("the user's marker");
  }, 120_000);

  it('refuses, naming it, a source larger than the file bound (a 9 MiB .contract was left out and the build said ok); an ELF program of any size in src-gen/ is still left out', async () => {
    const dir = project();
    writeFileSync(join(dir, 'extra.contract'), `// ${'x'.repeat(9 * 1024 * 1024)}\n`);
    const err = await prepareWorkspace(workspace(), { dir }, 'cactal', { ...DEFAULT_LIMITS }, () => {}).then(() => null, (e: Error) => e);
    expect(err?.message).toBe('extra.contract: file larger than 8388608 bytes (a project\'s file is read up to that size, never left out: the build would go on without it); nothing was built');
    const elf = project();
    rmSync(join(elf, 'extra.contract'), { force: true });
    writeFileSync(join(elf, 'src-gen', 'generated', 'big-program'), Buffer.concat([Buffer.from([0x7f, 0x45, 0x4c, 0x46]), Buffer.alloc(9 * 1024 * 1024)]));
    const ws = await prepare(elf);
    expect(existsSync(join(ws.workDir, 'src-gen', 'generated', 'big-program'))).toBe(false);
  }, 120_000);

  it('refuses, naming them, a GNUmakefile or makefile in the generated tree (make would read it instead of the generated Makefile: PWNED, "ok")', async () => {
    const arch = 'src-gen/generated/architecture';
    const dir = project();
    writeFileSync(join(dir, arch, 'GNUmakefile'), 'all: ; echo PWNED\nrun: ; echo PWNED\n');
    writeFileSync(join(dir, arch, 'modules/MSC_mod/makefile'), 'all: ; echo PWNED\n');
    const refusal = (source: Parameters<typeof prepareWorkspace>[1]) => prepareWorkspace(workspace(), source, 'cactal', { ...DEFAULT_LIMITS }, () => {}).then(() => null, (e: Error) => e.message);
    const said = (named: string) => `${named}: a makefile in the generated tree that is not the generated one (GNU make would read it instead of the generated Makefile, and its recipes would be the build); a Cactal build runs only the generated Makefiles: remove it, or rename it (the generated Makefiles never read it); nothing was built`;
    expect(await refusal({ dir })).toBe(said(`${arch}/GNUmakefile, ${arch}/modules/MSC_mod/makefile`));
    const files: Record<string, string> = {};
    for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) files[f] = readFileSync(join(TUTORIAL, f), 'utf8');
    expect(await refusal({ files: { ...files, [`${arch}/tools/GNUmakefile`]: 'all: ; echo PWNED\n' } })).toBe(said(`${arch}/tools/GNUmakefile`));
    // a makefile of the user's outside the generated tree, or a file make never reads by itself (*.mk), is no build
    rmSync(join(dir, arch, 'GNUmakefile'));
    rmSync(join(dir, arch, 'modules/MSC_mod/makefile'));
    writeFileSync(join(dir, 'GNUmakefile'), 'all: ; echo mine\n');
    writeFileSync(join(dir, arch, 'extra.mk'), 'all: ; echo PWNED\n');
    // nor one in src-gen/orphans/ (user code kept from a removed module: no make runs there)
    mkdirSync(join(dir, 'src-gen/orphans'), { recursive: true });
    writeFileSync(join(dir, 'src-gen/orphans/makefile'), 'all: ; echo old\n');
    const ws = await prepare(dir);
    expect(readFileSync(join(ws.workDir, MSC_C), 'utf8')).toContain("the user's marker");
  }, 120_000);

  it('refuses a link named GNUmakefile or makefile in the generated tree as a foreign makefile (remove it), not as a link to copy in, which would only meet that refusal next', async () => {
    const arch = 'src-gen/generated/architecture';
    const dir = project();
    writeFileSync(join(dir, 'mine.mk'), 'all: ; echo PWNED\n');
    symlinkSync(join(dir, 'mine.mk'), join(dir, arch, 'GNUmakefile'));
    writeFileSync(join(dir, arch, 'tools/makefile'), 'all: ; echo PWNED\n');
    const err = await prepareWorkspace(workspace(), { dir }, 'cactal', { ...DEFAULT_LIMITS }, () => {}).then(() => null, (e: Error) => e);
    expect(err?.message).toBe(`${arch}/GNUmakefile, ${arch}/tools/makefile: a makefile in the generated tree that is not the generated one (GNU make would read it instead of the generated Makefile, and its recipes would be the build); a Cactal build runs only the generated Makefiles: remove it, or rename it (the generated Makefiles never read it); nothing was built`);
    // a link of another name is still refused as a link
    rmSync(join(dir, arch, 'GNUmakefile'));
    rmSync(join(dir, arch, 'tools/makefile'));
    symlinkSync(join(dir, 'mine.mk'), join(dir, arch, 'extra.mk'));
    const link = await prepareWorkspace(workspace(), { dir }, 'cactal', { ...DEFAULT_LIMITS }, () => {}).then(() => null, (e: Error) => e);
    expect(link?.message).toMatch(/^src-gen\/generated\/architecture\/extra\.mk \(a symbolic link\): the build service never reads a project's source through a link /);
  }, 120_000);

  it("refuses code a regeneration would move to orphans/ (a private copy's orphan reaches no one: the build ran without it and said ok), naming region, file and line; carries a rename git merged over with a warning", async () => {
    const MSC = 'src-gen/generated/architecture/modules/MSC_mod/module.c';
    const problemsOf = async (dir: string) => {
      const ws = workspace();
      const out = await prepareWorkspace(ws, { dir }, 'cactal', { ...DEFAULT_LIMITS }, () => {});
      return { ok: out.ok, problems: out.problems.map((p) => `${p.file}:${p.line}: ${p.severity}: ${p.message}`), ws };
    };
    // protect_init_MSC holding the user's code, its ENABLED lost (MSD's ID, still generated, would be the same)
    const disabled = project();
    writeFileSync(join(disabled, MSC), readFileSync(join(disabled, MSC), 'utf8').replace('ID(protect_init_MSC) ENABLED START', 'ID(protect_init_MSC) START'));
    const refused = await problemsOf(disabled);
    expect(refused.ok).toBe(false);
    expect(refused.problems).toEqual([expect.stringMatching(/^generated\/architecture\/modules\/MSC_mod\/module\.c:\d+: error: protected region\(s\) protect_init_MSC not ENABLED, .*run `contract generate` on the project \(Generate All in the IDE: it moves that code to src-gen\/orphans\/, where you get it back\), then build again; left untouched$/)]);
    expect(existsSync(join(disabled, 'src-gen/orphans'))).toBe(false);
    // the exec region left with the ID of a module that is gone (PLN, renamed MSC on the other branch)
    const merged = project();
    const text = readFileSync(join(merged, MSC), 'utf8');
    writeFileSync(join(merged, MSC), text.replace('ID(protect_exec_MSC)', 'ID(protect_exec_PLN)'));
    const carried = await problemsOf(merged);
    expect(carried.ok, carried.problems.join('\n')).toBe(true);
    expect(carried.problems).toEqual([expect.stringMatching(/^generated\/architecture\/modules\/MSC_mod\/module\.c:\d+: warning: protected region protect_exec_PLN carried over to protect_exec_MSC: /)]);
    expect(readFileSync(join(carried.ws.workDir, MSC), 'utf8')).toBe(text);
  }, 120_000);

  it('builds a region cut whole from its own module.c (its indentation left there) and pasted into another: carried home with a warning, its own file not refused as edited outside its regions', async () => {
    const MSC = 'src-gen/generated/architecture/modules/MSC_mod/module.c';
    const MSD = 'src-gen/generated/architecture/modules/MSD_mod/module.c';
    const dir = project();
    const msc = readFileSync(join(dir, MSC), 'utf8');
    const cut = /\n {4}(\/\*PROTECTED REGION ID\(protect_exec_MSC\)[^]*?END\*\/)/.exec(msc)!;
    writeFileSync(join(dir, MSC), msc.replace(cut[0], '\n    '));
    writeFileSync(join(dir, MSD), readFileSync(join(dir, MSD), 'utf8').replace(/(protect_exec_MSD\) ENABLED START[^]*?PROTECTED REGION END\*\/)/, `$1\n    ${cut[1]}`));
    const ws = workspace();
    const out = await prepareWorkspace(ws, { dir }, 'cactal', { ...DEFAULT_LIMITS }, () => {});
    const problems = out.problems.map((p) => `${p.file}:${p.line}: ${p.severity}: ${p.message}`);
    expect(out.ok, problems.join('\n')).toBe(true);
    expect(problems).toEqual([expect.stringMatching(/^generated\/architecture\/modules\/MSD_mod\/module\.c:\d+: warning: protected region protect_exec_MSC is no region of this file but of generated\/architecture\/modules\/MSC_mod\/module\.c /)]);
    expect(readFileSync(join(ws.workDir, MSC), 'utf8')).toBe(msc);
    expect(existsSync(join(ws.stageDir, 'project/src-gen/orphans'))).toBe(false);
  }, 120_000);

  it("builds once an interrupted rename's journal is gone from the project (generate finished it): the stage drops its copy, which refused every later build of that workspace", async () => {
    const dir = project();
    const ws = workspace();
    const prepareIn = async () => {
      const log: string[] = [];
      const out = await prepareWorkspace(ws, { dir }, 'cactal', { ...DEFAULT_LIMITS }, (l: string) => log.push(l));
      return { out, log };
    };
    writeFileSync(join(dir, 'src-gen/.contract-rename.json'), JSON.stringify({ version: 1, kind: 'module', oldName: 'MSC', newName: 'MSK', files: [] }));
    const refused = await prepareIn();
    expect(refused.out.ok).toBe(false);
    expect(refused.out.problems).toEqual([expect.objectContaining({ file: '.contract-rename.json', severity: 'error', message: expect.stringContaining('an interrupted rename left its journal here') })]);
    // the log names the journal from the project folder, as the IDE's Build & Run shows it
    expect(refused.log).toContainEqual(expect.stringMatching(/^src-gen\/\.contract-rename\.json: error: an interrupted rename left its journal here/));
    rmSync(join(dir, 'src-gen/.contract-rename.json'));
    const built = await prepareIn();
    expect(built.out.ok, built.log.join('\n')).toBe(true);
    expect(existsSync(join(ws.stageDir, 'project/src-gen/.contract-rename.json'))).toBe(false);
  }, 120_000);

  it('mirrors the files the user deleted from src-gen/: a deleted module.c whose regions held code is generated with that code restored from the project\'s copy (said); deleted with the copy too, with its defaults (a warning says its regions held code), never built from the stale copy in work/; a deleted header leaves work/ while the build products stay', async () => {
    const dir = project();
    const ws = workspace();
    const prepareIn = async () => {
      const log: string[] = [];
      const out = await prepareWorkspace(ws, { dir }, 'cactal', { ...DEFAULT_LIMITS }, (l: string) => log.push(l));
      expect(out.ok, log.join('\n')).toBe(true);
      return log;
    };
    const helper = 'src-gen/generated/architecture/modules/MSC_mod/helper.h';
    writeFileSync(join(dir, helper), '#define HELPER 1\n');
    await prepareIn();
    expect(readFileSync(join(ws.workDir, MSC_C), 'utf8')).toContain("the user's marker");
    expect(existsSync(join(ws.workDir, helper))).toBe(true);
    // what a build leaves in work/ beside the sources
    const product = 'src-gen/generated/architecture/modules/MSC_mod/module.o';
    writeFileSync(join(ws.workDir, product), 'object');
    rmSync(join(dir, MSC_C));
    rmSync(join(dir, helper));
    const restored = await prepareIn();
    expect(readFileSync(join(ws.workDir, MSC_C), 'utf8')).toContain("the user's marker");
    expect(restored).toContainEqual(expect.stringMatching(/^src-gen\/generated\/architecture\/modules\/MSC_mod\/module\.c: warning: was not there \(deleted\?\): restored \d+ protected region\(s\) of src-gen\/generated\/architecture\/modules\/MSC_mod\/module\.c \(.*protect_init_MSC.*\) from the last generation's copy/));
    expect(existsSync(join(dir, MSC_C))).toBe(false); // the project's file comes back at its next generate
    expect(existsSync(join(ws.stageDir, 'project', helper))).toBe(false);
    expect(existsSync(join(ws.workDir, helper))).toBe(false);
    expect(readFileSync(join(ws.workDir, product), 'utf8')).toBe('object');
    // deleted with the copy: generated with its defaults, said
    rmSync(join(dir, 'src-gen/.contract-regions.json'));
    const log = await prepareIn();
    expect(readFileSync(join(ws.workDir, MSC_C), 'utf8')).not.toContain("the user's marker");
    // its regions held code (the project's manifest records which): said, not refused
    expect(log).toContainEqual(expect.stringMatching(/^src-gen\/generated\/architecture\/modules\/MSC_mod\/module\.c: warning: was not there \(deleted\?\), though its protected region\(s\) .*protect_init_MSC.* held code when it was last generated: .*`git checkout -- src-gen\/generated\/architecture\/modules\/MSC_mod\/module\.c`/));
    expect(readFileSync(join(ws.workDir, product), 'utf8')).toBe('object');
  }, 120_000);

  it('inline files (no project folder): the copy sent among them restores a generated file left out (said), without it the file comes with its defaults and the code is said lost', async () => {
    // the client's files as its last generation left them: a folder prepared once records them
    const dir = project();
    await prepare(dir);
    const COPY = 'src-gen/.contract-regions.json';
    expect(readFileSync(join(dir, COPY), 'utf8')).toContain("the user's marker");
    const inline: Record<string, string> = {};
    const walk = (rel: string): void => {
      for (const entry of readdirSync(join(dir, rel), { withFileTypes: true })) {
        const path = rel ? `${rel}/${entry.name}` : entry.name;
        if (entry.isDirectory()) {
          if (!/^(logs|run)$/.test(entry.name)) walk(path);
        } else if (path.endsWith('.contract') || path.startsWith('src-gen/')) {
          const data = readFileSync(join(dir, path));
          if (!data.includes(0)) inline[path] = data.toString('utf8'); // a program a make by hand left is no source
        }
      }
    };
    walk('');
    delete inline[MSC_C];
    const prepareInline = async (files: Record<string, string>) => {
      const ws = workspace();
      const log: string[] = [];
      const out = await prepareWorkspace(ws, { files }, 'cactal', { ...DEFAULT_LIMITS }, (l: string) => log.push(l));
      expect(out.ok, log.join('\n')).toBe(true);
      return { ws, log, out };
    };
    const restored = await prepareInline(inline);
    expect(readFileSync(join(restored.ws.workDir, MSC_C), 'utf8')).toContain("the user's marker");
    expect(restored.log).toContainEqual(expect.stringMatching(/^src-gen\/generated\/architecture\/modules\/MSC_mod\/module\.c: warning: was not there \(deleted\?\): restored \d+ protected region\(s\) of .*protect_init_MSC.* from the last generation's copy/));
    const { [COPY]: _copy, ...withoutCopy } = inline;
    const lost = await prepareInline(withoutCopy);
    expect(readFileSync(join(lost.ws.workDir, MSC_C), 'utf8')).not.toContain("the user's marker");
    expect(lost.log).toContainEqual(expect.stringMatching(/^src-gen\/generated\/architecture\/modules\/MSC_mod\/module\.c: warning: was not there \(deleted\?\), though its protected region\(s\) .*protect_init_MSC.* held code when it was last generated/));
  }, 120_000);

  it('refuses a folder without a .contract file, and one whose project is in a sub-folder with its own src-gen/ (built from there, the user\'s code would be left out)', async () => {
    const refusal = (source: Parameters<typeof prepareWorkspace>[1]) => prepareWorkspace(workspace(), source, 'cactal', { ...DEFAULT_LIMITS }, () => {}).then(() => null, (e: Error) => e.message);
    const empty = mkdtempSync(join(base, 'empty-'));
    writeFileSync(join(empty, 'notes.txt'), 'no model here\n');
    expect(await refusal({ dir: empty })).toBe('no .contract file in the project: nothing to build (a project is the folder of its .contract files)');
    expect(await refusal({ files: { 'notes.txt': '' } })).toBe('no .contract file in the project: nothing to build (a project is the folder of its .contract files)');
    const above = mkdtempSync(join(base, 'above-'));
    cpSync(project(), join(above, 'robot'), { recursive: true });
    const said = 'the project\'s .contract files are all in robot/, which has its own src-gen/ (its generated code and yours, which this build would leave out): build robot instead; nothing was built';
    expect(await refusal({ dir: above })).toBe(said);
    expect(await refusal({ files: { 'robot/a.contract': 'datatype T {int x = 1};', 'robot/src-gen/generated/x.c': '' } })).toBe(said);
    // a project whose own src-gen/ is there builds, sub-folders and all
    writeFileSync(join(above, 'top.contract'), 'datatype TopT {int y = 1};\n');
    expect(await refusal({ dir: above })).not.toBe(said);
    // a folder of several projects is not one project: refused, naming them
    expect(await refusal({ files: { 'a/a.contract': 'datatype A {int x = 1};', 'b/src/b.contract': 'datatype B {int x = 1};' } }))
      .toBe('the folder holds several projects (a/, b/): build one of them; nothing was built');
  }, 120_000);

  it('the Eclipse layout (src/*.contract, src-gen/ at the root) builds the root\'s tree; a second one, src/src-gen/, is said in the log', async () => {
    const log: string[] = [];
    await prepareWorkspace(workspace(), { files: { 'src/a.contract': 'datatype A {int x = 1};', 'src-gen/generated/notes.txt': 'mine', 'src/src-gen/generated/notes.txt': 'defaults' } }, 'cactal', { ...DEFAULT_LIMITS }, (l) => log.push(l));
    expect(log).toContain('warning: src/src-gen/ is a second generated tree of this project, not used: the project is the folder built and its tree src-gen/ (the outermost folder holding a src-gen/ is the project; docs/codegen.md "Where a project is"): move any code of yours out of src/src-gen/, then delete it');
  }, 120_000);
});
