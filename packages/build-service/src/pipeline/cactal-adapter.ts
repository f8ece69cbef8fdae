/**
 * The "prepare" step's link to the language and code generator packages (architecture.md Seam 4),
 * loaded lazily (in the bounded worker of generate-worker.ts) so the service still builds plain
 * Makefile projects when they are absent. Their results cross the worker boundary as the
 * packages' own types (structured-cloned), imported here as types only:
 *   loadWorkspace(dir)                      -> LoadedWorkspace.diagnostics: WorkspaceDiagnostic[]
 *   generateArchitecture(documents, outDir) -> GenerationReport (errors, warnings: GenerationProblem[])
 */
import type { WorkspaceDiagnostic } from '@contract-studio/language/node';
import type { GenerationProblem } from '@contract-studio/codegen';

export interface CactalProblem {
  file: string;
  line: number;
  column: number;
  severity: 'error' | 'warning' | 'info';
  message: string;
  /** The model diagnostic's stable code (docs/diagnostics.md), as `contract check` gives it; none for the generator's own problems. */
  code?: string;
  /** The model diagnostic's data, when it has any (docs/diagnostics.md names it per code: e.g. `threads` of architecture-over-process-limit). */
  data?: unknown;
}

export interface GenerateOutcome {
  problems: CactalProblem[];
  written: number;
  unchanged: number;
}

/** loadWorkspace's diagnostics (paths already relative to the project) as CactalProblems; hints count as info. */
export function workspaceProblems(diagnostics: readonly WorkspaceDiagnostic[]): CactalProblem[] {
  return diagnostics.map((d) => ({
    file: d.file,
    line: d.line,
    column: d.column,
    severity: d.severity === 'hint' ? 'info' : d.severity,
    message: d.message,
    code: d.code,
    ...(d.data !== undefined ? { data: d.data } : {}),
  }));
}

/** The generator's errors and warnings (paths relative to src-gen, line when known) as CactalProblems. */
export function generationProblems(report: { errors: readonly GenerationProblem[]; warnings: readonly GenerationProblem[] }): CactalProblem[] {
  const problems: CactalProblem[] = [];
  for (const [list, severity] of [[report.errors, 'error'], [report.warnings, 'warning']] as const) {
    for (const p of list) problems.push({ file: p.file, line: p.line ?? 0, column: 0, severity, message: p.message });
  }
  return problems;
}
