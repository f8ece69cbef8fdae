import { UriUtils, type URI } from 'langium';
import type { CactalProjects } from '../scoping/projects.js';

/**
 * Where the other occurrences of a duplicated name are, for messages: all occurrences but one in
 * `own` ("this file" for further ones in the same file), by file name when in the folder of `own`,
 * else by their path in the project (`src/althold.contract`), so that a file is never mistaken for
 * another of the same name.
 */
export function otherLocations(projects: CactalProjects, own: URI, occurrences: URI[]): string {
    const ownUri = own.toString();
    const ownDir = UriUtils.dirname(own).toString();
    const root = projects.rootOf(own);
    let skipped = false;
    const names: string[] = [];
    for (const uri of occurrences) {
        const key = uri.toString();
        if (key === ownUri && !skipped) { skipped = true; continue; }
        const name = key === ownUri ? 'this file'
            : UriUtils.dirname(uri).toString() === ownDir || !root ? UriUtils.basename(uri)
            : UriUtils.relative(root, uri);
        if (!names.includes(name)) names.push(name);
    }
    return names.join(', ') || 'this file';
}
