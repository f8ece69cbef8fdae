import { describe, it, expect } from 'vitest';
import fc from 'fast-check';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { NOT_A_LOG_WHY, parseTrace, type LogFile } from '@contract-studio/build-service/trace';
import { MonitorModel, type MonitorModelOptions } from './monitor-model.js';
import { recordedRunSteps } from './recorded-run.js';
import { piecedLog, type LogFile as PiecedLogFile } from '../views/run-logs.js';

const dir = fileURLToPath(new URL('./fixtures/tutorial-run', import.meta.url));
/** The tutorial's run: nine logs (more than a chunk looks back through for a line's text). */
const tutorial: LogFile[] = readdirSync(dir).map((name) => ({ name: `${name.slice(0, -4)}_26-Nov-2026-12h29m45s.csv`, text: readFileSync(join(dir, name), 'utf8') }));

const OPTS: MonitorModelOptions = { checkpointEvery: 16 };

/** The model of parseTrace's records pushed in order (what the page built before recorded-run.ts). */
function viaReader(files: LogFile[], opts = OPTS): MonitorModel {
  const m = new MonitorModel(opts);
  m.pushAll(parseTrace(files));
  return m;
}

/** The log as a download gives it (views/run-logs.ts piecedLog): its text cut after every `each`-th line end. */
function inPieces(f: LogFile, each: number): PiecedLogFile {
  const pieces: string[] = [];
  let from = 0;
  for (let at = 0, n = 0; (at = f.text.indexOf('\n', at) + 1) > 0; ) {
    if (++n % each === 0) {
      pieces.push(f.text.slice(from, at));
      from = at;
    }
  }
  if (from < f.text.length) pieces.push(f.text.slice(from));
  return piecedLog(f.name, pieces);
}

function viaRanges(files: PiecedLogFile[], every = 7, opts = OPTS): { model: MonitorModel; steps: number } {
  const steps = recordedRunSteps(files, every, opts);
  let n = 0;
  let step = steps.next();
  for (; !step.done; step = steps.next()) n++;
  // (a file that is no log, its first line not the runtime's header, is said: both readers refuse it whole)
  expect(step.value.leftOut.filter((n) => !n.endsWith(NOT_A_LOG_WHY))).toEqual([]);
  return { model: step.value.model, steps: n };
}

/**
 * The two models are the same: counts, marks, the live state and the state at 97 times (each scrub
 * back re-reads kept lines); and so is the model of the same logs read in pieces (a download's: a
 * line a piece, and three).
 */
function expectSame(files: LogFile[], opts = OPTS): MonitorModel {
  const full = viaReader(files, opts);
  const { model } = viaRanges(files, 7, opts);
  for (const m of [model, ...[1, 3].map((each) => viaRanges(files.map((f) => inPieces(f, each)), 7, opts).model)]) {
    expect(m.recordCount).toBe(full.recordCount);
    expect(m.t0).toBe(full.t0);
    expect(m.marks).toEqual(full.marks);
    expect(m.live).toEqual(full.live);
    for (let t = 0; t <= full.end; t += Math.max(1, full.end / 97)) {
      expect(m.stateAt(t), `t=${t}`).toEqual(full.stateAt(t));
      expect(m.exactAt(t)).toBe(full.exactAt(t));
    }
  }
  return model;
}

const W = '2026-11-26T12:00:00.000000Z';
const rule = (mono: string, f: string, r: string, on: boolean, cause = 'elapsed=1000ns') => `${mono},${W},SUP,sup_rule,,,0,${f}.${r} ${on ? 'active' : 'inactive'} cause=${cause}`;
const HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';

