import { describe, expect, it } from 'vitest';
import { addStdinEntry, emptyStdinEntries, relativePathProblem } from './stdin-entry.js';

describe('MODULE=FILE (a module\'s stdin from a file of the project)', () => {
  it('reads module -> file; a module named __proto__ is a name like another', () => {
    const into = emptyStdinEntries();
    expect(addStdinEntry(into, 'MAA=cmd/commands.txt')).toBeUndefined();
    expect(addStdinEntry(into, 'MSC=a=b.txt')).toBeUndefined();
    expect(addStdinEntry(into, '__proto__=p.txt')).toBeUndefined();
    expect({ ...into }).toEqual({ MAA: 'cmd/commands.txt', MSC: 'a=b.txt', ['__proto__']: 'p.txt' });
  });

  it('refuses what is no MODULE=FILE, a bad module name, a module given twice', () => {
    for (const bad of ['', 'MAA', 'MAA=', '=x.txt']) expect(addStdinEntry(emptyStdinEntries(), bad), bad).toBe('expected MODULE=FILE (e.g. MAA=commands.txt, FILE a file of the project)');
    expect(addStdinEntry(emptyStdinEntries(), 'M A=x')).toBe('"M A" is no module name (letters, digits and _, not starting with a digit)');
    expect(addStdinEntry(emptyStdinEntries(), '9M=x')).toBe('"9M" is no module name (letters, digits and _, not starting with a digit)');
    const into = emptyStdinEntries();
    addStdinEntry(into, 'MAA=a.txt');
    expect(addStdinEntry(into, 'MAA=b.txt')).toBe('module MAA is given twice (a.txt and b.txt): give it once');
    expect({ ...into }).toEqual({ MAA: 'a.txt' });
  });

  it('checkPath: FILE a plain path inside the project, relative to it', () => {
    expect(addStdinEntry(emptyStdinEntries(), 'MAA=../x', { checkPath: true })).toBe('path "../x" has an empty, "." or ".." component (a path inside the project, relative to it)');
    expect(addStdinEntry(emptyStdinEntries(), 'MAA=/etc/passwd', { checkPath: true })).toBe('absolute path not allowed: "/etc/passwd" (a path inside the project, relative to it)');
    expect(addStdinEntry(emptyStdinEntries(), 'MAA=../x')).toBeUndefined();
    expect(relativePathProblem('a\\b')).toBe('invalid character in path "a\\b"');
    expect(relativePathProblem('a//b')).toBe('path "a//b" has an empty, "." or ".." component');
    expect(relativePathProblem('a/b.txt')).toBeUndefined();
  });
});
