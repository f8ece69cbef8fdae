/**
 * Where things are in a Cactal project and its generated tree (docs/codegen.md "The generated
 * tree"): the one spelling every package uses.
 */

/** The folder of a project that holds the generated C tree (the default output of `contract generate`). */
export const SRC_GEN_DIR = 'src-gen';

/** The generated architecture inside the output folder (its top Makefile, modules/, common/, tools/). */
export const ARCHITECTURE_DIR = 'generated/architecture';

/** The architecture's folder relative to the project: `src-gen/generated/architecture`. */
export const SRC_GEN_ARCHITECTURE_DIR = `${SRC_GEN_DIR}/${ARCHITECTURE_DIR}`;

/** Path of a file of the generated architecture, relative to the output folder (`generated/architecture/<rel>`). */
export function architecturePath(rel: string): string {
    return `${ARCHITECTURE_DIR}/${rel}`;
}

/**
 * The folders that hold every one of `files` (project-relative `/` paths of its `.contract` files),
 * deepest first, the project's own folder ('') not included. A project run one folder too high
 * (`contract generate .` at a repository's root) has its files all in one of them, which has its
 * own `src-gen/`: `contract generate` and a build refuse it then, rather than make a second,
 * fresh tree here or build without the user's code.
 */
export function foldersHoldingAll(files: readonly string[]): string[] {
    if (!files.length) return [];
    let common = files[0]!.split('/').slice(0, -1);
    for (const f of files.slice(1)) {
        const parts = f.split('/').slice(0, -1);
        let n = 0;
        while (n < common.length && n < parts.length && common[n] === parts[n]) n++;
        common = common.slice(0, n);
    }
    return common.map((_, i) => common.slice(0, common.length - i).join('/'));
}

/**
 * What the files a generation copied to `src-gen/orphans/` hold, as the CLI's list and the IDE's
 * Generate panel name them: user code whose region or entity is gone, or, in a tree without a
 * manifest (an older version's, the Eclipse tool's), whole files holding lines outside the regions
 * that this generator does not write, which may be an older generator's lines only.
 */
export const ORPHANS_HOLD = 'code moved aside, or lines this generator does not write';

/** The record of what the generator wrote, in its output folder (codegen's writer/manifest.ts): a `src-gen/` holding it is a tree ContrACT Studio generated. */
export const MANIFEST_NAME = '.contract-manifest.json';

/** The last generation's copy of the user code in the protected regions, in its output folder (codegen's region-copy.ts): a generated file deleted by hand gets it back. */
export const REGION_COPY_NAME = '.contract-regions.json';

/** Folder of the output folder where a generation moves user code it cannot place (codegen's orphans.ts). */
export const ORPHANS_DIR = 'orphans';

/** The write lock of a generated tree, in its output folder (codegen's tree-lock.ts); no listing of the tree shows it. */
export const TREE_LOCK_NAME = '.contract-lock';

/** The journal of a rename under way, in its output folder (codegen's rename-journal.ts): there only while a rename runs, or after one was killed. */
export const RENAME_JOURNAL_NAME = '.contract-rename.json';
