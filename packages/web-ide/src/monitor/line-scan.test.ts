import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { LogClock, TRACE_KINDS, parseRecordLine, type KnownRecord } from '@contract-studio/build-service/trace';
import { scanLine, scanned } from './line-scan.js';
import { FOLDED_KINDS, applyRecord, applyUnfolded } from './apply-record.js';
import { HOT_KINDS, applyHotLine } from './hot-line.js';
import { MonitorModel } from './monitor-model.js';

const dir = fileURLToPath(new URL('./fixtures/tutorial-run', import.meta.url));
const tutorialLines = readdirSync(dir).flatMap((file) => readFileSync(join(dir, file), 'utf8').split('\n').slice(1).filter(Boolean).map((text) => ({ file, text })))
  .sort((a, b) => Number(BigInt(a.text.split(',')[0]!) - BigInt(b.text.split(',')[0]!)));

/** Each line, and hostile variants of it: every field broken in turn, commas and quotes added, cut, padded. */
function variants(line: string): string[] {
  const f = line.split(',');
  const out = [line, `${line},`, `${line}"`, line.replace(',', ',,'), line.slice(0, -1), `${line}\r`, ` ${line}`, line.replace(/^\d+/, '1'.repeat(21)),
    line.replace(/^\d+/, '12a'), line.replace(/^\d+/, ''), line + 'x'.repeat(5000)];
  for (let i = 0; i < f.length; i++) {
    for (const v of ['', 'x', '-1', '1'.repeat(16), 'A B', 'é', '"q"', 'a'.repeat(65), '0']) out.push([...f.slice(0, i), v, ...f.slice(i + 1)].join(','));
  }
  return out;
}

/** Hostile details for the kinds folded from the line in place: words missing, repeated, empty, numbers where names go, long numbers, signs. */
function detailVariants(line: string): string[] {
  const c = line.lastIndexOf(',');
  const head = line.slice(0, c + 1);
  const d = line.slice(c + 1);
  const out = [`${head}`, `${head} ${d}`, `${head}${d} `, `${head}${d.replace(/ /g, '  ')}`, `${head}x${d}`, `${head}${d} ${d}`];
  for (const key of ['schema', 'cycle', 'release_ns', 'response_ns', 'to_port']) {
    for (const v of ['', '-', '-7', '-0', '007', '1'.repeat(15), '1'.repeat(16), '12x', 'S2', '123', 'é']) {
      out.push(`${head}${d.replace(new RegExp(`(^| )${key}=[^ ]*`), `$1${key}=${v}`)}`);
      out.push(`${head}${key}=${v} ${d}`, `${head}x${key}=1 ${d}`, `${head}${key} ${d}`, `${head}${key}=`);
    }
  }
  return out;
}

const hotExamples = [...tutorialLines.map((l) => l.text), ...TRACE_KINDS.map((k) => k.example)].filter((l) => HOT_KINDS.has(l.split(',')[3]!));
const corpus = [...[...tutorialLines.map((l) => l.text), ...TRACE_KINDS.map((k) => k.example)].flatMap(variants), ...hotExamples.flatMap(detailVariants)];

