import { createHash } from 'node:crypto';
import { MANIFEST_NAME, conflictMarkerLines, conflictMarkers } from '@contract-studio/conventions';
import { parseRegions, type Region } from '../regions/parse-regions.js';
import { ORPHANS_DIR } from './orphans.js';
import type { OutputTree } from './output-tree.js';
import { treePathProblem } from './safe-paths.js';
import { LINE_HASHES, MAX_SKELETON_LINES, encodeLineHashes, skeletonLines } from './skeleton-lines.js';

/**
 * The manifest `<out>/.contract-manifest.json` lists the files the generator wrote last time and,
 * per protected region, a hash of the default content it generated. It tells which files belong
 * to deleted entities and whether a region still holds only the generator's default (no user code).
 */
export { MANIFEST_NAME };

/** The file's format, as serialiseManifest writes it. */
export interface Manifest {
    version: 1;
    /** path -> region ID -> hash of the generated default content */
    files: Record<string, Record<string, string>>;
    /**
     * path -> hash of the file's skeleton as written (skeletonHash): tells code written outside
     * the regions. Optional: manifests written before it have none (the check is then skipped).
     */
    skeletons?: Record<string, string>;
    /**
     * path -> a 24-bit hash of each line of that skeleton, 4 base64url characters a line
     * (skeleton-lines.ts): says which lines were written outside the regions. Optional, as above.
     */
    skeletonLines?: Record<string, string>;
    /**
     * path -> the IDs of its protected regions that held something else than their default (user
     * code) when the generator last wrote or kept the file; only files with such regions are
     * listed. Tells that a generated file now missing held code (deleted by hand): the generation
     * says so, and how to get it back. Written always (`{}` when no file holds code): a manifest
     * without it is of an older version, which does not tell.
     */
    userCode?: Record<string, string[]>;
    /**
     * path -> the IDs of the protected regions whose code was lost when the file was deleted and
     * generated anew with the defaults (or, the manifest before being of an older version, that
     * may have held code): every generation and build says so again until one of them holds code
     * again (the file restored, or code written there) or the file is generated no more.
     */
    lostUserCode?: Record<string, string[]>;
}

/** A loaded manifest: only entries whose path passed the checks (safe-paths.ts). */
export interface LoadedManifest {
    /** path -> region ID -> hash of the generated default content */
    files: Map<string, Record<string, string>>;
    /** path -> skeleton hash, for the paths of `files` that have a well-formed one (none in an older manifest). */
    skeletons: Map<string, string>;
    /** path -> encoded line hashes of the skeleton, for the paths of `skeletons` that have well-formed ones. */
    skeletonLines: Map<string, string>;
    /** path -> the region IDs that held user code (Manifest.userCode), for the paths of `files` that have a well-formed list. */
    userCode: Map<string, string[]>;
    /** Whether the manifest records userCode at all (false: of an older version, which cannot tell a file that held none). */
    recordsUserCode: boolean;
    /**
     * Whether the manifest has a skeletons field at all (false: of a version before that record, which
     * holds of each file only its regions' default hashes, nothing of its text outside them; a
     * malformed field is true: no older version wrote it).
     */
    recordsSkeletons: boolean;
    /** path -> the region IDs whose code a deletion lost (Manifest.lostUserCode), for the paths of `files` that have a well-formed list. */
    lostUserCode: Map<string, string[]>;
}

export function hashContent(content: string): string {
    return createHash('sha1').update(content, 'latin1').digest('hex').slice(0, 16);
}

/** What a hash of hashContent looks like; anything else in a manifest is ignored. */
const HASH = /^[0-9a-f]{16}$/;

/**
 * The skeleton of a file (byte string): its text outside the regions' contents, each region reduced
 * to its (normalised) ID, so that editing inside a region, toggling `ENABLED` or re-spacing a
 * marker does not change it, and code written anywhere else does. Throws RegionSyntaxError on a
 * malformed file.
 */
