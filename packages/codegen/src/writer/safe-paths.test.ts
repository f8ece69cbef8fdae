import { posix } from 'node:path';
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { checkTreePath, treePathProblem, UnsafePathError } from './safe-paths.js';

describe('treePathProblem: plain relative paths inside a tree only', () => {
    it.each([
        ['generated/architecture/Makefile', undefined],
        ['a', undefined],
        ['a..b/.hidden/c...d', undefined],
        ['', 'empty path'],
        ['/etc/passwd', 'absolute path'],
        ['..', 'empty, "." or ".." component'],
        ['../x', 'empty, "." or ".." component'],
        ['a/../../x', 'empty, "." or ".." component'],
        ['a/./b', 'empty, "." or ".." component'],
        ['a//b', 'empty, "." or ".." component'],
        ['a/', 'empty, "." or ".." component'],
        ['..\\x', 'backslash in the path'],
        ['a\u0000/../../x', 'control character (NUL, newline...) in the path'],
        ['a\nremoved: 1', 'control character (NUL, newline...) in the path'],
        ['x'.repeat(256), 'component longer than 255 characters'],
        [`${'a/'.repeat(2100)}b`, 'longer than 4096 characters'],
    ])('%j -> %s', (path, problem) => {
        expect(treePathProblem(path)).toBe(problem);
    });

    it('refuses what is not a string', () => {
        expect(treePathProblem(42)).toBe('not a string');
        expect(() => checkTreePath(null)).toThrow(UnsafePathError);
    });

    it('an accepted path, joined to a root, always stays strictly inside it', () => {
        const part = fc.oneof(fc.constantFrom('..', '.', '', 'a', 'b.c', '\\', '..\\..', '\u0000', '/'), fc.string({ maxLength: 4 }));
        fc.assert(
            fc.property(fc.array(part, { minLength: 1, maxLength: 8 }), fc.boolean(), (parts, absolute) => {
                const path = (absolute ? '/' : '') + parts.join('/');
                if (treePathProblem(path) !== undefined) return;
                const joined = posix.join('/root/tree', path);
                expect(joined.startsWith('/root/tree/')).toBe(true);
                expect(posix.normalize(path)).toBe(path);
            }),
            { numRuns: 2000 },
        );
    });
});
