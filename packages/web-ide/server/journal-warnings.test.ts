/** journalWarnings: a rename journal's outcome as Generate All's warnings, on the journal's file. */
import { describe, expect, it } from 'vitest';
import { journalWarnings } from './journal-warnings.js';

describe('journalWarnings', () => {
  it('one entry for the finished rename naming the files it wrote as they are, one per file left; a refused journal says why', () => {
    const summary = 'finished the rename of module MSC -> MSK that was interrupted (its journal src-gen/.contract-rename.json): 2 file(s) written, 0 already renamed';
    expect(journalWarnings({ finished: { summary, written: ['  two spaces.contract', 'warning: odd.contract'], warnings: ['sched.contract changed since the rename began (or is gone): left as it is; rename MSC there by hand'] } })).toEqual([
      { file: '.contract-rename.json', message: `${summary} (  two spaces.contract, warning: odd.contract)` },
      { file: '.contract-rename.json', message: 'sched.contract changed since the rename began (or is gone): left as it is; rename MSC there by hand' },
    ]);
    expect(journalWarnings({ finished: { summary, written: [], warnings: [] } })).toEqual([{ file: '.contract-rename.json', message: summary }]);
    expect(journalWarnings({ refused: 'src-gen/.contract-rename.json is not the journal of an unfinished rename (not JSON): nothing was changed; remove it to go on' }))
      .toEqual([{ file: '.contract-rename.json', message: 'src-gen/.contract-rename.json is not the journal of an unfinished rename (not JSON): nothing was changed; remove it to go on' }]);
    expect(journalWarnings({})).toEqual([]);
  });
});
