/**
 * `loadWorkspace` (`contract check`, `contract simulate`) on `.contract` entries a build does not
 * read: a file larger than 8 MiB is an error naming it (a 700 MB one ended check with V8's "Cannot
 * create a string longer than ..."), a link or a FIFO a warning (skipped without a word: check went
 * green where the build refused the project). An imported link keeps its own warning (import-link).
 */
import { execFileSync } from 'node:child_process';
import { mkdtempSync, rmSync, symlinkSync, truncateSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { loadWorkspace } from '../src/node/index.js';

const dir = mkdtempSync(join(tmpdir(), 'cactal-not-read-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('.contract entries a build does not read', () => {
    it('are said: too large an error, a link or a FIFO a warning; the rest is checked as before', async () => {
        writeFileSync(join(dir, 'ok.contract'), 'datatype U {int b = 1};\n');
        writeFileSync(join(dir, 'big.contract'), '');
        truncateSync(join(dir, 'big.contract'), 9 * 1024 * 1024); // sparse: no disk used
        writeFileSync(join(dir, 'elsewhere.txt'), 'datatype V {int c = 1};\n');
        symlinkSync(join(dir, 'elsewhere.txt'), join(dir, 'linked.contract'));
        execFileSync('mkfifo', [join(dir, 'pipe.contract')]);
        const ws = await loadWorkspace(dir);
        expect(ws.documents.map((d) => d.file)).toEqual(['ok.contract']);
        expect(ws.diagnostics.map((d) => [d.file, d.severity, d.code, d.message])).toEqual(expect.arrayContaining([
            ['big.contract', 'error', 'source-too-large', '9437184 bytes, above the 8388608 a project\'s file may hold: not read (a build refuses the project for it too)'],
            ['linked.contract', 'warning', 'source-not-file', 'a symbolic link: not read here, and a build (contract build, the IDE\'s build service) refuses the project for it, nothing built; put the file itself there'],
            ['pipe.contract', 'warning', 'source-not-file', expect.stringMatching(/^not a regular file \(a FIFO, socket or device\): not read here/)],
        ]));
        expect(ws.diagnostics).toHaveLength(3);
    });

    it('a folder too deep to list (its path longer than the system allows) is said, and the project around it is read', async () => {
        const deep = mkdtempSync(join(tmpdir(), 'cactal-deep-'));
        try {
            writeFileSync(join(deep, 'ok.contract'), 'datatype U {int b = 1};\n');
            // 2,100 nested folders, made from inside (each mkdir a short relative path)
            execFileSync('python3', ['-c', 'import os, sys\nos.chdir(sys.argv[1])\nfor name in ["junk"] + ["d"] * 2100:\n    os.mkdir(name)\n    os.chdir(name)', deep]);
            const ws = await loadWorkspace(deep);
            expect(ws.documents.map((d) => d.file)).toEqual(['ok.contract']);
            expect(ws.diagnostics.map((d) => [d.severity, d.code, d.message])).toEqual([
                ['warning', 'source-not-file', 'a folder that could not be listed (its path is longer than the system allows): any .contract file in it is not read'],
            ]);
            expect(ws.diagnostics[0]!.file).toMatch(/^junk\/d\/d\/.*\.\.\.$/);
            expect(ws.diagnostics[0]!.file.length).toBe(303);
        } finally {
            execFileSync('rm', ['-rf', deep]);
        }
    });
});
