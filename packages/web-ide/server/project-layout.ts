/**
 * The project rule of conventions' project-root.ts (docs/codegen.md "Where a project is") on the
 * server: Generate All refuses a folder that is inside another project (its root holds the
 * `src-gen/` with the user's code), and says which trees of the project it does not use.
 */
import { lstatSync } from 'node:fs';
import { join } from 'node:path';
import { SRC_GEN_DIR, projectRootsOf, unusedTreeWarning } from '@contract-studio/conventions';
import { HttpError } from './http-error.js';

const isTreeFolder = (path: string): boolean => lstatSync(path, { throwIfNoEntry: false })?.isDirectory() ?? false;

/** A workspace folder `project` ('' = the root) one of whose folders above holds a `src-gen/`: refused (409), naming the project it belongs to. */
export function checkProjectRoot(workspaceRoot: string, project: string): void {
  const parts = project.split('/').filter(Boolean);
  for (let n = 0; n < parts.length; n++) {
    const above = parts.slice(0, n).join('/');
    if (!isTreeFolder(join(workspaceRoot, above, SRC_GEN_DIR))) continue;
    const name = above || 'the workspace root';
    throw new HttpError(409, `${project} is not a project: it is inside project ${name}, which holds the generated tree ${above ? `${above}/` : ''}${SRC_GEN_DIR}/ (the outermost folder holding a ${SRC_GEN_DIR}/ is the project; docs/codegen.md "Where a project is"): generate ${name}; nothing was generated`);
  }
}

/** The warnings for the trees of project folder `dir` (opened path; workspace path `project`) that are not used, naming workspace paths. */
export function unusedTreeWarnings(dir: string, project: string, contractFiles: readonly string[]): string[] {
  const { unusedTrees } = projectRootsOf(contractFiles, (folder) => isTreeFolder(join(dir, folder, SRC_GEN_DIR)));
  return unusedTrees.map((u) => unusedTreeWarning(project ? `${project}/${u}` : u, project, project || 'the workspace root'));
}
