/**
 * The diagnostics of a `.contract` file holding git merge conflict markers (conventions'
 * conflictMarkers): one `merge-conflict-marker` error on each marker line, saying which side it
 * opens or closes and what to do. The document validator gives these alone: the parser's errors on
 * the markers, and on both sides read as one text, would only bury them.
 */
import type { ConflictMarker } from '@contract-studio/conventions';
import { conflictMarkerLines } from '@contract-studio/conventions';
import { DiagnosticSeverity, type Diagnostic } from 'vscode-languageserver-types';

const ROLE: Record<ConflictMarker['kind'], string> = {
    ours: 'your side of the conflict begins here',
    base: "the common ancestor's lines begin here",
    separator: 'their side begins here',
    theirs: 'their side ends here'
};

export function conflictMarkerDiagnostics(markers: readonly ConflictMarker[]): Diagnostic[] {
    const lines = conflictMarkerLines(markers);
    return markers.map((m) => ({
        severity: DiagnosticSeverity.Error,
        range: { start: { line: m.line - 1, character: 0 }, end: { line: m.line - 1, character: m.length } },
        message: `Unresolved git merge conflict (marker lines ${lines}): ${ROLE[m.kind]}. Keep the lines you want, delete the marker lines, and save; nothing else in this file is checked until then.`,
        code: 'merge-conflict-marker',
        source: 'cactal',
        data: { code: 'merge-conflict-marker' }
    }));
}
