/**
 * What a run's label in the Monitor's run list counts, as `contract trace` counts it (its line of
 * counts): the records are the readable ones; the lines of its logs that are no record are
 * counted apart, as unreadable lines (RecordCounts of the trace reader).
 */
import type { RecordCounts } from '@contract-studio/build-service/trace';
import type { MonitorView } from './model-view.js';

/** 50000 -> `50,000`. */
export function count(n: number): string {
  return n.toLocaleString('en-US');
}

/**
 * A run's counts, from its state after the last record; `carried`: unreadable lines that are not in
 * its model (a trace file's records of unreadable lines of the logs it was written from).
 */
export function recordCounts(model: Pick<MonitorView, 'live'>, carried = 0): RecordCounts {
  return { records: model.live.records, unreadable: model.live.unknownLines + carried };
}

/** `1,001 record(s)`, then `, 3 unreadable line(s)` when there are any. */
export function recordCountsText(c: RecordCounts): string {
  return `${count(c.records)} record(s)${c.unreadable ? `, ${count(c.unreadable)} unreadable line(s)` : ''}`;
}

/**
 * ` · 1,001 record(s), 3 unreadable line(s)` for the label of a log folder or of a job's CSV logs
 * when some of their lines are unreadable; '' when none is (the label then counts nothing).
 */
export function unreadableNote(c: RecordCounts): string {
  return c.unreadable ? ` · ${recordCountsText(c)}` : '';
}
