/**
 * The project a folder given to `contract generate`, `build` or `run` lies inside (docs/codegen.md
 * "Where a project is"): the nearest folder above it holding a generated tree, a `src-gen/` with
 * ContrACT Studio's manifest or with the tree's `generated/architecture/` (the Eclipse tool's tree,
 * which has no manifest). By the rule's first point that folder is the project of every `.contract`
 * file below it: a folder inside it is no project of its own. Generating or building it made an
 * empty second tree, `P/src/src-gen`, beside the user's code in `P/src-gen` (field test ft69: the
 * Eclipse layout `P/src/*.contract` + `P/src-gen/`, generated as `contract generate P/src`).
 */
import { lstatSync } from 'node:fs';
import { basename, dirname, join, relative } from 'node:path';
import { ARCHITECTURE_DIR, MANIFEST_NAME, SRC_GEN_DIR } from '@contract-studio/conventions';
import { safeName } from './terminal-text.js';

const isFolder = (path: string): boolean => lstatSync(path, { throwIfNoEntry: false })?.isDirectory() ?? false;
const isFile = (path: string): boolean => lstatSync(path, { throwIfNoEntry: false })?.isFile() ?? false;

/** `folder` holds a generated tree: `src-gen/` a real folder, with a manifest or a `generated/architecture/`. */
export function holdsGeneratedTree(folder: string): boolean {
    const tree = join(folder, SRC_GEN_DIR);
    return isFolder(tree) && (isFile(join(tree, MANIFEST_NAME)) || isFolder(join(tree, ARCHITECTURE_DIR)));
}

/** The nearest folder above `dir` (absolute) holding a generated tree, `dir` not inside that tree; null when there is none. */
export function enclosingProject(dir: string): string | null {
    for (let child = dir, above = dirname(dir); above !== child; child = above, above = dirname(above)) {
        if (basename(child) === SRC_GEN_DIR) continue; // inside a tree: it is no folder of the project's sources
        if (holdsGeneratedTree(above)) return above;
    }
    return null;
}

/**
 * The refusal of `contract <command> DIR` when DIR (`dir`, given as `dirArg`) lies inside a project,
 * naming it as the user can type it and the command to run instead; null when it does not.
 */
export function insideProjectRefusal(dir: string, dirArg: string, command: 'generate' | 'build' | 'run', nothing: string): string | null {
    const project = enclosingProject(dir);
    if (!project) return null;
    const shown = safeName(join(dirArg, relative(dir, project)));
    return `${safeName(dirArg)} is inside project ${shown}, whose generated tree ${join(shown, SRC_GEN_DIR)}/ holds your code (the folder holding a ${SRC_GEN_DIR}/ is the project: docs/codegen.md "Where a project is"): ${command} the project instead, contract ${command} ${shown}; nothing was ${nothing}`;
}
