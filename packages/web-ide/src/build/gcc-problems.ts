/**
 * A build's diagnostics (gcc's, the assembler's, the linker's: docs/build-service-api.md "gcc
 * diagnostic") as rows of the Problems panel: a file of the project's src-gen opens at its line
 * and column; one with no place in the project (the linker's `cannot find -lx`, a system header)
 * is listed under BUILD_WITHOUT_FILE, its place in its message, and opens nothing. Each is labelled
 * by where it comes from: `gcc` (the compiler, the assembler, the linker), or `run` for a
 * diagnostic of the run (`origin: 'run'`: a module crashed at that line). Pure.
 */
import type { Problem } from '../panels/problems.js';
import type { GccDiagnostic } from './build-panel.js';

/** The group of the build's errors that name no file of the project: they open nothing. */
export const BUILD_WITHOUT_FILE = '(build: outside the project)';

/** The Problems rows of `diags`, whose files are relative to the src-gen folder `srcGen` (ends with `/`). */
export function gccProblems(diags: readonly GccDiagnostic[], srcGen: string): Problem[] {
  return diags.map((x) => ({
    ...(x.file === null || x.file.startsWith('/')
      ? { path: BUILD_WITHOUT_FILE, line: 1, column: 1, message: `${x.file ? `${x.file}:${x.line ?? 0}: ` : ''}${x.message}` }
      : { path: srcGen + x.file, line: x.line ?? 1, column: x.column || 1, message: x.message + (x.protectedRegion ? ` (in region ${x.protectedRegion.id})` : '') }),
    severity: x.severity === 'note' ? 'info' : x.severity,
    source: x.origin === 'run' ? 'run' : 'gcc',
  }));
}
