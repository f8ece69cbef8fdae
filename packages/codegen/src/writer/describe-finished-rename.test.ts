/**
 * describeFinishedRename (rename-journal.ts): what finishing an interrupted rename did, as parts a
 * terminal or the IDE lays out its own way; file names are kept as they are (no text to parse back).
 */
import { describe, expect, it } from 'vitest';
import { describeFinishedRename } from './rename-journal.js';

describe('describeFinishedRename', () => {
    it('a summary, the files written and one warning per file left as it was, each file named by the caller', () => {
        const d = describeFinishedRename(
            { kind: 'enumeration', oldName: 'Mode', newName: 'Drive', written: [' spaced.contract', 'types.contract'], already: ['a.contract'], changed: ['warning: odd.contract'], identifiers: [['Mode', 'Drive']] },
            (f) => `robot/${f}`,
        );
        expect(d).toEqual({
            summary: 'finished the rename of enumeration Mode -> Drive that was interrupted (its journal src-gen/.contract-rename.json): 2 file(s) written, 1 already renamed',
            written: ['robot/ spaced.contract', 'robot/types.contract'],
            warnings: ['robot/warning: odd.contract changed since the rename began (or is gone): left as it is; rename Mode there by hand'],
        });
    });

    it('the uses in the regions\' code not rewritten (a capture) are a warning naming the region, the file in the tree and the old names', () => {
        const d = describeFinishedRename(
            {
                kind: 'datatype', oldName: 'Position', newName: 'Pose', written: ['a.contract'], already: [], changed: [],
                identifiers: [['Position', 'Pose'], ['eq_Position', 'eq_Pose']],
                refused: { file: 'generated/architecture/modules/MAB_mod/module.c', line: 40, id: 'protect_exec_MAB', word: 'Pose', context: 'code' },
            },
            (f) => `robot/${f}`,
        );
        expect(d.warnings).toEqual([
            "'Pose' is already used in the code of protected region protect_exec_MAB (robot/src-gen/generated/architecture/modules/MAB_mod/module.c:40): uses of 'Position', 'eq_Position' were not rewritten: change them by hand, the build fails until then",
        ]);
    });
});
