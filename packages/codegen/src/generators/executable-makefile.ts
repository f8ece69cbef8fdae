import { posix } from 'node:path';
import { architecturePath } from '@contract-studio/conventions';
import type { GeneratedFile } from '../writer/write-tree.js';
import { commonFiles, hasComputedInclude, includedFiles, type TreeText } from './header-dependencies.js';

/** The generated tree's common/ folder (the shared headers). */
export const COMMON_DIR = architecturePath('common');

/**
 * The files of common/ an executable's Makefile makes it depend on: those its sources include,
 * generated or yours (undefined: unknown, every header of common/), and every generated one.
 */
export interface CommonHeaderDependencies {
    included: string[] | undefined;
    generated: string[];
    /**
     * The files of the executable's own folder its sources include (names in that folder; its
     * sources not among them): named in the Makefile, so that one deleted changes the Makefile,
     * which its executable depends on (rebuilt: the compiler then says the file is missing).
     */
    own?: string[] | undefined;
    /**
     * Its sources, or a file they include, have an `#include` the generator cannot follow (a macro
     * name): every file of your own at common/'s top is then a dependency too (one too many, never
     * one too few).
     */
    unfollowed?: boolean;
}

/**
 * The Makefile lines defining COMMON_HEADERS (the headers of common/ the executable includes) and
 * GENERATED_COMMON_HEADERS, by name; `common` is common/ as the Makefile names it (e.g. `../../common`).
 */
export function commonHeaderVariables(common: string, deps: CommonHeaderDependencies): string {
    // by their path in common/ (a file of your own may be in a subfolder)
    const names = (paths: string[]) => paths.map((p) => posix.relative(COMMON_DIR, p));
    const variable = (name: string, values: string[]) => [`${name} =`, ...values].join(' ');
    return [
        deps.included !== undefined
            ? `# the files of ${common} this executable includes: named by its sources (protected regions too) or by the files they include`
            : `# a file could not be read when this Makefile was generated: every header of ${common}`,
        variable('COMMON_HEADERS', deps.included !== undefined ? names(deps.included) : [`$(notdir $(wildcard ${common}/*.h))`]),
        `# the headers the generator writes in ${common}`,
        variable('GENERATED_COMMON_HEADERS', names(deps.generated)),
        '# the files of this folder the sources include (one removed changes this Makefile, which the executable depends on)',
        variable('OWN_FILES', deps.own ?? []),
    ].join('\n');
}

/**
 * The prerequisites of an executable on common/: the files it includes, found by the generator in
 * the tree as written (a file of yours included since is found at the next generation, which
 * `contract build` makes first). When the generator could not follow every include (a file it
 * could not read, an `#include` of a macro name), also every `.h`, `.c` and `.inc` of your own at
 * common/'s top: a dependency too many, never one too few.
 */
export function commonHeaderPrerequisites(common: string, deps: CommonHeaderDependencies): string {
    const included = `$(addprefix ${common}/,$(COMMON_HEADERS))`;
    if (deps.included !== undefined && !deps.unfollowed) return included;
    return `${included} $(filter-out $(addprefix ${common}/,$(GENERATED_COMMON_HEADERS)),$(wildcard ${common}/*.h ${common}/*.c ${common}/*.inc))`;
}

/** An executable's Makefile to generate: at `path`, compiling `sources` (tree paths) in `own` (its folder). */
export interface ExecutableMakefile {
    path: string;
    sources: string[];
    own: string;
    render: (deps: CommonHeaderDependencies) => string;
}

/**
 * The Makefiles of executables (modules', control tools'), each with its text for the freshly
 * generated tree (`files`, every protected region at its default) and how to derive it again from
 * the tree as written, protected regions included (the writer calls `derive` after writing the
 * other files): each executable depends on the headers of common/ it can include, no other
 * generated one, so that a change to one datatype rebuilds only the executables using it.
 */
export function executableMakefiles(makefiles: readonly ExecutableMakefile[], files: readonly GeneratedFile[]): GeneratedFile[] {
    const generated = files.map((f) => f.path).filter((p) => posix.dirname(p) === COMMON_DIR && p.endsWith('.h')).sort();
    const generatedSet = new Set(generated);
    const fresh = new Map(files.map((f) => [f.path, f.content]));
    return makefiles.map(({ path, sources, own, render }) => {
        const text = (textOf: TreeText) => {
            const folders = { own, common: COMMON_DIR };
            const files = includedFiles(sources, folders, textOf);
            return render({
                included: files && commonFiles(files, generatedSet, COMMON_DIR),
                generated,
                own: files?.filter((p) => posix.dirname(p) === own).map((p) => posix.basename(p)),
                unfollowed: files !== undefined && [...sources, ...files].some((p) => hasComputedInclude(textOf(p) ?? '')),
            });
        };
        let content: string | undefined;
        // the text for a fresh tree is made when asked for: the writer derives it from the tree as written instead
        return { path, get content() { return (content ??= text((p) => fresh.get(p))); }, derive: text };
    });
}
