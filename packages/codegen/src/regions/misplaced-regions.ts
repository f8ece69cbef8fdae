import { parseRegions } from './parse-regions.js';

/**
 * Protected regions found in the wrong generated file: a git merge (or a paste) put module Y's
 * `protect_exec_Y` with its code into module X's module.c. A region ID names its entity, so the
 * new output says which file it belongs to (its home). When that is unambiguous — the region is
 * in no other wrong file, its home file is readable, and there its region holds the generated
 * default (or is missing, or the file is not there yet) — its code is carried home, byte for byte,
 * with a warning; otherwise it is orphaned as before, the warning naming its home.
 */

/** A region carried from the file it was found in to the file that generates its ID. */
export interface MisplacedMove {
    id: string;
    /** The file it was found in. */
    from: string;
    /** Its home: the one file of the new output that generates its ID. */
    to: string;
    /** 1-based line of its start marker in `from`. */
    line: number;
    /** Its content, byte for byte. */
    content: string;
}

export interface MisplacedPlan {
    /** Region ID -> the one file of the new output generating it (IDs two files generate are left out). */
    homes: ReadonlyMap<string, string>;
    /** Home file -> region ID -> the content carried into it. */
    into: ReadonlyMap<string, ReadonlyMap<string, string>>;
    /** File found in -> the regions carried out of it. */
    outOf: ReadonlyMap<string, readonly MisplacedMove[]>;
}

/**
 * What is on disk at a generated path: its text, undefined when there is no such file, null when
 * it cannot be used (unreadable, a link, conflict markers, malformed regions: left to the writer).
 */
export type ExistingText = (path: string) => string | null | undefined;

/** Whether `content` of region `id` is the generator's default (no user code) in `path`, the file generating that ID. */
export type IsDefaultIn = (path: string, id: string, content: string) => boolean;

const parsed = (text: string, file: string) => {
    try {
        return parseRegions(text, file).regions;
    } catch {
        return undefined; // malformed: the writer reports it
    }
};

export function planMisplacedRegions(output: readonly { path: string; content: string }[], existing: ExistingText, isDefault: IsDefaultIn): MisplacedPlan {
    const homes = new Map<string, string>();
    const twice = new Set<string>();
    const freshIds = new Map<string, Set<string>>();
    for (const f of output) {
        const ids = new Set(parseRegions(f.content, `${f.path} (generated output)`).regions.map((r) => r.id));
        freshIds.set(f.path, ids);
        for (const id of ids) {
            if (homes.has(id) && homes.get(id) !== f.path) twice.add(id);
            homes.set(id, f.path);
        }
    }
    for (const id of twice) homes.delete(id);
    const into = new Map<string, Map<string, string>>();
    const outOf = new Map<string, MisplacedMove[]>();
    // every region with user code found outside its home, by ID
    const found = new Map<string, MisplacedMove[]>();
    for (const f of output) {
        const text = existing(f.path);
        if (!text) continue;
        for (const r of parsed(text, f.path) ?? []) {
            const home = homes.get(r.id);
            if (home === undefined || home === f.path || freshIds.get(f.path)!.has(r.id)) continue;
            if (!r.enabled || isDefault(home, r.id, r.content)) continue;
            found.set(r.id, [...(found.get(r.id) ?? []), { id: r.id, from: f.path, to: home, line: r.line, content: r.content }]);
        }
    }
    for (const [id, moves] of found) {
        if (moves.length !== 1) continue; // in two wrong files: which one is meant?
        const move = moves[0]!;
        const homeText = existing(move.to);
        if (homeText === null) continue;
        if (homeText !== undefined) {
            const regions = parsed(homeText, move.to);
            if (!regions) continue;
            const own = regions.find((r) => r.id === id);
            if (own && !isDefault(move.to, id, own.content)) continue; // its home has code of its own there
        }
        into.set(move.to, (into.get(move.to) ?? new Map<string, string>()).set(id, move.content));
        outOf.set(move.from, [...(outOf.get(move.from) ?? []), move]);
    }
    return { homes, into, outOf };
}

/** `text` (well formed) with the contents of the regions named in `contents` replaced, byte for byte. */
export function fillRegions(text: string, file: string, contents: ReadonlyMap<string, string>): string {
    let out = '';
    let cursor = 0;
    for (const r of parseRegions(text, file).regions) {
        const content = contents.get(r.id);
        if (content === undefined) continue;
        out += text.slice(cursor, r.contentStart) + content;
        cursor = r.contentEnd;
    }
    return out + text.slice(cursor);
}

/**
 * `text` (well formed) without the regions whose IDs another file generates (`homes`), each with
 * its line when nothing else is on it: what the file's skeleton is once they are gone home (or to
 * orphans/). A region pasted in is no edit outside the regions.
 */
export function withoutForeignRegions(text: string, file: string, homes: ReadonlyMap<string, string>): string {
    let out = '';
    let cursor = 0;
    for (const r of parseRegions(text, file).regions) {
        const home = homes.get(r.id);
        if (home === undefined || home === file) continue;
        let start = r.start;
        let end = r.end;
        const lineStart = text.lastIndexOf('\n', start - 1) + 1;
        const newline = text.indexOf('\n', end);
        const lineEnd = newline < 0 ? text.length : newline + 1;
        if (lineStart >= cursor && /^[ \t]*$/.test(text.slice(lineStart, start)) && /^[ \t]*\r?\n?$/.test(text.slice(end, lineEnd))) {
            start = lineStart;
            end = lineEnd;
        }
        out += text.slice(cursor, start);
        cursor = end;
    }
    return out + text.slice(cursor);
}
