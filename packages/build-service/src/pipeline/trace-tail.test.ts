import { appendFileSync, mkdirSync, mkdtempSync, openSync, readFileSync, readdirSync, rmSync, symlinkSync, truncateSync, writeFileSync, writeSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, test } from 'vitest';
import { CSV_HEADER, MAX_LINE_CHARS, NOT_A_LOG_WHY, parseLogFile, parseRecordLine, parseStreamedLine } from '../trace/parse.js';
import type { TraceLine } from './job-events.js';
import { CUT_MARK, TraceLineSplitter } from './trace-lines.js';
import { monoOf, TraceOrder } from './trace-order.js';
import { TRACE_TAIL_BOUNDS, TraceTail, type TraceTailBounds } from './trace-tail.js';

const rec = (mono: number | bigint, module = 'MAA', event = 'module_started', detail = 'pid=1 priority=40'): string =>
  `${mono},2026-11-24T18:30:15.123456Z,${module},${event},,,0,${detail}`;

describe('TraceLineSplitter', () => {
  test('partial lines wait for their newline; header and empty lines are counted, not sent; \\r dropped', () => {
    const s = new TraceLineSplitter('M_1.csv');
    const text = `${CSV_HEADER}\n${rec(1)}\n\n${rec(2)}\r\n${rec(3)}\n`;
    const out: TraceLine[] = [];
    for (let i = 0; i < text.length; i += 7) out.push(...s.push(Buffer.from(text.slice(i, i + 7))));
    expect(out).toEqual([
      { file: 'M_1.csv', line: 2, text: rec(1) },
      { file: 'M_1.csv', line: 4, text: rec(2) },
      { file: 'M_1.csv', line: 5, text: rec(3) },
    ]);
    expect(parseLogFile({ name: 'M_1.csv', text }).map((r) => r.kind)).toEqual(['module_started', 'module_started', 'module_started']);
    expect(s.offset).toBe(Buffer.byteLength(text));
  });

  test('a line over MAX_LINE_CHARS is sent once, cut and flagged, and never held whole', () => {
    const s = new TraceLineSplitter('M_1.csv');
    const out: TraceLine[] = [];
    out.push(...s.push(Buffer.from(`${CSV_HEADER}\n`)));
    const big = Buffer.alloc(1024 * 1024, 'x');
    for (let i = 0; i < 10; i++) out.push(...s.push(big)); // 10 MB without a newline
    expect(out).toHaveLength(1);
    expect(out[0]!.line).toBe(2);
    expect(out[0]!.text).toBe('x'.repeat(MAX_LINE_CHARS) + CUT_MARK);
    expect(parseRecordLine('M_1.csv', 2, out[0]!.text)).toMatchObject({ kind: 'unknown', reason: `line longer than ${MAX_LINE_CHARS} characters` });
    out.push(...s.push(Buffer.from(`tail of it\n${rec(5)}\n`)));
    expect(out.slice(1)).toEqual([{ file: 'M_1.csv', line: 3, text: rec(5) }]);
  });

  test('lines ending before quietUntil (an earlier run) are counted only; end() gives a last unterminated line', () => {
    const old = `${CSV_HEADER}\n${rec(1)}\n`;
    const s = new TraceLineSplitter('M_1.csv', Buffer.byteLength(old));
    const out = s.push(Buffer.from(`${old}${rec(2)}\n${rec(3)}`));
    expect(out).toEqual([{ file: 'M_1.csv', line: 3, text: rec(2) }]);
    expect(s.end()).toEqual([{ file: 'M_1.csv', line: 4, text: rec(3), cut: true }]);
  });

  test('a file whose line 1 is not the runtime\'s header (no log): its line 1 is sent, no later line; read whole, it is one unknown record', () => {
    // a module's code made `ORD_<date>.csv` in logs/: ORD's deadline miss, its clock consistent
    const miss = rec(5_000_000_000, 'ORD', 'ord_deadline_miss', 'schema=goTo cycle=3 tick_ns=4999000000');
    const text = `${miss}\n${rec(5_000_000_100, 'ORD', 'ord_deadline_miss', 'schema=goTo cycle=4 tick_ns=4999000100')}\n`;
    for (const step of [1, 7, text.length]) {
      const s = new TraceLineSplitter('ORD_1.csv');
      const out: TraceLine[] = [];
      for (let i = 0; i < text.length; i += step) out.push(...s.push(Buffer.from(text.slice(i, i + step))));
      out.push(...s.end());
      expect(out).toEqual([{ file: 'ORD_1.csv', line: 1, text: miss }]);
    }
    expect(parseLogFile({ name: 'ORD_1.csv', text })).toEqual([{ kind: 'unknown', file: 'ORD_1.csv', line: 1, reason: NOT_A_LOG_WHY, text: miss }]);
    expect(parseStreamedLine('ORD_1.csv', 1, miss)).toEqual(parseLogFile({ name: 'ORD_1.csv', text })[0]);
    // counted while nobody received (past the kept bound): said by the next push all the same
    const s = new TraceLineSplitter('ORD_1.csv');
    s.count(Buffer.from(text));
    expect(s.push(Buffer.from(`${rec(5_000_000_200, 'ORD', 'ord_deadline_miss', 'schema=goTo cycle=5 tick_ns=1')}\n`))).toEqual([{ file: 'ORD_1.csv', line: 1, text: miss }]);
  });
});

