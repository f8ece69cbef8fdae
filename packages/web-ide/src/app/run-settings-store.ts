/**
 * The run settings, kept in the browser (localStorage), one record for the server's origin: the
 * duration, init time, CPUs and real-time go for every project; the start request and the stdin
 * files (they name a project's own supervisor, modules and files) are kept per project, under
 * `projects[where]` (`where`: the workspace root and the project folder), so saving the settings
 * of one project of a workspace leaves the others' as they were.
 *
 * Earlier versions kept one start request (`start`, with `startFor` naming its project, or none: it
 * went for any) and one stdin text (`stdin`, `stdinFor`): a project with no entry of its own under
 * `projects` still reads them, and a save keeps those of the other projects.
 */
import { MIN_READY_TIMEOUT_SECONDS } from '@contract-studio/conventions';

export const RUN_SETTINGS_KEY = 'contract-studio:run-settings';

/** The settings of one project; `stdin` as kept (read it with keptStdin: it may be an earlier version's text, or edited by hand). */
export type RunSettings = { duration: number; start?: string; readyTimeout?: number; cpus?: string; realtime?: boolean; stdin?: unknown };

/** What a save writes for one project. */
export type SavedRunSettings = { duration: number; start: string; readyTimeout?: number; cpus?: string; realtime: boolean; stdin: Record<string, string> };

type ProjectSettings = { start?: string; stdin?: Record<string, string> };
type Kept = { duration?: unknown; readyTimeout?: unknown; cpus?: unknown; realtime?: unknown; start?: unknown; startFor?: unknown; stdin?: unknown; stdinFor?: unknown; projects?: unknown };

/** Whether `v` is a ready timeout a run may ask for (seconds: MIN_READY_TIMEOUT_SECONDS or more). */
export const isReadyTimeout = (v: unknown): v is number => typeof v === 'number' && Number.isFinite(v) && v >= MIN_READY_TIMEOUT_SECONDS;

const isRecord = (v: unknown): v is Record<string, unknown> => typeof v === 'object' && v !== null && !Array.isArray(v);

function kept(): Kept {
  try {
    const v: unknown = JSON.parse(localStorage.getItem(RUN_SETTINGS_KEY) ?? '{}');
    return isRecord(v) ? v : {};
  } catch {
    return {};
  }
}

/** The projects' own settings kept (a copy; an entry that is no object left out). */
function projectsOf(v: Kept): Record<string, ProjectSettings> {
  const out: Record<string, ProjectSettings> = {};
  if (isRecord(v.projects)) for (const [where, p] of Object.entries(v.projects)) if (isRecord(p)) out[where] = p as ProjectSettings;
  return out;
}

/** The run settings for the project at `where` (`root/project`). */
export function readRunSettings(where: string): RunSettings {
  const v = kept();
  const own = projectsOf(v)[where];
  const start = own ? (typeof own.start === 'string' && own.start ? own.start : undefined)
    : typeof v.start === 'string' && v.start && (v.startFor === undefined || v.startFor === where) ? v.start : undefined;
  const stdin = own ? own.stdin : v.stdin && v.stdinFor === where ? v.stdin : undefined;
  return {
    duration: typeof v.duration === 'number' && v.duration > 0 ? v.duration : 10,
    start,
    readyTimeout: isReadyTimeout(v.readyTimeout) ? v.readyTimeout : undefined,
    cpus: typeof v.cpus === 'string' && v.cpus ? v.cpus : undefined,
    realtime: v.realtime === true || undefined,
    stdin,
  };
}

/** Saves `s` for the project at `where`: the settings of every project, its own ones for it only. */
export function saveRunSettings(where: string, s: SavedRunSettings): void {
  const v = kept();
  const projects = projectsOf(v);
  projects[where] = { ...(s.start ? { start: s.start } : {}), ...(Object.keys(s.stdin).length ? { stdin: { ...s.stdin } } : {}) };
  // an earlier version's start request and stdin text, kept for the projects they were for (not this one: saved above)
  const earlier = {
    ...(typeof v.start === 'string' && v.start && v.startFor !== where ? { start: v.start, ...(v.startFor !== undefined ? { startFor: v.startFor } : {}) } : {}),
    ...(v.stdin !== undefined && v.stdinFor !== undefined && v.stdinFor !== where ? { stdin: v.stdin, stdinFor: v.stdinFor } : {}),
  };
  localStorage.setItem(RUN_SETTINGS_KEY, JSON.stringify({
    duration: s.duration, ...(s.readyTimeout !== undefined ? { readyTimeout: s.readyTimeout } : {}), ...(s.cpus ? { cpus: s.cpus } : {}),
    ...(s.realtime ? { realtime: true } : {}), ...earlier, projects,
  }));
}