describe('a live line read in place (line-scan.ts, hot-line.ts)', () => {
  it('is read exactly when the full reader reads it as a record of an unfolded kind, with the same time', () => {
    let quick = 0;
    for (const line of corpus) {
      // the time the model reads off a line of an unfolded kind (monitor-model.ts pushLineIn)
      const q = scanLine(line, 0, line.length) && !FOLDED_KINDS.has(scanned.kind) ? scanned.mono : undefined;
      const r = parseRecordLine('x.csv', 2, line);
      const unfolded = r.kind !== 'unknown' && !FOLDED_KINDS.has(r.kind);
      if (q !== undefined) {
        quick++;
        expect(unfolded, line).toBe(true);
        expect(q).toBe(Number((r as KnownRecord).monoNs));
      } else if (!line.includes('"')) {
        // only a quoted line of such a kind goes to the full reader although it is one
        expect(unfolded, line).toBe(false);
      }
    }
    expect(quick).toBeGreaterThan(500); // the corpus holds many such lines, not only rejects
  });

  it('folds a line of a kind every periodic cycle writes, in place, as parsing it and applying the record does', () => {
    const base = new MonitorModel();
    for (const l of tutorialLines) base.pushLine(l.file, 2, l.text);
    let hot = 0;
    for (const line of corpus) {
      const r = parseRecordLine('x.csv', 2, line);
      // the line in the middle of a batch, between lines that would mislead a reader going past it
      const text = `1,2,"3\n${line}\n schema=S9 cycle=9 to_port=9 response_ns=9,,`;
      const from = text.indexOf('\n') + 1;
      const accepted = scanLine(text, from, from + line.length);
      if (accepted && r.kind !== 'unknown') expect(scanned.mono, line).toBe(Number((r as KnownRecord).monoNs));
      if (!accepted || !HOT_KINDS.has(scanned.kind)) {
        if (!line.includes('"')) expect(r.kind !== 'unknown' && HOT_KINDS.has(r.kind), line).toBe(false);
        continue;
      }
      hot++;
      expect(r.kind, line).toBe(scanned.kind);
      const quick = structuredClone(base.live);
      applyHotLine(quick, text, 123, base.t0!);
      const full = structuredClone(base.live);
      applyRecord(full, r, 123, base.t0!);
      expect(quick, line).toEqual(full);
    }
    expect(hot).toBeGreaterThan(1000);
  }, 30_000); // 2.5 s alone; over 5 s on a host busy with other tests

  it('is of a kind that applyRecord leaves alone but for the count and the time', () => {
    // every kind of the trace table, folded into a state that already holds a run
    const base = new MonitorModel();
    for (const l of tutorialLines) base.pushLine(l.file, 2, l.text);
    for (const k of TRACE_KINDS) {
      const r = parseRecordLine('x.csv', 2, k.example);
      expect(r.kind, k.example).toBe(k.kind);
      const folded = structuredClone(base.live);
      applyRecord(folded, r, 123, base.t0!);
      const counted = structuredClone(base.live);
      applyUnfolded(counted, 123);
      if (!FOLDED_KINDS.has(k.kind)) expect(folded, k.kind).toEqual(counted);
    }
  });

  it('gives the model the same states, marks and counts as the full reader, on the tutorial run and hostile lines', () => {
    const lines = [...tutorialLines.map((l) => l.text), ...tutorialLines.flatMap((l, i) => (i % 5 === 0 ? variants(l.text) : []))];
    const quick = new MonitorModel({ checkpointEvery: 16 });
    const batched = new MonitorModel({ checkpointEvery: 16 });
    const full = new MonitorModel({ checkpointEvery: 16 });
    // the full reader with the log's time check, as the model checks each log's lines (log-clock.ts)
    const clock = new LogClock();
    lines.forEach((text, i) => {
      quick.pushLine('x.csv', i + 2, text);
      full.push(parseRecordLine('x.csv', i + 2, text, clock));
    });
    // the same lines as ranges of batches of 50, as the live run's trace events bring them
    for (let i = 0; i < lines.length; i += 50) {
      const batch = lines.slice(i, i + 50);
      const text = batch.join('\n');
      let from = 0;
      batch.forEach((line, j) => {
        batched.pushLineIn('x.csv', i + j + 2, text, from, from + line.length);
        from += line.length + 1;
      });
    }
    expect(batched.live).toEqual(full.live);
    expect(batched.marks).toEqual(full.marks);
    expect(quick.recordCount).toBe(full.recordCount);
    expect(quick.live).toEqual(full.live);
    expect(quick.marks).toEqual(full.marks);
    expect(quick.live.unknownLines).toBeGreaterThan(0);
    for (let t = 0; t <= full.end; t += full.end / 97) {
      expect(quick.stateAt(t)).toEqual(full.stateAt(t));
      expect(batched.stateAt(t)).toEqual(full.stateAt(t));
    }
  });
});