describe('TraceLineSplitter: any chunking, and counting', () => {
  /** A small deterministic generator (the chunk sizes). */
  const lcg = (seed: number) => () => (seed = (seed * 1103515245 + 12345) % 2 ** 31) / 2 ** 31;
  const text = [
    CSV_HEADER,
    rec(1, 'MAA', 'user', 'é€😀 multi-byte'),
    '',
    `${rec(2)}\r`,
    'garbage without a time',
    'y'.repeat(MAX_LINE_CHARS), // the longest line sent whole
    'z'.repeat(MAX_LINE_CHARS + 1), // one byte over: cut
    `${'€'.repeat(2000)}`, // 6000 bytes of 3-byte characters: cut (at a byte, as the bound is)
    rec(3),
    rec(4), // no newline: end() gives it
  ].join('\n');
  const bytes = Buffer.from(text);
  const all = (chunks: Buffer[]): TraceLine[] => {
    const s = new TraceLineSplitter('M_1.csv');
    const out = chunks.flatMap((c) => s.push(c));
    expect(s.offset).toBe(bytes.length);
    return [...out, ...s.end()];
  };

  test('the lines do not depend on where the reads cut the bytes (characters, \\r\\n and long lines split)', () => {
    const whole = all([bytes]);
    expect(whole.map((l) => l.line)).toEqual([2, 4, 5, 6, 7, 8, 9, 10]);
    expect(whole[0]!.text).toBe(rec(1, 'MAA', 'user', 'é€😀 multi-byte'));
    expect(whole[1]!.text).toBe(rec(2));
    expect(whole[3]!.text).toBe('y'.repeat(MAX_LINE_CHARS));
    expect(whole[4]!.text).toBe('z'.repeat(MAX_LINE_CHARS) + CUT_MARK);
    expect(whole[5]!.text.endsWith(CUT_MARK)).toBe(true);
    expect(whole.slice(6).map((l) => l.text)).toEqual([rec(3), rec(4)]);
    for (let seed = 1; seed <= 40; seed++) {
      const rnd = lcg(seed);
      const chunks: Buffer[] = [];
      for (let i = 0; i < bytes.length; ) {
        const n = 1 + Math.floor(rnd() * (seed % 2 ? 40 : 9000));
        chunks.push(Buffer.from(bytes.subarray(i, i + n))); // copies: the tail reuses its read buffer
        i += n;
      }
      expect(all(chunks)).toEqual(whole);
    }
  });

  test('count(): lines consumed without being made keep the numbering; a line the switch cuts is not sent', () => {
    const s = new TraceLineSplitter('M_1.csv');
    const head = Buffer.from(`${CSV_HEADER}\n${rec(1)}\n${rec(2)}\n${rec(3).slice(0, 10)}`);
    expect(s.push(head)).toEqual([{ file: 'M_1.csv', line: 2, text: rec(1) }, { file: 'M_1.csv', line: 3, text: rec(2) }]);
    // rec(3) begun while pushed, finished while counted; rec(5) begun while counted, finished while pushed
    const counted = Buffer.from(`${rec(3).slice(10)}\n${rec(4)}\n${rec(5).slice(0, 7)}`);
    const last = s.count(counted);
    expect(counted.toString('utf8', last, counted.indexOf(10, last))).toBe(rec(4));
    expect(s.nextLine).toBe(6);
    expect(s.push(Buffer.from(`${rec(5).slice(7)}\n${rec(6)}\n`))).toEqual([{ file: 'M_1.csv', line: 7, text: rec(6) }]);
    expect(s.count(Buffer.from('no newline at all'))).toBe(-1);
    // line 8 begun while counted: skipped up to its newline
    expect(s.push(Buffer.from(` still\n${rec(9)}\n`))).toEqual([{ file: 'M_1.csv', line: 9, text: rec(9) }]);
  });

  test('monoOf reads what /^(\\d{1,20}),/ reads', () => {
    for (const t of ['0,x', '123,', '882454447912,2026', '9'.repeat(15) + ',', '9'.repeat(16) + ',', '1'.repeat(20) + ',', '1'.repeat(21) + ',', ',1', '12', '', '12a,', ' 1,', '18446744073709551615,a']) {
      const m = /^(\d{1,20}),/.exec(t);
      expect(monoOf(t), t).toBe(m ? BigInt(m[1]!) : -1n);
    }
  });
});

