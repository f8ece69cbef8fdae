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
 * All of it runs under the generated-tree lock, on the project folder as opened (project-folder.ts).
 */
import { join } from 'node:path';
import { SRC_GEN_DIR } from '@contract-studio/conventions';
import type { RenameEntityResponse } from './api-types.js';
import type { FileLocks } from './file-locks.js';
import { fileVersion } from './file-version.js';
import type { GeneratedTreeLock } from './generated-tree-lock.js';
import { saveWorkspaceFile, withProjectTreeLock } from './guarded-write.js';
import { HttpError } from './http-error.js';
import { renameGeneratedEntity, renameInScenarioFiles, renameInUserCode } from './integrations.js';
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
}

/** More members than an enumeration of a sane model has: refused. */
const MAX_MEMBERS = 10_000;

/** The request's body checked: 400 with what is wrong. */
function checkRequest(body: Record<string, unknown>): RenameRequest {
  const { project, from, to, kind, owner, members } = body;
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
    ...(members !== undefined ? { members: members as string[] } : {}),
  };
}

export async function renameEntity(paths: WorkspacePaths, treeLock: GeneratedTreeLock, fileLocks: FileLocks, body: Record<string, unknown>): Promise<RenameEntityResponse> {
  const { project: projectArg, from, to, kind, owner, members } = checkRequest(body);
  const projectDir = paths.resolve(projectArg);
  const project = paths.toRelative(projectDir);
  try {
    return await treeLock.run(() => inProjectFolder(paths, projectDir, (dir) => withProjectTreeLock(dir, async () => {
      const srcGen = join(dir, SRC_GEN_DIR);
      const moved = kind === undefined || GENERATED_NAME_KINDS.has(kind) ? await renameGeneratedEntity(srcGen, from, to, kind) : { movedPaths: [], regionIds: [] };
      const code = kind !== undefined && USER_CODE_KINDS.has(kind) ? await renameInUserCode(srcGen, kind, from, to, owner, members) : { rewritten: [], remaining: [] };
      const scenarios: RenameEntityResponse['scenarios'] = [];
      const scenariosLeft: RenameEntityResponse['scenariosLeft'] = [];
      if (kind !== undefined) {
        const changes = await renameInScenarioFiles(dir, [srcGen], { kind, oldName: from, newName: to, ...(owner !== undefined ? { owner } : {}) });
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
      }
      return {
        movedPaths: moved.movedPaths, regionIds: moved.regionIds, rewritten: code.rewritten, remaining: code.remaining, scenarios, scenariosLeft,
        ...(code.refused ? { refused: code.refused } : {}),
      };
    })));
  } catch (e) {
    if (e instanceof HttpError) throw e; // a package not built: 503
    throw new HttpError(409, (e as Error).message);
  }
}
