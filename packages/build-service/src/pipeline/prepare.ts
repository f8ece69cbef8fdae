/**
 * The "prepare" step: project -> stage/ (trusted copy) -> for Cactal projects load, validate and
 * generate src-gen/ -> sync into work/ (the sandbox's folder) -> index the protected regions of
 * the tree, so gcc diagnostics can say when they fall in user code.
 */
import { createHash } from 'node:crypto';
import { promises as fsp } from 'node:fs';
import { join } from 'node:path';
import type { Limits } from '../limits.js';
import { LimitHitError, SERVICE_BOUNDS } from '../limits.js';
import type { CactalProblem } from './cactal-adapter.js';
import { generateProjectBounded } from './generate-worker.js';
import { findProtectedRegions, type ProtectedRegion } from './protected-regions.js';
import { dropStaleWorkSources } from './work-sources.js';
import { foreignMakefiles, foreignMakefilesMessage } from './foreign-makefiles.js';
import { orphanedDefinitions, type OrphanedDefinitions } from './orphan-hints.js';
import type { UserCopy } from './gcc-diagnostics.js';
import type { Workspace } from './workspaces.js';
import { generatorIdentity, type GenerationCache } from '../cache/generation-cache.js';
import { checkRelativePath, listFilesNoFollow, readFileHeadNoFollow, readFileNoFollow, removeTreeNoFollow, syncFileNoFollow } from '../util/safe-fs.js';
import { SRC_GEN_ARCHITECTURE_DIR, SRC_GEN_DIR, TREE_LOCK_NAME, architecturePath, projectRootsOf, unusedTreeWarning } from '@contract-studio/conventions';
import { makefileExecutables } from '@contract-studio/codegen/run-executables';
import { recordUserCode } from '@contract-studio/codegen/record-user-code';

export type ProjectKind = 'cactal' | 'make';

export type ProjectSource = { dir: string } | { files: Record<string, string> };

export const MAX_FILE_BYTES = SERVICE_BOUNDS.projectFileBytes;
export const MAX_PROJECT_BYTES = SERVICE_BOUNDS.projectBytes;

/** Folder (relative to work/) the build reports diagnostics against and runs make in. */
export function treeRoot(kind: ProjectKind): string {
  return kind === 'cactal' ? SRC_GEN_DIR : '';
}

export function makeDir(kind: ProjectKind): string {
  return kind === 'cactal' ? SRC_GEN_ARCHITECTURE_DIR : '';
}

/**
 * make's arguments naming the makefile of the folder it runs in: a generated tree's own `Makefile`
 * (its recursive makes name theirs too); a plain Makefile project's make chooses as it always does.
 */
export function generatedMakefileArgs(kind: ProjectKind): string[] {
  return kind === 'cactal' ? ['-f', 'Makefile'] : [];
}

export interface PrepareOutcome {
  ok: boolean;
  problems: CactalProblem[];
  regions: Map<string, ProtectedRegion[]>;
  /** The user's src-gen/ copies of the tree's C files that are not the files built (gcc-diagnostics.ts UserCopy). */
  userCopies: Map<string, UserCopy>;
  /** Files of work/ rewritten by this prepare (0 on a no-op rebuild). */
  synced: number;
  /** A Cactal project's executables, as its generated architecture Makefile names them (what `make run` starts); else null. */
  executables: string[] | null;
  /** The functions defined in the project's src-gen/orphans/ copies (orphan-hints.ts): a link error missing one says where it went. */
  orphanedDefinitions?: OrphanedDefinitions;
}

/** The folders a run writes its output to (LOG_DIR, RUN_DIR), anywhere in the project: never read. */
const RUN_OUTPUT_DIR = /(^|\/)(logs|run)$/;

/** What of a project folder is copied: Cactal sources, the generated tree with user code, Makefile projects. */
function acceptProjectPath(kind: ProjectKind) {
  return (rel: string, isDir: boolean): boolean => {
    const base = rel.split('/').pop() ?? rel;
    const inTree = rel.startsWith(`${SRC_GEN_DIR}/`);
    if (base === 'node_modules' || base === '.git' || base === TREE_LOCK_NAME) return false;
    if (base.startsWith('.') && !inTree) return false;
    if (isDir) return !RUN_OUTPUT_DIR.test(rel);
    if (/\.(o|a|so|out|csv|log)$/.test(base)) return false;
    if (kind === 'cactal') return rel.endsWith('.contract') || inTree;
    return true;
  };
}

