/**
 * What became of a rename journal Generate All found (integrations.ts finishInterruptedRename), as
 * the Generate panel's warnings, each on the journal's file: one entry for the finished rename
 * naming the files it wrote, one per file it left as it was; or why the journal was left.
 */
import { RENAME_JOURNAL_NAME } from '@contract-studio/conventions';
import type { JournalOutcome } from './integrations.js';

export function journalWarnings(journal: JournalOutcome): Array<{ file: string; message: string }> {
  const { finished, refused } = journal;
  const messages = [
    ...(finished ? [`${finished.summary}${finished.written.length ? ` (${finished.written.join(', ')})` : ''}`, ...finished.warnings] : []),
    ...(refused !== undefined ? [refused] : []),
  ];
  return messages.map((message) => ({ file: RENAME_JOURNAL_NAME, message }));
}
