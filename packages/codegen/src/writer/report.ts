/** A problem attached to a file of the tree (path relative to the output folder, 1-based line when known). */
export interface GenerationProblem {
    file: string;
    line?: number;
    message: string;
}

/** What one generation did to the output folder. Every path is relative to that folder, '/'-separated. */
export interface GenerationReport {
    /** Files that did not exist. */
    created: string[];
    /** Files whose content changed. */
    updated: string[];
    /** Files left as they were (not rewritten: their mtime stays). */
    unchanged: string[];
    /** Orphan files written under `orphans/` (user code whose region or file no longer exists). */
    orphaned: string[];
    /** Generated files of deleted entities that held no user code, deleted. */
    removed: string[];
    /** Problems that left a file untouched (malformed protected regions, unreadable file) or a model error. */
    errors: GenerationProblem[];
    /** Things the user should know: orphaned code, a corrupt manifest. */
    warnings: GenerationProblem[];
    /** How many files were written, the manifest included (0 when nothing changed). */
    filesWritten: number;
}

export function emptyReport(): GenerationReport {
    return { created: [], updated: [], unchanged: [], orphaned: [], removed: [], errors: [], warnings: [], filesWritten: 0 };
}

export function formatProblem(p: GenerationProblem): string {
    return p.line !== undefined ? `${p.file}:${p.line}: ${p.message}` : `${p.file}: ${p.message}`;
}
