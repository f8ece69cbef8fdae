/**
 * Carry-over of a renamed entity in an existing generated tree (docs/codegen.md, "Renaming an
 * entity"): its files and folders are renamed and the protected-region IDs that name it rewritten,
 * so that the next generation finds the user code under the new IDs and nothing becomes an orphan.
 * Shared by the IDE's rename refactoring and `contract rename`, so that both behave the same.
 * User code is handled as byte strings and kept byte for byte.
 */
import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import { START_MARKER } from '../regions/markers.js';
import { parseRegions } from '../regions/parse-regions.js';
import { bytesOf } from './byte-string.js';
import { cWords, type WordContext } from './c-identifiers.js';
import { hashContent, loadManifest, MANIFEST_NAME, serialiseManifest, skeletonHash, type ManifestLoad } from './manifest.js';
import { ORPHANS_DIR } from './orphans.js';
import { OutputTree } from './output-tree.js';
import { checkTreeRoot, linkRefused } from './safe-paths.js';

const ENTITY_NAME = /^[A-Za-z][A-Za-z0-9_]*$/;

export interface RenameGeneratedReport {
    movedPaths: Array<{ from: string; to: string }>;
    rewrittenFiles: string[];
    regionIds: Array<{ file: string; from: string; to: string }>;
    /** `MODULE_DESCRIPTION` regions still holding the generated default (`"synchronous module OLD"`), now naming NEW. */
    descriptions: Array<{ file: string; line: number; from: string; to: string }>;
}

/** What is carried over per rewritten file, for the manifest: its skeleton before and after, and changed default hashes. */
interface FileCarry {
    skeletonBefore?: string;
    skeletonAfter?: string;
    /** region ID (new) -> [hash of the content before, hash after] */
    contents: Map<string, [string, string]>;
}

/** Rewrites one protected-region ID when the entity name is one of its `_`/`.`-separated parts. */
export function renameRegionId(id: string, from: string, to: string): string {
    return id
        .split(/([_.])/)
        .map((part) => (part === from ? to : part))
        .join('');
}

/** File or folder names that carry an entity name in the generated tree (docs/codegen.md). */
export function renameGeneratedName(name: string, from: string, to: string): string {
    const patterns: Array<[string, string]> = [
        [`${from}_mod`, `${to}_mod`],
        [`control${from}.c`, `control${to}.c`],
        [`makecontrol${from}`, `makecontrol${to}`],
        [`Shared${from}.h`, `Shared${to}.h`],
        [`SharedFunction${from}.h`, `SharedFunction${to}.h`],
    ];
    for (const [a, b] of patterns) if (name === a) return b;
    return name;
}

/**
 * Carries a renamed entity (module, supervisor, datatype or function) over in the generated tree
 * `srcGen` (a missing folder is nothing to carry). Refuses invalid names, and a target path that
 * already exists (nothing is overwritten). The manifest follows the moved paths and IDs.
 */
export async function renameInGeneratedTree(srcGen: string, from: string, to: string): Promise<RenameGeneratedReport> {
    if (!ENTITY_NAME.test(from) || !ENTITY_NAME.test(to)) throw new Error(`invalid entity name: ${from} -> ${to}`);
    const report: RenameGeneratedReport = { movedPaths: [], rewrittenFiles: [], regionIds: [], descriptions: [] };
    // the generator's rules (docs/codegen.md, "What generate refuses"): src-gen is a real folder
    // holding no symlink; checked before anything moves, so that a refusal changes nothing
    try {
        if (!checkTreeRoot(srcGen)) return report;
    } catch (e) {
        throw new Error(`cannot carry ${from} -> ${to} over: ${(e as Error).message}`);
    }
    const link = firstLink(srcGen, '');
    if (link) throw new Error(`cannot carry ${from} -> ${to} over: src-gen/${linkRefused(srcGen, link).message}`);
    const tree = new OutputTree(srcGen);
    try {
        const loaded = loadManifest(tree); // before anything moves: the recorded skeletons are of the files as they were
        const carries = new Map<string, FileCarry>();
        walk(tree, '', from, to, report, carries);
        carryManifest(tree, loaded, from, to, report, carries);
    } finally {
        tree.close();
    }
    return report;
}

