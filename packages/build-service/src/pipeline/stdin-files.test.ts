import { mkdirSync, mkdtempSync, readFileSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { STDIN_FILE_BYTES, parseStdinField, stageStdinFiles } from './stdin-files.js';

const base = mkdtempSync(join(tmpdir(), 'stdin-files-'));
afterAll(() => rmSync(base, { recursive: true, force: true }));

describe('a run\'s stdin files', () => {
  it('the request field: module names to plain relative paths of the project', () => {
    expect(parseStdinField({ MAA: 'cmd/commands.txt' })).toEqual({ MAA: 'cmd/commands.txt' });
    expect(() => parseStdinField('MAA=x')).toThrow('stdin must be an object module name -> a file of the project');
    expect(() => parseStdinField({ 'M A': 'x' })).toThrow('stdin: "M A" is no module name');
    expect(() => parseStdinField({ MAA: 3 })).toThrow('stdin.MAA must be the path of a file of the project');
    expect(() => parseStdinField({ MAA: '/etc/passwd' })).toThrow('stdin.MAA: absolute path not allowed: "/etc/passwd" (a path inside the project, relative to it)');
    expect(() => parseStdinField({ MAA: 'a/../../x' })).toThrow('stdin.MAA: path "a/../../x" has an empty, "." or ".." component');
  });

  it('copies a regular file of the project into the work dir; refuses a link, a folder, a missing or too large file', async () => {
    const project = join(base, 'project');
    const work = join(base, 'work');
    mkdirSync(join(project, 'cmd'), { recursive: true });
    mkdirSync(work);
    writeFileSync(join(project, 'cmd', 'commands.txt'), '3\n');
    writeFileSync(join(base, 'secret.txt'), 'host file\n');
    symlinkSync(join(base, 'secret.txt'), join(project, 'linked.txt'));
    symlinkSync(base, join(project, 'up'));
    writeFileSync(join(project, 'big.txt'), Buffer.alloc(STDIN_FILE_BYTES + 1, 0x33));
    expect(await stageStdinFiles({ dir: project }, { MAA: 'cmd/commands.txt' }, work, '/work')).toEqual(['STDIN_MAA=/work/.contract-stdin/MAA']);
    expect(readFileSync(join(work, '.contract-stdin', 'MAA'), 'utf8')).toBe('3\n');
    const refused = (file: string) => stageStdinFiles({ dir: project }, { MAA: file }, work, '/work').then(() => '', (e: Error) => e.message);
    for (const f of ['linked.txt', 'up/secret.txt', 'cmd', 'nothing.txt']) expect(await refused(f)).toBe(`stdin of MAA: ${f} is not a regular file of the project (not there, a folder, or reached through a symbolic link); nothing was run`);
    expect(await refused('big.txt')).toBe(`stdin of MAA: big.txt is larger than ${STDIN_FILE_BYTES} bytes (a module's stdin file is read up to that size); nothing was run`);
    // a project given as files: the file is one of them
    expect(await stageStdinFiles({ files: { 'a.contract': '', 'in.txt': 'x\n' } }, { MSC: 'in.txt' }, work, '/work')).toEqual(['STDIN_MSC=/work/.contract-stdin/MSC']);
    expect(readFileSync(join(work, '.contract-stdin', 'MSC'), 'utf8')).toBe('x\n');
  });
});
