/**
 * Carry-over of a renamed entity in an existing generated tree (docs/codegen.md, "Renaming an
 * entity"): its files and folders are renamed and the protected-region IDs that name it rewritten,
 * so that the next generation finds the user code under the new IDs and nothing becomes an orphan.
 * Shared by the IDE's rename refactoring and `contract rename`, so that both behave the same.
 * User code is handled as byte strings and kept byte for byte.
 */
import { loadRegionCopy, writeRegionCopy } from './region-copy.js';
import { readdirSync } from 'node:fs';
import { join } from 'node:path';
import { START_MARKER } from '../regions/markers.js';
import { parseRegions } from '../regions/parse-regions.js';
import { bytesOf } from './byte-string.js';
import { hashContent, loadManifest, MANIFEST_NAME, manifestTextLike, serialiseManifest, skeletonHash, type ManifestLoad } from './manifest.js';
import { encodeLineHashes, skeletonLines } from './skeleton-lines.js';
import { OutputTree } from './output-tree.js';
import { ORPHANS_DIR } from './orphans.js';
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
    /** The rewritten file's skeleton line hashes (encoded), beside skeletonAfter. */
    linesAfter?: string;
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

/** The file and folder names an entity of each kind gives the generated tree (docs/codegen.md). */
const GENERATED_NAMES: Record<string, Array<(name: string) => string>> = {
    module: [(n) => `${n}_mod`, (n) => `control${n}.c`, (n) => `makecontrol${n}`],
    supervisor: [(n) => `${n}_mod`, (n) => `control${n}.c`, (n) => `makecontrol${n}`],
    datatype: [(n) => `Shared${n}.h`],
    enumeration: [(n) => `Shared${n}.h`],
    function: [(n) => `SharedFunction${n}.h`],
};

/**
 * A file or folder name renamed when it carries the entity's name in the generated tree: only the
 * names an entity of `kind` gives (an enumeration named like a module does not move the module's
 * folder); any kind's when the kind is not known.
 */
export function renameGeneratedName(name: string, from: string, to: string, kind?: string): string {
    const patterns = (kind !== undefined ? GENERATED_NAMES[kind] : undefined) ?? Object.values(GENERATED_NAMES).flat();
    for (const pattern of patterns) if (name === pattern(from)) return pattern(to);
    return name;
}

/** One carry-over: the names, and how it renames a generated file's or folder's name and a region ID. */
interface Carry {
    from: string;
    to: string;
    renameName(name: string): string;
    renameId(id: string): string;
}

/**
 * Whether the protected-region IDs of the generated tree name an entity of `kind` (the language's
 * word; undefined: an entity of unknown kind, whose IDs are renamed). An enumeration's are not: its
 * `Shared<Enum>.h` has no region, and an enumeration may be named like a region's role (`init`,
 * `exec`) that is no part of its name.
 */
function regionIdsName(kind: string | undefined): boolean {
    return kind !== 'enumeration';
}

/**
 * Carries a renamed entity (module, supervisor, datatype, enumeration or function; `kind`, the
 * language's word for it, when known) over in the generated tree `srcGen` (a missing folder is
 * nothing to carry). Refuses invalid names, and a target path that already exists (nothing is
 * overwritten). The manifest follows the moved paths and IDs.
 */
