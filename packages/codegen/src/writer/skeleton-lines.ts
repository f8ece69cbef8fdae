import { parseRegions, type Region } from '../regions/parse-regions.js';

/**
 * Where code was written outside the protected regions. The manifest keeps, beside each file's
 * skeleton hash (manifest.ts), a short hash of every line of that skeleton as the generator wrote
 * it. Diffing those against the lines of the file on disk names the lines someone else wrote (or
 * removed), even when the model changed the generated code since: the regenerated file is not
 * what the edit is compared with.
 *
 * A line of the skeleton is a line of the file outside the regions' contents, a whole region
 * (start marker to end marker) standing as its ID on the line where it starts; a trailing CR is
 * not part of it (a CRLF checkout is no edit).
 */

/** Characters of the encoded hash of one line (4 base64url characters: 24 bits). */
const CHARS_PER_LINE = 4;
const ALPHABET = 'ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_';
/** What an encoded list looks like; anything else in a manifest is ignored. */
export const LINE_HASHES = /^(?:[A-Za-z0-9_-]{4})*$/;
/** More lines than any generated file has: a manifest entry naming more is ignored (it is read from the project folder). */
export const MAX_SKELETON_LINES = 1_000_000;
/** Above this many cells, the middle of two lists is not diffed line by line (reported as one block). */
const MAX_DIFF_CELLS = 4_000_000;

export interface SkeletonLines {
    /** 24-bit hash of each skeleton line. */
    hashes: number[];
    /** 1-based line of the file where each skeleton line starts. */
    fileLines: number[];
}

const FNV_OFFSET = 0x811c9dc5;
const FNV_PRIME = 0x01000193;
/** FNV-1a of the characters of text[from, to) (a byte string's), continuing from `h`. */
function feed(h: number, text: string, from: number, to: number): number {
    for (let i = from; i < to; i++) h = Math.imul(h ^ (text.charCodeAt(i) & 0xff), FNV_PRIME);
    return h;
}
/** The 24 bits a line's hash keeps. */
const fold = (h: number) => ((h >>> 24) ^ h) & 0xffffff;

/**
 * The skeleton lines of a file (byte string), each with its hash and the file line it starts on.
 * The hash runs over the file's text in place (no string is built per line): the skeleton of a
 * generated file is hashed whenever it changed.
 */
export function skeletonLines(text: string, file: string, regions: Region[] = parseRegions(text, file).regions): SkeletonLines {
    const hashes: number[] = [];
    const fileLines: number[] = [];
    let line = 1;
    let h = FNV_OFFSET;
    let startLine = 1;
    /** Feeds text[from, to) to the line being hashed, ending a line at each newline (a CR before it left out). */
    const addText = (from: number, to: number) => {
        let i = from;
        for (let nl = text.indexOf('\n', i); nl >= 0 && nl < to; nl = text.indexOf('\n', i)) {
            const end = nl > i && text.charCodeAt(nl - 1) === 13 ? nl - 1 : nl;
            hashes.push(fold(feed(h, text, i, end)));
            fileLines.push(startLine);
            h = FNV_OFFSET;
            line++;
            startLine = line;
            i = nl + 1;
        }
        h = feed(h, text, i, to);
    };
    let cursor = 0;
    for (const r of regions) {
        addText(cursor, r.start);
        // the region stands as its ID between two NULs
        h = feed(Math.imul(h, FNV_PRIME), r.id, 0, r.id.length);
        h = Math.imul(h, FNV_PRIME);
        for (let i = text.indexOf('\n', r.start); i >= 0 && i < r.end; i = text.indexOf('\n', i + 1)) line++;
        cursor = r.end;
    }
    addText(cursor, text.length);
    hashes.push(fold(h));
    fileLines.push(startLine);
    return { hashes, fileLines };
}

/**
 * The hashes of the skeleton lines of `text` (a freshly generated file) on which a region of `ids`
 * starts: such a line of the recorded skeleton, gone from a file on disk that lacks the region (cut
 * from it, its code carried back home by this generation: misplaced-regions.ts), loses no code.
 */
export function regionLineHashes(text: string, file: string, ids: Iterable<string>): Set<number> {
    const wanted = new Set(ids);
    if (wanted.size === 0) return new Set();
    const regions = parseRegions(text, file).regions;
    const lines = skeletonLines(text, file, regions);
    const out = new Set<number>();
    for (const r of regions) {
        if (!wanted.has(r.id)) continue;
        const j = lines.fileLines.indexOf(r.line);
        if (j >= 0) out.add(lines.hashes[j]!);
    }
    return out;
}

export function encodeLineHashes(hashes: readonly number[]): string {
    let out = '';
    for (const h of hashes) out += ALPHABET[(h >>> 18) & 63]! + ALPHABET[(h >>> 12) & 63]! + ALPHABET[(h >>> 6) & 63]! + ALPHABET[h & 63]!;
    return out;
}

export function decodeLineHashes(encoded: string): number[] {
    const out: number[] = [];
    for (let i = 0; i + CHARS_PER_LINE <= encoded.length; i += CHARS_PER_LINE) {
        let h = 0;
        for (let k = 0; k < CHARS_PER_LINE; k++) h = (h << 6) | ALPHABET.indexOf(encoded[i + k]!);
        out.push(h);
    }
    return out;
}

/** What was written outside the regions, in lines of the file on disk. */
export interface EditsOutside {
    /** File lines that the generator did not write there (added or changed), ascending. */
    written: number[];
    /** Where skeleton lines the generator wrote are gone (not replaced by a written line): the file line before them (0: the top). */
    removedAfter: number[];
    /** How many lines written or removed were left out as no edit (EditsExcused). */
    excused: number;
}

