import { parseRegions, type Region } from './parse-regions.js';

/** Says whether `content` is what the generator writes by default in region `id` (i.e. holds no user code). */
export type DefaultContentCheck = (id: string, content: string) => boolean;

/**
 * Says whether `content` is the default the generator wrote last time in region `id` when that is
 * known (the manifest's hash): true or false; undefined when nothing is known.
 */
export type KnownDefaultCheck = (id: string, content: string) => boolean | undefined;

export interface MergeResult {
    /** The new file text: the generated output with every ENABLED region of the existing file kept byte for byte. */
    text: string;
    /** Regions of the existing file whose ID is gone from the new output and that hold user content. */
    orphans: Region[];
    /**
     * Regions of the existing file that are not ENABLED (the user removed or mistyped the word) and
     * whose content, replaced by the generated default in `text`, was not a default: it differs from
     * the default the manifest knows for that region or, without one, from the fresh default.
     */
    disabled: Region[];
}

/**
 * Merges freshly generated text with the existing file, by region ID. The generated text must be
 * well formed (a generator bug otherwise); a malformed existing file throws RegionSyntaxError.
 */
export function mergeRegions(generated: string, existing: string, file: string, isDefault: DefaultContentCheck, knownDefault?: KnownDefaultCheck): MergeResult {
    const fresh = parseRegions(generated, `${file} (generated output)`);
    const old = parseRegions(existing, file);
    const oldById = new Map(old.regions.map((r) => [r.id, r]));
    const disabled: Region[] = [];
    let text = '';
    let cursor = 0;
    for (const r of fresh.regions) {
        const kept = oldById.get(r.id);
        text += generated.slice(cursor, r.contentStart);
        text += kept?.enabled ? kept.content : r.content;
        cursor = r.contentEnd;
        if (kept && !kept.enabled && kept.content !== r.content && knownDefault?.(r.id, kept.content) !== true) disabled.push(kept);
    }
    text += generated.slice(cursor);
    const freshIds = new Set(fresh.regions.map((r) => r.id));
    const orphans = old.regions.filter((r) => !freshIds.has(r.id) && r.enabled && !isDefault(r.id, r.content));
    return { text, orphans, disabled };
}

/** The user-owned regions of a file that is going away (its entity was deleted). */
export function userRegions(existing: string, file: string, isDefault: DefaultContentCheck): Region[] {
    return parseRegions(existing, file).regions.filter((r) => r.enabled && !isDefault(r.id, r.content));
}
