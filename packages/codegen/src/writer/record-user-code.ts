/**
 * A build's record of the user code in a project's generated tree (docs/codegen.md, "A generated
 * file deleted"): `contract build`/`run` and the IDE's builds generate into a private copy of the
 * project, so without this the project's manifest kept the record of its last `contract generate`,
 * and the usual loop (generate once, then write code, build, run) left the code it wrote unrecorded:
 * a file deleted then was generated anew with the defaults, silently.
 *
 * Before a build reads the project, this reads each generated file the manifest lists and records
 * which of its regions hold user code (Manifest.userCode) and their contents (the copy,
 * region-copy.ts). The manifest is rewritten only when that record changes, the copy only when
 * what it holds changes; no generated file is written. A file missing (deleted), unreadable, with
 * conflict markers or malformed regions keeps its previous record. Nothing is recorded without a
 * readable manifest, while a rename's journal is there, or while another writer holds the tree
 * (its own generation records it).
 */
import { lstatSync } from 'node:fs';
import { conflictRefusal } from './conflicts.js';
import { MANIFEST_NAME, loadManifest, manifestTextLike, regionsHoldingCode, serialiseManifest } from './manifest.js';
import { OutputTree } from './output-tree.js';
import { loadRegionCopy, regionBodies, writeRegionCopy, REGION_COPY_NAME, type RegionBodies } from './region-copy.js';
import { hasRenameJournal } from './rename-journal.js';

/** What a generated file of the tree may weigh to be read here (as a build reads a project's file). */
const MAX_FILE_BYTES = 8 * 1024 * 1024;

export interface UserCodeRecord {
    /** The bookkeeping files rewritten (the manifest, the copy), relative to the tree. */
    written: string[];
    /** Why nothing (or not everything) was recorded, when it matters to the user. */
    warnings: string[];
}

/** Records the user code of the generated tree `outDir` (a project's src-gen); a tree that is not there records nothing. */
export function recordUserCode(outDir: string): UserCodeRecord {
    const result: UserCodeRecord = { written: [], warnings: [] };
    try {
        if (!lstatSync(outDir).isDirectory()) return result;
    } catch {
        return result;
    }
    const tree = new OutputTree(outDir);
    try {
        if (!tree.tryLock()) return result; // another writer: its generation records it
        if (hasRenameJournal(tree)) return result;
        const loaded = loadManifest(tree);
        const manifest = loaded.manifest;
        if (!manifest || loaded.unreadable !== undefined) return result;
        const copy = loadRegionCopy(tree, new Set(manifest.files.keys()));
        const userCode = new Map(manifest.userCode);
        const lostUserCode = new Map(manifest.lostUserCode);
        const bodies: RegionBodies = new Map(copy.bodies);
        for (const [path, defaults] of manifest.files) {
            let text: string | undefined;
            let held: string[];
            try {
                text = tree.read(path, MAX_FILE_BYTES);
                if (text === undefined || conflictRefusal(text)) continue; // deleted, or a merge to resolve: its record stays
                held = regionsHoldingCode(text, path, defaults);
            } catch {
                continue; // a link, too large, malformed regions: its record stays (the generation says what is wrong)
            }
            if (held.length > 0) {
                userCode.set(path, held);
                bodies.set(path, regionBodies(text, path, held));
            } else {
                userCode.delete(path);
                bodies.delete(path);
            }
            if (lostUserCode.get(path)?.some((id) => held.includes(id))) lostUserCode.delete(path);
        }
        const previous = tree.read(MANIFEST_NAME);
        const text = manifestTextLike(previous, serialiseManifest(manifest.files, manifest.skeletons, manifest.skeletonLines, userCode, lostUserCode));
        // written only for the record: a manifest that dropped entries (problems) is left as its generation wrote it
        if (previous !== text && loaded.problems.length === 0 && recordChanged(manifest.userCode, userCode, manifest.lostUserCode, lostUserCode, manifest.recordsUserCode)) {
            tree.write(MANIFEST_NAME, Buffer.from(text, 'utf8'));
            result.written.push(MANIFEST_NAME);
        }
        if (copy.problem) result.warnings.push(`${REGION_COPY_NAME}: ${copy.problem}: written anew from the generated files as they are`);
        if (writeRegionCopy(tree, bodies)) result.written.push(REGION_COPY_NAME);
    } catch (e) {
        result.warnings.push(`${MANIFEST_NAME}: the user code of the protected regions was not recorded (${(e as Error).message}): a generated file deleted now may be generated anew without it`);
    } finally {
        tree.close();
    }
    return result;
}

function sameLists(a: ReadonlyMap<string, string[]>, b: ReadonlyMap<string, string[]>): boolean {
    if (a.size !== b.size) return false;
    for (const [path, ids] of a) if (b.get(path)?.join(',') !== ids.join(',')) return false;
    return true;
}

/** Whether the record differs from the manifest's (one of an older version, without userCode, always does). */
function recordChanged(oldHeld: ReadonlyMap<string, string[]>, held: ReadonlyMap<string, string[]>, oldLost: ReadonlyMap<string, string[]>, lost: ReadonlyMap<string, string[]>, recorded: boolean): boolean {
    return !recorded || !sameLists(oldHeld, held) || !sameLists(oldLost, lost);
}

/** What the IDE's delete confirmation says of one generated file. */
export interface UserCodeOfFile {
    /** Its protected regions holding user code, as recorded. */
    regions: string[];
    /** Whether the copy holds them all: a generation brings them back when the file is deleted. */
    restorable: boolean;
}

/**
 * The regions of generated file `path` (relative to the tree `outDir`) that hold user code, once
 * recorded (recordUserCode), and whether the copy holds them all (`restorable`: a generation
 * brings them back when the file is deleted): what the IDE's delete confirmation says.
 */
export function userCodeOf(outDir: string, path: string): UserCodeOfFile {
    return userCodeOfFiles(outDir, [path]).get(path) ?? { regions: [], restorable: false };
}

/**
 * userCodeOf for several files of one tree (the files of a folder the IDE deletes), the tree's
 * user code recorded once: each of `paths` whose regions hold code, with its regions and whether
 * the copy holds them all; the others are left out.
 */
export function userCodeOfFiles(outDir: string, paths: readonly string[]): Map<string, UserCodeOfFile> {
    const held = new Map<string, UserCodeOfFile>();
    recordUserCode(outDir);
    try {
        if (!lstatSync(outDir).isDirectory()) return held;
    } catch {
        return held;
    }
    const tree = new OutputTree(outDir);
    try {
        const manifest = loadManifest(tree).manifest;
        if (!manifest) return held;
        const bodies = loadRegionCopy(tree, new Set(manifest.files.keys())).bodies;
        for (const path of paths) {
            const regions = manifest.userCode.get(path) ?? [];
            if (regions.length === 0) continue;
            const saved = bodies.get(path);
            held.set(path, { regions, restorable: regions.every((id) => saved?.has(id)) });
        }
        return held;
    } catch {
        return new Map();
    } finally {
        tree.close();
    }
}