/** The first symlink under `abs` (relative path), found without following any. */
function firstLink(abs: string, rel: string): string | undefined {
    const entries = readdirSync(abs, { withFileTypes: true }).sort((a, b) => (a.name < b.name ? -1 : a.name > b.name ? 1 : 0));
    for (const e of entries) {
        const childRel = rel ? `${rel}/${e.name}` : e.name;
        if (e.isSymbolicLink()) return childRel;
        if (e.isDirectory()) {
            const found = firstLink(join(abs, e.name), childRel);
            if (found) return found;
        }
    }
    return undefined;
}

/** Renames and rewrites under folder `rel` of the tree; every entry is reached from opened folders (output-tree.ts). */
function walk(tree: OutputTree, rel: string, from: string, to: string, report: RenameGeneratedReport, carries: Map<string, FileCarry>): void {
    for (const e of tree.list(rel) ?? []) {
        const newName = renameGeneratedName(e.name, from, to);
        let childRel = rel ? `${rel}/${e.name}` : e.name;
        if (newName !== e.name) {
            const newRel = rel ? `${rel}/${newName}` : newName;
            if (tree.stat(newRel)) throw new Error(`cannot carry ${childRel} over: ${newName} already exists`);
            tree.rename(rel, e.name, newName);
            report.movedPaths.push({ from: childRel, to: newRel });
            childRel = newRel;
        }
        if (e.isDirectory()) walk(tree, childRel, from, to, report, carries);
        else if (e.isFile()) rewriteRegions(tree, childRel, from, to, report, carries);
    }
}

/** The generated default of a module's description region (module-source.ts), for module `name`. */
const DEFAULT_DESCRIPTION = /^"(synchronous|asynchronous) module ([A-Za-z][A-Za-z0-9_]*)"$/;

function rewriteRegions(tree: OutputTree, rel: string, from: string, to: string, report: RenameGeneratedReport, carries: Map<string, FileCarry>): void {
    if (!/\.(c|h)$/.test(rel)) return;
    const text = tree.read(rel);
    if (text === undefined || !text.includes('PROTECTED')) return;
    let changed = false;
    let next = text.replace(START_MARKER, (all: string, rawId: string) => {
        const id = rawId.trim();
        const renamed = renameRegionId(id, from, to);
        if (renamed === id) return all;
        changed = true;
        report.regionIds.push({ file: rel, from: id, to: renamed });
        return all.replace(`(${rawId})`, `(${rawId.replace(id, renamed)})`);
    });
    if (!changed) return;
    const carry: FileCarry = { contents: new Map() };
    try {
        carry.skeletonBefore = skeletonHash(text, rel);
        // MODULE_DESCRIPTION("synchronous module OLD") is the generated default, kept because the
        // region is ENABLED: it follows the rename (a description the user wrote is left alone)
        const description = parseRegions(next, rel).regions.find((r) => r.id === `protect_description_${to}`);
        const m = description ? DEFAULT_DESCRIPTION.exec(description.content) : null;
        if (description && m && m[2] === from) {
            const content = `"${m[1]} module ${to}"`;
            next = next.slice(0, description.contentStart) + content + next.slice(description.contentEnd);
            carry.contents.set(description.id, [hashContent(description.content), hashContent(content)]);
            report.descriptions.push({ file: rel, line: description.line, from: description.content, to: content });
        }
        carry.skeletonAfter = skeletonHash(next, rel);
    } catch {
        // a malformed file: its IDs are carried over as text; generate reports it (file and line) and leaves it untouched
    }
    carries.set(rel, carry);
    tree.write(rel, bytesOf(next));
    report.rewrittenFiles.push(rel);
}

/**
 * The manifest's paths and region IDs follow the carry-over, so moved defaults stay recognised;
 * a skeleton hash that matched the file before its region IDs were rewritten is replaced by the
 * rewritten file's (the carry-over is no edit outside the regions); one that did not match stays
 * (the user's edit outside the regions is still reported at the next generation).
 */