/**
 * Whether an entry of the project that is not a regular file (a link, a FIFO) stands where a source
 * is read: a `.contract` file, anything of the generated tree (the user's code is there), any file
 * of a Makefile project. Such an entry is refused, never followed: left out, the build would use
 * the generated default code instead of the user's, and say it succeeded.
 */
function isProjectSource(kind: ProjectKind, rel: string, accept: (rel: string, isDir: boolean) => boolean): boolean {
  if (RUN_OUTPUT_DIR.test(rel)) return false;
  if (kind === 'make') return accept(rel, false) || accept(rel, true);
  return rel.endsWith('.contract') || rel === SRC_GEN_DIR || rel.startsWith(`${SRC_GEN_DIR}/`) ? accept(rel, false) || accept(rel, true) : false;
}

/** The refusal of a project whose sources include links or other non-files (the first 5 named). */
function notReadMessage(refused: string[]): string {
  const named = refused.slice(0, 5).join(', ') + (refused.length > 5 ? ` and ${refused.length - 5} more` : '');
  return `${named}: the build service never reads a project's source through a link (nor a FIFO or device): `
    + 'put the file itself there (`cp --remove-destination "$(readlink -f F)" F` for a link F); nothing was built';
}

/** An ELF file (a compiled program or object): the build products of a local build in src-gen/. */
const isElf = (data: Buffer): boolean => data.length >= 4 && data[0] === 0x7f && data[1] === 0x45 && data[2] === 0x4c && data[3] === 0x46;

/** Reads the project's files (never through links); returns them and a digest of paths + contents. */
async function readProject(source: ProjectSource, kind: ProjectKind): Promise<{ wanted: Map<string, Buffer>; digest: string; warnings: string[] }> {
  const wanted = new Map<string, Buffer>();
  let total = 0;
  const add = (rel: string, data: Buffer): void => {
    if (data.length > MAX_FILE_BYTES) throw new PrepareError(`${rel}: file larger than ${MAX_FILE_BYTES} bytes (a project's file is read up to that size, never left out: the build would go on without it); nothing was built`);
    total += data.length;
    if (total > MAX_PROJECT_BYTES) throw new PrepareError(`project larger than ${MAX_PROJECT_BYTES} bytes`);
    if (wanted.size >= SERVICE_BOUNDS.projectFiles) throw new PrepareError(`project of more than ${SERVICE_BOUNDS.projectFiles} files (a job is given that many at most); nothing was built`);
    wanted.set(checkRelativePath(rel), data);
  };
  // the folders holding a `src-gen/` below the project's own (a project in a sub-folder: checkProjectFolder)
  const nestedTrees = new Set<string>();
  if ('files' in source) {
    for (const [rel, text] of Object.entries(source.files)) add(rel, Buffer.from(text, 'utf8'));
    for (const rel of wanted.keys()) {
      const at = rel.indexOf(`/${SRC_GEN_DIR}/`);
      if (at > 0) nestedTrees.add(rel.slice(0, at));
    }
  } else {
    const acceptPath = acceptProjectPath(kind);
    const refused: { rel: string; what: string }[] = [];
    const accept = (rel: string, isDir: boolean): boolean => {
      if (isDir && rel.endsWith(`/${SRC_GEN_DIR}`)) nestedTrees.add(rel.slice(0, -SRC_GEN_DIR.length - 1));
      return acceptPath(rel, isDir);
    };
    const files = await listFilesNoFollow(source.dir, accept, '', (rel, what) => {
      if (isProjectSource(kind, rel, accept)) refused.push({ rel, what });
    });
    // a link (or FIFO) named as a foreign makefile gets that refusal, whose advice (remove it) ends
    // the matter: the link's own (copy the file in) would only meet the makefile's refusal next
    const foreignLinks = kind === 'cactal' ? foreignMakefiles(refused.map((r) => r.rel)) : [];
    if (foreignLinks.length) {
      const foreign = foreignMakefiles([...files, ...foreignLinks]);
      throw new PrepareError(foreignMakefilesMessage(foreign), foreign);
    }
    if (refused.length) throw new PrepareError(notReadMessage(refused.map(({ rel, what }) => `${rel} (${what === 'symlink' ? 'a symbolic link' : 'not a regular file'})`)));
    for (const rel of files) {
      // one byte past the bound is read: a larger file fails the job, naming it (add); it was left out
      // without a word, and a 9 MiB .contract that check refused built "ok" without it
      const data = await readFileHeadNoFollow(source.dir, rel, MAX_FILE_BYTES + 1);
      if (!data) continue; // gone since it was listed
      // a program an earlier local build made (make in src-gen/) is no source: left out, whatever its mode or size
      if (kind === 'cactal' && rel.startsWith(`${SRC_GEN_DIR}/`) && isElf(data)) continue;
      add(rel, data);
    }
  }
  let warnings: string[] = [];
  if (kind === 'cactal') {
    warnings = checkProjectFolder([...wanted.keys()], nestedTrees);
    const foreign = foreignMakefiles(wanted.keys());
    if (foreign.length) throw new PrepareError(foreignMakefilesMessage(foreign), foreign);
  }
  const hash = createHash('sha256').update(kind);
  for (const rel of [...wanted.keys()].sort()) hash.update('\0').update(rel).update('\0').update(wanted.get(rel)!);
  return { wanted, digest: hash.digest('hex'), warnings };
}