export function skeletonText(text: string, file: string, regions: Region[] = parseRegions(text, file).regions): string {
    let out = '';
    let cursor = 0;
    for (const r of regions) {
        out += `${text.slice(cursor, r.start)}\u0000${r.id}\u0000`;
        cursor = r.end;
    }
    return out + text.slice(cursor);
}

/**
 * The hash of a skeleton, line endings read as LF: a checkout that turned LF into CRLF (git's
 * autocrlf) loses no code and is no edit outside the regions.
 */
function skeletonDigest(skeleton: string): string {
    return hashContent(skeleton.includes('\r') ? skeleton.replace(/\r\n/g, '\n') : skeleton);
}

export function skeletonHash(text: string, file: string): string {
    return skeletonDigest(skeletonText(text, file));
}

/**
 * What the manifest records of a freshly generated file (byte string): its regions' default hashes,
 * its skeleton hash, and (`lines()`, computed when asked: a file whose skeleton hash is the recorded
 * one keeps the recorded line hashes) its skeleton's line hashes.
 */
export function fileRecord(generated: string, file: string): { defaults: Record<string, string>; skeleton: string; lines: () => string } {
    const defaults: Record<string, string> = {};
    const regions = parseRegions(generated, file).regions;
    for (const r of regions) defaults[r.id] = hashContent(r.content);
    return {
        defaults,
        skeleton: skeletonDigest(skeletonText(generated, file, regions)),
        lines: () => encodeLineHashes(skeletonLines(generated, file, regions).hashes),
    };
}

/** The default-content hashes of a freshly generated file (byte string). */
export function regionDefaults(generated: string, file: string): Record<string, string> {
    return fileRecord(generated, file).defaults;
}

export interface ManifestLoad {
    manifest?: LoadedManifest;
    /** Why the manifest, or some of its entries, were ignored (one warning each). */
    problems: string[];
    /**
     * Set when a manifest is there but could not be read (conflict markers, not JSON, unknown
     * format): what is wrong with it, as a clause ("holds git merge conflict markers"). There is then
     * no record of what the generator wrote: it cannot tell its own lines from the user's.
     */
    unreadable?: string;
}

/**
 * What to do about a manifest that could not be read (paths from the project root): one holding git
 * conflict markers is resolved by taking either side; any other is written anew by generate.
 */
export function unreadableManifestAdvice(unreadable: string): string {
    return unreadable === CONFLICTED
        ? `take either side of it (git checkout --theirs src-gen/${MANIFEST_NAME}, or --ours), then run \`contract generate\` on the project`
        : `run \`contract generate\` on the project (it writes it anew)`;
}

/** ManifestLoad.unreadable of a manifest holding git's conflict markers. */
export const CONFLICTED = 'holds git merge conflict markers';

/**
 * Why a manifest entry is not a file the generator may act on, or undefined. The manifest is read
 * from the project folder (untrusted): an entry is a plain relative path inside the output tree,
 * and never the manifest itself or an orphan (user code the generator only ever adds to).
 */
export function manifestEntryProblem(path: string): string | undefined {
    const problem = treePathProblem(path);
    if (problem) return problem;
    if (path === MANIFEST_NAME) return 'the manifest itself';
    if (path === ORPHANS_DIR || path.startsWith(`${ORPHANS_DIR}/`)) return `under ${ORPHANS_DIR}/ (user code, never a generated file)`;
    return undefined;
}

/** Region ID -> hash when `value` is such a table of strings, else {} (no default known). */
function defaultsOf(value: unknown): Record<string, string> {
    const out: Record<string, string> = {};
    if (typeof value !== 'object' || value === null || Array.isArray(value)) return out;
    for (const [id, hash] of Object.entries(value)) if (typeof hash === 'string') out[id] = hash;
    return out;
}

/**
 * Reads `<out>/.contract-manifest.json` through `tree` (never through a link: a link is an
 * UnsafePathError for the caller). Entries with a bad path are dropped with a problem naming
 * them, never acted on; an unreadable or unknown manifest is ignored with a problem.
 */
