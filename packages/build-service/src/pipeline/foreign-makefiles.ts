/**
 * Makefiles of the user's generated tree that are not the generated ones. GNU make, run in a folder
 * without `-f`, reads `GNUmakefile`, then `makefile`, then `Makefile`: a `GNUmakefile` placed beside
 * the generated `Makefile` (a cloned repository's, or a hostile one's) would be the build, and its
 * `all`/`run` could print anything and end "ok" with no module built or run. The build runs every
 * make of the tree with `-f Makefile` (job.ts, and the recursive makes of codegen's generated
 * Makefiles), which include no other file; a project holding such a file is still refused, naming
 * it: nothing of the user's is left out without a word, and no one reads a success that their
 * makefile did not make.
 */
import { SRC_GEN_DIR, visibleText } from '@contract-studio/conventions';

/** The names GNU make reads before `Makefile` in a folder it is run in without `-f`. */
export const MAKEFILE_NAMES_BEFORE_THE_GENERATED = ['GNUmakefile', 'makefile'] as const;

/** Where the build's makes run: the generated tree's `generated/` (not `orphans/`, which no make reads). */
const BUILT = `${SRC_GEN_DIR}/generated/`;

/** The project-relative paths (`src-gen/generated/...`) among `files` that make would read instead of a generated Makefile. */
export function foreignMakefiles(files: Iterable<string>): string[] {
  const names: ReadonlySet<string> = new Set(MAKEFILE_NAMES_BEFORE_THE_GENERATED);
  return [...files].filter((rel) => rel.startsWith(BUILT) && names.has(rel.split('/').pop()!)).sort();
}

/**
 * The refusal of a project whose generated tree holds such makefiles (the first 5 named), each
 * path as `pathOf` writes it: the service's, relative to the project; the CLI's, from where the
 * command was typed (`DIR/src-gen/...`).
 */
export function foreignMakefilesMessage(found: readonly string[], pathOf: (rel: string) => string = (rel) => rel): string {
  const named = found.slice(0, 5).map((f) => visibleText(pathOf(f))).join(', ') + (found.length > 5 ? ` and ${found.length - 5} more` : '');
  return `${named}: a makefile in the generated tree that is not the generated one (GNU make would read it instead of `
    + 'the generated Makefile, and its recipes would be the build); a Cactal build runs only the generated Makefiles: '
    + 'remove it, or rename it (the generated Makefiles never read it); nothing was built';
}
