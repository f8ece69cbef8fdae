import { parseRegions } from './parse-regions.js';

/** A region whose ID was carried over to the one the fresh output has in its place. */
export interface CarriedRegion {
    from: string;
    to: string;
    /** 1-based line of its start marker. */
    line: number;
}

/** The kind of a region ID, and the name it was made with: `protect_exec_` and `PLN` of `protect_exec_PLN`. */
function split(id: string): { kind: string; name: string } {
    const cut = id.lastIndexOf('_') + 1;
    return { kind: id.slice(0, cut), name: id.slice(cut) };
}

/**
 * A rename merged by git (docs/codegen.md "Renames"): one side renamed module PLN to GTG (its file
 * moved, its IDs `protect_*_GTG`), the other wrote code in `protect_exec_PLN`, and the merge left
 * GTG's file with that ID. When that is unambiguous, the region takes the ID the fresh output has
 * in its place, content byte for byte:
 * - its ID is nowhere in the new output, nor its name in a region ID's end or in a generated
 *   file's path (no `protect_*_PLN`, no `PLN_mod/`, `controlPLN.c`: PLN is gone, whatever its kind);
 * - the file lacks the fresh output's region of that kind (`protect_exec_GTG`), and that kind has
 *   exactly one such region missing and one such region gone;
 * - every region carried in the file changes the same name to the same name (PLN -> GTG).
 * Anything else carries nothing (the merge then orphans the region, as before). Returns the
 * existing text with the carried start markers' IDs rewritten, and what was carried.
 */
export interface GeneratedOutput {
    /** Every region ID of the new output. */
    ids: ReadonlySet<string>;
    /** Every generated file's path. */
    paths: readonly string[];
}

/** Whether the new output still generates something named `name`: a region ID ending in `_name`, a path holding it. */
function stillGenerated(name: string, output: GeneratedOutput): boolean {
    for (const id of output.ids) if (id.endsWith(`_${name}`)) return true;
    return output.paths.some((p) => p.includes(name));
}

export function carryRenamedRegions(existing: string, file: string, freshIds: readonly string[], outputOf: () => GeneratedOutput): { text: string; carried: CarriedRegion[] } {
    const none = { text: existing, carried: [] };
    const regions = parseRegions(existing, file).regions;
    const fresh = new Set(freshIds);
    const present = new Set(regions.map((r) => r.id));
    const gone = regions.filter((r) => !fresh.has(r.id));
    const missing = freshIds.filter((id) => !present.has(id));
    if (gone.length === 0 || missing.length === 0) return none;
    const output = outputOf();
    const goneByKind = new Map<string, typeof gone>();
    for (const r of gone) goneByKind.set(split(r.id).kind, [...(goneByKind.get(split(r.id).kind) ?? []), r]);
    const missingByKind = new Map<string, string[]>();
    for (const id of missing) missingByKind.set(split(id).kind, [...(missingByKind.get(split(id).kind) ?? []), id]);
    const pairs: { region: (typeof gone)[number]; to: string }[] = [];
    let renaming: string | undefined;
    for (const [kind, ids] of missingByKind) {
        const candidates = goneByKind.get(kind) ?? [];
        if (ids.length !== 1 || candidates.length !== 1) continue;
        const region = candidates[0]!;
        // its entity still exists: the region is not this file's
        if (output.ids.has(region.id) || stillGenerated(split(region.id).name, output)) continue;
        const names = `${split(region.id).name} -> ${split(ids[0]!).name}`;
        if (renaming !== undefined && renaming !== names) return none; // two different renames in one file: ambiguous
        renaming = names;
        pairs.push({ region, to: ids[0]! });
    }
    if (pairs.length === 0) return none;
    let text = existing;
    for (const { region, to } of [...pairs].sort((a, b) => b.region.start - a.region.start)) {
        const marker = text.slice(region.start, region.contentStart);
        const rewritten = marker.replace(`(${region.rawId})`, `(${to})`);
        text = text.slice(0, region.start) + rewritten + text.slice(region.contentStart);
    }
    return { text, carried: pairs.map(({ region, to }) => ({ from: region.id, to, line: region.line })).sort((a, b) => a.line - b.line) };
}
