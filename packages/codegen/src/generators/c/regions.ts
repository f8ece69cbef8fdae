import { joinToNode, NL, type Generated } from 'langium/generate';
import { END, startMarker } from '../../regions/markers.js';

/** Multi-line text as a generator node, so that `expandToNode` indents every line to the substitution's column. */
export function lines(text: string): Generated {
    return joinToNode(text.split('\n'), (l) => l, { separator: NL });
}

/**
 * A protected region as a generator writes it: markers on their own lines around `body`
 * (a block region, indented where it is substituted), or inline (`MODULE_AUTHOR(<region>"name"<end>)`).
 */
export function blockRegion(id: string, body: string): Generated {
    const trimmed = body.endsWith('\n') ? body.slice(0, -1) : body;
    return lines(`${startMarker(id)}\n${trimmed}\n${END}`);
}

export function inlineRegion(id: string, body: string): string {
    return `${startMarker(id)}${body}${END}`;
}
