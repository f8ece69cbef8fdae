/**
 * The last generation's copy of the user code in the protected regions (docs/codegen.md, "A
 * generated file deleted"): `src-gen/.contract-regions.json`, beside the manifest, holds for each
 * generated file the content of its regions that held code (Manifest.userCode) when it was last
 * generated, or recorded by a build. A generated file deleted by hand is generated anew with those
 * contents restored instead of the defaults.
 *
 * The copy is untrusted like everything in the tree (a project folder may come from anyone): read
 * through OutputTree (no link, at most MAX_COPY_BYTES), only paths the manifest lists and region
 * IDs the generated file has are used, a content that holds a region marker is ignored; anything
 * else makes the copy unreadable (a warning, no region restored from it), never a crash. It is
 * written only when what it holds changes.
 */
import { REGION_COPY_NAME, scanRegions } from '@contract-studio/conventions';
import { parseRegions } from '../regions/parse-regions.js';
import type { OutputTree } from './output-tree.js';
import { UnsafePathError } from './safe-paths.js';

export { REGION_COPY_NAME };

/** The copy's size bound: read up to this, written only the files that fit (in path order). */
export const MAX_COPY_BYTES = 16 * 1024 * 1024;

/** path -> region ID -> content (a byte string, as the writer reads files). */
export type RegionBodies = Map<string, Map<string, string>>;

export interface RegionCopyLoad {
    bodies: RegionBodies;
    /** Why the copy could not be used (a warning), when it is there but unusable. */
    problem?: string;
}

const REGION_ID = /^[A-Za-z_][A-Za-z0-9_]{0,254}$/;

/** A content stored as text when it is valid UTF-8, else as `{ base64 }` (a file in another encoding). */
type StoredBody = string | { base64: string };

function storeBody(bytes: string): StoredBody {
    const buffer = Buffer.from(bytes, 'latin1');
    const text = buffer.toString('utf8');
    return Buffer.from(text, 'utf8').equals(buffer) ? text : { base64: buffer.toString('base64') };
}

function loadBody(value: unknown): string | undefined {
    if (typeof value === 'string') return Buffer.from(value, 'utf8').toString('latin1');
    if (typeof value === 'object' && value !== null && typeof (value as { base64?: unknown }).base64 === 'string') {
        return Buffer.from((value as { base64: string }).base64, 'base64').toString('latin1');
    }
    return undefined;
}

/** Whether a content can stand in a region: it holds no marker of its own (it would end or nest one). */
function plainBody(body: string): boolean {
    if (body.includes('PROTECTED REGION')) return false;
    const scan = scanRegions(body);
    return scan.regions.length === 0 && scan.errors.length === 0;
}

/** The contents of the regions `ids` of `text` (a generated file as written, well formed). */
export function regionBodies(text: string, file: string, ids: readonly string[]): Map<string, string> {
    const wanted = new Set(ids);
    return new Map(parseRegions(text, file).regions.filter((r) => wanted.has(r.id)).map((r) => [r.id, r.content]));
}

/**
 * Reads the copy through `tree`: the bodies of the files of `listed` (the manifest's files). A copy
 * that is not there is no problem (an older version's tree, or no file ever held code); one that is
 * a link, too large, not JSON or not of this shape is a problem and yields no body at all.
 */
export function loadRegionCopy(tree: OutputTree, listed: ReadonlySet<string>): RegionCopyLoad {
    const bodies: RegionBodies = new Map();
    let text: string | undefined;
    try {
        text = tree.read(REGION_COPY_NAME, MAX_COPY_BYTES);
    } catch (e) {
        if (e instanceof UnsafePathError) return { bodies, problem: `not read (${e.message})` };
        return { bodies, problem: `not read (${(e as Error).message})` };
    }
    if (text === undefined) return { bodies };
    let data: unknown;
    try {
        data = JSON.parse(Buffer.from(text, 'latin1').toString('utf8'));
    } catch (e) {
        return { bodies, problem: `unreadable (${(e as Error).message})` };
    }
    const files = (data as { version?: unknown; files?: unknown } | null)?.files;
    if ((data as { version?: unknown } | null)?.version !== 1 || typeof files !== 'object' || files === null || Array.isArray(files)) {
        return { bodies, problem: 'of an unknown format' };
    }
    for (const [path, regions] of Object.entries(files)) {
        if (!listed.has(path) || typeof regions !== 'object' || regions === null || Array.isArray(regions)) continue;
        const kept = new Map<string, string>();
        for (const [id, value] of Object.entries(regions)) {
            const body = loadBody(value);
            if (REGION_ID.test(id) && body !== undefined && plainBody(body)) kept.set(id, body);
        }
        if (kept.size > 0) bodies.set(path, kept);
    }
    return { bodies };
}

/** The copy's JSON text (sorted paths, the regions in file order); undefined when no file holds code. Files past MAX_COPY_BYTES are left out. */
export function serialiseRegionCopy(bodies: RegionBodies): string | undefined {
    const files: Record<string, Record<string, StoredBody>> = {};
    let size = 0;
    for (const path of [...bodies.keys()].sort()) {
        const regions = bodies.get(path)!;
        if (regions.size === 0) continue;
        const stored = Object.fromEntries([...regions].map(([id, body]) => [id, storeBody(body)]));
        const entrySize = JSON.stringify(stored).length + path.length;
        if (size + entrySize > MAX_COPY_BYTES - 1024) continue;
        size += entrySize;
        files[path] = stored;
    }
    if (Object.keys(files).length === 0) return undefined;
    return JSON.stringify({ version: 1, about: 'the user code of the protected regions as last generated or built: a generated file deleted by hand is generated again with it (docs/codegen.md)', files }, null, 1) + '\n';
}

/**
 * Writes the copy when its text changes (removed when no file holds code). Returns whether a file
 * was written or removed.
 */
export function writeRegionCopy(tree: OutputTree, bodies: RegionBodies): boolean {
    const text = serialiseRegionCopy(bodies);
    let previous: string | undefined;
    try {
        previous = tree.read(REGION_COPY_NAME, MAX_COPY_BYTES);
    } catch (e) {
        if (!(e instanceof UnsafePathError) || e.link !== undefined) throw e;
        previous = undefined; // too large: replaced
    }
    if (text === undefined) return previous !== undefined && tree.remove(REGION_COPY_NAME);
    if (previous !== undefined && Buffer.from(previous, 'latin1').toString('utf8') === text) return false;
    tree.write(REGION_COPY_NAME, Buffer.from(text, 'utf8'));
    return true;
}
