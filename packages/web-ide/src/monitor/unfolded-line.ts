/**
 * The time of a live trace line the Monitor's fold does not use, read without parsing the line.
 * A 1 kHz schema's trace is largely records that change nothing the Monitor draws (acks,
 * `ord_finished`, `data_received`, ...): for those the model needs only the record's time.
 * Parsing such a line (splitting it, a record and its fields made) took 1.2 µs of the page's main
 * thread, reading its time takes about half that and makes no object. The checks are
 * parseRecordLine's own for such a line (docs/runtime-api.md "Trace records"; the field checks
 * are the reader's, field-checks.ts), so a line this accepts is exactly one that parseRecordLine
 * reads as a record of an unfolded kind; anything else (a quoted field, a malformed line, a
 * folded kind) is left to the full reader.
 */
import { MAX_LINE_CHARS, isDigitsIn, isModuleNameIn, traceKind } from '@contract-studio/build-service/trace';
import { FOLDED_KINDS } from './apply-record.js';

/** mono_ns of `line` when it is a well-formed record of a kind applyRecord does not fold; else undefined. */
export function unfoldedLineTime(line: string): number | undefined {
  if (line.length > MAX_LINE_CHARS || line.includes('"')) return undefined;
  const c1 = line.indexOf(',');
  const c2 = line.indexOf(',', c1 + 1);
  const c3 = line.indexOf(',', c2 + 1);
  const c4 = line.indexOf(',', c3 + 1);
  const c5 = line.indexOf(',', c4 + 1);
  const c6 = line.indexOf(',', c5 + 1);
  const c7 = line.indexOf(',', c6 + 1);
  // exactly eight fields: seven commas, none in the detail
  if (c1 < 0 || c2 < 0 || c3 < 0 || c4 < 0 || c5 < 0 || c6 < 0 || c7 < 0 || line.indexOf(',', c7 + 1) >= 0) return undefined;
  if (!isDigitsIn(line, 1, 20, 0, c1) || !isModuleNameIn(line, c2 + 1, c3)) return undefined;
  if ((c6 > c5 + 1 && !isDigitsIn(line, 1, 9, c5 + 1, c6)) || !isDigitsIn(line, 1, 15, c6 + 1, c7)) return undefined;
  const event = line.slice(c3 + 1, c4);
  if (FOLDED_KINDS.has(event) || !traceKind(event)) return undefined;
  return Number(line.slice(0, c1));
}