export function loadManifest(tree: OutputTree): ManifestLoad {
    const text = tree.read(MANIFEST_NAME);
    if (text === undefined) return { problems: [] };
    let data: { version?: unknown; files?: unknown };
    try {
        data = JSON.parse(Buffer.from(text, 'latin1').toString('utf8')) as typeof data;
    } catch (e) {
        const markers = conflictMarkers(text);
        if (markers.length > 0) {
            return { problems: [`holds git merge conflict markers (lines ${conflictMarkerLines(markers)}): unreadable, ignored`], unreadable: CONFLICTED };
        }
        return { problems: [`unreadable manifest, ignored (${(e as Error).message})`], unreadable: 'is unreadable' };
    }
    if (data?.version !== 1 || typeof data.files !== 'object' || data.files === null || Array.isArray(data.files)) {
        return { problems: ['unknown manifest format, ignored'], unreadable: 'has an unknown format' };
    }
    const files = new Map<string, Record<string, string>>();
    const problems: string[] = [];
    for (const [path, value] of Object.entries(data.files)) {
        const problem = manifestEntryProblem(path);
        if (problem) problems.push(`entry ${JSON.stringify(path)} dropped (${problem}): nothing read, written or deleted for it`);
        else files.set(path, defaultsOf(value));
    }
    // skeleton hashes (optional): only for the files kept above, only well-formed hashes; the rest
    // is ignored (no check for that file), never acted on
    const skeletons = new Map<string, string>();
    const recorded = (data as { skeletons?: unknown }).skeletons;
    if (typeof recorded === 'object' && recorded !== null && !Array.isArray(recorded)) {
        for (const [path, hash] of Object.entries(recorded)) {
            if (files.has(path) && typeof hash === 'string' && HASH.test(hash)) skeletons.set(path, hash);
        }
    }
    const skeletonLineTable = new Map<string, string>();
    const lines = (data as { skeletonLines?: unknown }).skeletonLines;
    if (typeof lines === 'object' && lines !== null && !Array.isArray(lines)) {
        for (const [path, encoded] of Object.entries(lines)) {
            if (skeletons.has(path) && typeof encoded === 'string' && encoded.length <= 4 * MAX_SKELETON_LINES && LINE_HASHES.test(encoded)) {
                skeletonLineTable.set(path, encoded);
            }
        }
    }
    const held = (data as { userCode?: unknown }).userCode;
    const userCode = regionLists(held, files);
    const lostUserCode = regionLists((data as { lostUserCode?: unknown }).lostUserCode, files);
    const recordsUserCode = typeof held === 'object' && held !== null && !Array.isArray(held);
    const recordsSkeletons = recorded !== undefined;
    return { manifest: { files, skeletons, skeletonLines: skeletonLineTable, userCode, recordsUserCode, recordsSkeletons, lostUserCode }, problems };
}

/** A manifest's path -> region IDs table (userCode, lostUserCode): only paths of `files` with a well-formed list; anything else is ignored. */
function regionLists(value: unknown, files: ReadonlyMap<string, unknown>): Map<string, string[]> {
    const lists = new Map<string, string[]>();
    if (typeof value !== 'object' || value === null || Array.isArray(value)) return lists;
    for (const [path, ids] of Object.entries(value)) {
        if (files.has(path) && Array.isArray(ids) && ids.length <= MAX_USER_CODE_REGIONS && ids.every((id) => typeof id === 'string' && REGION_ID.test(id))) lists.set(path, ids as string[]);
    }
    return lists;
}

/**
 * The default hashes to record for a file as merged (`text`, well formed): the fresh output's
 * (`fresh`), but a region that still holds the default the generator wrote there before
 * (`previous`, the manifest's), which this generator writes differently, keeps that hash: an
 * ENABLED region is kept byte for byte, and an older default left in it is still no user code
 * (not listed in Manifest.userCode, not orphaned when its region goes, replaced when ENABLED is removed).
 */
