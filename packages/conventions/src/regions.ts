/**
 * Protected regions of generated C (docs/codegen.md "Protected regions"):
 *   /*PROTECTED REGION ID(<id>) ENABLED START*\/ ... /*PROTECTED REGION END*\/
 * The markers and the one reading of them that the generator (merge), the IDE (read-only
 * skeleton, save guard) and the build service (gcc errors mapped to regions) share, so a region
 * one of them accepts is the same region for all.
 *
 * The reading is tolerant: blanks and line breaks between the marker's words (code pasted from
 * the report's PDF has them), blanks around the ID, and the report's spelling `additionnal` (read
 * as `additional`). The start marker may lack `ENABLED` (the user asks for the default to be
 * regenerated).
 */

/** Matches a start marker; group 1 = the ID as written, group 2 = `ENABLED` when present. */
export const START_MARKER = /\/\*\s*PROTECTED\s+REGION\s+ID\s*\(([^()\r\n]*)\)\s*(ENABLED\s+)?START\s*\*\//g;
/** Matches an end marker. */
export const END_MARKER = /\/\*\s*PROTECTED\s+REGION\s+END\s*\*\//g;

const ANY_MARKER = new RegExp(`${START_MARKER.source}|${END_MARKER.source}`, 'g');

/** The start marker the generators write (always ENABLED: a fresh region keeps what the user types). */
export function startMarker(id: string): string {
    return `/*PROTECTED REGION ID(${id}) ENABLED START*/`;
}

/** The end marker the generators write. */
export const END = '/*PROTECTED REGION END*/';

/** Wraps `content` in a region, the way generators write one. */
export function region(id: string, content: string): string {
    return `${startMarker(id)}${content}${END}`;
}

/**
 * The report spells some IDs `additionnal`; the generators write `additional`. Both spellings
 * designate the same region when reading existing files.
 */
export function normaliseRegionId(id: string): string {
    return id.trim().replace(/additionnal/g, 'additional');
}

/** One well-formed protected region of a text. */
export interface ScannedRegion {
    /** The normalised ID (trimmed, `additionnal` read as `additional`). */
    id: string;
    /** The ID as written in the file. */
    rawId: string;
    enabled: boolean;
    /** Offsets in the text: the start marker begins at `start`, the content spans [contentStart, contentEnd), the end marker ends at `end`. */
    start: number;
    contentStart: number;
    contentEnd: number;
    end: number;
    /** 1-based lines of the start and of the end marker. */
    line: number;
    endLine: number;
}

/** A malformed structure: START without END, nested START, END without START, empty or duplicate ID. */
export interface RegionScanError {
    /** Offset and 1-based line of the marker at fault (for START without END: of that START). */
    offset: number;
    line: number;
    message: string;
}

export interface RegionScan {
    /** The regions that have both markers, in text order. */
    regions: ScannedRegion[];
    /** Every structural problem, in text order (the first is the one a strict reader stops at). */
    errors: RegionScanError[];
}

/**
 * Maps offsets to 1-based line numbers. Queries come in increasing order (markers are in text
 * order), so newlines are counted incrementally: no per-character pass over files with few markers.
 */
function lineLocator(text: string): (offset: number) => number {
    let line = 1;
    // the next line feed not yet counted (-1: none left): found once, so that a long text without
    // line feeds is not searched to its end on every query (that made many markers quadratic)
    let nextNl = text.indexOf('\n');
    return (offset) => {
        while (nextNl !== -1 && nextNl < offset) {
            line++;
            nextNl = text.indexOf('\n', nextNl + 1);
        }
        return line;
    };
}

/**
 * A marker-like comment that is no marker: `/*` and `PROTECTED REGION`, then at most
 * NEAR_MISS_SPAN characters up to the closing `*\/`. Every repetition is bounded, so one attempt
 * costs at most a few hundred steps and a scan stays linear in the text (ReDoS-safe).
 */
const NEAR_MISS_SPAN = 240;
const NEAR_MISS = new RegExp(`\\/\\*\\s{0,16}PROTECTED[^*]{0,${NEAR_MISS_SPAN}}\\*\\/`, 'g');
const NEAR_MISS_ID = /^\/\*\s*PROTECTED\s+REGION\s+ID\s*\(([^()\r\n]*)\)\s*([^]*?)\s*\*\/$/;

/** Number of line feeds in text[from, to) (a bounded pass: never searches past `to`). */
function countNewlines(text: string, from: number, to: number): number {
    let n = 0;
    for (let i = from; i < to; i++) if (text.charCodeAt(i) === 10) n++;
    return n;
}

