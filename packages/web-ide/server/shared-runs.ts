/**
 * The runs of this IDE, shared by its tabs (docs/ide.md "Several tabs"). Every Build & Run (or
 * build) submitted to the embedded build service is announced to every tab on /api/events
 * (`event: job`, data `{ id, action, project }`), and a tab that connects — a new tab, a reload,
 * a reconnection — is told the ones still going (`event: jobs`, data `{ jobs: [...] }`), so a tab
 * that follows no job can follow one another tab started: its log, its Monitor, its Stop.
 * Only jobs on a project folder inside the workspace are announced, by their path relative to it.
 *
 * The recent Build & Run jobs (`GET /api/recent-runs`, the Monitor's run list in every tab): the IDE
 * server is a client of its build service with a key of its own (X-Contract-Client, made at its
 * start), sent with every job submitted through it that names no key of its own; the service's own
 * listing of that key's jobs (the ones it keeps: its last 50) gives them, newest first.
 */
import { createHash, randomBytes } from 'node:crypto';
import type { IncomingMessage } from 'node:http';
import { isAbsolute, relative, sep } from 'node:path';
import type { RecentRun, SharedJob } from './api-types.js';

/** The Build & Run jobs the Monitor's run list offers from the build service. */
export const RECENT_RUNS = 10;
/** The build service's header naming who may list a job (its router's CLIENT_HEADER). */
const CLIENT_HEADER = 'x-contract-client';

/** What this needs of a build-service job (its id, whether it ended, its request, how it is). */
interface JobLike {
  id: string;
  isDone: boolean;
  request: { action: 'build' | 'run'; projectKey: string | null };
  status?: string;
  createdAt?: number;
  finishedAt?: number | null;
  result?: { ok: boolean; message: string } | null;
}

/** What this needs of the build service (JobService). */
export interface JobsLike {
  onSubmitted(listener: (job: JobLike) => void): () => void;
  /** The jobs kept, newest first; with `owner` (a digest of a client key), that client's only. */
  list(owner?: string): JobLike[];
}

export class SharedRuns {
  private readonly unsubscribe: () => void;
  /** The IDE server's client key with its build service (never sent to a page). */
  private readonly key = randomBytes(24).toString('hex');
  /** Its digest, as the service keeps it per job (the service's router: sha256 of the key). */
  private readonly owner = createHash('sha256').update(this.key).digest('hex');

  /** `root`: the workspace's real path (the service names projects by their real path). */
  constructor(private readonly jobs: JobsLike, private readonly root: string, announce: (job: SharedJob) => void) {
    this.unsubscribe = jobs.onSubmitted((job) => {
      const shared = this.describe(job);
      if (shared) announce(shared);
    });
  }

  /** The jobs not finished yet, newest first. */
  going(): SharedJob[] {
    return this.jobs.list().filter((j) => !j.isDone).map((j) => this.describe(j)).filter((j): j is SharedJob => !!j);
  }

  /**
   * A request on its way to the build service: a job submitted (`POST /api/jobs`) with no client key
   * of its own gets the IDE server's, so that it is listed by recent().
   */
  claim(req: IncomingMessage, pathname: string): void {
    if (req.method === 'POST' && pathname === '/api/jobs' && req.headers[CLIENT_HEADER] === undefined) req.headers[CLIENT_HEADER] = this.key;
  }

  /**
   * The last `limit` Build & Run jobs submitted through this IDE server on a project folder of the
   * workspace that the build service still keeps, newest first: the service's listing of the IDE
   * server's key. A job it no longer keeps (past its last 50) is not listed.
   */
  recent(limit = RECENT_RUNS): RecentRun[] {
    const runs: RecentRun[] = [];
    for (const job of this.jobs.list(this.owner)) {
      if (runs.length >= limit) break;
      const shared = job.request.action === 'run' ? this.describe(job) : undefined;
      if (!shared) continue;
      runs.push({
        id: shared.id, project: shared.project, status: job.status ?? (job.isDone ? 'failed' : 'running'),
        createdAt: job.createdAt ?? 0, finishedAt: job.finishedAt ?? null, ok: job.result?.ok ?? null, message: job.result?.message ?? null,
      });
    }
    return runs;
  }

  close(): void {
    this.unsubscribe();
  }

  private describe(job: JobLike): SharedJob | undefined {
    const key = job.request.projectKey;
    if (!key) return undefined;
    const rel = relative(this.root, key);
    if (rel === '..' || rel.startsWith(`..${sep}`) || isAbsolute(rel)) return undefined;
    return { id: job.id, action: job.request.action, project: rel.split(sep).join('/') };
  }
}
