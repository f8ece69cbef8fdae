/** The simulator's reader of hostile files (scenarios, src-gen headers): a FIFO is refused at once, never waited on. */
import { execFileSync } from 'node:child_process';
import { mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { readRegularFile } from '../src/read-regular-file.js';

const dir = mkdtempSync(join(tmpdir(), 'sim-read-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('readRegularFile', () => {
    it('reads a regular file; refuses a FIFO without waiting for a writer, a link, a folder, a file past the bound', () => {
        writeFileSync(join(dir, 'a.scenario'), 'at 0s: expect SUP.f active\n');
        expect(readRegularFile(join(dir, 'a.scenario'), 1000).toString()).toBe('at 0s: expect SUP.f active\n');
        execFileSync('mkfifo', [join(dir, 'fifo.scenario')]);
        // before O_NONBLOCK the open blocked this thread for ever (no writer ever comes)
        expect(readRegularFile(join(dir, 'fifo.scenario'), 1000)).toEqual({ error: 'not a regular file' });
        symlinkSync(join(dir, 'a.scenario'), join(dir, 'link.scenario'));
        expect(readRegularFile(join(dir, 'link.scenario'), 1000)).toEqual({ error: 'a symbolic link (not followed)' });
        expect(readRegularFile(dir, 1000)).toEqual({ error: 'not a regular file' });
        expect(readRegularFile(join(dir, 'a.scenario'), 5)).toEqual({ error: 'larger than 5 bytes' });
    });
});
