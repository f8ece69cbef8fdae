import { posix } from 'node:path';

/**
 * A file's text in the generated tree as it stands after the generation (protected regions
 * included); undefined when there is no such file. Throws when it cannot tell (a file that could
 * not be read or written).
 */
export type TreeText = (path: string) => string | undefined;

/** One `#include` line of C text: the name between the quotes or angle brackets. */
export interface IncludeLine {
    name: string;
    /** `#include "name"` (searched first in the including file's folder), not `#include <name>`. */
    quoted: boolean;
}

const INCLUDE = /^[ \t]*#[ \t]*include[ \t]*(?:"([^"\r\n]+)"|<([^>\r\n]+)>)/gm;

/**
 * The `#include` lines of `text`, in order: the generator's and those written in protected
 * regions alike. Commented-out or `#if 0` lines count too (a dependency too many, never one too few).
 */
export function includeLines(text: string): IncludeLine[] {
    return [...text.matchAll(INCLUDE)].map((m) => (m[1] !== undefined ? { name: m[1], quoted: true } : { name: m[2]!, quoted: false }));
}

const COMPUTED_INCLUDE = /^[ \t]*#[ \t]*include[ \t]*[^"<\s]/m;

/** Whether `text` has an `#include` whose name is a macro (`#include HELPER_H`): one the generator cannot follow. */
export function hasComputedInclude(text: string): boolean {
    return COMPUTED_INCLUDE.test(text);
}

/** Where an executable's compilation looks for headers (tree paths): its own folder (`-I.`) and common/ (`-I<common>`). */
export interface IncludeFolders {
    own: string;
    common: string;
}

/**
 * The tree paths an `#include` of `including` can name: for `"name"`, the including file's folder,
 * then the executable's own folder and common/; for `<name>`, those two. Paths leaving the tree
 * (`../..` past its root, absolute names) are the runtime's or the system's: none.
 */
function candidates(including: string, line: IncludeLine, folders: IncludeFolders): string[] {
    if (posix.isAbsolute(line.name)) return [];
    const dirs = line.quoted ? [posix.dirname(including), folders.own, folders.common] : [folders.own, folders.common];
    const paths = dirs.map((d) => posix.normalize(posix.join(d, line.name))).filter((p) => !p.startsWith('../') && p !== '..');
    return [...new Set(paths)];
}

/**
 * The files of common/ (the headers of `generatedCommon`, the tree paths of those the generator
 * writes there, and any file of your own there, in a subfolder too) that compiling `sources` can
 * include: named by an `#include` of a source, or of a header of the
 * tree those include, and so on (the generated headers' own includes, those written in protected
 * regions, and those of a user's header in the tree), sorted. Every candidate of an include that
 * exists is followed (a dependency too many, never one too few). Undefined when a file could not
 * be read: the caller then depends on every header.
 */
export function includedCommonHeaders(sources: string[], folders: IncludeFolders, generatedCommon: ReadonlySet<string>, textOf: TreeText): string[] | undefined {
    const files = includedFiles(sources, folders, textOf);
    return files && commonFiles(files, generatedCommon, folders.common);
}

/** Those of `files` (tree paths) that are in common/: a generated header, or a file of your own there (a helper .c, a header in a subfolder). */
export function commonFiles(files: readonly string[], generatedCommon: ReadonlySet<string>, common: string): string[] {
    return files.filter((p) => generatedCommon.has(p) || p.startsWith(`${common}/`));
}

/**
 * Every file of the tree that compiling `sources` can include (as includedCommonHeaders follows
 * them: any folder, the own folder's files too), not `sources` themselves, sorted; undefined when a
 * file could not be read.
 */
export function includedFiles(sources: string[], folders: IncludeFolders, textOf: TreeText): string[] | undefined {
    const seen = new Set<string>(sources);
    const pending = [...sources];
    const found = new Set<string>();
    try {
        for (let path = pending.pop(); path !== undefined; path = pending.pop()) {
            const text = textOf(path);
            if (text === undefined) continue;
            for (const line of includeLines(text)) {
                for (const candidate of candidates(path, line, folders)) {
                    if (seen.has(candidate) || textOf(candidate) === undefined) continue;
                    seen.add(candidate);
                    pending.push(candidate);
                    found.add(candidate);
                }
            }
        }
    } catch {
        return undefined;
    }
    return [...found].sort();
}
