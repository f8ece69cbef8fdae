/**
 * Serialises the operations that read and rewrite the generated tree of a workspace: Generate All,
 * the rename carry-over, and the guarded saves of generated files (a save reads the file, merges,
 * then writes it; Generate All must not rewrite the file in between, or its new skeleton would be
 * lost). One lock per IDE server; operations run one after the other, in call order.
 */
export class GeneratedTreeLock {
  private tail: Promise<unknown> = Promise.resolve();

  run<T>(operation: () => Promise<T>): Promise<T> {
    const result = this.tail.then(operation, operation);
    this.tail = result.catch(() => undefined);
    return result;
  }
}
