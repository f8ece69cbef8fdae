import { conflictMarkerLines, conflictMarkers } from '@contract-studio/conventions';

/**
 * Why a file of the tree that holds git's merge conflict markers is refused, or undefined: an
 * unresolved merge (`UU` in `git status`) is no file the generator may merge, strip, orphan or
 * delete (docs/codegen.md "Malformed files"). The markers are found anywhere, inside a protected
 * region too: the file is left as git wrote it until the conflict is resolved.
 */
export function conflictRefusal(text: string): { line: number; message: string } | undefined {
    const markers = conflictMarkers(text);
    if (markers.length === 0) return undefined;
    return {
        line: markers[0]!.line,
        message: `holds git merge conflict markers (lines ${conflictMarkerLines(markers)}): resolve the merge conflict first (keep the code you want, remove the marker lines), then generate again; left untouched`,
    };
}
