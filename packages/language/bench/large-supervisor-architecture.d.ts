/** Path of the large supervisor file in the generated architecture. */
export declare const LARGE_SUPERVISOR_FILE: string;
/** relative path -> content of the field-sized architecture (70 files, a 350-line supervisor). */
export declare function generateLargeSupervisorArchitecture(): Map<string, string>;
/** Writes the architecture under dir; returns the number of files. */
export declare function writeLargeSupervisorArchitecture(dir: string): number;