function carryManifest(tree: OutputTree, loaded: ManifestLoad, from: string, to: string, report: RenameGeneratedReport, carries: Map<string, FileCarry>): void {
    if (!loaded.manifest || (report.movedPaths.length === 0 && report.regionIds.length === 0)) return;
    const movePath = (path: string): string => {
        for (const m of report.movedPaths) {
            if (path === m.from || path.startsWith(`${m.from}/`)) return m.to + path.slice(m.from.length);
        }
        return path;
    };
    const files = new Map<string, Record<string, string>>();
    const skeletons = new Map<string, string>();
    for (const [path, regions] of loaded.manifest.files) {
        const moved = movePath(path);
        const carry = carries.get(moved);
        const ids: Record<string, string> = {};
        for (const [id, hash] of Object.entries(regions)) {
            const renamed = renameRegionId(id, from, to);
            const content = carry?.contents.get(renamed);
            ids[renamed] = content && content[0] === hash ? content[1] : hash;
        }
        files.set(moved, ids);
        const skeleton = loaded.manifest.skeletons.get(path);
        if (skeleton === undefined) continue;
        skeletons.set(moved, carry && carry.skeletonBefore === skeleton && carry.skeletonAfter !== undefined ? carry.skeletonAfter : skeleton);
    }
    tree.write(MANIFEST_NAME, Buffer.from(serialiseManifest(files, skeletons), 'utf8'));
}

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
 * language's rename: `module`, `datatype`, `function`, `port`, `parameter`, ...): the name itself,
 * and for a datatype the generated functions and header named after it (`eq_TypeA`, ...,
 * `SharedTypeA` of `#include "SharedTypeA.h"`), for a function its header (`SharedFunctiondoit`).
 */
export function mentionMatcher(kind: string, name: string): (word: string) => boolean {
    const words = new Set([name, ...identifierRenames(kind, name, name).keys()]);
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

function openTreeForCarry(srcGen: string, what: string): OutputTree | undefined {
    try {
        if (!checkTreeRoot(srcGen)) return undefined;
    } catch (e) {
        throw new Error(`cannot ${what}: ${(e as Error).message}`);
    }
    const link = firstLink(srcGen, '');
    if (link) throw new Error(`cannot ${what}: src-gen/${linkRefused(srcGen, link).message}`);
    return new OutputTree(srcGen);
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
    /** Why uses in code were not rewritten, when they were not. */
    refused?: string;
}

/** The generated functions named after a datatype (shared-type-header.ts, shared-enum-header.ts). */
const TYPE_FUNCTIONS = ['serialize', 'deserialize', 'set', 'get', 'print', 'eq', 'diff', 'inf', 'sup', 'infeq', 'supeq'];

/**
 * The C identifiers a rename changes in user code, old -> new: a port's or parameter's variable,
 * a function, a datatype and its generated functions (`eq_TypeA`, `print_TypeA`, ...). Empty for
 * other kinds (a module's or supervisor's name is in strings, if anywhere: reported, not rewritten).
 */
export function identifierRenames(kind: string, from: string, to: string): Map<string, string> {
    if (kind === 'port' || kind === 'parameter' || kind === 'function') return new Map([[from, to]]);
    if (kind === 'datatype') return new Map([[from, to], ...TYPE_FUNCTIONS.map((f): [string, string] => [`${f}_${from}`, `${f}_${to}`])]);
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
 * Carries a rename over in the user code of the generated tree `srcGen` (only the files under a
 * folder `<owner>_mod` when `owner` is given: a port or parameter is a variable of its module's
 * module.c): every use of an old name of `renames` in the protected regions' code, as a whole C
 * identifier and not a member name (`x.old`, `p->old`) nor in a comment or literal, becomes the
 * new name. Refused (nothing changed, every use reported) when a new name is already a word of
 * that code (a local of that name would capture the uses). User code is otherwise kept byte for
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
        const newNames = new Set(renames.values());
        const taken = files.flatMap((f) => mentionsIn(f.rel, f.text, (w) => newNames.has(w)).filter((m) => m.context === 'code'));
        if (taken.length > 0) {
            const t = taken[0]!;
            report.refused = `'${t.word}' is already used in the code of protected region ${t.id} (${t.file}:${t.line}): uses of '${[...renames.keys()].join("', '")}' were not rewritten`;
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
