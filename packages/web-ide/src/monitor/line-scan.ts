/**
 * Reads a live trace line in place: `text.slice(from, to)` is the line, and `text` is usually the
 * whole trace event it came in (build-service trace/wire.ts forEachTraceLine), so nothing is cut
 * out of it. A 1 kHz schema brings some 20,000 lines a second; cutting each into fields (strings,
 * a record, its fields object) was most of what the live run's worker allocated, and its garbage
 * collections took a CPU from the browser's compositor on a two-CPU machine
 * (docs/monitor-performance.md "The live run's worker").
 *
 * scanLine makes exactly parseRecordLine's checks of a line without a quoted field (the field
 * checks are the reader's own, field-checks.ts; given the line's log, that the record is of its
 * module, foreignRecordReason): a line it accepts is one the full reader reads as
 * a record of that kind, with that time. Anything else (a quoted field, a malformed line) is left
 * to the full reader, which says what is wrong with it.
 */
import { MAX_LINE_CHARS, ORD_MODULE, TRACE_KINDS, isDigitsIn, isModuleNameIn, isUserEventName, monoBeyondInt64, moduleOfLog, posingAs, type TraceArea } from '@contract-studio/build-service/trace';

/**
 * What the last successful scanLine read (one object, reused: a scan makes none).
 * `comma[i]` is the position of the line's (i+1)-th comma; the fields are
 * mono_ns, wall_time, module, event, peer, port, size, detail.
 */
export const scanned = {
  comma: new Int32Array(7),
  /** The record's mono_ns, as Number() of its digits. */
  mono: 0,
  /** The record's kind (the trace table's own string). */
  kind: '',
  /** The line's end. */
  to: 0,
};

/** The trace table's kinds by length, to name a line's event without cutting it out. */
const KINDS_BY_LENGTH: string[][] = [];
for (const { kind } of TRACE_KINDS) (KINDS_BY_LENGTH[kind.length] ??= []).push(kind);
/** The area of each kind (an engine's own kinds: log-clock.ts posingAs). */
const AREA = new Map<string, TraceArea>(TRACE_KINDS.map((k) => [k.kind, k.area]));

/** The kind whose name is text[from, to), or undefined. */
function kindIn(text: string, from: number, to: number): string | undefined {
  const same = KINDS_BY_LENGTH[to - from];
  if (same) for (const k of same) if (text.startsWith(k, from)) return k;
  return undefined;
}

/** Number() of text[from, to), which holds only digits (exact: up to 15 by hand, more by Number). */
export function digitsValue(text: string, from: number, to: number): number {
  if (to - from > 15) return Number(text.slice(from, to));
  let v = 0;
  for (let i = from; i < to; i++) v = v * 10 + (text.charCodeAt(i) - 48);
  return v;
}

/**
 * Whether text[from, to) is a record line the full reader accepts (eight unquoted fields, the
 * mono_ns, module, port and size checks, an event of the trace table or a module's own); if so, `scanned` holds
 * its commas, time and kind.
 */
export function scanLine(text: string, from: number, to: number, file?: string): boolean {
  if (to - from > MAX_LINE_CHARS) return false;
  const comma = scanned.comma;
  let n = 0;
  for (let i = from; i < to; i++) {
    const c = text.charCodeAt(i);
    if (c === 44 /* , */) {
      // exactly eight fields: seven commas, none in the detail
      if (n === 7) return false;
      comma[n++] = i;
    } else if (c === 34 /* " */) return false;
  }
  if (n !== 7) return false;
  const c1 = comma[0]!, c2 = comma[1]!, c3 = comma[2]!, c4 = comma[3]!, c5 = comma[4]!, c6 = comma[5]!, c7 = comma[6]!;
  if (!isDigitsIn(text, 1, 20, from, c1) || monoBeyondInt64(text, from, c1) || !isModuleNameIn(text, c2 + 1, c3)) return false;
  // a record of another module than the log's (its module's code wrote it): the full reader says so
  if (file !== undefined) {
    const owner = moduleOfLog(file);
    if (owner !== undefined && (c3 - c2 - 1 !== owner.length || !text.startsWith(owner, c2 + 1))) return false;
  }
  if ((c6 > c5 + 1 && !isDigitsIn(text, 1, 9, c5 + 1, c6)) || !isDigitsIn(text, 1, 15, c6 + 1, c7)) return false;
  // an event of the table, or a module's own (a `user` record, as the full reader reads it)
  let kind = kindIn(text, c3 + 1, c4) ?? (isUserEventName(text, c3 + 1, c4) ? 'user' : undefined);
  if (!kind) return false;
  // an engine's own kind written by another module is that module's own record (the reader's posingAs)
  const area = AREA.get(kind)!;
  if ((area === 'scheduler' || area === 'supervisor') && posingAs(area, c3 - c2 - 1 === ORD_MODULE.length && text.startsWith(ORD_MODULE, c2 + 1) ? ORD_MODULE : '') !== undefined) kind = 'user';
  scanned.kind = kind;
  scanned.mono = digitsValue(text, from, c1);
  scanned.to = to;
  return true;
}

/**
 * A small cache of the short strings a live trace repeats (module and schema names): a field
 * read as one of them is that string, not a new one. Bounded; a name it does not hold is cut out
 * as usual.
 */
const NAMES: string[] = [];
const MAX_NAMES = 64;
let nextName = 0;

/** text[from, to) as a string, the cached one when it is there. */
export function nameIn(text: string, from: number, to: number): string {
  const n = to - from;
  for (let i = 0; i < NAMES.length; i++) {
    const s = NAMES[i]!;
    if (s.length === n && text.startsWith(s, from)) return s;
  }
  const s = text.slice(from, to);
  if (n > 64) return s;
  if (NAMES.length < MAX_NAMES) NAMES.push(s);
  else {
    NAMES[nextName] = s;
    nextName = (nextName + 1) % MAX_NAMES;
  }
  return s;
}