/** Differences that lose no code, left out of editsOutside's lists (counted in `excused`). */
export interface EditsExcused {
    /** A line of the file on disk (1-based) that holds no code: a whitespace-only one (blankLines). */
    written?: (fileLine: number) => boolean;
    /** A recorded line (its hash) whose removal loses nothing: the line of a region carried back into the file. */
    removed?: (hash: number) => boolean;
}

/** Whether a line (1-based) of `text` holds nothing but whitespace: no code, whoever wrote it. */
export function blankLines(text: string): (line: number) => boolean {
    let starts: number[] | undefined;
    return (line) => {
        if (!starts) {
            starts = [0];
            for (let nl = text.indexOf('\n'); nl >= 0; nl = text.indexOf('\n', nl + 1)) starts.push(nl + 1);
        }
        const start = starts[line - 1];
        if (start === undefined) return false;
        const end = line < starts.length ? starts[line]! : text.length;
        return /^\s*$/.test(text.slice(start, end));
    };
}

/**
 * The lines of `current` (skeleton lines of the file on disk) that are not in `recorded` (the
 * generator's, from the manifest), and where recorded lines were removed: a longest common
 * subsequence of the two hash lists, after their common head and tail; what `excused` says loses
 * no code is only counted.
 */
export function editsOutside(recorded: readonly number[], current: SkeletonLines, excused: EditsExcused = {}): EditsOutside {
    const b = current.hashes;
    let head = 0;
    while (head < recorded.length && head < b.length && recorded[head] === b[head]) head++;
    let tail = 0;
    while (tail < recorded.length - head && tail < b.length - head && recorded[recorded.length - 1 - tail] === b[b.length - 1 - tail]) tail++;
    const n = recorded.length - head - tail;
    const m = b.length - head - tail;
    const written: number[] = [];
    const removedAfter: number[] = [];
    let excusedCount = 0;
    const lineBefore = (j: number) => (j > 0 ? current.fileLines[j - 1]! : 0);
    const addWritten = (j: number) => {
        const line = current.fileLines[j]!;
        if (excused.written?.(line)) excusedCount++;
        else if (written[written.length - 1] !== line) written.push(line);
    };
    /** Recorded line `i` (an index of `recorded`; undefined: a block of them) gone, before the file's skeleton line `j`. */
    const addRemoved = (j: number, i?: number) => {
        if (i !== undefined && excused.removed?.(recorded[i]!)) {
            excusedCount++;
            return;
        }
        const after = lineBefore(j);
        if (removedAfter[removedAfter.length - 1] !== after) removedAfter.push(after);
    };
    // a generated line replaced by another is a line written, not also one removed
    const result = (): EditsOutside => {
        const writtenSet = new Set(written);
        return { written, removedAfter: removedAfter.filter((after) => !writtenSet.has(after) && !writtenSet.has(after + 1)), excused: excusedCount };
    };
    if (n === 0 || m === 0 || n * m > MAX_DIFF_CELLS) {
        for (let j = head; j < head + m; j++) addWritten(j);
        // (a block of lines removed is named as one: nothing in it excused, but a lone line)
        if (n > 0) addRemoved(head, n === 1 ? head : undefined);
        return result();
    }
    // lcs[i][j]: the longest common subsequence of recorded[head+i..] and b[head+j..]
    const width = m + 1;
    const lcs = new Uint32Array((n + 1) * width);
    for (let i = n - 1; i >= 0; i--) {
        for (let j = m - 1; j >= 0; j--) {
            lcs[i * width + j] = recorded[head + i] === b[head + j]
                ? lcs[(i + 1) * width + j + 1]! + 1
                : Math.max(lcs[(i + 1) * width + j]!, lcs[i * width + j + 1]!);
        }
    }
    let i = 0;
    let j = 0;
    while (i < n || j < m) {
        if (i < n && j < m && recorded[head + i] === b[head + j]) {
            i++;
            j++;
        } else if (j < m && (i === n || lcs[i * width + j + 1]! >= lcs[(i + 1) * width + j]!)) {
            addWritten(head + j);
            j++;
        } else {
            addRemoved(head + j, head + i);
            i++;
        }
    }
    return result();
}

/** `line 12`, `lines 12-14`, ... for ascending line numbers, at most `max` runs named. */
export function runsText(lines: readonly number[], max = 3): string {
    const runs: [number, number][] = [];
    for (const l of lines) {
        const last = runs[runs.length - 1];
        if (last && l === last[1] + 1) last[1] = l;
        else runs.push([l, l]);
    }
    const named = runs.slice(0, max).map(([a, b]) => (a === b ? `${a}` : `${a}-${b}`));
    const more = runs.length > max ? ` and ${runs.length - max} more place(s)` : '';
    return `${lines.length === 1 ? 'line' : 'lines'} ${named.join(', ')}${more}`;
}

/** The words of a warning for `edits` (empty when they name nothing: identical hashes). */
export function describeEdits(edits: EditsOutside): { line?: number; where: string } {
    const parts: string[] = [];
    if (edits.written.length > 0) parts.push(`${runsText(edits.written)} not written by the generator`);
    if (edits.removedAfter.length > 0) {
        const places = edits.removedAfter.map((l) => (l === 0 ? 'at the top' : `after line ${l}`));
        parts.push(`generated lines removed ${places.slice(0, 3).join(', ')}${places.length > 3 ? ` and ${places.length - 3} more place(s)` : ''}`);
    }
    const line = edits.written[0] ?? (edits.removedAfter.length > 0 ? Math.max(1, edits.removedAfter[0]!) : undefined);
    return { line, where: parts.join('; ') };
}
