/**
 * The recent Build & Run jobs of the workspace in the Monitor's run list (docs/watching-a-run.md
 * "Opening it"): the IDE server lists them from its build service (`GET /api/recent-runs`, the
 * service's listing of the IDE server's jobs, its last 50 kept), so every tab — one opened after
 * the tab that ran a job was closed — can replay them. Pure: what is offered, and how it is labelled.
 */
import type { RecentRun } from '../../server/api-types.js';
import { jobOutcome } from './live-follow-protocol.js';
import { liveRunLabel } from './live-run-label.js';

const JOB_ID = /^[A-Za-z0-9_-]{1,100}$/;
const ENDED = new Set(['succeeded', 'failed', 'cancelled']);

/** A recent job as the run list offers it: its entry's id (`job:ID`), label, and how it ended (undefined: going on). */
export interface RecentEntry {
  id: string;
  jobId: string;
  label: string;
  outcome?: string;
  project: string;
}

/** The jobs of an answer of `GET /api/recent-runs` that are well formed (anything else is dropped). */
export function recentRunsOf(answer: unknown): RecentRun[] {
  const jobs = (answer as { jobs?: unknown } | null)?.jobs;
  if (!Array.isArray(jobs)) return [];
  return jobs.filter((j): j is RecentRun => {
    const r = j as Partial<RecentRun> | null;
    return !!r && typeof r.id === 'string' && JOB_ID.test(r.id) && typeof r.project === 'string' && typeof r.status === 'string' && typeof r.createdAt === 'number';
  });
}

/** `18:31:05`, and its date before it when it is not today's (`2026-12-06 18:31:05`), in local time. */
export function startTime(ms: number, now = Date.now()): string {
  const d = new Date(ms);
  const two = (n: number) => String(n).padStart(2, '0');
  const time = `${two(d.getHours())}:${two(d.getMinutes())}:${two(d.getSeconds())}`;
  const today = new Date(now);
  const sameDay = d.getFullYear() === today.getFullYear() && d.getMonth() === today.getMonth() && d.getDate() === today.getDate();
  return sameDay ? time : `${d.getFullYear()}-${two(d.getMonth() + 1)}-${two(d.getDate())} ${time}`;
}

/**
 * The run list's entry of a recent job: `Build & Run job j-… · started 18:31:05 · ended: succeeded`
 * (the project named when it is not the workspace itself: `· robot`), or `· running: pick it to
 * follow it live` while it goes on.
 */
export function recentEntry(run: RecentRun, now = Date.now()): RecentEntry {
  const ended = ENDED.has(run.status);
  const outcome = ended ? (run.status === 'cancelled' ? 'cancelled' : jobOutcome({ ok: run.ok === true, message: run.message ?? undefined })) : undefined;
  const where = run.project ? ` · ${run.project}` : '';
  const head = liveRunLabel(run.id).replace(' · live', '');
  const state = outcome !== undefined ? ` · ended: ${outcome}` : ' · running: pick it to follow it live';
  return { id: `job:${run.id}`, jobId: run.id, label: `${head}${where} · started ${startTime(run.createdAt, now)}${state}`, outcome, project: run.project };
}
