/**
 * Where a project's root is (and so its `src-gen/`): the one rule of `contract generate`,
 * `build`, `run`, a build job and the IDE (docs/codegen.md "Where a project is").
 *
 * Inside an opened folder (the DIR given to the CLI, the workspace of `contract serve`), the root
 * of the project a path belongs to is:
 *
 * 1. the outermost folder, from the opened folder down to the path's own folder, that holds a
 *    `src-gen/` folder: the generated tree holds the user's code, so the folder that has one is
 *    the project (the Eclipse layout `P/src/*.contract` + `P/src-gen/` is project `P`); any other
 *    `src-gen/` on the way down is a second tree of the same project, not used, and said;
 * 2. without one: the opened folder, when it holds a `.contract` file itself or all its
 *    `.contract` files are in one first-level folder (`P/src/*.contract`: project `P`, as
 *    `contract generate P` writes `P/src-gen`);
 * 3. otherwise (a folder of several projects, like `examples/`): the first-level folder holding
 *    the path.
 */
import { SRC_GEN_DIR } from './layout.js';

export interface ProjectRoot {
    /** The project's folder, relative to the opened folder with `/` separators ('' = the opened folder). */
    root: string;
    /** Folders below the root, on the way to the path, that hold a `src-gen/` too: trees of this project that are not used. */
    unusedTrees: string[];
}

/**
 * `hasTree(folder)`: folder ('' = the opened folder) holds a `src-gen/` folder (a real folder, not
 * a link). `contractFiles`: the `.contract` files of the opened folder, relative (for rules 2 and 3).
 */
export type TreeProbe = (folder: string) => boolean;

/** The folders holding `path` (a relative file path), outermost first, up to the first `src-gen` component (a generated tree's inside is no project). */
function foldersOf(path: string): string[] {
    const parts = path.split('/').filter(Boolean).slice(0, -1);
    const out = [''];
    for (let i = 0; i < parts.length && parts[i] !== SRC_GEN_DIR; i++) out.push(parts.slice(0, i + 1).join('/'));
    return out;
}

/** A `.contract` file of the opened folder itself (not one imported from outside it, `../lib/x.contract`), outside any generated tree. */
const isOwnModel = (f: string): boolean => !f.startsWith('/') && !f.split('/').slice(0, -1).some((c) => c === '..' || c === SRC_GEN_DIR);

/** The root of the project that `path` (relative to the opened folder) belongs to, by the rule above. */
export function projectRootOf(path: string, hasTree: TreeProbe, contractFiles: readonly string[]): ProjectRoot {
    return projectRootFinder(contractFiles, hasTree)(path);
}

/**
 * `projectRootOf` for many paths of one opened folder: what rules 2 and 3 need of its `.contract`
 * files is worked out once, so each path costs only the probes of its own folders (the language
 * asks it for every file of a workspace).
 */
export function projectRootFinder(contractFiles: readonly string[], hasTree: TreeProbe): (path: string) => ProjectRoot {
    const models = contractFiles.filter(isOwnModel);
    const oneProject = models.some((f) => !f.includes('/')) || new Set(models.map((f) => f.slice(0, f.indexOf('/')))).size <= 1;
    return (path) => {
        const trees = foldersOf(path).filter((f) => hasTree(f));
        if (trees.length) return { root: trees[0]!, unusedTrees: trees.slice(1) };
        if (oneProject) return { root: '', unusedTrees: [] };
        const slash = path.indexOf('/');
        return { root: slash < 0 ? '' : path.slice(0, slash), unusedTrees: [] };
    };
}

/** The projects of an opened folder's `.contract` files: their roots (sorted), and every unused tree met on the way to them. */
export function projectRootsOf(contractFiles: readonly string[], hasTree: TreeProbe): ProjectRoot & { roots: string[] } {
    const roots = new Set<string>();
    const unused = new Set<string>();
    const rootOf = projectRootFinder(contractFiles, hasTree);
    for (const f of contractFiles.filter(isOwnModel)) {
        const r = rootOf(f);
        roots.add(r.root);
        for (const u of r.unusedTrees) unused.add(u);
    }
    const sorted = [...roots].sort();
    return { roots: sorted, root: sorted[0] ?? '', unusedTrees: [...unused].sort() };
}

/** A log line of `unusedTreeWarning` (with its `warning: `). */
export const UNUSED_TREE_LINE = /^warning: .*\/ is a second generated tree of this project, not used: /;

/**
 * The warning (without its `warning: `) for a tree of the project that is not used: `unused` and
 * `root` (the project's folder, '' when paths are shown from it) as the caller shows folders;
 * `rootName` what the project is called.
 */
export function unusedTreeWarning(unused: string, root: string, rootName = root): string {
    const tree = `${root ? `${root.replace(/\/+$/, '')}/` : ''}${SRC_GEN_DIR}/`;
    return `${unused}/${SRC_GEN_DIR}/ is a second generated tree of this project, not used: the project is ${rootName} and its tree ${tree} (the outermost folder holding a ${SRC_GEN_DIR}/ is the project; docs/codegen.md "Where a project is"): move any code of yours out of ${unused}/${SRC_GEN_DIR}/, then delete it`;
}
