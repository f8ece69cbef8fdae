import { END_MARKER, START_MARKER, normaliseRegionId } from './markers.js';
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

interface Marker {
    kind: 'start' | 'end';
    index: number;
    length: number;
    rawId: string;
    enabled: boolean;
}

function collectMarkers(text: string): Marker[] {
    const markers: Marker[] = [];
    for (const m of text.matchAll(START_MARKER)) {
        markers.push({ kind: 'start', index: m.index, length: m[0].length, rawId: m[1] ?? '', enabled: m[2] !== undefined });
    }
    for (const m of text.matchAll(END_MARKER)) {
        markers.push({ kind: 'end', index: m.index, length: m[0].length, rawId: '', enabled: false });
    }
    return markers.sort((a, b) => a.index - b.index);
}

/**
 * Maps offsets to 1-based line numbers. Queries come in increasing order (markers are sorted), so
 * newlines are counted incrementally: no per-character pass over files that have few markers.
 */
function lineLocator(text: string): (offset: number) => number {
    let line = 1;
    let scanned = 0;
    return (offset) => {
        if (offset < scanned) {
            line = 1;
            scanned = 0;
        }
        for (let nl = text.indexOf('\n', scanned); nl !== -1 && nl < offset; nl = text.indexOf('\n', nl + 1)) line++;
        scanned = offset;
        return line;
    };
}

/**
 * Splits a file into its protected regions. Throws RegionSyntaxError (file + line) for a START
 * without END, a nested START, an END without START, an empty or duplicate ID.
 */
export function parseRegions(text: string, file: string): ParsedFile {
    const lineOf = lineLocator(text);
    const regions: Region[] = [];
    const seen = new Map<string, number>();
    let open: Marker | undefined;
    for (const marker of collectMarkers(text)) {
        if (marker.kind === 'start') {
            if (open) {
                throw new RegionSyntaxError(file, lineOf(marker.index),
                    `nested protected region start '${marker.rawId}' inside region '${open.rawId}' (opened line ${lineOf(open.index)}, never closed)`);
            }
            const id = normaliseRegionId(marker.rawId);
            if (id === '') throw new RegionSyntaxError(file, lineOf(marker.index), 'protected region with an empty ID');
            const previous = seen.get(id);
            if (previous !== undefined) {
                throw new RegionSyntaxError(file, lineOf(marker.index),
                    `duplicate protected region ID '${id}' (first at line ${previous})`);
            }
            seen.set(id, lineOf(marker.index));
            open = marker;
        } else {
            if (!open) throw new RegionSyntaxError(file, lineOf(marker.index), 'protected region END without a START');
            const contentStart = open.index + open.length;
            regions.push({
                id: normaliseRegionId(open.rawId),
                rawId: open.rawId,
                enabled: open.enabled,
                content: text.slice(contentStart, marker.index),
                start: open.index,
                contentStart,
                contentEnd: marker.index,
                end: marker.index + marker.length,
                line: lineOf(open.index),
            });
            open = undefined;
        }
    }
    if (open) {
        throw new RegionSyntaxError(file, lineOf(open.index), `protected region '${open.rawId}' START without END`);
    }
    return { text, regions };
}
