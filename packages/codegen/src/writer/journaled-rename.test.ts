/**
 * The rename sequence `contract rename` and the IDE's rename share (journaled-rename.ts): journal,
 * tree carried over, project files, journal removed; a failed step named, the journal removed
 * only when the project's files are as they were.
 */
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { runJournaledRename, RenameStepError } from './journaled-rename.js';
import { RENAME_JOURNAL_NAME, type RenameJournal } from './rename-journal.js';
import { scratchDirs } from '../test-support/temp-dir.js';

const scratch = scratchDirs('journaled-rename-');
const MODULES = 'generated/architecture/modules';
const CODE = '/*PROTECTED REGION ID(protect_exec_MSC) ENABLED START*/\nint speed = 3; (void)speed;\n/*PROTECTED REGION END*/\n';

/** A tree with MSC's module.c (a region using `speed`), and the journal of renaming MSC to MSK and `speed` to `rate`. */
function fixture(): { srcGen: string; journal: RenameJournal } {
    const srcGen = scratch();
    mkdirSync(join(srcGen, MODULES, 'MSC_mod'), { recursive: true });
    writeFileSync(join(srcGen, MODULES, 'MSC_mod/module.c'), CODE);
    const journal: RenameJournal = {
        version: 1, kind: 'module', oldName: 'MSC', newName: 'MSK', generatedNames: true, identifiers: [['speed', 'rate']],
        files: [{ path: 'arch.contract', before: '0'.repeat(64), after: 'module MSK' }],
    };
    return { srcGen, journal };
}

describe('runJournaledRename', () => {
    it('writes the journal, carries the tree over, then writes the files while the journal is there, and removes it', async () => {
        const { srcGen, journal } = fixture();
        const seen: string[] = [];
        const { carried, written } = await runJournaledRename(srcGen, journal, {
            journaled: true,
            step: (at) => seen.push(`${at}: journal ${existsSync(join(srcGen, RENAME_JOURNAL_NAME))}`),
            writeFiles: (c) => {
                seen.push(`files: journal ${existsSync(join(srcGen, RENAME_JOURNAL_NAME))}, ${c.moved?.movedPaths.length} moved`);
                return 'wrote';
            },
        });
        expect(seen).toEqual(['journaled: journal true', 'tree carried over: journal true', 'files: journal true, 1 moved']);
        expect(written).toBe('wrote');
        expect(existsSync(join(srcGen, RENAME_JOURNAL_NAME))).toBe(false);
        expect(readFileSync(join(srcGen, MODULES, 'MSK_mod/module.c'), 'utf8')).toContain('ID(protect_exec_MSK) ENABLED START*/\nint rate = 3; (void)rate;');
        expect(carried.code?.rewritten.map((r) => r.id)).toEqual(['protect_exec_MSK']);
    });

    it('a carry-over refused (a target path taken) removes the journal and writes no file', async () => {
        const { srcGen, journal } = fixture();
        mkdirSync(join(srcGen, MODULES, 'MSK_mod'));
        let wrote = false;
        const run = runJournaledRename(srcGen, journal, { journaled: true, writeFiles: () => { wrote = true; } });
        await expect(run).rejects.toMatchObject({ name: 'RenameStepError', step: 'carry-over', message: expect.stringContaining('MSK_mod already exists') });
        expect(wrote).toBe(false);
        expect(existsSync(join(srcGen, RENAME_JOURNAL_NAME))).toBe(false);
        expect(readFileSync(join(srcGen, MODULES, 'MSC_mod/module.c'), 'utf8')).toBe(CODE);
    });

    it('files that fail to be written leave the journal for the next generation to finish the rename', async () => {
        const { srcGen, journal } = fixture();
        const run = runJournaledRename(srcGen, journal, { journaled: true, writeFiles: () => { throw new Error('EIO: i/o error'); } });
        await expect(run).rejects.toMatchObject({ step: 'files', message: 'EIO: i/o error' });
        expect(JSON.parse(readFileSync(join(srcGen, RENAME_JOURNAL_NAME), 'utf8'))).toMatchObject({ oldName: 'MSC', newName: 'MSK' });
    });

    it('a journal that cannot be written changes nothing', async () => {
        const { srcGen, journal } = fixture();
        mkdirSync(join(srcGen, RENAME_JOURNAL_NAME)); // a folder where the journal goes
        const run = runJournaledRename(srcGen, journal, { journaled: true, writeFiles: () => undefined });
        const error = await run.catch((e: unknown) => e);
        expect(error).toBeInstanceOf(RenameStepError);
        expect((error as RenameStepError).step).toBe('journal');
        expect(readFileSync(join(srcGen, MODULES, 'MSC_mod/module.c'), 'utf8')).toBe(CODE);
    });

    it('without a journal (none asked) the tree is still carried over and the files written', async () => {
        const { srcGen, journal } = fixture();
        const seen: boolean[] = [];
        await runJournaledRename(srcGen, journal, { journaled: false, writeFiles: () => { seen.push(existsSync(join(srcGen, RENAME_JOURNAL_NAME))); } });
        expect(seen).toEqual([false]);
        expect(existsSync(join(srcGen, MODULES, 'MSK_mod/module.c'))).toBe(true);
    });
});
