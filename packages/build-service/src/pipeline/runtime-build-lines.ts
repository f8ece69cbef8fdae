/**
 * The lines of one shared runtime build (runtime-cache.ts), told to the jobs waiting for it: each
 * job follows the build from when it asks for it (the lines so far first, then the later ones, in
 * order) until it stops waiting (it was cancelled) or the build ends. A job cancelled during the
 * first job's build no longer gets its lines (they went on into its log after its cancel); a job
 * that joins a build in progress gets what it missed, so its log says what the build did and why
 * it failed.
 */

export type RuntimeLineStream = 'stdout' | 'stderr';
export type RuntimeLineListener = (line: string, stream: RuntimeLineStream) => void;

/** Lines kept for a job joining a build in progress (a runtime build prints a few dozen). */
export const RUNTIME_BUILD_LINES_KEPT = 2000;

export class RuntimeBuildLines {
  private readonly kept: [string, RuntimeLineStream][] = [];
  /** Lines let go of beyond RUNTIME_BUILD_LINES_KEPT (a joining job is told how many). */
  private dropped = 0;
  private readonly followers = new Set<RuntimeLineListener>();
  private ended = false;

  /** One line of the build: kept, and told to every job following it now. */
  line(line: string, stream: RuntimeLineStream): void {
    if (this.ended) return;
    this.kept.push([line, stream]);
    if (this.kept.length > RUNTIME_BUILD_LINES_KEPT) {
      this.kept.shift();
      this.dropped++;
    }
    for (const f of [...this.followers]) tell(f, line, stream);
  }

  /**
   * `listener` gets the lines so far, then the later ones, until `until` settles (the job stopped
   * waiting) or the build ends.
   */
  follow(listener: RuntimeLineListener, until?: Promise<unknown>): void {
    if (this.dropped) tell(listener, `(${this.dropped} earlier line(s) of this runtime build not kept)`, 'stdout');
    for (const [line, stream] of this.kept) tell(listener, line, stream);
    if (this.ended) return;
    this.followers.add(listener);
    const leave = (): void => void this.followers.delete(listener);
    until?.then(leave, leave);
  }

  /** The build ended: no line is told any more. */
  end(): void {
    this.ended = true;
    this.followers.clear();
  }
}

/** A listener that throws (a job's log failing) costs neither the build nor the other jobs. */
function tell(listener: RuntimeLineListener, line: string, stream: RuntimeLineStream): void {
  try {
    listener(line, stream);
  } catch {
    /* the follower's fault */
  }
}
