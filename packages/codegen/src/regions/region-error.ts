/** A problem found in a file's protected regions, located by file and 1-based line. */
export class RegionSyntaxError extends Error {
    constructor(
        readonly file: string,
        readonly line: number,
        readonly detail: string,
    ) {
        super(`${file}:${line}: ${detail}`);
        this.name = 'RegionSyntaxError';
    }
}
