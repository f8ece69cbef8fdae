/**
 * POST /api/rename-entity: what follows a rename the editor made in the `.contract` files
 * (docs/ide.md, "Rename carry-over"), the same three steps as `contract rename`:
 * - an entity that names generated files (module, supervisor, datatype, enumeration, function; no
 *   `kind`: the same) moves its generated paths and region IDs (codegen's renameInGeneratedTree);
 * - a name the user code uses (port, parameter, datatype, enumeration with its constants from its
 *   `members`, enumeration member, function) is rewritten in the code of the protected regions
 *   (codegen's renameIdentifiersInGeneratedTree);
 * - a name a scenario writes (module, supervisor, schema, supervision function, port, datatype,
 *   enumeration, enumeration member; a rule label, local or parameter of a supervision function) is rewritten in the project's `.scenario` files (the language package's
 *   renameInScenarios), each file saved as the editor saves it: in its queue, its folder opened
 *   without following links, refused if it changed since it was read (then listed in `scenariosLeft`).
 * - the `.contract` files the editor's rename changed (`files`: their text after it and the version
 *   it was made on) are written here, after the generated tree, as `contract rename` writes them.
 * All of it runs under the generated-tree lock, on the project folder as opened (project-folder.ts),
 * journaled as `contract rename` journals it (codegen rename-journal.ts): before anything changes,
 * `src-gen/.contract-rename.json` holds each project file's version before and text after; it is
 * removed once every file is written. A rename stopped half-way (the server killed, a disk error) is
 * finished by the next Generate All or `contract generate`, never half-applied: the renamed
 * module's code is not moved to orphans/ by a generation of the model not renamed yet.
 */
import { lstat } from 'node:fs/promises';
import { join } from 'node:path';
import { SRC_GEN_DIR } from '@contract-studio/conventions';
import type { RenameEntityResponse } from './api-types.js';
import type { FileLocks } from './file-locks.js';
import { fileVersion } from './file-version.js';
import type { GeneratedTreeLock } from './generated-tree-lock.js';
import { saveWorkspaceFile, withProjectTreeLock } from './guarded-write.js';
import { HttpError } from './http-error.js';
import { journaledRename, renameInScenarioFiles, userCodeRenames } from './integrations.js';
import { inProjectFolder } from './project-folder.js';
import type { WorkspacePaths } from './workspace-paths.js';

/** Kinds of rename whose name the user code of the generated C uses. */
const USER_CODE_KINDS = new Set(['port', 'parameter', 'datatype', 'enumeration', 'enumeration member', 'function']);
/** Kinds of rename whose name is a generated file's or a region ID's (the tree's paths and IDs move). */
const GENERATED_NAME_KINDS = new Set(['module', 'supervisor', 'datatype', 'enumeration', 'function']);
/** Every kind the request takes: those above and those a `.scenario` file can name. */
export const RENAME_KINDS: ReadonlySet<string> = new Set([...USER_CODE_KINDS, ...GENERATED_NAME_KINDS, 'schema', 'supervision function', 'rule label', 'local', 'function parameter']);
/**
 * Kinds that need the entity's owner: a port's or parameter's module, a supervision function's
 * supervisor, an enumeration member's enumeration, a rule label's, local's or function
 * parameter's function (`SUP.function`).
 */
const OWNED_KINDS: Record<string, string> = {
  port: 'module', parameter: 'module', 'supervision function': 'supervisor', 'enumeration member': 'enumeration',
  'rule label': 'function (SUP.function)', local: 'function (SUP.function)', 'function parameter': 'function (SUP.function)',
};

export interface RenameRequest {
  project: string;
  from: string;
  to: string;
  kind?: string;
  owner?: string;
  /** A renamed enumeration's members (its C constants `<Enum>_<member>` follow it). */
  members?: string[];
  /** The project's `.contract` files as the rename left them in the editor (checkFiles, once the project is known): written here, journaled. */
  files: unknown;
}

export interface RenamedFile {
  /** Workspace path, in the project, outside its src-gen. */
  path: string;
  /** The text after the rename. */
  text: string;
  /** The version (SHA-256) of the file on disk the rename was made on. */
  base: string;
}

