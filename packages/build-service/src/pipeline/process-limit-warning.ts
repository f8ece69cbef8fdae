/**
 * `contract check`'s architecture-over-process-limit warning (packages/language, docs/diagnostics.md)
 * is about the build service's DEFAULT process limit: a job whose own limit fits the architecture
 * (`contract run --limit processes=512`, `contract serve --limit`) does not repeat it.
 */
import { runThreads } from '@contract-studio/conventions';
import type { CactalProblem } from './cactal-adapter.js';

/** The warning's first words (packages/language/src/validation/architecture-checks.ts): the architecture's processes. */
const RUNS = /^This architecture runs (\d{1,9}) processes /;

/** Whether `problem` is still true of a job whose process limit is `processes` (every other problem is). */
export function holdsUnderProcessLimit(problem: CactalProblem, processes: number): boolean {
  if (problem.code !== 'architecture-over-process-limit') return true;
  const m = RUNS.exec(problem.message);
  return !m || runThreads(Number(m[1])) > processes;
}
