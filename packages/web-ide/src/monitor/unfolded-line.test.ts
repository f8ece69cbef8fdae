import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { TRACE_KINDS, parseRecordLine, type KnownRecord } from '@contract-studio/build-service/trace';
import { unfoldedLineTime } from './unfolded-line.js';
import { FOLDED_KINDS, applyRecord, applyUnfolded } from './apply-record.js';
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

const corpus = [...tutorialLines.map((l) => l.text), ...TRACE_KINDS.map((k) => k.example)].flatMap(variants);

describe('a line the fold does not use, read without parsing it', () => {
  it('is read exactly when the full reader reads it as a record of an unfolded kind, with the same time', () => {
    let quick = 0;
    for (const line of corpus) {
      const q = unfoldedLineTime(line);
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
    const full = new MonitorModel({ checkpointEvery: 16 });
    lines.forEach((text, i) => {
      quick.pushLine('x.csv', i + 2, text);
      full.push(parseRecordLine('x.csv', i + 2, text), text);
    });
    expect(quick.recordCount).toBe(full.recordCount);
    expect(quick.live).toEqual(full.live);
    expect(quick.marks).toEqual(full.marks);
    expect(quick.live.unknownLines).toBeGreaterThan(0);
    for (let t = 0; t <= full.end; t += full.end / 97) expect(quick.stateAt(t)).toEqual(full.stateAt(t));
  });
});