describe('a recorded run built from its logs read in place (recorded-run.ts)', () => {
  it('gives the model parseTrace\'s records give, on the tutorial\'s run, in small steps', () => {
    const model = expectSame(tutorial);
    expect(model.recordCount).toBe(tutorial.reduce((n, f) => n + f.text.split('\n').slice(1).filter(Boolean).length, 0));
    expect(model.marks.filter((m) => m.kind === 'rule').map((m) => m.label.split(' ← ')[0])).toContain('action.SECOND active');
    // it yields as it goes: reading and folding 250 lines 7 at a time
    expect(viaRanges(tutorial).steps).toBeGreaterThan(60);
  });

  it('keeps each log\'s text apart, when logs are alike to the byte or read in a different order', () => {
    // two logs with the same text (a copied module log): their lines are ranges of two texts
    // (named for no module: a log named as MSCX's holding MSC's records would be foreign lines, and
    // one named for MSC a second log of it, said)
    const twin = tutorial.map((f, k) => ({ name: `copy-${k}.csv`, text: f.text }));
    expectSame([...tutorial, ...twin]);
    expectSame([...tutorial].reverse());
    // a bound of 64 records kept: the oldest chunks go and are reused for later stretches
    const bounded = expectSame([...tutorial, ...twin], { checkpointEvery: 16, keepRecords: 64 });
    expect(bounded.exactAt(0)).toBe(false);
  });

  it('reads what the trace reader reads of hostile logs: CRLF, no last newline, garbage, lines out of order, headers out of place', () => {
    const hostile = tutorial.map((f, k) => {
      const lines = f.text.split('\n');
      const body = lines.slice(1).filter(Boolean);
      // a line moved back (a clock step), garbage between records, a header again, a broken rule
      if (body.length > 6) [body[2], body[5]] = [body[5]!, body[2]!];
      body.splice(1, 0, 'garbage', '', ' ', '"quoted,field",x', HEADER, `12a,${W},SUP,sup_rule,,,0,x`, rule('1', 'f', 'R', true).replace('f.R ', 'f R '));
      body.push(`${'9'.repeat(21)},${W},SUP,module_exit,,,0,status=0`, 'x'.repeat(5000));
      const text = [HEADER, ...body].join(k % 2 ? '\r\n' : '\n');
      // some without their last newline, one with a blank line before its header (no log then: refused whole, by both readers)
      return { name: f.name, text: k === 0 ? `\n${text}` : k % 3 ? text : `${text}\n` };
    });
    const model = expectSame(hostile);
    expect(model.live.unknownLines).toBeGreaterThan(20);
  });

  it('orders records by their whole mono_ns (20 digits), then by log name, then by line', () => {
    // past 2^53 ns two times a nanosecond apart are one double: the order is read off the digits
    // (below 2^63: a later time is no time of a record, log-clock.ts)
    const big = 9_223_372_036_854_775_000n;
    const files: LogFile[] = [
      { name: 'A_x.csv', text: [HEADER, rule(`${big + 1n}`, 'f', 'R1', true), rule(`${big + 3n}`, 'f', 'R1', false), ''].join('\n') },
      { name: 'B_x.csv', text: [HEADER, rule(`${big}`, 'f', 'R2', true), rule(`${big + 2n}`, 'f', 'R2', false), rule(`${big + 3n}`, 'f', 'R3', true), ''].join('\n') },
    ];
    const order = (m: MonitorModel) => m.marks.map((x) => x.label.split(' ← ')[0]);
    const { model } = viaRanges(files);
    expect(order(model)).toEqual(order(viaReader(files)));
    expect(order(model)).toEqual(['f.R2 active', 'f.R1 active', 'f.R2 inactive', 'f.R1 inactive', 'f.R3 active']);
    // equal times in two logs: the log named first goes first; leading zeros are the same time
    const equal: LogFile[] = [
      { name: 'E_x.csv', text: [HEADER, rule('5', 'f', 'R6', true), rule('6', 'f', 'R6', false), ''].join('\n') },
      { name: 'D_x.csv', text: [HEADER, rule('00005', 'f', 'R5', true), rule('4', 'f', 'R7', true), rule('7', 'f', 'R5', false), ''].join('\n') },
    ];
    const same = viaRanges(equal).model;
    expect(order(same)).toEqual(order(viaReader(equal)));
    expect(order(same)).toEqual(['f.R7 active', 'f.R5 active', 'f.R6 active', 'f.R6 inactive', 'f.R5 inactive']);
  });

  it('reads a record naming another module than its log\'s as a line that is no record (its log\'s module wrote it), as the trace reader does', () => {
    const W2 = '2026-11-24T18:30:15.123456Z';
    const hog = [HEADER, `1000,${W2},HOG,module_started,,,0,pid=7 priority=0`,
      // ORD's deadline miss, SUP's rule change and KILL, forged by HOG's code
      `1,${W2},ORD,ord_deadline_miss,,,0,schema=loop cycle=3`,
      `99999999999999999,${W2},SUP,sup_rule,,,0,guard.NORMAL active cause=HOG:0 value="forged"`,
      `2000,${W2},SUP,request_received,contract-launch,,22,KILL (the job was cancelled)`,
      `3000,${W2},HOG,user,,,0,own`, ''].join('\n');
    const sup = [HEADER, rule('1500', 'guard', 'LINK', true), ''].join('\n');
    const files: LogFile[] = [{ name: 'HOG_6-Dec-2026-09h00m00s.csv', text: hog }, { name: 'SUP_6-Dec-2026-09h00m00s.csv', text: sup }];
    const model = expectSame(files);
    expect(model.live.unknownLines).toBe(3);
    expect(model.t0).toBe(1000);
    expect(model.end).toBe(2000);
    expect(model.marks.map((m) => m.label)).not.toContainEqual(expect.stringContaining('NORMAL'));
    expect(model.marks.map((m) => m.label)).not.toContainEqual(expect.stringContaining('asked to stop'));
    expect(parseTrace(files).filter((r) => r.kind === 'unknown').map((r) => (r as { reason: string }).reason)).toEqual([
      "a record of ORD in HOG's log (a module's log holds its own records only: HOG's code wrote this line?)",
      "a record of SUP in HOG's log (a module's log holds its own records only: HOG's code wrote this line?)",
      "a record of SUP in HOG's log (a module's log holds its own records only: HOG's code wrote this line?)",
    ]);
  });

  it('marks a record its log ends inside (no line end: its module was killed while writing it), as contract trace tells it; not a line that is no record', () => {
    const CUT = 'cut: its log ends inside this record, with no line end; the record may have lost its end (its module was killed while writing it)';
    const files: LogFile[] = [
      // the rule change, cut after its fields: still a record
      { name: 'SUP_x.csv', text: [HEADER, rule('5', 'f', 'R1', true), rule('9', 'f', 'R1', false)].join('\n') },
      // a scanned kind, cut inside its detail
      { name: 'MSC_x.csv', text: [HEADER, '6,2026-11-24T18:30:15.123456Z,MSC,request_received,ORD,,0,STA'].join('\n') },
      // a line that is no record: counted unreadable, not marked
      { name: 'MSA_x.csv', text: [HEADER, '7,2026-11-24T18:30:15.123456Z,MSA,request_rec'].join('\n') },
      // ends with its line end: nothing
      { name: 'MAA_x.csv', text: [HEADER, '8,2026-11-24T18:30:15.123456Z,MAA,request_received,ORD,,0,START', ''].join('\n') },
    ];
    const model = expectSame(files);
    const cuts = model.marks.filter((m) => m.label === CUT);
    expect(cuts.map((m) => [m.where, m.t, m.kind])).toEqual([['MSC', 1, 'error'], ['SUP', 4, 'error']]);
    expect(model.live.unknownLines).toBe(1);
  });

  it('orders as parseTrace does, any logs: times out of order, equal, unreadable lines between, any step (property)', () => {
    // rule changes, whose marks show the order; garbage and a bad rule take the time before them in their log
    const line = fc.oneof(
      fc.constantFrom('bad', `7,${W},SUP,sup_rule,,,0,f R active cause=x`, `x,${W},SUP,sup_rule,,,0,f.R active cause=x`),
      fc.tuple(fc.integer({ min: 0, max: 40 }), fc.integer({ min: 0, max: 3 }), fc.boolean()).map(([t, r, on]) => rule(`${t}`, 'f', `R${r}`, on, `elapsed=${t}ns`)),
    );
    const log = fc.tuple(fc.constantFrom('A.csv', 'B.csv', 'C.csv', 'D.csv'), fc.array(line, { maxLength: 25 }), fc.boolean())
      .map(([name, lines, crlf]) => ({ name, text: [HEADER, ...lines].join(crlf ? '\r\n' : '\n') }));
    fc.assert(fc.property(fc.array(log, { maxLength: 5 }), fc.integer({ min: 1, max: 9 }), fc.integer({ min: 0, max: 4 }), (files, every, each) => {
      const full = viaReader(files);
      // read whole, or in pieces of `each` lines (a download's)
      const { model } = viaRanges(each ? files.map((f) => inPieces(f, each)) : files, every);
      expect(model.marks).toEqual(full.marks);
      expect(model.recordCount).toBe(full.recordCount);
      expect(model.live).toEqual(full.live);
    }), { numRuns: 300 });
  });

  it('leaves out, and says, the rest of a log past a bound of lines that are not records', () => {
    const garbage = Array.from({ length: 50 }, (_, i) => `junk ${i}`);
    const records = tutorial.find((f) => f.name.startsWith('SUP_'))!.text.split('\n').slice(1).filter(Boolean);
    const files: LogFile[] = [
      { name: 'x.csv', text: [HEADER, ...records.slice(0, 3), ...garbage, ...records.slice(3)].join('\n') },
      { name: 'y.csv', text: [HEADER, ...garbage.slice(0, 10), ...records].join('\n') },
    ];
    const steps = recordedRunSteps(files, 7, OPTS, 20);
    let step = steps.next();
    while (!step.done) step = steps.next();
    const { model, leftOut } = step.value;
    // x: 3 records, then 20 unreadable lines kept; the 21st and the rest left out. y: whole
    expect(leftOut).toEqual(['x.csv: more than 20 lines that are not trace records, the rest of it from line 25 left out']);
    expect(model.recordCount).toBe(3 + 20 + 10 + records.length);
    expect(model.live.unknownLines).toBe(30);
    // under the bound, nothing is left out
    const whole = recordedRunSteps(files, 7, OPTS, 50);
    let w = whole.next();
    while (!w.done) w = whole.next();
    expect(w.value.leftOut).toEqual([]);
    expect(w.value.model.recordCount).toBe(viaReader(files).recordCount);
  });

  it('says a module with two logs (a run writes one: the other is another run\'s, or forged by some module\'s code), as contract trace says it', () => {
    const ord = (name: string, cycle: number) => ({ name, text: `${HEADER}\n${1000 + cycle},${W},ORD,ord_deadline_miss,,,0,schema=S cycle=${cycle} tick_ns=1\n` });
    const steps = recordedRunSteps([ord('ORD_6-Dec-2026-10h00m00s.csv', 1), ord('ORD_6-Dec-2026-99h99m99s.csv', 2), { name: 'SUP_6-Dec-2026-10h00m00s.csv', text: `${HEADER}\n` }], 7, OPTS);
    let step = steps.next();
    while (!step.done) step = steps.next();
    // before, read as one without a word (forged deadline misses shown as ORD's)
    expect(step.value.leftOut).toEqual(['ORD: 2 logs of it (ORD_6-Dec-2026-10h00m00s.csv, ORD_6-Dec-2026-99h99m99s.csv), read as one: a run writes one log per module (two runs\' logs together, or a file named as its log that is not one)']);
  });

  it('builds nothing of logs with no record', () => {
    const empty = [{ name: 'A.csv', text: '' }, { name: 'B.csv', text: `${HEADER}\n` }, { name: 'C.csv', text: `${HEADER}\n\n\n` }];
    expect(viaRanges(empty).model.recordCount).toBe(0);
    expectSame(empty);
  });
});
