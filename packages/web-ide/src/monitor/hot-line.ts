/**
 * Folds a live trace line of the kinds a periodic schema writes at every cycle (releases,
 * completions, runs, data posted) straight from the line, read in place by line-scan.ts: the
 * same fold as parsing it (parseRecordLine) and applying the record (applyRecord), without the
 * strings and objects the parse makes. line-scan.test.ts checks both ways give the same states
 * on the tutorial run and on hostile variants of every line.
 *
 * The detail's `key=value` words are found with the reader's own checks (field-checks.ts
 * wordValueIn, isPlainIntegerIn: the first word `key=`; a value of `-?` and 1 to 15 digits is a
 * number, anything else a string).
 */
import { isPlainIntegerIn, spaceIn, wordValueIn } from '@contract-studio/build-service/trace';
import { foldComplete, foldDataPosted, foldRelease, foldRun } from './apply-record.js';
import { digitsValue, nameIn, scanned } from './line-scan.js';
import type { MonitorState, Ns } from './monitor-state.js';

/** The kinds applyHotLine folds. */
export const HOT_KINDS: ReadonlySet<string> = new Set(['run_started', 'run_finished', 'ord_release', 'ord_complete', 'data_posted']);

/** The detail word `key` as a number (the reader's num(fields[key])), or undefined. */
export function numberOf(text: string, from: number, to: number, key: string): number | undefined {
  const v = wordValueIn(text, key, from, to);
  if (v < 0) return undefined;
  const e = spaceIn(text, v, to);
  if (!isPlainIntegerIn(text, v, e)) return undefined;
  return text.charCodeAt(v) === 45 ? -digitsValue(text, v + 1, e) : digitsValue(text, v, e);
}

/** The detail word `key` as a non-empty string that is not a number (the reader's str(fields[key])), or undefined. */
function nameOf(text: string, from: number, to: number, key: string): string | undefined {
  const v = wordValueIn(text, key, from, to);
  if (v < 0) return undefined;
  const e = spaceIn(text, v, to);
  if (e === v || isPlainIntegerIn(text, v, e)) return undefined;
  return nameIn(text, v, e);
}

/**
 * What readCycleLine read, as places in the line (one object, reused: a read makes no string):
 * the schema is text[schemaFrom, schemaTo), the module (the line's peer) text[moduleFrom, moduleTo).
 */
export const cycleLine = { schemaFrom: 0, schemaTo: 0, cycle: 0, moduleFrom: 0, moduleTo: 0 };

/** The schema and cycle of the last `ord_release` line applyHotLine folded (undefined: not in the line, or not of the reader's type). */
export const hotRelease = { schema: undefined as string | undefined, cycle: undefined as number | undefined, lateNs: 0 };

/**
 * Reads the schema, cycle and module (its peer) of the `ord_release` or `ord_finished` line
 * scanLine last accepted into `cycleLine`, as the parsed record types them (a schema that is a
 * string, not a number; a cycle that is a number; a peer that is not empty): false when one of
 * them is missing.
 */
export function readCycleLine(text: string): boolean {
  const c = scanned.comma;
  const to = scanned.to;
  const detail = c[6]! + 1;
  if (c[4]! === c[3]! + 1) return false;
  const v = wordValueIn(text, 'schema', detail, to);
  if (v < 0) return false;
  const e = spaceIn(text, v, to);
  if (e === v || isPlainIntegerIn(text, v, e)) return false;
  const cycle = numberOf(text, detail, to, 'cycle');
  if (cycle === undefined) return false;
  cycleLine.schemaFrom = v;
  cycleLine.schemaTo = e;
  cycleLine.cycle = cycle;
  cycleLine.moduleFrom = c[3]! + 1;
  cycleLine.moduleTo = c[4]!;
  return true;
}

/**
 * Folds the line scanLine last accepted (a kind of HOT_KINDS) into `s` at time `t` (`t0`: the
 * run's first mono_ns), as applyRecord does with its parsed record.
 */
export function applyHotLine(s: MonitorState, text: string, t: Ns, t0: number): void {
  const c = scanned.comma;
  const to = scanned.to;
  const detail = c[6]! + 1;
  s.records++;
  s.t = t;
  switch (scanned.kind) {
    case 'run_started':
    case 'run_finished':
      foldRun(s, nameIn(text, c[1]! + 1, c[2]!), scanned.kind === 'run_started', t, scanned.kind === 'run_finished' ? numberOf(text, detail, to, 'cpu_ns') : undefined);
      return;
    case 'ord_release': {
      const schema = nameOf(text, detail, to, 'schema');
      const cycle = numberOf(text, detail, to, 'cycle');
      const releaseNs = numberOf(text, detail, to, 'release_ns');
      const tickNs = releaseNs === undefined ? undefined : numberOf(text, detail, to, 'tick_ns');
      foldRelease(s, schema, cycle, releaseNs, t, t0, tickNs, nameIn(text, c[3]! + 1, c[4]!));
      // what a deadline miss names (MonitorModel): the release's schema and cycle, as read here, and how late ORD sent it
      hotRelease.schema = schema;
      hotRelease.cycle = cycle;
      hotRelease.lateNs = releaseNs !== undefined && tickNs !== undefined ? releaseNs - tickNs : 0;
      return;
    }
    case 'ord_complete':
      foldComplete(s, nameOf(text, detail, to, 'schema'), numberOf(text, detail, to, 'response_ns'));
      return;
    case 'data_posted': {
      const port = c[5]! > c[4]! + 1 ? digitsValue(text, c[4]! + 1, c[5]!) : null;
      foldDataPosted(s, nameIn(text, c[1]! + 1, c[2]!), port, nameIn(text, c[3]! + 1, c[4]!), numberOf(text, detail, to, 'to_port'), t);
      return;
    }
  }
}
