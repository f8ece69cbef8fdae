import type { RunController } from './run-controller.js';
import type { ServerEvents } from './server-events.js';
import type { SharedJob } from '../../server/api-types.js';

function sharedJob(v: unknown): v is SharedJob {
  const j = v as Partial<SharedJob> | null;
  return !!j && typeof j.id === 'string' && (j.action === 'build' || j.action === 'run') && typeof j.project === 'string';
}

/**
 * Runs started in another tab (docs/ide.md "Several tabs"): the IDE server announces each one on
 * /api/events (`job`), and the ones still going when this tab connects (`jobs`, newest first).
 * A tab that follows no job of its own follows it: the log, the Monitor, Stop.
 */
export function followSharedRuns(events: ServerEvents, runs: RunController): void {
  events.on('job', (job) => {
    if (sharedJob(job)) void runs.followShared(job);
  });
  events.on('jobs', (d) => {
    const jobs = (d as { jobs?: unknown } | null)?.jobs;
    const newest = Array.isArray(jobs) ? jobs.find(sharedJob) : undefined;
    if (newest) void runs.followShared(newest);
  });
}
