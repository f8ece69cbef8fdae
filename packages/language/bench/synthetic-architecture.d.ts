export interface SyntheticOptions {
    /** Type files (default 10). */
    typeFiles?: number;
    /** Periodic schemas, 5 synchronous modules each by default (default 160). */
    periodicSchemas?: number;
    /** Event schemas, 5 asynchronous modules each by default (default 40). */
    eventSchemas?: number;
    /** Modules per schema (default 5). */
    modulesPerSchema?: number;
    /** Supervisors (default 20); the first activates all the others. */
    supervisors?: number;
}
/** Three-letter name number i (AAA, AAB, ...), never ORD. */
export declare function threeLetterName(i: number): string;
/** relative path -> content of a valid synthetic Cactal architecture. */
export declare function generateSyntheticArchitecture(options?: SyntheticOptions): Map<string, string>;
/** Writes the architecture under dir; returns the number of files. */
export declare function writeSyntheticArchitecture(dir: string, options?: SyntheticOptions): number;
