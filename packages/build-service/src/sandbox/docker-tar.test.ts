/**
 * The tar that carries a job's work dir into its Docker volume keeps mtimes to the nanosecond and
 * is the same bytes for the same tree: make inside the container compares a source saved a
 * fraction of a second after the last build against that build's objects, and an unchanged tree
 * is not copied again (its digest).
 */
import { execFileSync } from 'node:child_process';
import { mkdtempSync, rmSync, utimesSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, describe, expect, it } from 'vitest';
import { tarOf } from './docker.js';

let dir = '';
afterEach(() => rmSync(dir, { recursive: true, force: true }));

describe('the work dir tar of the Docker sandbox', () => {
  it('keeps sub-second mtimes, and the same tree gives the same bytes', async () => {
    dir = mkdtempSync(join(tmpdir(), 'docker-tar-'));
    writeFileSync(join(dir, 'main.c'), 'int main(void) { return 0; }\n');
    utimesSync(join(dir, 'main.c'), 1_800_000_000.25, 1_800_000_000.75);
    const tar = await tarOf(dir);
    // what tar itself reads back from it (GNU tar's default format would say .000000000)
    const listed = execFileSync('tar', ['-tv', '--full-time', '-f', '-'], { input: tar }).toString();
    expect(listed).toMatch(/main\.c/);
    expect(listed).toMatch(/\d\d:\d\d:\d\d\.75\d*\s+\.\/main\.c/);
    // reading the file (atime) changes nothing; a second tar is the same bytes
    execFileSync('cat', [join(dir, 'main.c')]);
    expect((await tarOf(dir)).equals(tar)).toBe(true);
  });
});
