/**
 * Which of the launcher's lines are only news. contract-launch writes every line to stderr (they
 * are diagnostics, not the architecture's output), so the log showed "module LOC (pid 15) exited
 * with status 0" and "all modules stopped cleanly" in the error colour of stderr. These are shown
 * in the plain colour; any other launcher line (a module that died or failed, a refused start, a
 * module not ready, a bad option) keeps the error colour.
 */
const NEWS: readonly RegExp[] = [
  /^run directory \S/,
  /^modules pinned to CPUs \S/,
  /^CPU wake-up latency held at \d+ us /,
  /^\d+ module\(s\) running$/,
  /^started [A-Za-z_]\w*\.[A-Za-z_]\w*\(/,
  // the stop, with why when the build service said (`stopping: the job was cancelled`)
  /^stopping(?:: [ -~]{1,120})?$/,
  /^module \S+ \(pid \d+\) exited with status 0$/,
  // a module stopped by the launcher's own SIGTERM at the end of a run (a death by signal says "died")
  /^module \S+ \(pid \d+\) terminated by signal 15 \([^)]*\)$/,
  /^all modules stopped cleanly$/,
  /^stopped \d+ module\(s\) of \S/,
];

/** Whether a launcher line (its `contract-launch: ` prefix removed) is only news, not a problem. */
export function isLauncherNews(line: string): boolean {
  return NEWS.some((re) => re.test(line));
}
