import { describe, expect, it } from 'vitest';
import { foldersHoldingAll } from './layout.js';

describe('foldersHoldingAll', () => {
    it('gives the folders above every file, deepest first, without the project folder', () => {
        expect(foldersHoldingAll(['robot/a/x.contract', 'robot/a/b/y.contract'])).toEqual(['robot/a', 'robot']);
        expect(foldersHoldingAll(['robot/x.contract'])).toEqual(['robot']);
        expect(foldersHoldingAll(['robot/x.contract', 'other/y.contract'])).toEqual([]);
        expect(foldersHoldingAll(['x.contract', 'robot/y.contract'])).toEqual([]);
        expect(foldersHoldingAll([])).toEqual([]);
    });
});
