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
