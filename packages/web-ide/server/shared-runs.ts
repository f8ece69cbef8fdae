/**
 * The runs of this IDE, shared by its tabs (docs/ide.md "Several tabs"). Every Build & Run (or
 * build) submitted to the embedded build service is announced to every tab on /api/events
 * (`event: job`, data `{ id, action, project }`), and a tab that connects — a new tab, a reload,
 * a reconnection — is told the ones still going (`event: jobs`, data `{ jobs: [...] }`), so a tab
 * that follows no job can follow one another tab started: its log, its Monitor, its Stop.
 * Only jobs on a project folder inside the workspace are announced, by their path relative to it.
 */
import { isAbsolute, relative, sep } from 'node:path';
import type { SharedJob } from './api-types.js';

/** What this needs of a build-service job (its id, whether it ended, its request). */
interface JobLike {
  id: string;
  isDone: boolean;
  request: { action: 'build' | 'run'; projectKey: string | null };
}

/** What this needs of the build service (JobService). */
export interface JobsLike {
  onSubmitted(listener: (job: JobLike) => void): () => void;
  list(): JobLike[];
}

export class SharedRuns {
  private readonly unsubscribe: () => void;

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
