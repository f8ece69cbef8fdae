import { parseRegions, type Region } from './parse-regions.js';

/** Says whether `content` is what the generator writes by default in region `id` (i.e. holds no user code). */
export type DefaultContentCheck = (id: string, content: string) => boolean;

export interface MergeResult {
    /** The new file text: the generated output with every ENABLED region of the existing file kept byte for byte. */
    text: string;
    /** Regions of the existing file whose ID is gone from the new output and that hold user content. */
    orphans: Region[];
}

/**
 * Merges freshly generated text with the existing file, by region ID. The generated text must be
 * well formed (a generator bug otherwise); a malformed existing file throws RegionSyntaxError.
 */
export function mergeRegions(generated: string, existing: string, file: string, isDefault: DefaultContentCheck): MergeResult {
    const fresh = parseRegions(generated, `${file} (generated output)`);
    const old = parseRegions(existing, file);
    const oldById = new Map(old.regions.map((r) => [r.id, r]));
    let text = '';
    let cursor = 0;
    for (const r of fresh.regions) {
        const kept = oldById.get(r.id);
        text += generated.slice(cursor, r.contentStart);
        text += kept?.enabled ? kept.content : r.content;
        cursor = r.contentEnd;
    }
    text += generated.slice(cursor);
    const freshIds = new Set(fresh.regions.map((r) => r.id));
    const orphans = old.regions.filter((r) => !freshIds.has(r.id) && r.enabled && !isDefault(r.id, r.content));
    return { text, orphans };
}

/** The user-owned regions of a file that is going away (its entity was deleted). */
export function userRegions(existing: string, file: string, isDefault: DefaultContentCheck): Region[] {
    return parseRegions(existing, file).regions.filter((r) => r.enabled && !isDefault(r.id, r.content));
}
