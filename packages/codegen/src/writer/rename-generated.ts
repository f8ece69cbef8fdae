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
import { bytesOf } from './byte-string.js';
import { loadManifest, MANIFEST_NAME, serialiseManifest } from './manifest.js';
import { OutputTree } from './output-tree.js';
import { checkTreeRoot, linkRefused } from './safe-paths.js';

const ENTITY_NAME = /^[A-Za-z][A-Za-z0-9_]*$/;

export interface RenameGeneratedReport {
    movedPaths: Array<{ from: string; to: string }>;
    rewrittenFiles: string[];
    regionIds: Array<{ file: string; from: string; to: string }>;
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
    const report: RenameGeneratedReport = { movedPaths: [], rewrittenFiles: [], regionIds: [] };
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
        walk(tree, '', from, to, report);
        carryManifest(tree, from, to, report);
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
function walk(tree: OutputTree, rel: string, from: string, to: string, report: RenameGeneratedReport): void {
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
        if (e.isDirectory()) walk(tree, childRel, from, to, report);
        else if (e.isFile()) rewriteRegions(tree, childRel, from, to, report);
    }
}

function rewriteRegions(tree: OutputTree, rel: string, from: string, to: string, report: RenameGeneratedReport): void {
    if (!/\.(c|h)$/.test(rel)) return;
    const text = tree.read(rel);
    if (text === undefined || !text.includes('PROTECTED')) return;
    let changed = false;
    const next = text.replace(START_MARKER, (all: string, rawId: string) => {
        const id = rawId.trim();
        const renamed = renameRegionId(id, from, to);
        if (renamed === id) return all;
        changed = true;
        report.regionIds.push({ file: rel, from: id, to: renamed });
        return all.replace(`(${rawId})`, `(${rawId.replace(id, renamed)})`);
    });
    if (changed) {
        tree.write(rel, bytesOf(next));
        report.rewrittenFiles.push(rel);
    }
}

/** The manifest's paths and region IDs follow the carry-over, so moved defaults stay recognised. */
function carryManifest(tree: OutputTree, from: string, to: string, report: RenameGeneratedReport): void {
    const loaded = loadManifest(tree);
    if (!loaded.manifest || (report.movedPaths.length === 0 && report.regionIds.length === 0)) return;
    const movePath = (path: string): string => {
        for (const m of report.movedPaths) {
            if (path === m.from || path.startsWith(`${m.from}/`)) return m.to + path.slice(m.from.length);
        }
        return path;
    };
    const files = new Map<string, Record<string, string>>();
    for (const [path, regions] of loaded.manifest.files) {
        const ids: Record<string, string> = {};
        for (const [id, hash] of Object.entries(regions)) ids[renameRegionId(id, from, to)] = hash;
        files.set(movePath(path), ids);
    }
    tree.write(MANIFEST_NAME, Buffer.from(serialiseManifest(files), 'utf8'));
}