/**
 * Mirrors the project into its stage: every staged file the project no longer has is dropped (a
 * stale .contract would still load; a stale src-gen/ file would be merged as the user's: a module.c
 * deleted to have it generated from scratch kept its old regions, a deleted helper header was still
 * included; a rename's journal that generate removed refused every later build), then the
 * project's files are written. What the stage's generation adds is generated again from the model.
 */
async function stageProject(wanted: Map<string, Buffer>, stageProjectDir: string): Promise<void> {
  for (const rel of await listFilesNoFollow(stageProjectDir)) {
    if (!wanted.has(rel)) await removeTreeNoFollow(join(stageProjectDir, rel));
  }
  for (const [rel, data] of wanted) await syncFileNoFollow(stageProjectDir, rel, data);
}

/** The warnings a staged tree's generation gave (the service's own file in stage/), [] when none can be read. */
async function readStagedWarnings(file: string): Promise<CactalProblem[]> {
  try {
    const data = JSON.parse(await fsp.readFile(file, 'utf8')) as unknown;
    return Array.isArray(data) ? data.filter((p): p is CactalProblem => typeof p === 'object' && p !== null && typeof (p as CactalProblem).message === 'string' && (p as CactalProblem).severity === 'warning' && typeof (p as CactalProblem).file === 'string') : [];
  } catch {
    return [];
  }
}

/**
 * Where a prepare problem is, from the project folder, as the log says it: the model's at its
 * `.contract` file, line and column; the generator's (relative to src-gen) at `src-gen/FILE` and
 * its line when known (the generator's own notes, "(manifest)" or an absolute path, as they are).
 */
export function problemAt(p: CactalProblem): string {
  if (p.file.endsWith('.contract')) return `${p.file}:${p.line}:${p.column}`;
  const file = p.file.startsWith('(') || p.file.startsWith('/') ? p.file : `${SRC_GEN_DIR}/${p.file}`;
  return p.line ? `${file}:${p.line}` : file;
}

/** A project prepare refuses; `foreignMakefiles`: the refused makefiles of its generated tree (foreign-makefiles.ts), project-relative, when that is why. */
export class PrepareError extends Error {
  constructor(message: string, readonly foreignMakefiles: readonly string[] = []) {
    super(message);
  }
}

/**
 * A Cactal project with no `.contract` file is refused; so is one whose root, by the rule of
 * conventions' project-root.ts (docs/codegen.md "Where a project is"), is not the folder built:
 * its `.contract` files all in a sub-folder that has its own `src-gen/` (a build run one folder too
 * high: the user's code in that `src-gen/` would not be built, the generated defaults would), or
 * a folder of several projects. Answers the warnings for trees of the project that are not used.
 */
