/**
 * A rename carried into the user code of the generated tree (docs/codegen.md, "Your code that uses
 * the renamed name"): which C identifiers a rename changes (identifierRenames), their uses in the
 * protected regions' code rewritten (renameIdentifiersInGeneratedTree), and the regions that still
 * mention the old name afterwards (findRegionMentions), for `contract rename` and the IDE.
 */
import { cEnumMember } from '../generators/c/c-syntax.js';
import { parseRegions } from '../regions/parse-regions.js';
import { bytesOf } from './byte-string.js';
import { cWords, type WordContext } from './c-identifiers.js';
import { ORPHANS_DIR } from './orphans.js';
import type { OutputTree } from './output-tree.js';
import { openTreeForCarry } from './rename-generated.js';

/** A protected region whose content mentions a name (file and line of the mention). */
export interface RegionMention {
    file: string;
    line: number;
    /** The region's ID. */
    id: string;
    /** The word found (the name, or a generated name made of it: `eq_TypeA`, `SharedTypeA`). */
    word: string;
    /** Where in the region: C code (the build needs it changed), a comment, or a string or character literal. */
    context: WordContext;
}

/**
 * Whether a word of user code refers to the entity `name` of kind `kind` (the words of the
 * language's rename: `module`, `datatype`, `enumeration`, `function`, `port`, `parameter`, ...):
 * the name itself, and for a datatype or an enumeration the generated functions and header named
 * after it (`eq_TypeA`, ..., `SharedTypeA` of `#include "SharedTypeA.h"`) and an enumeration's
 * constants (`Mode_AUTO`), for a function its header (`SharedFunctiondoit`); for an enumeration
 * member only its constant (`Mode_AUTO`: the bare member name is no C name).
 */
export function mentionMatcher(kind: string, name: string, enumeration: EnumerationNames = {}): (word: string) => boolean {
    return oldNamesMatcher(kind, name, identifierRenames(kind, name, name, enumeration).keys());
}

/**
 * mentionMatcher of a rename of `name`, of kind `kind`, whose C identifiers (identifierRenames'
 * old names) are `identifiers`: a rename's journal holds them (finishing a rename killed half-way).
 */
export function oldNamesMatcher(kind: string, name: string, identifiers: Iterable<string>): (word: string) => boolean {
    const words = new Set([...(kind === 'enumeration member' ? [] : [name]), ...identifiers]);
    if (kind === 'datatype' || kind === 'enumeration') words.add(`Shared${name}`);
    if (kind === 'function') words.add(`SharedFunction${name}`);
    return (w) => words.has(w);
}

/** Generated C files (.c, .h) of the tree, `orphans/` excepted, reached from opened folders. */
function generatedCFiles(tree: OutputTree, rel: string, out: string[]): string[] {
    for (const e of tree.list(rel) ?? []) {
        const child = rel ? `${rel}/${e.name}` : e.name;
        if (e.isDirectory()) {
            if (child !== ORPHANS_DIR) generatedCFiles(tree, child, out);
        } else if (e.isFile() && /\.(c|h)$/.test(e.name)) out.push(child);
    }
    return out.sort();
}

function lineOf(text: string, offset: number, from: number, fromLine: number): number {
    let line = fromLine;
    for (let i = from; i < offset; i++) if (text.charCodeAt(i) === 10) line++;
    return line;
}

/** The mentions of `matches` in the protected regions of `text` (member names in code excepted). A malformed file has none. */
function mentionsIn(rel: string, text: string, matches: (word: string) => boolean): RegionMention[] {
    const out: RegionMention[] = [];
    let regions;
    try {
        regions = parseRegions(text, rel).regions;
    } catch {
        return out; // generate reports a malformed file with its line
    }
    for (const r of regions) {
        for (const w of cWords(r.content)) {
            if (!matches(w.word) || (w.context === 'code' && w.member)) continue;
            out.push({ file: rel, line: lineOf(text, r.contentStart + w.offset, r.start, r.line), id: r.id, word: w.word, context: w.context });
        }
    }
    return out;
}


/**
 * The protected regions of the generated tree `srcGen` that still mention a name (after a rename:
 * user code the rename could not change), optionally only in files under a folder `<owner>_mod`.
 * Paths relative to `srcGen`; `orphans/` is not searched. A missing tree has none.
 */