export async function renameInGeneratedTree(srcGen: string, from: string, to: string, kind?: string): Promise<RenameGeneratedReport> {
    if (!ENTITY_NAME.test(from) || !ENTITY_NAME.test(to)) throw new Error(`invalid entity name: ${from} -> ${to}`);
    const carry: Carry = {
        from, to,
        renameName: (name) => renameGeneratedName(name, from, to, kind),
        renameId: regionIdsName(kind) ? (id) => renameRegionId(id, from, to) : (id) => id,
    };
    const report: RenameGeneratedReport = { movedPaths: [], rewrittenFiles: [], regionIds: [], descriptions: [] };
    // the generator's rules (docs/codegen.md, "What generate refuses"): src-gen is a real folder
    // holding no symlink; checked before anything moves, so that a refusal changes nothing
    const tree = openTreeForCarry(srcGen, `carry ${from} -> ${to} over`);
    if (!tree) return report;
    try {
        tree.lock(); // one writer of the tree at a time (tree-lock.ts)
        const loaded = loadManifest(tree); // before anything moves: the recorded skeletons are of the files as they were
        const carries = new Map<string, FileCarry>();
        // every target checked before anything moves: a refusal leaves the tree as it was
        const conflict = firstConflict(tree, '', carry);
        if (conflict) throw new Error(`cannot carry ${conflict.path} over: ${conflict.taken} already exists`);
        walk(tree, '', carry, report, carries);
        carryManifest(tree, loaded, carry, report, carries);
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

/** The first entry under folder `rel` whose renamed name is taken beside it (walk's order), or undefined. */
function firstConflict(tree: OutputTree, rel: string, carry: Carry): { path: string; taken: string } | undefined {
    for (const e of tree.list(rel) ?? []) {
        if (rel === '' && e.name === ORPHANS_DIR) continue;
        const childRel = rel ? `${rel}/${e.name}` : e.name;
        const newName = carry.renameName(e.name);
        if (newName !== e.name && tree.stat(rel ? `${rel}/${newName}` : newName)) return { path: childRel, taken: newName };
        if (e.isDirectory()) {
            const inner = firstConflict(tree, childRel, carry);
            if (inner) return inner;
        }
    }
    return undefined;
}

/** Renames and rewrites under folder `rel` of the tree; every entry is reached from opened folders (output-tree.ts). */
function walk(tree: OutputTree, rel: string, carry: Carry, report: RenameGeneratedReport, carries: Map<string, FileCarry>): void {
    for (const e of tree.list(rel) ?? []) {
        // orphans are user code as it was moved aside, named for where it came from: never carried over
        if (rel === '' && e.name === ORPHANS_DIR) continue;
        const newName = carry.renameName(e.name);
        let childRel = rel ? `${rel}/${e.name}` : e.name;
        if (newName !== e.name) {
            const newRel = rel ? `${rel}/${newName}` : newName;
            if (tree.stat(newRel)) throw new Error(`cannot carry ${childRel} over: ${newName} already exists`);
            tree.rename(rel, e.name, newName);
            report.movedPaths.push({ from: childRel, to: newRel });
            childRel = newRel;
        }
        if (e.isDirectory()) walk(tree, childRel, carry, report, carries);
        else if (e.isFile()) rewriteRegions(tree, childRel, carry, report, carries);
    }
}

/** The generated default of a module's description region (module-source.ts), for module `name`. */
const DEFAULT_DESCRIPTION = /^"(synchronous|asynchronous) module ([A-Za-z][A-Za-z0-9_]*)"$/;

function rewriteRegions(tree: OutputTree, rel: string, { from, to, renameId }: Carry, report: RenameGeneratedReport, carries: Map<string, FileCarry>): void {
    if (!/\.(c|h)$/.test(rel)) return;
    const text = tree.read(rel);
    if (text === undefined || !text.includes('PROTECTED')) return;
    let changed = false;
    let next = text.replace(START_MARKER, (all: string, rawId: string) => {
        const id = rawId.trim();
        const renamed = renameId(id);
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
        carry.linesAfter = encodeLineHashes(skeletonLines(next, rel).hashes);
    } catch {
        // a malformed file: its IDs are carried over as text; generate reports it (file and line) and leaves it untouched
    }
    carries.set(rel, carry);
    tree.write(rel, bytesOf(next));
    report.rewrittenFiles.push(rel);
}

/**
 * The manifest's paths and region IDs follow the carry-over, so moved defaults (and the record of
 * the regions holding user code) stay recognised;
 * a skeleton hash that matched the file before its region IDs were rewritten is replaced by the
 * rewritten file's (the carry-over is no edit outside the regions); one that did not match stays
 * (the user's edit outside the regions is still reported at the next generation).
 */
function carryManifest(tree: OutputTree, loaded: ManifestLoad, { from, to, renameName, renameId }: Carry, report: RenameGeneratedReport, carries: Map<string, FileCarry>): void {
    if (!loaded.manifest) return;
    // each component as walk() renames it (not only the paths this walk moved): a carry-over killed
    // after moving the folders but before writing the manifest is finished by running it again
    const movePath = (path: string): string => {
        const parts = path.split('/');
        if (parts[0] === ORPHANS_DIR) return path;
        return parts.map(renameName).join('/');
    };
    let changed = report.movedPaths.length > 0 || report.regionIds.length > 0;
    for (const [path, regions] of loaded.manifest.files) {
        if (changed) break;
        changed = movePath(path) !== path || Object.keys(regions).some((id) => renameId(id) !== id);
    }
    if (!changed) return;
    const files = new Map<string, Record<string, string>>();
    const skeletons = new Map<string, string>();
    const lineTable = new Map<string, string>();
    const userCode = new Map<string, string[]>();
    const lostUserCode = new Map<string, string[]>();
    for (const [path, regions] of loaded.manifest.files) {
        const moved = movePath(path);
        const held = loaded.manifest.userCode.get(path);
        if (held) userCode.set(moved, held.map(renameId));
        const lost = loaded.manifest.lostUserCode.get(path);
        if (lost) lostUserCode.set(moved, lost.map(renameId));
        const carry = carries.get(moved);
        const ids: Record<string, string> = {};
        for (const [id, hash] of Object.entries(regions)) {
            const renamed = renameId(id);
            const content = carry?.contents.get(renamed);
            ids[renamed] = content && content[0] === hash ? content[1] : hash;
        }
        files.set(moved, ids);
        const skeleton = loaded.manifest.skeletons.get(path);
        if (skeleton === undefined) continue;
        // a file this walk did not rewrite, though its IDs name the entity: rewritten by a carry-over
        // that was killed before the manifest (rename-journal.ts), followed as if rewritten now
        const earlier = carry === undefined && Object.keys(regions).some((id) => renameId(id) !== id) ? carriedEarlier(tree, moved, skeleton, from, to) : undefined;
        const followed = carry !== undefined && carry.skeletonBefore === skeleton && carry.skeletonAfter !== undefined;
        skeletons.set(moved, followed ? carry.skeletonAfter! : earlier?.skeleton ?? skeleton);
        // line hashes name the region IDs: they follow with the hash, or (an edit outside the
        // regions not carried) are dropped, and the next generation's warning names the first
        // line that differs instead
        const lines = followed ? carry.linesAfter : carry ? undefined : earlier ? earlier.lines : loaded.manifest.skeletonLines.get(path);
        if (lines !== undefined) lineTable.set(moved, lines);
    }
    // the copy of the regions' user code (region-copy.ts) follows: paths and region IDs
    const copy = loadRegionCopy(tree, new Set(loaded.manifest.files.keys()));
    if (!copy.problem && copy.bodies.size > 0) {
        writeRegionCopy(tree, new Map([...copy.bodies].map(([path, bodies]) => [movePath(path), new Map([...bodies].map(([id, body]) => [renameId(id), body]))])));
    }
    // in the line-ending style of the manifest it replaces (a CRLF checkout's stays CRLF), as generate writes it
    tree.write(MANIFEST_NAME, Buffer.from(manifestTextLike(tree.read(MANIFEST_NAME), serialiseManifest(files, skeletons, lineTable, loaded.manifest.recordsUserCode ? userCode : undefined, lostUserCode)), 'utf8'));
}

/**
 * The skeleton of file `rel` when its region IDs were already rewritten from `from` to `to` and,
 * but for them, its skeleton is still the recorded one (`recorded`): the generator's file, carried
 * over by an earlier, interrupted walk. Undefined otherwise (an edit outside the regions stays one).
 */
function carriedEarlier(tree: OutputTree, rel: string, recorded: string, from: string, to: string): { skeleton: string; lines: string } | undefined {
    try {
        const text = tree.read(rel);
        if (text === undefined) return undefined;
        const back = text.replace(START_MARKER, (all: string, rawId: string) => {
            const id = rawId.trim();
            const renamed = renameRegionId(id, to, from);
            return renamed === id ? all : all.replace(`(${rawId})`, `(${rawId.replace(id, renamed)})`);
        });
        if (back === text || skeletonHash(back, rel) !== recorded) return undefined;
        return { skeleton: skeletonHash(text, rel), lines: encodeLineHashes(skeletonLines(text, rel).hashes) };
    } catch {
        return undefined; // a malformed file: generate reports it
    }
}

/** The tree to carry a change over in: refused (an error naming `what`) when src-gen is not a real folder or holds a link; undefined when there is none. */
export function openTreeForCarry(srcGen: string, what: string): OutputTree | undefined {
    try {
        if (!checkTreeRoot(srcGen)) return undefined;
    } catch (e) {
        throw new Error(`cannot ${what}: ${(e as Error).message}`);
    }
    const link = firstLink(srcGen, '');
    if (link) throw new Error(`cannot ${what}: src-gen/${linkRefused(srcGen, link).message}`);
    return new OutputTree(srcGen);
}
