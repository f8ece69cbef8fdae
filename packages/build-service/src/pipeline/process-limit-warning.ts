/**
 * `contract check`'s architecture-over-process-limit warning (packages/language, docs/diagnostics.md)
 * is about the build service's DEFAULT process limit: a job whose own limit fits the architecture
 * (`contract run --limit processes=512`, `contract serve --limit`) does not repeat it. Read from
 * the diagnostic's code and data (`threads`: its processes and threads), never from its words.
 */
import type { CactalProblem } from './cactal-adapter.js';

/** The processes and threads the warning counts (its data's `threads`), or undefined when it holds no such whole number. */
function threadsOf(problem: CactalProblem): number | undefined {
  const threads = (problem.data as { threads?: unknown } | null | undefined)?.threads;
  return typeof threads === 'number' && Number.isSafeInteger(threads) && threads > 0 ? threads : undefined;
}

/** Whether `problem` is still true of a job whose process limit is `processes` (every other problem is, and a warning without its count). */
export function holdsUnderProcessLimit(problem: CactalProblem, processes: number): boolean {
  if (problem.code !== 'architecture-over-process-limit') return true;
  const threads = threadsOf(problem);
  return threads === undefined || threads > processes;
}