export function findRegionMentions(srcGen: string, matches: (word: string) => boolean, owner?: string): RegionMention[] {
    const tree = openTreeForCarry(srcGen, 'search the protected regions');
    if (!tree) return [];
    try {
        const out: RegionMention[] = [];
        for (const rel of generatedCFiles(tree, '', [])) {
            if (owner !== undefined && !rel.split('/').includes(`${owner}_mod`)) continue;
            const text = tree.read(rel);
            if (text !== undefined && text.includes('PROTECTED')) out.push(...mentionsIn(rel, text, matches));
        }
        return out;
    } finally {
        tree.close();
    }
}

export interface IdentifierCarryReport {
    /** Regions whose code was rewritten: uses of an old name (whole C identifiers, in code, not member names) now use the new one. */
    rewritten: Array<{ file: string; line: number; id: string; occurrences: number }>;
    /** Mentions of the old names left in the searched regions: in comments and literals, or in code when the rewrite was refused. */
    remaining: RegionMention[];
    /**
     * Why uses in code were not rewritten, when they were not: the first use in code of a new name
     * in a file whose code also uses the old one (its file relative to the tree, as every file
     * here), which a local of that name would capture.
     */
    refused?: RegionMention;
}

/**
 * Why a carry was refused (IdentifierCarryReport.refused), as one sentence: the new name's use, at
 * `where` (its file relative to the tree and line by default; the CLI's from where it ran).
 */
export function carryRefusedMessage(taken: RegionMention, oldNames: readonly string[], where = `${taken.file}:${taken.line}`): string {
    return `'${taken.word}' is already used in the code of protected region ${taken.id} (${where}): uses of '${oldNames.join("', '")}' were not rewritten`;
}

/** The generated functions named after a datatype (shared-type-header.ts, shared-enum-header.ts). */
const TYPE_FUNCTIONS = ['serialize', 'deserialize', 'set', 'get', 'print', 'eq', 'diff', 'inf', 'sup', 'infeq', 'supeq'];

/**
 * What the C names of an enumeration are made of besides its name (shared-enum-header.ts): its
 * members, for an enumeration's rename (the constants `<Enum>_<member>`), and the enumeration, for
 * a member's rename (its constant).
 */
export interface EnumerationNames {
    /** The members of a renamed enumeration. */
    members?: readonly string[];
    /** The enumeration of a renamed member. */
    enumeration?: string;
}

/**
 * The C identifiers a rename changes in user code, old -> new: a port's or parameter's variable,
 * a function, a datatype and its generated functions (`eq_TypeA`, `print_TypeA`, ...), an
 * enumeration, its generated functions and its constants (`Mode_AUTO` -> `Drive_AUTO`), an
 * enumeration member's constant (`Mode_AUTO` -> `Mode_AUTOMATIC`). Empty for other kinds (a
 * module's or supervisor's name is in strings, if anywhere: reported, not rewritten).
 */
export function identifierRenames(kind: string, from: string, to: string, enumeration: EnumerationNames = {}): Map<string, string> {
    if (kind === 'port' || kind === 'parameter' || kind === 'function') return new Map([[from, to]]);
    const typeFunctions = TYPE_FUNCTIONS.map((f): [string, string] => [`${f}_${from}`, `${f}_${to}`]);
    if (kind === 'datatype') return new Map([[from, to], ...typeFunctions]);
    if (kind === 'enumeration') {
        const constants = (enumeration.members ?? []).map((m): [string, string] => [cEnumMember(from, m), cEnumMember(to, m)]);
        return new Map([[from, to], ...typeFunctions, ...constants]);
    }
    if (kind === 'enumeration member' && enumeration.enumeration !== undefined) {
        return new Map([[cEnumMember(enumeration.enumeration, from), cEnumMember(enumeration.enumeration, to)]]);
    }
    return new Map();
}

/** `text` with every use in code (not a member name) of an identifier of `renames` replaced; how many. */
function renameIdentifiers(text: string, renames: Map<string, string>): { text: string; count: number } {
    let out = '';
    let cursor = 0;
    let count = 0;
    for (const w of cWords(text)) {
        const to = w.context === 'code' && !w.member ? renames.get(w.word) : undefined;
        if (to === undefined) continue;
        out += text.slice(cursor, w.offset) + to;
        cursor = w.offset + w.word.length;
        count++;
    }
    return { text: out + text.slice(cursor), count };
}

