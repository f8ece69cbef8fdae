/**
 * The modules contract-launch saw crash (a signal, a non-zero exit: before or while the run
 * stopped), read from its own lines, for the failed run's message: `run failed: module MSC crashed
 * (died by signal 11 (Segmentation fault))` rather than make's exit status alone, which reads like
 * a build failure. The launcher's words (runtime/launcher/contract-launch.c reap, docs/runtime-api.md
 * "contract-launch"): `module X (pid N) died by signal ...` / `exited with status N ...`, then
 * `FAILED: module X crashed` at the end.
 */

/** How a module ended, as the launcher said it. */
const END_LINE = /^module ([A-Za-z_]\w*) \(pid \d+\) (exited with status \d+(?: while the run stopped)?|died by signal .{1,200})$/;
const FAILED_LINE = /^FAILED: module ([A-Za-z_]\w*) crashed$/;
/** Crashes named in one message at most (the others counted). */
const NAMED = 4;

export class LauncherCrashes {
  private readonly how = new Map<string, string>();
  private readonly crashed: string[] = [];

  /** A line of contract-launch (its `contract-launch: ` prefix removed). */
  line(text: string): void {
    const end = END_LINE.exec(text);
    if (end) {
      if (this.how.size < 1024) this.how.set(end[1]!, end[2]!);
      return;
    }
    const failed = FAILED_LINE.exec(text);
    if (failed && !this.crashed.includes(failed[1]!) && this.crashed.length < 1024) this.crashed.push(failed[1]!);
  }

  /** The modules that crashed, in the order the launcher named them, each with how it ended (undefined: no exit line read). */
  failures(): { module: string; how: string | undefined }[] {
    return this.crashed.map((module) => ({ module, how: this.how.get(module) }));
  }

  /** `module MSC crashed (died by signal 11 (...))`, `2 modules crashed: MSC (...), MAB (...)`; undefined when none did. */
  summary(): string | undefined {
    const failures = this.failures();
    if (!failures.length) return undefined;
    const one = (f: { module: string; how: string | undefined }) => `${f.module} (${f.how ?? 'no exit line'})`;
    if (failures.length === 1) return `module ${failures[0]!.module} crashed (${failures[0]!.how ?? 'no exit line'})`;
    const named = failures.slice(0, NAMED).map(one).join(', ');
    const more = this.crashed.length > NAMED ? ` and ${this.crashed.length - NAMED} more` : '';
    return `${this.crashed.length} modules crashed: ${named}${more}`;
  }
}
