/**
 * Hints added to gcc's message for code carried over from the ContrACT Eclipse tool, which no
 * longer compiles as it did (docs/migrating.md): said where the error is, in the CLI and the IDE alike.
 */
const HINTS: readonly { when: RegExp; hint: string }[] = [
  {
    // gcc quotes with ‘’ in a UTF-8 locale, '' in the C locale
    when: /^[‘'`]logFile[’'`] undeclared\b/,
    hint: "the ContrACT Eclipse tool's `FILE* logFile` is gone: libmodule writes each module's CSV log; add a record to it with ContractLog() (docs/runtime-api.md, docs/migrating.md)",
  },
];

/** `message` with the hint of the first migration problem it names, when it names one. */
export function withMigrationHint(message: string): string {
  const found = HINTS.find((h) => h.when.test(message));
  return found ? `${message}; ${found.hint}` : message;
}
