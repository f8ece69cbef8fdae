import { describe, expect, it } from 'vitest';
import { StdinRowProblem, keptStdin, stdinFromRows, stdinRows } from './stdin-setting.js';

/** The problem stdinFromRows throws for `rows`: its message, row and column. */
function refusal(rows: string[][]): { message: string; row: number; column: number } | undefined {
  try {
    stdinFromRows(rows);
    return undefined;
  } catch (e) {
    if (!(e instanceof StdinRowProblem)) throw e;
    return { message: e.message, row: e.row, column: e.column };
  }
}

describe("the run settings' stdin rows", () => {
  it('one row per module: any path of the project, commas, spaces and unicode included, taken as typed; empty rows are no entry', () => {
    expect({ ...stdinFromRows([]) }).toEqual({});
    expect({ ...stdinFromRows([['', ''], [' MAA ', 'in,put/a b,c.txt'], ['MSC', 'données/é 1.txt'], ['', '  ']]) }).toEqual({ MAA: 'in,put/a b,c.txt', MSC: 'données/é 1.txt' });
    expect({ ...stdinFromRows([['MAA', 'x=y.txt']]) }).toEqual({ MAA: 'x=y.txt' });
    expect(stdinRows(stdinFromRows([['MAA', 'a,b.txt'], ['MSC', 'in.txt']]))).toEqual([['MAA', 'a,b.txt'], ['MSC', 'in.txt']]);
  });

  it('a bad row named, with why, and the input to mend', () => {
    expect(refusal([['MAA', 'a.txt'], ['MSC', '']])).toEqual({ message: 'stdin row 2: module MSC reads no file: give a file of the project, from its folder (or remove the row)', row: 1, column: 1 });
    expect(refusal([['', 'a.txt']])).toEqual({ message: 'stdin row 1: no module reads "a.txt": give its name (e.g. MAA)', row: 0, column: 0 });
    expect(refusal([['MAA', '../commands.txt']])).toEqual({ message: 'stdin row 1: path "../commands.txt" has an empty, "." or ".." component (a path inside the project, relative to it)', row: 0, column: 1 });
    expect(refusal([['MAA', '/etc/passwd']])).toEqual({ message: 'stdin row 1: absolute path not allowed: "/etc/passwd" (a path inside the project, relative to it)', row: 0, column: 1 });
    expect(refusal([['M-A', 'x.txt']])?.row).toBe(0);
    expect(refusal([['M-A', 'x.txt']])).toMatchObject({ message: expect.stringContaining('stdin row 1: "M-A" is no module name'), column: 0 });
    expect(refusal([['MAA', 'a.txt'], ['MAA', 'b.txt']])).toEqual({ message: 'stdin row 2: module MAA is given twice (a.txt and b.txt): give it once', row: 1, column: 0 });
  });
});

describe('the stdin entries kept in the browser', () => {
  it("this version's object, any path", () => {
    expect({ ...keptStdin({ MAA: 'a, b.txt' }) }).toEqual({ MAA: 'a, b.txt' });
    expect({ ...keptStdin(undefined) }).toEqual({});
  });

  it("an earlier version's text: MODULE=path entries, commas between, spaces around them and around = taken away", () => {
    expect({ ...keptStdin('MAA=commands.txt, MSC = input/msc.txt ,') }).toEqual({ MAA: 'commands.txt', MSC: 'input/msc.txt' });
  });

  it('a bad entry (edited by hand) named, with why', () => {
    expect(() => keptStdin('MAA')).toThrow('stdin: bad entry "MAA": expected MODULE=FILE (e.g. MAA=commands.txt, FILE a file of the project)');
    expect(() => keptStdin({ MAA: '../commands.txt' })).toThrow('stdin: bad entry "MAA=../commands.txt": path "../commands.txt" has an empty, "." or ".." component (a path inside the project, relative to it)');
    expect(() => keptStdin({ MAA: 3 })).toThrow('stdin: bad entry "MAA=": expected MODULE=FILE');
    expect(() => keptStdin('MAA=a.txt, MAA=b.txt')).toThrow('stdin: bad entry "MAA=b.txt": module MAA is given twice (a.txt and b.txt): give it once');
  });
});