export function mergedDefaults(text: string, file: string, fresh: Record<string, string>, previous: Record<string, string> | undefined): Record<string, string> {
    if (previous === undefined) return fresh;
    const kept = { ...fresh };
    for (const r of parseRegions(text, file).regions) {
        const old = previous[r.id];
        if (old !== undefined && fresh[r.id] !== undefined && old !== fresh[r.id] && hashContent(r.content) === old) kept[r.id] = old;
    }
    return kept;
}

/** What a region ID in Manifest.userCode looks like (the generator's IDs); anything else is ignored. */
const REGION_ID = /^[A-Za-z_][A-Za-z0-9_]{0,254}$/;
/** More regions than a generated file has: such a list is ignored. */
const MAX_USER_CODE_REGIONS = 10_000;

/**
 * The IDs of the regions of `text` (a generated file as written, well formed) whose content is not
 * their default of `defaults` (user code), in the file's order: Manifest.userCode.
 */
export function regionsHoldingCode(text: string, file: string, defaults: Record<string, string>): string[] {
    return parseRegions(text, file).regions.filter((r) => defaults[r.id] !== undefined && defaults[r.id] !== hashContent(r.content)).map((r) => r.id);
}

/**
 * Deterministic JSON text of a manifest (sorted paths); skeleton hashes, line hashes and the regions
 * holding user code only for listed files (userCode whenever given, `{}` when none; lostUserCode
 * only when some file has lost code).
 */
export function serialiseManifest(files: Map<string, Record<string, string>>, skeletons?: Map<string, string>, skeletonLineTable?: Map<string, string>, userCode?: Map<string, string[]>, lostUserCode?: Map<string, string[]>): string {
    const sorted: Record<string, Record<string, string>> = {};
    const paths = [...files.keys()].sort();
    for (const path of paths) sorted[path] = files.get(path)!;
    const manifest: Manifest = { version: 1, files: sorted };
    if (skeletons) {
        const sortedSkeletons: Record<string, string> = {};
        for (const path of paths) {
            const hash = skeletons.get(path);
            if (hash !== undefined) sortedSkeletons[path] = hash;
        }
        manifest.skeletons = sortedSkeletons;
    }
    if (skeletons && skeletonLineTable) {
        const sortedLines: Record<string, string> = {};
        for (const path of paths) {
            const encoded = skeletonLineTable.get(path);
            if (encoded !== undefined && skeletons.has(path)) sortedLines[path] = encoded;
        }
        manifest.skeletonLines = sortedLines;
    }
    const listed = (table: Map<string, string[]>) => Object.fromEntries(paths.filter((path) => (table.get(path)?.length ?? 0) > 0).map((path) => [path, table.get(path)!]));
    if (userCode) manifest.userCode = listed(userCode);
    const lost = lostUserCode && listed(lostUserCode);
    if (lost && Object.keys(lost).length > 0) manifest.lostUserCode = lost;
    return JSON.stringify(manifest, null, 1) + '\n';
}

/** Whether `text` ends its lines with CRLF: some do, and no more end with a bare LF. */
export function hasCrlfEndings(text: string): boolean {
    let crlf = 0;
    let lf = 0;
    for (let i = text.indexOf('\n'); i >= 0; i = text.indexOf('\n', i + 1)) {
        if (i > 0 && text.charCodeAt(i - 1) === 13) crlf++;
        else lf++;
    }
    return crlf > 0 && lf <= crlf;
}

/**
 * The manifest text (serialiseManifest's, LF) in the line-ending style of the manifest it replaces
 * (`previous`, undefined: none): a CRLF checkout's manifest (git's autocrlf) stays CRLF, as the C
 * files do, so it is not rewritten, nor shown changed, for its line endings alone. Generate and a
 * rename's carry-over write it through this.
 */
export function manifestTextLike(previous: string | undefined, text: string): string {
    return previous !== undefined && hasCrlfEndings(previous) ? text.replace(/\r?\n/g, '\r\n') : text;
}

/**
 * Without a manifest entry, a region counts as default when it holds nothing but blanks and the
 * generator's `//TODO` placeholder: anything else is kept as user code.
 */
export function looksLikeDefault(content: string): boolean {
    return content.replace(/\/\/\s*TODO/g, '').trim() === '';
}
