/**
 * What the IDE tells its language worker about the workspace's projects (docs/codegen.md "Where a
 * project is"): the worker holds only the files opened so far, the IDE lists the whole tree.
 */
import { SRC_GEN_DIR } from '@contract-studio/conventions';

export interface ProjectLayout {
  /** The workspace folder's URI (`file:///workspace`). */
  root: string;
  /** The folders holding a `src-gen/` folder, relative to the root ('' = the root itself), sorted. */
  trees: string[];
  /** Every `.contract` file of the workspace, relative to the root, sorted. */
  contracts: string[];
}

/** The layout of a workspace whose folders are `dirs` and `.contract` files `contracts` (paths relative to the root). */
export function projectLayout(root: string, dirs: Iterable<string>, contracts: readonly string[]): ProjectLayout {
  const suffix = `/${SRC_GEN_DIR}`;
  const trees = [...dirs].filter((d) => d === SRC_GEN_DIR || d.endsWith(suffix)).map((d) => (d === SRC_GEN_DIR ? '' : d.slice(0, -suffix.length)));
  return { root, trees: trees.sort(), contracts: [...contracts].sort() };
}
