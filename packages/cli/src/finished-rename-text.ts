/**
 * What finishing an interrupted rename did, as the terminal says it (codegen rename-journal.ts
 * describeFinishedRename): the summary, each file written indented below it, then a `warning:`
 * line per file left as it was.
 */
import type { FinishedRenameDescription } from '@contract-studio/codegen';

export function finishedRenameText(d: FinishedRenameDescription): string {
    return [d.summary, ...d.written.map((f) => `  ${f}`), ...d.warnings.map((w) => `warning: ${w}`)].map((l) => `${l}\n`).join('');
}