/**
 * The uses in code of a new name of `renames` that a rewrite of file `rel` would capture: those of
 * a file whose code also uses the old name it replaces (a local or a global of the new name there
 * would take the rewritten uses; a file is one translation unit, so any two of its regions count).
 * A file whose code holds the new name and not the old one has nothing to rewrite, nothing to
 * capture: the new name's own uses, or a file rewritten already (by a rename killed half-way,
 * whose finishing carries the rename over again).
 */
function capturingUses(rel: string, text: string, renames: Map<string, string>): RegionMention[] {
    const names = new Set([...renames.keys(), ...renames.values()]);
    const inCode = mentionsIn(rel, text, (w) => names.has(w)).filter((m) => m.context === 'code');
    const usedOld = new Set(inCode.map((m) => m.word).filter((w) => renames.has(w)));
    const capturedBy = new Set([...renames].filter(([from]) => usedOld.has(from)).map(([, to]) => to));
    return inCode.filter((m) => capturedBy.has(m.word));
}

/**
 * Carries a rename over in the user code of the generated tree `srcGen` (only the files under a
 * folder `<owner>_mod` when `owner` is given: a port or parameter is a variable of its module's
 * module.c): every use of an old name of `renames` in the protected regions' code, as a whole C
 * identifier and not a member name (`x.old`, `p->old`) nor in a comment or literal, becomes the
 * new name. Refused (nothing changed, every use reported) when a file's code uses both an old name
 * and the new one replacing it (a local of the new name would capture the uses: capturingUses); a
 * file already using only the new name (rewritten before a rename was killed) does not stop the others. User code is otherwise kept byte for
 * byte; files' skeletons do not change; `orphans/` is not touched.
 */
export function renameIdentifiersInGeneratedTree(srcGen: string, renames: Map<string, string>, owner?: string): IdentifierCarryReport {
    for (const name of [...renames.keys(), ...renames.values(), ...(owner !== undefined ? [owner] : [])]) {
        if (!/^[A-Za-z_][A-Za-z0-9_]*$/.test(name)) throw new Error(`invalid name: ${name}`);
    }
    const report: IdentifierCarryReport = { rewritten: [], remaining: [] };
    if (renames.size === 0) return report;
    const tree = openTreeForCarry(srcGen, `carry ${[...renames.keys()][0]} -> ${[...renames.values()][0]} over in the protected regions`);
    if (!tree) return report;
    try {
        tree.lock(); // one writer of the tree at a time (tree-lock.ts)
        const files: Array<{ rel: string; text: string; regions: ReturnType<typeof parseRegions>['regions'] }> = [];
        for (const rel of generatedCFiles(tree, '', [])) {
            if (owner !== undefined && !rel.split('/').includes(`${owner}_mod`)) continue;
            const text = tree.read(rel);
            if (text === undefined || !text.includes('PROTECTED')) continue;
            try {
                files.push({ rel, text, regions: parseRegions(text, rel).regions });
            } catch {
                // malformed: left as it is (generate reports it with its line)
            }
        }
        const taken = files.flatMap((f) => capturingUses(f.rel, f.text, renames));
        if (taken.length > 0) {
            report.refused = taken[0]!;
        } else {
            for (const f of files) {
                let next = '';
                let cursor = 0;
                for (const r of f.regions) {
                    const renamed = renameIdentifiers(r.content, renames);
                    if (renamed.count === 0) continue;
                    next += f.text.slice(cursor, r.contentStart) + renamed.text;
                    cursor = r.contentEnd;
                    report.rewritten.push({ file: f.rel, line: r.line, id: r.id, occurrences: renamed.count });
                }
                if (cursor === 0) continue;
                next += f.text.slice(cursor);
                tree.write(f.rel, bytesOf(next));
                f.text = next;
            }
        }
        for (const f of files) report.remaining.push(...mentionsIn(f.rel, f.text, (w) => renames.has(w)));
        return report;
    } finally {
        tree.close();
    }
}

/** A renamed port or parameter of module `owner`: renameIdentifiersInGeneratedTree on that module's files. */
export function renameIdentifierInGeneratedTree(srcGen: string, owner: string, from: string, to: string): IdentifierCarryReport {
    return renameIdentifiersInGeneratedTree(srcGen, new Map([[from, to]]), owner);
}
