/**
 * A real follower of `contract run --trace FILE.jsonl` during a real run (bubblewrap): a read loop
 * that follows the file by its path (reopening it whenever the path names another file, as `tail
 * -F` does) reads every record once, and what it read is the final file byte for byte. A normal
 * run's file is only appended to: at its end it is left as written (the same file, not a new one
 * renamed over the path), and stderr says nothing of it. Before, the end of every normal run wrote
 * the file again (the launcher's `exited with status 0` lines of the stop placed at their own
 * times): the follower read every record twice. packages/cli/README.md "Following a trace file".
 */
import { spawn, spawnSync } from 'node:child_process';
import { closeSync, cpSync, fstatSync, openSync, readFileSync, readSync, statSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

const canRun = spawnSync('bwrap', ['--version']).status === 0;
const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));
const CLI = fileURLToPath(new URL('../bin/contract.js', import.meta.url));

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-trace-follower-');
    cpSync(TUTORIAL, join(root, 'tut'), { recursive: true, filter: (src) => !/\/(logs|run)$/.test(src) });
}, 120_000);
afterAll(() => removeSeededScratch(root));

/** Follows `path` by name every 10 ms until `done()`: the bytes read, and how many files it opened at that path. */
async function follow(path: string, done: () => boolean): Promise<{ text: string; opened: number }> {
    let fd: number | undefined;
    let ino = -1;
    let opened = 0;
    const chunks: Buffer[] = [];
    const buffer = Buffer.alloc(1 << 20);
    const readNew = () => {
        if (fd === undefined) return;
        for (let n; (n = readSync(fd, buffer, 0, buffer.length, null)) > 0;) chunks.push(Buffer.from(buffer.subarray(0, n)));
    };
    for (let last = false; !last;) {
        last = done();
        let there: number | undefined;
        try {
            there = statSync(path).ino;
        } catch {
            there = undefined; // not made yet
        }
        if (there !== undefined && there !== ino) {
            readNew(); // the rest of the file it had (a follower by name reads it to its end first)
            if (fd !== undefined) closeSync(fd);
            fd = openSync(path, 'r');
            ino = fstatSync(fd).ino;
            opened++;
        }
        readNew();
        if (!last) await new Promise((r) => setTimeout(r, 10));
    }
    if (fd !== undefined) closeSync(fd);
    return { text: Buffer.concat(chunks).toString('utf8'), opened };
}

describe.skipIf(!canRun)('contract run --trace followed live by its path', () => {
    it('the follower reads each record once, the final file is what it read, the file is never replaced', async () => {
        const file = join(root, 'run.jsonl');
        const child = spawn(process.execPath, [CLI, 'run', 'tut', '--sandbox', 'bwrap', '--duration', '3s', '--trace', file], { cwd: root, env: process.env, stdio: ['ignore', 'pipe', 'pipe'] });
        let stderr = '';
        child.stderr.on('data', (d: Buffer) => (stderr += d.toString()));
        child.stdout.resume();
        let code: number | null | undefined;
        child.on('close', (c) => (code = c));
        const followed = await follow(file, () => code !== undefined);
        expect(code, stderr).toBe(0);
        const final = readFileSync(file, 'utf8');
        const lines = final.trim().split('\n');
        expect(lines.filter((l) => l.includes('"kind":"module_started"'))).toHaveLength(9);
        expect(followed.opened).toBe(1); // one file at that path from its first record to the end
        expect(followed.text).toBe(final); // every record once, in the final file's order
        expect(new Set(lines).size).toBe(lines.length);
        expect(stderr).not.toContain('was written again');
        expect(stderr).toMatch(new RegExp(`trace: ${lines.length} record\\(s\\) in `));
        // a normal run's stop: no launcher_line (each module's end is its exit record)
        expect(final).not.toContain('"kind":"launcher_line"');
    }, 240_000);
});