/** Where a rename may stop, for a test's simulated crash: after the journal is written, after the generated tree is carried over. */
export type RenameStep = 'journaled' | 'tree carried over';

/** More members than an enumeration of a sane model has: refused. */
const MAX_MEMBERS = 10_000;
/** More renamed files, or text, than a journal holds (codegen's MAX_JOURNAL_BYTES): refused. */
const MAX_FILES = 10_000;
const MAX_FILES_BYTES = 48 * 1024 * 1024;

/** The renamed `.contract` files of the request checked against project folder `project` (workspace path, '' for the root). */
function checkFiles(files: unknown, project: string): RenamedFile[] {
  if (files === undefined) return [];
  if (!Array.isArray(files) || files.length > MAX_FILES) throw new HttpError(400, `files are at most ${MAX_FILES} renamed .contract files`);
  const prefix = project ? `${project}/` : '';
  let bytes = 0;
  const seen = new Set<string>();
  return files.map((f: unknown) => {
    const { path, text, base } = (f ?? {}) as Record<string, unknown>;
    if (typeof path !== 'string' || typeof text !== 'string' || typeof base !== 'string' || !/^[0-9a-f]{64}$/.test(base)) throw new HttpError(400, 'each file is { path, text, base } (base: the version the rename was made on)');
    const rel = path.startsWith(prefix) ? path.slice(prefix.length) : '';
    if (!rel.endsWith('.contract') || rel.split('/').some((p) => p === '' || p === '.' || p === '..') || rel === SRC_GEN_DIR || rel.startsWith(`${SRC_GEN_DIR}/`) || seen.has(rel)) {
      throw new HttpError(400, `file ${JSON.stringify(path.slice(0, 200))}: not a .contract file of the project, once, outside ${SRC_GEN_DIR}`);
    }
    seen.add(rel);
    bytes += Buffer.byteLength(text, 'utf8');
    if (bytes > MAX_FILES_BYTES) throw new HttpError(400, 'the renamed files are larger than a rename journal holds');
    return { path, text, base };
  });
}

/** The request's body checked: 400 with what is wrong. */
function checkRequest(body: Record<string, unknown>): RenameRequest {
  const { project, from, to, kind, owner, members, files } = body;
  if (typeof from !== 'string' || typeof to !== 'string') throw new HttpError(400, 'from and to are required');
  if (project !== undefined && typeof project !== 'string') throw new HttpError(400, 'project must be a workspace folder');
  if (kind !== undefined && !(typeof kind === 'string' && RENAME_KINDS.has(kind))) throw new HttpError(400, `kind must be one of ${[...RENAME_KINDS].join(', ')}`);
  const ownerKind = typeof kind === 'string' ? OWNED_KINDS[kind] : undefined;
  const ownerShape = ownerKind?.startsWith('function') ? /^[A-Za-z_]\w*\.[A-Za-z_]\w*$/ : /^[A-Za-z_]\w*$/;
  if (owner !== undefined && !(typeof owner === 'string' && ownerShape.test(owner))) {
    throw new HttpError(400, `owner must be ${ownerKind?.startsWith('function') ? 'a supervision function as SUP.function' : ownerKind === 'enumeration' ? 'an enumeration name' : 'a module or supervisor name'}`);
  }
  if (ownerKind && owner === undefined) throw new HttpError(400, `a ${kind} rename needs its ${ownerKind} (owner)`);
  if (members !== undefined && !(kind === 'enumeration' && Array.isArray(members) && members.length <= MAX_MEMBERS && members.every((m) => typeof m === 'string' && /^[A-Za-z_]\w*$/.test(m)))) {
    throw new HttpError(400, 'members are the names of a renamed enumeration\'s members (kind enumeration)');
  }
  return {
    project: project ?? '', from, to, ...(kind !== undefined ? { kind } : {}), ...(owner !== undefined ? { owner } : {}),
    ...(members !== undefined ? { members: members as string[] } : {}), files,
  };
}