function checkProjectFolder(files: readonly string[], nestedTrees: ReadonlySet<string>): string[] {
  const models = files.filter((f) => f.endsWith('.contract'));
  if (!models.length) throw new PrepareError('no .contract file in the project: nothing to build (a project is the folder of its .contract files)');
  const ownTree = files.some((f) => f.startsWith(`${SRC_GEN_DIR}/`));
  const { roots, unusedTrees } = projectRootsOf(models, (folder) => (folder === '' ? ownTree : nestedTrees.has(folder)));
  if (roots.length > 1) {
    throw new PrepareError(`the folder holds several projects (${roots.map((r) => `${r}/`).join(', ')}): build one of them; nothing was built`);
  }
  const sub = roots[0] ?? '';
  if (sub !== '') {
    throw new PrepareError(`the project's .contract files are all in ${sub}/, which has its own ${SRC_GEN_DIR}/ (its generated code and yours, which this build would leave out): build ${sub} instead; nothing was built`);
  }
  return unusedTrees.map((u) => `warning: ${unusedTreeWarning(u, '', 'the folder built')}`);
}

export async function prepareWorkspace(
  ws: Workspace,
  source: ProjectSource,
  kind: ProjectKind,
  limits: Limits,
  log: (line: string) => void,
  cancelled?: Promise<void>,
  generated?: GenerationCache,
): Promise<PrepareOutcome> {
  const stageProjectDir = join(ws.stageDir, 'project');
  await fsp.mkdir(stageProjectDir, { recursive: true, mode: 0o700 });
  if (kind === 'cactal' && 'dir' in source) {
    // the project's record of its user code (docs/codegen.md "A generated file deleted"): what this
    // build generates goes to its private copy, so the project's own manifest learns here which
    // regions hold code, and the copy of that code that brings a deleted generated file back
    for (const w of recordUserCode(join(source.dir, SRC_GEN_DIR)).warnings) log(`warning: ${SRC_GEN_DIR}/${w}`);
  }
  const { wanted, digest, warnings } = await readProject(source, kind);
  for (const w of warnings) log(w);
  if (kind === 'cactal') {
    // the generator's time and memory grow with the model: a model above the bound never reaches it
    let modelBytes = 0;
    for (const [rel, data] of wanted) if (rel.endsWith('.contract')) modelBytes += data.length;
    if (modelBytes > limits.modelBytes) {
      log(`the model has ${modelBytes} bytes of .contract files, above the ${limits.modelBytes}-byte limit (modelBytes)`);
      throw new LimitHitError({ name: 'modelBytes', value: limits.modelBytes, unit: 'bytes', mechanism: 'service-check' });
    }
  }
  const digestFile = join(ws.stageDir, 'inputs.sha256');
  const previous = await fsp.readFile(digestFile, 'utf8').catch(() => '');
  // the staged tree is current for the same inputs generated by the same generator: after an
  // upgrade of ContrACT Studio, an unchanged project is generated again (its tables follow the new
  // runtime); a stamp of an older version (the digest alone) never matches
  const stamp = kind === 'cactal' ? `${digest} generator=${generatorIdentity()}` : digest;
  let problems: CactalProblem[] = [];
  // the warnings of the generation that made the staged tree: said again when it is reused, so that
  // no build is silent about them (a deleted file restored or lost: docs/codegen.md "A generated file deleted")
  const warningsFile = join(ws.stageDir, 'generation-warnings.json');
  if (previous === stamp) {
    // same inputs as the last successful prepare of this workspace: the staged tree is current
    log('project unchanged since the last build: generation skipped');
    if (kind === 'cactal') {
      problems = await readStagedWarnings(warningsFile);
      for (const p of problems) log(`${problemAt(p)}: ${p.severity}: ${p.message}`);
    }
  } else if (kind === 'cactal') {
    await fsp.rm(digestFile, { force: true });
    const stageGen = join(stageProjectDir, SRC_GEN_DIR);
    const freshStage = !(await fsp.lstat(stageGen).catch(() => null));
    await stageProject(wanted, stageProjectDir);
    const t0 = Date.now();
    const hit = await generated?.get(digest);
    let outcome;
    if (hit && hit.written + hit.unchanged > limits.generatedFiles) {
      throw new LimitHitError({ name: 'generatedFiles', value: limits.generatedFiles, unit: 'count', mechanism: 'service-check' });
    }
    if (hit) {
      // the same inputs were generated before (another folder, another command): that tree, not a new load
      await removeTreeNoFollow(stageGen);
      await fsp.mkdir(stageGen, { mode: 0o700 });
      for (const [rel, f] of hit.files) await syncFileNoFollow(stageGen, rel, f.data, undefined, f.executable ? 0o755 : 0o644);
      outcome = hit;
      log(`generated tree taken from the build cache (same inputs and generator) in ${Date.now() - t0} ms`);
    } else {
      outcome = await generateProjectBounded(stageProjectDir, stageGen, limits, cancelled);
      if (generated && freshStage && !outcome.problems.some((p) => p.severity === 'error')) {
        const files = new Map<string, { data: Buffer; executable: boolean }>();
        for (const rel of await listFilesNoFollow(stageGen)) {
          const data = await readFileNoFollow(stageGen, rel, MAX_FILE_BYTES);
          if (data) files.set(rel, { data, executable: ((await fsp.lstat(join(stageGen, rel))).mode & 0o111) !== 0 });
        }
        await generated.put(digest, { ...outcome, files }).catch((e: Error) => log(`warning: the generated tree was not stored in the build cache: ${e.message}`));
      }
    }
    problems = outcome.problems;
    for (const p of problems) log(`${problemAt(p)}: ${p.severity}: ${p.message}`);
    if (problems.some((p) => p.severity === 'error')) {
      log(`the project has ${problems.filter((p) => p.severity === 'error').length} error(s): nothing generated`);
      return { ok: false, problems, regions: new Map(), userCopies: new Map(), synced: 0, executables: null };
    }
    log(`generated src-gen/ (${outcome.written} file(s) written, ${outcome.unchanged} unchanged) in ${Date.now() - t0} ms`);
    await fsp.writeFile(warningsFile, JSON.stringify(problems.filter((p) => p.severity === 'warning')));
  } else {
    await fsp.rm(digestFile, { force: true });
    await stageProject(wanted, stageProjectDir);
  }
  const root = treeRoot(kind);
  const stageTree = root ? join(stageProjectDir, root) : stageProjectDir;
  const regions = new Map<string, ProtectedRegion[]>();
  const userCopies = new Map<string, UserCopy>();
  let synced = 0;
  let executables: string[] | null = null;
  const tCopy = Date.now();
  const files = await listFilesNoFollow(stageTree, (rel) => !/(^|\/)(logs|run)(\/|$)/.test(rel));
  for (const rel of files) {
    const data = await readFileNoFollow(stageTree, rel, MAX_FILE_BYTES);
    if (!data) continue;
    const target = root ? `${root}/${rel}` : rel;
    const st = await fsp.lstat(join(stageTree, rel));
    const mode = st.mode & 0o111 ? 0o755 : 0o644;
    if (await syncFileNoFollow(ws.workDir, target, data, ws.owner, mode)) synced++;
    if (kind === 'cactal' && rel === architecturePath('Makefile')) executables = makefileExecutables(data.toString('utf8'));
    if (/\.(c|h)$/.test(rel)) {
      const found = findProtectedRegions(data.toString('utf8'));
      if (found.length) regions.set(rel, found);
      // the user's copy (the project's src-gen/ as sent), when it is not this file: a model changed
      // since the last generate: gcc's lines are this file's, the user reads theirs
      if (kind === 'cactal') {
        const mine = wanted.get(`${SRC_GEN_DIR}/${rel}`);
        if (!mine) userCopies.set(rel, { regions: null });
        else if (!mine.equals(data)) userCopies.set(rel, { regions: findProtectedRegions(mine.toString('utf8')) });
      }
    }
  }
  // what the project no longer has leaves work/ too (the build's products stay)
  const dropped = await dropStaleWorkSources(ws.stageDir, ws.workDir, files.map((rel) => (root ? `${root}/${rel}` : rel)));
  await fsp.writeFile(digestFile, stamp);
  log(`work tree ready: ${files.length} file(s), ${synced} updated${dropped ? `, ${dropped} removed` : ''}${ws.reused ? ' (incremental)' : ''} in ${Date.now() - tCopy} ms`);
  return { ok: true, problems, regions, userCopies, synced, executables, ...(kind === 'cactal' ? { orphanedDefinitions: orphanedDefinitions(wanted) } : {}) };
}
