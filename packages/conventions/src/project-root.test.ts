import { describe, expect, it } from 'vitest';
import { projectRootOf, projectRootsOf, unusedTreeWarning } from './project-root.js';

const trees = (...folders: string[]) => (folder: string) => folders.includes(folder);

describe('projectRootOf: one rule for the CLI, a build and the IDE', () => {
    const eclipse = ['src/a.contract', 'src/b.contract'];
    it('the Eclipse layout: .contract files in src/, src-gen/ at the root: the root is the project', () => {
        expect(projectRootOf('src/a.contract', trees(''), eclipse)).toEqual({ root: '', unusedTrees: [] });
        // its generated files too (the active tab of a module.c)
        expect(projectRootOf('src-gen/generated/architecture/modules/MAA_mod/module.c', trees(''), eclipse).root).toBe('');
    });
    it('the Eclipse layout before any generation: the root too (as `contract generate P` writes P/src-gen)', () => {
        expect(projectRootOf('src/a.contract', trees(), eclipse)).toEqual({ root: '', unusedTrees: [] });
    });
    it('two trees for one project: the outermost is used, the other named', () => {
        expect(projectRootOf('src/a.contract', trees('', 'src'), eclipse)).toEqual({ root: '', unusedTrees: ['src'] });
        expect(projectRootsOf(eclipse, trees('', 'src'))).toMatchObject({ roots: [''], unusedTrees: ['src'] });
    });
    it('the .contract files at the root', () => {
        expect(projectRootOf('a.contract', trees(), ['a.contract', 'lib/b.contract'])).toEqual({ root: '', unusedTrees: [] });
    });
    it('a folder of several projects (examples/): each first-level folder, or its folder holding a src-gen/', () => {
        const files = ['tutorial/a.contract', 'other/src/b.contract'];
        expect(projectRootOf('tutorial/a.contract', trees('tutorial'), files).root).toBe('tutorial');
        expect(projectRootOf('other/src/b.contract', trees('tutorial'), files).root).toBe('other');
        expect(projectRootOf('other/src/b.contract', trees('tutorial', 'other'), files).root).toBe('other');
        expect(projectRootsOf(files, trees('tutorial')).roots).toEqual(['other', 'tutorial']);
    });
    it('a project one folder down that has its own src-gen/ (a repository root opened)', () => {
        expect(projectRootsOf(['robot/a.contract'], trees('robot')).roots).toEqual(['robot']);
    });
    it('files imported from outside the folder, and .contract files inside a generated tree, are no project of it', () => {
        expect(projectRootsOf(['../lib/x.contract', 'src/a.contract', 'src-gen/orphans/y.contract'], trees('..', ''))).toMatchObject({ roots: [''], unusedTrees: [] });
    });
    it('the warning names both trees', () => {
        expect(unusedTreeWarning('P/src', 'P')).toMatch(/^P\/src\/src-gen\/ is a second generated tree of this project, not used: the project is P and its tree P\/src-gen\//);
    });
});
