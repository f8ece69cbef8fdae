import { describe, expect, it } from 'vitest';
import { parseStdinSetting, stdinSettingText } from './stdin-setting.js';

describe("the run settings' stdin field", () => {
  it('MODULE=path entries, commas between, spaces around them and around = taken away', () => {
    expect({ ...parseStdinSetting('') }).toEqual({});
    expect({ ...parseStdinSetting('MAA=commands.txt, MSC = input/msc.txt ,') }).toEqual({ MAA: 'commands.txt', MSC: 'input/msc.txt' });
    expect(stdinSettingText(parseStdinSetting(' MAA =commands.txt,MSC=in.txt'))).toBe('MAA=commands.txt, MSC=in.txt');
  });

  it('a bad entry named, with why', () => {
    expect(() => parseStdinSetting('MAA')).toThrow('stdin: bad entry "MAA": expected MODULE=FILE (e.g. MAA=commands.txt, FILE a file of the project)');
    expect(() => parseStdinSetting('MAA=../commands.txt')).toThrow('stdin: bad entry "MAA=../commands.txt": path "../commands.txt" has an empty, "." or ".." component (a path inside the project, relative to it)');
    expect(() => parseStdinSetting('MAA=/etc/passwd')).toThrow('stdin: bad entry "MAA=/etc/passwd": absolute path not allowed: "/etc/passwd" (a path inside the project, relative to it)');
    expect(() => parseStdinSetting('M-A=x.txt')).toThrow('stdin: bad entry "M-A=x.txt": "M-A" is no module name');
    expect(() => parseStdinSetting('MAA=a.txt, MAA=b.txt')).toThrow('stdin: bad entry "MAA=b.txt": module MAA is given twice (a.txt and b.txt): give it once');
  });
});
