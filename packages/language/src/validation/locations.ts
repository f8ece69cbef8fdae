import type { URI } from 'langium';

/**
 * Where the other occurrences of a duplicated name are, for messages: the file names of all
 * occurrences but one in `ownUri` ("this file" for further ones in the same file).
 */
export function otherLocations(ownUri: string, occurrences: URI[]): string {
    let skipped = false;
    const names: string[] = [];
    for (const uri of occurrences) {
        const key = uri.toString();
        if (key === ownUri && !skipped) { skipped = true; continue; }
        const name = key === ownUri ? 'this file' : (uri.path.split('/').pop() ?? key);
        if (!names.includes(name)) names.push(name);
    }
    return names.join(', ') || 'this file';
}