describe('TraceOrder', () => {
  const line = (file: string, mono: number): TraceLine => ({ file, line: 0, text: rec(mono) });
  test('a record waits until every other log is read past its time, or the window', () => {
    const o = new TraceOrder(100);
    o.track('A.csv');
    o.track('B.csv');
    o.add('A.csv', [line('A.csv', 10), line('A.csv', 30)], 0);
    expect(o.release(0)).toEqual([]); // B has not been read past 10
    o.add('B.csv', [line('B.csv', 20)], 10);
    expect(o.release(10).map((l) => l.text)).toEqual([rec(10), rec(20)]); // watermark 20
    expect(o.release(99)).toEqual([]);
    expect(o.release(100).map((l) => l.text)).toEqual([rec(30)]); // held 100 ms
    o.add('B.csv', [line('B.csv', 25)], 150); // later than the window: sent, counted late
    expect(o.release(150).map((l) => l.text)).toEqual([rec(25)]);
    expect(o.late).toBe(1);
  });

  test('with the modules\' clock, a record the window old goes without waiting to be held that long', () => {
    const o = new TraceOrder(100);
    o.track('A.csv');
    o.track('B.csv');
    o.add('A.csv', [line('A.csv', 10), line('A.csv', 200_000_000)], 0);
    expect(o.release(1, { nowMono: 50_000_000n })).toEqual([]); // B not read past 10, read 1 ms ago, 50 ms old
    expect(o.release(2, { nowMono: 200_000_000n }).map((l) => l.text)).toEqual([rec(10)]); // 200 ms old, held 2 ms
    expect(o.release(3, { nowMono: 200_000_000n, behind: true })).toEqual([]);
    expect(o.release(4, { nowMono: 1_300_000_000n, behind: true }).map((l) => l.text)).toEqual([rec(200_000_000)]);
  });

  test('flush marks: a log known whole past a record lets it go at once; one whose module holds older records holds it, past the window', () => {
    const o = new TraceOrder(100, 60_000);
    o.track('A.csv');
    o.track('B.csv');
    o.add('A.csv', [line('A.csv', 10), line('A.csv', 30)], 0);
    o.mark('A.csv', 35n);
    o.mark('B.csv', 40n); // B holds nothing: whole up to 40 without a record of its own
    expect(o.release(1, { nowMono: 41n }).map((l) => l.text)).toEqual([rec(10), rec(30)]);
    o.add('A.csv', [line('A.csv', 50)], 2);
    o.mark('A.csv', 55n);
    o.mark('B.csv', 44n); // B's oldest held record is at 45
    // 200 ms later: the (unmarked) window would have let 50 go; B's mark still holds it
    expect(o.release(200, { nowMono: 200_000_000n })).toEqual([]);
    o.add('B.csv', [line('B.csv', 45)], 300);
    o.mark('B.csv', 300_000_000n);
    expect(o.release(300, { nowMono: 300_000_000n }).map((l) => l.text)).toEqual([rec(45), rec(50)]);
    expect(o.late).toBe(0);
    // a log without a mark brings the (short) window back for everyone
    o.track('C.csv');
    o.add('A.csv', [line('A.csv', 400_000_000)], 301);
    expect(o.release(302, { nowMono: 400_000_001n })).toEqual([]);
    expect(o.release(401, { nowMono: 400_000_001n }).map((l) => l.text)).toEqual([rec(400_000_000)]);
  });

  test('a log whose mark is stuck on an old record (its module blocked or killed) holds the others back once, not every record', () => {
    const ms = 1_000_000;
    const o = new TraceOrder(100, 1000);
    o.track('A.csv');
    o.track('B.csv');
    o.mark('B.csv', BigInt(5 * ms)); // B holds a record of 5 ms + 1 ns, and never writes it
    o.add('A.csv', [line('A.csv', 10 * ms)], 10);
    o.mark('A.csv', BigInt(11 * ms));
    expect(o.release(11, { nowMono: 11n * BigInt(ms) })).toEqual([]);
    expect(o.release(900, { nowMono: 900n * BigInt(ms) })).toEqual([]);
    // B's mark has not moved for the hold: A's records no longer wait for B
    expect(o.release(1006, { nowMono: 1006n * BigInt(ms) }).map((l) => l.text)).toEqual([rec(10 * ms)]);
    o.add('A.csv', [line('A.csv', 1010 * ms)], 1010);
    o.mark('A.csv', BigInt(1011 * ms));
    expect(o.release(1011, { nowMono: 1011n * BigInt(ms) }).map((l) => l.text)).toEqual([rec(1010 * ms)]);
    // B's mark moves again (it was only blocked): it holds the watermark again
    o.add('B.csv', [line('B.csv', 5 * ms + 1)], 1020);
    o.mark('B.csv', BigInt(1015 * ms));
    o.add('A.csv', [line('A.csv', 1018 * ms)], 1020);
    o.mark('A.csv', BigInt(1020 * ms));
    expect(o.release(1020, { nowMono: 1020n * BigInt(ms) }).map((l) => l.text)).toEqual([rec(5 * ms + 1)]);
    expect(o.late).toBe(1); // B's blocked record came after newer ones
  });

  test('garbage keeps its place after the record before it; module_exit frees the watermark', () => {
    const o = new TraceOrder(1000);
    o.track('A.csv');
    o.track('B.csv');
    o.add('A.csv', [line('A.csv', 10), { file: 'A.csv', line: 0, text: 'garbage' }, line('A.csv', 40)], 0);
    o.add('B.csv', [line('B.csv', 20), { file: 'B.csv', line: 0, text: rec(50, 'MAB', 'module_exit', 'status=0') }], 0);
    expect(o.release(1).map((l) => l.text)).toEqual([rec(10), 'garbage', rec(20), rec(40)]);
    expect(o.release(2, { all: true }).map((l) => l.text)).toEqual([rec(50, 'MAB', 'module_exit', 'status=0')]);
    expect(o.held).toBe(0);
  });

  test('a module_crashed record (a crashed module\'s last) frees the watermark as module_exit does', () => {
    const o = new TraceOrder(1000);
    o.track('A.csv');
    o.track('B.csv');
    o.add('A.csv', [line('A.csv', 10), line('A.csv', 40)], 0);
    o.add('B.csv', [line('B.csv', 20)], 0);
    // B's log is known whole up to 20 only: A's 40 waits for it
    expect(o.release(1).map((l) => l.text)).toEqual([rec(10), rec(20)]);
    o.add('B.csv', [{ file: 'B.csv', line: 0, text: rec(30, 'MAB', 'module_crashed', 'signal 11 (SIGSEGV) records=2') }], 1);
    expect(o.release(2).map((l) => l.text)).toEqual([rec(30, 'MAB', 'module_crashed', 'signal 11 (SIGSEGV) records=2'), rec(40)]);
    expect(o.held).toBe(0);
  });
});

