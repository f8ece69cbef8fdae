/**
 * A container's processes as its engine lists them (`docker top`, ps run by the engine on its own
 * host: it needs no room in the container, which at its process limit has none), as a
 * ProcessTable for forking-module.ts: which module forked past the limit when the container's
 * cgroup is not read here (a remote engine). The listing is the engine's, read as hostile: rows
 * past MAX_ROWS, and rows whose pid or parent is no number, are left out; a name is kept to 64
 * characters.
 */
import type Docker from 'dockerode';
import type { ProcessTable } from './forking-module.js';

/** `ps -o` columns asked for: pid, parent pid, the kernel's name of the process. */
export const TOP_PS_ARGS = '-o pid,ppid,comm';
/** Rows read at most (a limit of thousands of processes). */
const MAX_ROWS = 4096;
const PID = /^\d{1,10}$/;

/** The pids and the table of an engine's `top` answer ({Titles, Processes}). */
export function processTableOfTop(top: unknown): { pids: number[]; table: ProcessTable } {
  const names = new Map<number, string>();
  const parents = new Map<number, number>();
  const rows = (top as { Processes?: unknown })?.Processes;
  const titles = (top as { Titles?: unknown })?.Titles;
  const col = (name: string): number => (Array.isArray(titles) ? titles.findIndex((t) => typeof t === 'string' && t.trim().toUpperCase() === name) : -1);
  const [pidAt, ppidAt, nameAt] = [col('PID'), col('PPID'), Math.max(col('COMMAND'), col('COMM'))];
  if (Array.isArray(rows) && pidAt >= 0 && ppidAt >= 0 && nameAt >= 0) {
    for (const row of rows.slice(0, MAX_ROWS)) {
      if (!Array.isArray(row)) continue;
      const [pid, ppid, name] = [row[pidAt], row[ppidAt], row[nameAt]];
      if (typeof pid !== 'string' || typeof ppid !== 'string' || typeof name !== 'string' || !PID.test(pid) || !PID.test(ppid)) continue;
      names.set(Number(pid), name.slice(0, 64));
      parents.set(Number(pid), Number(ppid));
    }
  }
  return { pids: [...names.keys()], table: { nameOf: (pid) => names.get(pid) ?? '', parentOf: (pid) => parents.get(pid) ?? 0 } };
}

/** The container's processes as its engine lists them; none when it cannot (the container gone, an engine that refuses). */
export async function engineProcesses(container: Docker.Container): Promise<{ pids: number[]; table: ProcessTable }> {
  try {
    return processTableOfTop(await container.top({ ps_args: TOP_PS_ARGS }));
  } catch {
    return processTableOfTop(undefined);
  }
}
