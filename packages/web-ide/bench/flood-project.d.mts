/** The tutorial with MSA flooding its stdout (flood-project.mjs). */
export function floodProject(dir: string, rate: number, seconds: number): void;