describe('TraceTail on a folder written while it is read', () => {
  let work: string;
  let logs: string;
  let traced: TraceLine[];
  let liveOnly: TraceLine[] = [];
  let events: number;
  let system: string[];
  const sink = {
    trace: (l: TraceLine[]) => {
      events++;
      traced.push(...l);
    },
    live: (l: TraceLine[]) => void liveOnly.push(...l),
    system: (l: string) => void system.push(l),
  };
  const fast: TraceTailBounds = { ...TRACE_TAIL_BOUNDS, pollMs: 5, orderWindowMs: 20 };
  const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
  beforeEach(() => {
    work = mkdtempSync(join(tmpdir(), 'trace-tail-'));
    logs = join(work, 'logs');
    traced = [];
    events = 0;
    system = [];
  });
  afterEach(() => rmSync(work, { recursive: true, force: true }));

  test('partial lines, garbage, a 10 MB line, a link named X.csv, a FIFO: no throw, bounded, the files\' lines exactly once, in order', async () => {
    // a window longer than this test's pauses on a loaded machine (a 2 ms sleep may take 50): the
    // order comes from the watermark here (A and B both progress)
    const tail = await TraceTail.start(work, sink, { ...fast, orderWindowMs: 1000 }); // logs/ does not exist yet
    await sleep(20);
    mkdirSync(logs);
    symlinkSync('/etc/passwd', join(logs, 'X.csv'));
    execFileSync('mkfifo', [join(logs, 'F.csv')]);
    const a = join(logs, 'A_1.csv');
    const b = join(logs, 'B_1.csv');
    writeFileSync(a, `${CSV_HEADER}\n`);
    writeFileSync(b, `${CSV_HEADER}\n`);
    // mono_ns as the modules write them: the host's CLOCK_MONOTONIC at the record
    const mono = (): bigint => process.hrtime.bigint();
    for (let i = 0; i < 30; i++) {
      const r = rec(mono(), 'A');
      appendFileSync(a, r.slice(0, 10));
      await sleep(2);
      appendFileSync(a, r.slice(10) + '\n');
      appendFileSync(b, rec(mono(), 'B') + '\n');
      if (i === 10) appendFileSync(b, 'garbage,,"\n');
      if (i === 20) appendFileSync(a, 'y'.repeat(10 * 1024 * 1024) + '\n');
    }
    appendFileSync(b, rec(mono(), 'B')); // no newline: the run ended mid-record
    await tail.finish();
    expect(system).toEqual([]);
    for (const [name, path] of [['A_1.csv', a], ['B_1.csv', b]] as const) {
      const text = readFileSync(path, 'utf8');
      // a file's last line without its line end is a record marked cut (parse.ts unendedLine); the
      // live channel sends its text as any line, unmarked (the Monitor shows it as any record)
      const want = parseLogFile({ name, text }).map((r) => {
        const { cut: _cut, ...rest } = r as typeof r & { cut?: true };
        return rest;
      });
      const got = traced.filter((l) => l.file === name);
      expect(got.map((l) => parseRecordLine(name, l.line, l.text))).toEqual(want);
    }
    expect(traced.some((l) => l.file === 'X.csv' || l.file === 'F.csv')).toBe(false);
    const monos = traced.map((l) => /^(\d+),/.exec(l.text)?.[1]).filter(Boolean).map(Number);
    expect(monos).toEqual([...monos].sort((x, y) => x - y));
    expect(traced.find((l) => l.text.endsWith(CUT_MARK))?.text.length).toBe(MAX_LINE_CHARS + CUT_MARK.length);
    expect(events).toBeGreaterThan(1); // live: several events, not one at the end
  });

  /** A flush mark as the runtime keeps it (runtime/src/csvlog.c): one page, its first word. */
  const markFile = (log: string): ((word: bigint) => void) => {
    const path = `${log}.mark`;
    writeFileSync(path, Buffer.alloc(4096));
    const fd = openSync(path, 'r+');
    const b = Buffer.alloc(8);
    return (word: bigint) => {
      b.writeBigUInt64LE(word);
      writeSync(fd, b, 0, 8, 0);
    };
  };

  test('a module that holds its records longer than the window is not overtaken: its mark holds the others', async () => {
    mkdirSync(logs);
    const a = join(logs, 'A_1.csv');
    const b = join(logs, 'B_1.csv');
    const tail = await TraceTail.start(work, sink, { ...fast, orderWindowMs: 20, markHoldMs: 60_000 });
    // as a module starts: its mark, then its log
    const markA = markFile(a);
    const markB = markFile(b);
    markA(0n);
    markB(0n);
    writeFileSync(a, `${CSV_HEADER}\n`);
    writeFileSync(b, `${CSV_HEADER}\n`);
    const mono = (): bigint => process.hrtime.bigint();
    // B logs a record and keeps it in its buffer (computing, sleeping) while A writes newer ones
    const held = mono();
    markB(held);
    for (let i = 0; i < 10; i++) {
      appendFileSync(a, rec(mono(), 'A') + '\n');
      await sleep(15);
    }
    await sleep(100); // many windows: without B's mark A's records would have gone before B's
    expect(traced).toEqual([]);
    appendFileSync(b, rec(held, 'B') + '\n'); // B writes it: everything goes, in order
    markB(0n);
    for (let i = 0; i < 500 && traced.length < 11; i++) await sleep(10);
    expect(traced.map((l) => l.file)).toEqual(['B_1.csv', ...Array(10).fill('A_1.csv')]);
    // A goes on alone while B holds nothing: sent without waiting for B's next record
    appendFileSync(a, rec(mono(), 'A') + '\n');
    for (let i = 0; i < 500 && traced.length < 12; i++) await sleep(10);
    expect(traced).toHaveLength(12);
    await tail.finish();
    expect(system).toEqual([]);
  });

  test('a change of logs/ wakes a read without waiting for the poll; a mark left by a killed module is removed at the end', async () => {
    mkdirSync(logs);
    const a = join(logs, 'A_1.csv');
    const tail = await TraceTail.start(work, sink, { ...fast, pollMs: 600_000, wakeMs: 2, orderWindowMs: 600_000, markHoldMs: 600_000 });
    markFile(a)(0n);
    writeFileSync(a, `${CSV_HEADER}\n`);
    await sleep(20);
    appendFileSync(a, rec(process.hrtime.bigint(), 'A') + '\n');
    for (let i = 0; i < 500 && traced.length === 0; i++) await sleep(10);
    expect(traced).toHaveLength(1); // no poll in 10 minutes, no window: the watch read it, the mark released it
    appendFileSync(a, rec(process.hrtime.bigint(), 'A') + '\n');
    for (let i = 0; i < 500 && traced.length === 1; i++) await sleep(10);
    expect(traced).toHaveLength(2);
    await tail.finish();
    expect(readdirSync(logs)).toEqual(['A_1.csv']);
    expect(system).toEqual([]);
  });

  test('while a client watches, every module is asked (its mark\'s second word) to write its log after 10 ms; 0 when none does', async () => {
    mkdirSync(logs);
    const tail = await TraceTail.start(work, sink, { ...fast, watchedFlushMs: 10 });
    const a = join(logs, 'A_1.csv');
    markFile(a)(0n);
    writeFileSync(a, `${CSV_HEADER}\n`);
    const asked = (log: string): bigint => readFileSync(`${log}.mark`).readBigUInt64LE(8);
    for (let i = 0; i < 500 && !traced.length; i++) {
      if (i === 0) appendFileSync(a, rec(process.hrtime.bigint(), 'A') + '\n');
      await sleep(10);
    }
    expect(traced).toHaveLength(1); // A's log (and its mark) are open
    expect(asked(a)).toBe(0n);
    tail.setWatched(true);
    expect(asked(a)).toBe(10_000_000n);
    // a module started while watched is asked as soon as its mark is opened
    const b = join(logs, 'B_1.csv');
    markFile(b)(0n);
    writeFileSync(b, `${CSV_HEADER}\n${rec(process.hrtime.bigint(), 'B')}\n`);
    for (let i = 0; i < 500 && traced.length < 2; i++) await sleep(10);
    expect(asked(b)).toBe(10_000_000n);
    tail.setWatched(false);
    expect([asked(a), asked(b)]).toEqual([0n, 0n]);
    await tail.finish();
    expect(system).toEqual([]);
  });

  /** A tail followed by a client (modules asked for 20 ms flush boundaries) that reads only when logs/ changes. */
  const startWatched = async (wakeMs: number): Promise<TraceTail> => {
    mkdirSync(logs);
    const tail = await TraceTail.start(work, sink, { ...fast, pollMs: 600_000, wakeMs, watchedFlushMs: 20, orderWindowMs: 600_000, markHoldMs: 600_000 });
    tail.setWatched(true);
    return tail;
  };

  test('while watched, a change is read at once when every module has written its log for the last flush boundary, after wakeMs while one has not', async () => {
    const tail = await startWatched(600);
    const a = join(logs, 'A_1.csv');
    const b = join(logs, 'B_1.csv');
    const markA = markFile(a);
    const markB = markFile(b);
    markA(0n);
    markB(0n);
    writeFileSync(b, `${CSV_HEADER}\n`);
    writeFileSync(a, `${CSV_HEADER}\n${rec(process.hrtime.bigint(), 'A')}\n`);
    const until = async (n: number): Promise<number> => {
      const t0 = Date.now();
      for (let i = 0; i < 1000 && traced.length < n; i++) await sleep(5);
      return Date.now() - t0;
    };
    await until(1); // both logs are open now
    await sleep(1300); // (reads come at most one per wakeMs; asking the modules for the flush delay wrote their marks, a change too)
    // A writes while both marks say their modules hold nothing: nothing more is coming, read now
    appendFileSync(a, rec(process.hrtime.bigint(), 'A') + '\n');
    expect(await until(2)).toBeLessThan(300);
    expect(traced).toHaveLength(2);
    await sleep(50);
    // B holds a record logged before the last boundary (20 ms): it will write at any moment, so the
    // read waits wakeMs to take both together (A's record, older than B's, may go: the mark says so)
    const held = process.hrtime.bigint() - 30_000_000n;
    markB(held);
    appendFileSync(a, rec(held - 1_000_000n, 'A') + '\n');
    await sleep(150);
    expect(traced).toHaveLength(2);
    expect(await until(3)).toBeGreaterThan(250);
    expect(traced).toHaveLength(3);
    markB(0n);
    await tail.finish();
    expect(system).toEqual([]);
  });

  test('a program that writes its log without end, its mark saying it holds nothing, gets one read per wakeMs at most', async () => {
    const tail = await startWatched(50);
    const a = join(logs, 'A_1.csv');
    markFile(a)(0n);
    writeFileSync(a, `${CSV_HEADER}\n`);
    const t0 = Date.now();
    let written = 0;
    while (Date.now() - t0 < 500) {
      appendFileSync(a, rec(process.hrtime.bigint(), 'A') + '\n');
      written++;
      await sleep(1);
    }
    const spent = Date.now() - t0;
    await tail.finish();
    expect(traced).toHaveLength(written);
    // each read sends what it released in one event (and finish() one more)
    expect(events).toBeLessThanOrEqual(Math.ceil(spent / 50) + 2);
    expect(events).toBeGreaterThan(3); // read while it wrote, not only at the end
    expect(system).toEqual([]);
  });

  test('a file truncated mid-run stops its own trace with one line; the others go on', async () => {
    mkdirSync(logs);
    const a = join(logs, 'A_1.csv');
    const b = join(logs, 'B_1.csv');
    writeFileSync(a, `${CSV_HEADER}\n${rec(1, 'A')}\n`);
    writeFileSync(b, `${CSV_HEADER}\n`);
    const tail = await TraceTail.start(work, sink, fast);
    appendFileSync(a, `${rec(2, 'A')}\n`);
    // read before the truncation (a fixed sleep lost this race on a loaded machine)
    await expect.poll(() => traced.length, { timeout: 5_000, interval: 10 }).toBe(1);
    truncateSync(a, 0);
    appendFileSync(a, `${rec(3, 'A')}\n`);
    appendFileSync(b, `${rec(4, 'B')}\n`);
    await sleep(40);
    await tail.finish();
    expect(traced.map((l) => l.text)).toEqual([rec(2, 'A'), rec(4, 'B')]); // rec 1 was there before the run
    expect(system).toHaveLength(1);
    expect(system[0]).toMatch(/A_1\.csv shrank while it was read/);
  });

  test('an earlier run\'s logs (a reused workspace) are not read and do not hold the order back', async () => {
    mkdirSync(logs);
    const old = join(logs, 'OLD_1.csv');
    writeFileSync(old, `${CSV_HEADER}\n` + `${rec(1, 'OLD')}\n`.repeat(100_000)); // ~6 MB, never grows
    const a = join(logs, 'A_2.csv');
    const tail = await TraceTail.start(work, sink, { ...fast, orderWindowMs: 60_000 });
    writeFileSync(a, `${CSV_HEADER}\n${rec(process.hrtime.bigint(), 'A')}\n`);
    // with OLD not holding the watermark, A's record goes at the next poll, not after the (here 60 s) window
    for (let i = 0; i < 200 && traced.length === 0; i++) await sleep(10);
    expect(traced.map((l) => l.file)).toEqual(['A_2.csv']);
    await tail.finish();
    expect(traced.map((l) => l.file)).toEqual(['A_2.csv']);
    expect(system).toEqual([]);
  });

  test('thousands of files and the kept-lines bound: bounded, one system line, never a throw', async () => {
    mkdirSync(logs);
    for (let i = 0; i < 2000; i++) writeFileSync(join(logs, `M${i}_1.csv`), `${CSV_HEADER}\n${rec(i)}\n${rec(i + 10_000)}\n`);
    const tail = await TraceTail.start(work, sink, { ...fast, files: 50, linesKept: 70, linesPerEvent: 8 });
    for (let i = 0; i < 2000; i++) appendFileSync(join(logs, `M${i}_1.csv`), `${rec(20_000 + i)}\n`);
    await sleep(50);
    await tail.finish();
    expect(traced).toHaveLength(50); // one new record in each of the 50 files tailed
    expect(system.some((l) => /more than 50 logs/.test(l))).toBe(true);

    traced = [];
    liveOnly = [];
    system = [];
    const tail2 = await TraceTail.start(work, sink, { ...fast, files: 300, linesKept: 70, linesPerEvent: 8 });
    for (let i = 0; i < 2000; i++) appendFileSync(join(logs, `M${i}_1.csv`), `${rec(30_000 + i)}\n`);
    await tail2.finish();
    // 70 kept for replay, the other 230 of the 300 tailed files' new records sent live only, none twice
    expect(traced).toHaveLength(70);
    expect(liveOnly).toHaveLength(230);
    expect(new Set([...traced, ...liveOnly].map((l) => `${l.file}:${l.line}`)).size).toBe(300);
    expect(system.filter((l) => /70 records kept for replay/.test(l))).toHaveLength(1);
  });

  test('records read in one wake go in one trace event, in mono_ns order across the files, none lost', async () => {
    mkdirSync(logs);
    const tail = await TraceTail.start(work, sink, { ...fast, pollMs: 600_000, wakeMs: 2, orderWindowMs: 600_000, markHoldMs: 600_000 });
    // three modules' logs written at once (in one tick: the wake comes after), each ending with module_exit
    const files = ['A_1.csv', 'B_1.csv', 'C_1.csv'];
    files.forEach((name, k) => {
      const lines = Array.from({ length: 300 }, (_, i) => rec(1_000_000 + 3 * i + k, name[0]));
      writeFileSync(join(logs, name), `${CSV_HEADER}\n${lines.join('\n')}\n${rec(2_000_000 + k, name[0], 'module_exit', 'reason=ended')}\n`);
    });
    for (let i = 0; i < 500 && traced.length < 903; i++) await sleep(10);
    expect(traced).toHaveLength(903);
    expect(events).toBe(1);
    const monos = traced.map((l) => monoOf(l.text));
    expect(monos).toEqual([...monos].sort((a, b) => (a < b ? -1 : a > b ? 1 : 0)));
    for (const name of files) expect(traced.filter((l) => l.file === name).map((l) => l.line)).toEqual(Array.from({ length: 301 }, (_, i) => i + 2));
    await tail.finish();
    expect(system).toEqual([]);
  });

  test('past the kept bound with no client attached, lines are counted, not made; a client then gets the later ones, numbered, none twice', async () => {
    mkdirSync(logs);
    const a = join(logs, 'A_1.csv');
    writeFileSync(a, `${CSV_HEADER}\n`);
    liveOnly = [];
    const tail = await TraceTail.start(work, sink, { ...fast, linesKept: 5 });
    let mono = 1000;
    const more = (n: number): void => appendFileSync(a, Array.from({ length: n }, () => rec(mono++, 'A') + '\n').join(''));
    more(10); // lines 2..11: 5 kept, 5 live
    for (let i = 0; i < 500 && liveOnly.length < 5; i++) await sleep(10);
    expect(traced.map((l) => l.line)).toEqual([2, 3, 4, 5, 6]);
    expect(liveOnly.map((l) => l.line)).toEqual([7, 8, 9, 10, 11]);
    more(10); // lines 12..21: nobody watches
    for (let i = 0; i < 500 && tail.countedLines < 10; i++) await sleep(10);
    expect(tail.countedLines).toBe(10);
    tail.setWatched(true);
    more(3); // lines 22..24
    for (let i = 0; i < 500 && liveOnly.length < 8; i++) await sleep(10);
    await tail.finish();
    expect(liveOnly.slice(5)).toEqual([22, 23, 24].map((line) => ({ file: 'A_1.csv', line, text: rec(1000 + line - 2, 'A') })));
    expect(traced).toHaveLength(5);
    expect(system.filter((l) => /5 records kept for replay/.test(l))).toHaveLength(1);
  });

  test('lines that are no record past unreadableKept are counted in one entry, not sent, and take no room of the records kept for replay', async () => {
    mkdirSync(logs);
    const j = join(logs, 'J_1.csv');
    const junk = Array.from({ length: 50 }, (_, i) => `\u0001junk ${i}`);
    liveOnly = [];
    const tail = await TraceTail.start(work, sink, { ...fast, linesKept: 10, unreadableKept: 3 });
    writeFileSync(j, [CSV_HEADER, rec(1, 'J'), ...junk, ...[2, 3, 4, 5].map((m) => rec(m, 'J')), '7 is no time either', ''].join('\n'));
    await tail.finish();
    // before, the 50 junk lines were sent and took the kept room: the records after them went live-only
    expect(liveOnly).toEqual([]);
    expect(traced).toEqual([
      { file: 'J_1.csv', line: 2, text: rec(1, 'J') },
      ...junk.slice(0, 3).map((text, i) => ({ file: 'J_1.csv', line: 3 + i, text })),
      { file: 'J_1.csv', line: 6, text: '', unsent: 47 },
      ...[2, 3, 4, 5].map((m, i) => ({ file: 'J_1.csv', line: 53 + i, text: rec(m, 'J') })),
      { file: 'J_1.csv', line: 57, text: '', unsent: 1 },
    ]);
    expect(system.filter((l) => /more than 3 lines of the logs are no record/.test(l))).toHaveLength(1);
  });

  test('a sparse log of 1 TiB: read no further than the collector keeps of a log (finish() returns)', async () => {
    mkdirSync(logs);
    const tail = await TraceTail.start(work, sink, fast);
    const h = join(logs, 'H_1.csv');
    writeFileSync(h, `${CSV_HEADER}\n${rec(1, 'H')}\n`);
    truncateSync(h, 2 ** 40); // zeros without a newline, nothing on the disk: a full read would take many minutes
    await tail.finish();
    expect(traced.filter((l) => l.file === 'H_1.csv').map((l) => l.text)).toEqual([rec(1, 'H'), expect.stringMatching(/^\0+/)]);
    expect(system).toEqual([]);
  });

  test('logs/ planted as a link: not followed, one line', async () => {
    const outside = mkdtempSync(join(tmpdir(), 'trace-outside-'));
    writeFileSync(join(outside, 'S_1.csv'), `${CSV_HEADER}\n${rec(1)}\n`);
    symlinkSync(outside, logs);
    const tail = await TraceTail.start(work, sink, fast);
    appendFileSync(join(outside, 'S_1.csv'), `${rec(2)}\n`);
    await sleep(30);
    await tail.finish();
    rmSync(outside, { recursive: true, force: true });
    expect(traced).toEqual([]);
    expect(system).toEqual([expect.stringMatching(/logs\/ is not a directory \((ELOOP|ENOTDIR)\)/)]);
  });
});