/** Blanks and line breaks collapsed, for quoting a marker's words in a message. */
function words(s: string): string {
    return s.trim().split(/\s+/).join(' ');
}

/**
 * The last start marker with a typo in text[from, to) (between the previous marker and an END
 * that has no START), with the message that names it, or undefined. Each stretch of text is
 * searched once (stretches between markers do not overlap): linear overall.
 */
function nearMissStart(text: string, from: number, to: number): { offset: number; message: string } | undefined {
    if (to - from < 12) return undefined;
    const stretch = text.slice(from, to);
    if (!stretch.includes('PROTECTED')) return undefined;
    let found: { offset: number; message: string } | undefined;
    for (const m of stretch.matchAll(NEAR_MISS)) {
        const marker = m[0];
        const id = NEAR_MISS_ID.exec(marker);
        let message: string;
        if (id) {
            const tail = words(id[2]!);
            if (tail === '' || /\bEND\b/i.test(tail)) continue; // `ID(x) END`: not meant as a start
            message = `protected region start '${words(id[1]!)}' is malformed: '${tail}' (expected 'ENABLED START' or 'START')`;
        } else {
            // an END with a typo is not a start either; a start-like comment without a readable ID is
            if (/^\/\*\s*PROTECTED\s+REGION\s+E\w*\s*\*\/$/.test(marker) || !/START|ID/.test(marker)) continue;
            message = `protected region start marker is malformed: '${words(marker)}' (expected '/*PROTECTED REGION ID(<id>) ENABLED START*/')`;
        }
        found = { offset: from + m.index, message };
    }
    return found;
}

/**
 * Finds the protected regions of `text` and every structural problem. A nested START replaces the
 * open region (which is then never closed); a region with an empty or duplicate ID is still a
 * region (and an error).
 */
export function scanRegions(text: string): RegionScan {
    const lineOf = lineLocator(text);
    const regions: ScannedRegion[] = [];
    const errors: RegionScanError[] = [];
    const seen = new Map<string, number>();
    let open: { rawId: string; enabled: boolean; start: number; contentStart: number; line: number } | undefined;
    /** End of the previous marker: a near-miss start marker is looked for between it and a stray END. */
    let previousEnd = 0;
    for (const m of text.matchAll(ANY_MARKER)) {
        const at = m.index;
        const line = lineOf(at);
        if (m[1] === undefined) {
            if (!open) {
                // a start marker with a typo (`ENABELD START`) is no start: say so at its line rather than at this END
                const miss = nearMissStart(text, previousEnd, at);
                if (miss) errors.push({ offset: miss.offset, line: line - countNewlines(text, miss.offset, at), message: miss.message });
                else {
                    // right after a region that ended: its END may be the one too many (one typed in
                    // the region, or a marker in a string), not this one
                    const before = regions[regions.length - 1];
                    const closedBefore = before !== undefined && before.end === previousEnd ? `; region '${before.rawId}' before it ended at line ${before.endLine}: is that END (or a marker inside a string or comment of its code) one too many?` : '';
                    errors.push({ offset: at, line, message: `protected region END without a START${closedBefore}` });
                }
                previousEnd = at + m[0].length;
                continue;
            }
            regions.push({
                id: normaliseRegionId(open.rawId),
                rawId: open.rawId,
                enabled: open.enabled,
                start: open.start,
                contentStart: open.contentStart,
                contentEnd: at,
                end: at + m[0].length,
                line: open.line,
                endLine: line,
            });
            open = undefined;
            previousEnd = at + m[0].length;
            continue;
        }
        const rawId = m[1];
        if (open) {
            errors.push({ offset: at, line, message: `nested protected region start '${rawId}' inside region '${open.rawId}' (opened line ${open.line}, never closed)` });
        }
        const id = normaliseRegionId(rawId);
        if (id === '') errors.push({ offset: at, line, message: 'protected region with an empty ID' });
        const previous = seen.get(id);
        if (previous !== undefined) errors.push({ offset: at, line, message: `duplicate protected region ID '${id}' (first at line ${previous})` });
        else seen.set(id, line);
        open = { rawId, enabled: m[2] !== undefined, start: at, contentStart: at + m[0].length, line };
        previousEnd = at + m[0].length;
    }
    if (open) errors.push({ offset: open.start, line: open.line, message: `protected region '${open.rawId}' START without END` });
    return { regions, errors };
}
