/**
 * One queue per workspace file: the saves of a file (PUT /api/file) run one after the other, so
 * the compare of a save's base version with the disk and its write happen with no other save of
 * that file in between (two tabs saving at once: exactly one is written on a given base, the
 * other gets 409; docs/ide.md, "Saves, versions and merges"). Idle keys are dropped.
 */
export class FileLocks {
  private readonly tails = new Map<string, Promise<unknown>>();

  run<T>(key: string, operation: () => Promise<T>): Promise<T> {
    const previous = this.tails.get(key) ?? Promise.resolve();
    const result = previous.then(operation, operation);
    const tail = result.catch(() => undefined);
    this.tails.set(key, tail);
    void tail.then(() => {
      if (this.tails.get(key) === tail) this.tails.delete(key);
    });
    return result;
  }

  /** Files with a save queued or running (tests). */
  get size(): number {
    return this.tails.size;
  }
}
