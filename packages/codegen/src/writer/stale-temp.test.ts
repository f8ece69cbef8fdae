/** Stale temporary files of killed generators are removed on the next write of their folder; live writers' are kept. */
import { spawn, spawnSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, symlinkSync, utimesSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterEach, describe, expect, it } from 'vitest';
import { tempDir } from '../test-support/temp-dir.js';
import { pidAlive } from './stale-temp.js';
import { writeTree } from './write-tree.js';

let cleanups: Array<() => void> = [];
afterEach(() => {
    cleanups.forEach((c) => c());
    cleanups = [];
});
function out(): string {
    const t = tempDir('codegen-temp-');
    cleanups.push(t.cleanup);
    return t.dir;
}

/** The temporary file name atomic-write.ts uses (`.<name>.tmp-<pid>`), spelled out: the test pins the format. */
const tempName = (name: string, pid = process.pid): string => `.${name}.tmp-${pid}`;

/** The pid of a process that has exited (and been reaped). */
function deadPid(): number {
    const r = spawnSync(process.execPath, ['-e', '']);
    expect(pidAlive(r.pid!)).toBe(false);
    return r.pid!;
}

describe('stale temporary files (atomic-write.ts, stale-temp.ts)', () => {
    it('removes the temp files of dead writers and old ones, keeps a live writer\'s, on the next write of that folder', () => {
        const dir = out();
        const live = spawn('sleep', ['30'], { stdio: 'ignore' });
        cleanups.push(() => live.kill());
        const gen = join(dir, 'generated');
        mkdirSync(gen);
        const dead = tempName('a.c', deadPid());
        const liveTmp = tempName('b.c', live.pid!);
        const oldLive = tempName('c.c', live.pid!);
        for (const n of [dead, liveTmp, oldLive]) writeFileSync(join(gen, n), 'half a file');
        const hourAgo = new Date(Date.now() - 3600_000);
        utimesSync(join(gen, oldLive), hourAgo, hourAgo);
        // a folder the generation does not write into keeps its temp files (cleaned on its next write)
        mkdirSync(join(dir, 'untouched'));
        writeFileSync(join(dir, 'untouched', dead), 'half a file');

        const r = writeTree(dir, [{ path: 'generated/x.c', content: 'int x;\n' }]);
        expect(r.errors).toEqual([]);
        expect(existsSync(join(gen, dead))).toBe(false);
        expect(existsSync(join(gen, oldLive))).toBe(false);
        expect(readFileSync(join(gen, liveTmp), 'utf8')).toBe('half a file');
        expect(existsSync(join(dir, 'untouched', dead))).toBe(true);
        expect(readFileSync(join(gen, 'x.c'), 'utf8')).toBe('int x;\n');
    });

    it('never writes through a link planted at the temp file\'s own name', () => {
        const dir = out();
        const victim = join(dir, 'victim.txt');
        writeFileSync(victim, 'precious');
        mkdirSync(join(dir, 'generated'));
        symlinkSync(victim, join(dir, 'generated', tempName('x.c')));
        const r = writeTree(dir, [{ path: 'generated/x.c', content: 'int x;\n' }]);
        expect(r.errors).toEqual([]);
        expect(readFileSync(victim, 'utf8')).toBe('precious');
        expect(readFileSync(join(dir, 'generated/x.c'), 'utf8')).toBe('int x;\n');
        expect(existsSync(join(dir, 'generated', tempName('x.c')))).toBe(false);
    });
});
