import { scanRegions } from '@contract-studio/conventions';
import { RegionSyntaxError } from './region-error.js';

/** One protected region of a file: where its content lies and whether the user owns it. */
export interface Region {
    /** The normalised ID (`additionnal` read as `additional`). */
    id: string;
    /** The ID as written in the file. */
    rawId: string;
    enabled: boolean;
    /** The bytes between the start and the end marker, exactly. */
    content: string;
    /** Offsets in the file text: start marker begins at `start`, content spans [contentStart, contentEnd), end marker ends at `end`. */
    start: number;
    contentStart: number;
    contentEnd: number;
    end: number;
    /** 1-based line of the start marker. */
    line: number;
}

export interface ParsedFile {
    text: string;
    regions: Region[];
}

/**
 * Splits a file into its protected regions. Throws RegionSyntaxError (file + line) for a START
 * without END, a nested START, an END without START, an empty or duplicate ID.
 */
export function parseRegions(text: string, file: string): ParsedFile {
    const scan = scanRegions(text);
    const first = scan.errors[0];
    if (first) throw new RegionSyntaxError(file, first.line, first.message);
    return {
        text,
        regions: scan.regions.map((r) => ({
            id: r.id,
            rawId: r.rawId,
            enabled: r.enabled,
            content: text.slice(r.contentStart, r.contentEnd),
            start: r.start,
            contentStart: r.contentStart,
            contentEnd: r.contentEnd,
            end: r.end,
            line: r.line,
        })),
    };
}