export async function renameEntity(
  paths: WorkspacePaths, treeLock: GeneratedTreeLock, fileLocks: FileLocks, body: Record<string, unknown>,
  /** Tests only: called at each step; what it throws stops the rename there, as a crash would (the journal left). */
  step?: (at: RenameStep) => void,
): Promise<RenameEntityResponse> {
  const { project: projectArg, from, to, kind, owner, members, files: asked } = checkRequest(body);
  const projectDir = paths.resolve(projectArg);
  const project = paths.toRelative(projectDir);
  const files = checkFiles(asked, project);
  const inProject = (file: string) => (project ? file.slice(project.length + 1) : file);
  try {
    return await treeLock.run(() => inProjectFolder(paths, projectDir, (dir) => withProjectTreeLock(dir, async (journal) => {
      if (journal.refused) throw new HttpError(409, `${journal.refused}; nothing was renamed`);
      const srcGen = join(dir, SRC_GEN_DIR);
      const generatedNames = kind === undefined || GENERATED_NAME_KINDS.has(kind);
      const identifiers = kind !== undefined && USER_CODE_KINDS.has(kind) ? await userCodeRenames(kind, from, to, owner, members) : undefined;
      const changes = kind !== undefined ? await renameInScenarioFiles(dir, [srcGen], { kind, oldName: from, newName: to, ...(owner !== undefined ? { owner } : {}) }) : [];
      // journal, generated tree, project files, journal removed: the sequence of contract rename
      // (codegen journaled-rename.ts); stopped after the journal, the next generation finishes the rename
      const journaled = (files.length > 0 || changes.length > 0) && (await lstat(srcGen).catch(() => undefined))?.isDirectory() === true;
      const renameJournal = {
        version: 1 as const, kind: kind ?? 'entity', oldName: from, newName: to, generatedNames,
        identifiers: [...(identifiers?.renames ?? [])], ...(identifiers?.owner !== undefined ? { identifierOwner: identifiers.owner } : {}),
        files: [
          ...files.map((f) => ({ path: inProject(f.path), before: f.base, after: f.text })),
          ...changes.map((c) => ({ path: c.file, before: fileVersion(Buffer.from(c.original, 'utf8')), after: c.text })),
        ],
      };
      const filesLeft: RenameEntityResponse['filesLeft'] = [];
      const written: RenameEntityResponse['written'] = [];
      const scenarios: RenameEntityResponse['scenarios'] = [];
      const scenariosLeft: RenameEntityResponse['scenariosLeft'] = [];
      const writeFiles = async () => {
        for (const f of files) {
          try {
            written.push({ file: f.path, version: (await saveWorkspaceFile(paths, f.path, Buffer.from(f.text, 'utf8'), treeLock, { base: f.base, fileLocks })).version });
          } catch (e) {
            if (!(e instanceof HttpError)) throw e; // the journal stays: the next generation finishes the rename
            filesLeft.push({ file: f.path, reason: e.message });
          }
        }
        for (const change of changes) {
          const rel = project ? `${project}/${change.file}` : change.file;
          try {
            await saveWorkspaceFile(paths, rel, Buffer.from(change.text, 'utf8'), treeLock, { base: fileVersion(Buffer.from(change.original, 'utf8')), fileLocks });
          } catch (e) {
            if (!(e instanceof HttpError)) throw e;
            scenariosLeft.push({ file: rel, reason: e.message });
            continue;
          }
          for (const edit of change.edits) scenarios.push({ file: rel, line: edit.line, before: edit.before, after: edit.after });
        }
      };
      // every file written (or left, said): the rename is whole, its journal removed
      const { moved, code } = await journaledRename(srcGen, renameJournal, { journaled, writeFiles, ...(step ? { step } : {}) });
      return {
        movedPaths: moved.movedPaths, regionIds: moved.regionIds, rewritten: code.rewritten, remaining: code.remaining, scenarios, scenariosLeft,
        written, filesLeft, ...(code.refused ? { refused: code.refused } : {}),
      };
    })));
  } catch (e) {
    if (e instanceof HttpError) throw e; // a package not built: 503
    throw new HttpError(409, (e as Error).message);
  }
}
