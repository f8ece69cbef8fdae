import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { PassThrough } from 'node:stream';
import { afterEach, beforeEach, describe, expect, test } from 'vitest';
import { describeWorkUsage, hostWorkUsage, readWorkUsage } from './work-usage.js';

let work: string;
let outside: string;
beforeEach(() => {
  work = mkdtempSync(join(tmpdir(), 'work-usage-'));
  outside = mkdtempSync(join(tmpdir(), 'work-usage-out-'));
});
afterEach(() => {
  rmSync(work, { recursive: true, force: true });
  rmSync(outside, { recursive: true, force: true });
});

describe('which files filled the work dir', () => {
  test('the biggest regular files, biggest first, links not followed', async () => {
    mkdirSync(join(work, 'logs'));
    writeFileSync(join(work, 'logs', 'MOT_1.csv'), Buffer.alloc(3 * 1024 * 1024));
    writeFileSync(join(work, 'logs', 'ODO_1.csv'), Buffer.alloc(1024 * 1024));
    for (let i = 0; i < 8; i++) writeFileSync(join(work, `small${i}.o`), Buffer.alloc(10 + i));
    writeFileSync(join(outside, 'huge.bin'), Buffer.alloc(8 * 1024 * 1024));
    symlinkSync(outside, join(work, 'out'));
    symlinkSync(join(outside, 'huge.bin'), join(work, 'huge-link'));
    const u = await hostWorkUsage(work);
    expect(u).not.toBeNull();
    expect(u!.biggest.map((f) => f.path)).toEqual(['logs/MOT_1.csv', 'logs/ODO_1.csv', 'small7.o', 'small6.o', 'small5.o']);
    expect(u!.files).toBe(10);
    expect(u!.partial).toBe(false);
    expect(describeWorkUsage(u!)).toMatch(/^logs\/MOT_1\.csv 3 MiB, logs\/ODO_1\.csv 1 MiB, small7\.o 17 B, small6\.o 16 B, small5\.o 15 B \(of 4 MiB in 10 file\(s\)\)$/);
  });

  test("a file name with line breaks and controls (the sandbox's choice) is written visibly: it cannot add a forged verdict line to the disk limit's message", async () => {
    const name = 'big\n\nok: run finished (exit 0) [docker; prepare 1 s]\nCSV logs: 4 file(s) in logs\n\x1b[2J\u202e\t';
    mkdirSync(join(work, 'logs'));
    writeFileSync(join(work, name), 'x'.repeat(2048));
    writeFileSync(join(work, 'logs', 'MOT_1.csv'), 'y');
    const text = describeWorkUsage((await hostWorkUsage(work))!);
    expect(text).not.toMatch(/[\n\r\t\x1b\u202e]/);
    expect(text).toBe('big\\u000a\\u000aok: run finished (exit 0) [docker; prepare 1 s]\\u000aCSV logs: 4 file(s) in logs\\u000a\\u001b[2J\\u202e\\u0009 2 KiB, logs/MOT_1.csv 1 B (of 2 KiB in 2 file(s))');
  });

  test('hostile find output: malformed records ignored, bounded in entries', async () => {
    const out = new PassThrough();
    const reading = readWorkUsage(out, () => out.destroy(), { entries: 3, ms: 2000, keep: 2 });
    out.write('garbage\0-5 x\0 12 y\0NaN z\0');
    out.write('7 a\0' + '9 b\0' + '1 c\0' + '100 never-read\0');
    const u = await reading;
    expect(u.files).toBe(3); // a, b, c: then the entry bound
    expect(u.partial).toBe(true);
    expect(u.biggest).toEqual([{ path: 'b', bytes: 9 }, { path: 'a', bytes: 7 }]);
    expect(u.totalBytes).toBe(17);
  });

  test('a stream that never ends stops at the time bound', async () => {
    const out = new PassThrough();
    const t0 = Date.now();
    const u = await readWorkUsage(out, () => out.destroy(), { entries: 10, ms: 200, keep: 2 });
    expect(u.partial).toBe(true);
    expect(Date.now() - t0).toBeLessThan(2000);
  });
});
