/**
 * Tests' reading of one run the three ways the Monitor reads a run: live lines read in place,
 * parsed records, and a recorded run's CSV logs (recorded-run.ts). Each log's lines are the
 * records only (the CSV header is added); live and parsed get every log's lines in time order.
 */
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { MonitorModel, type MonitorModelOptions } from './monitor-model.js';
import { recordedRunSteps } from './recorded-run.js';

export const CSV_HEADER = 'mono_ns,wall_time,module,event,peer,port,size,detail';

export interface TestLog {
  name: string;
  lines: string[];
}

/** The run's records in time order (their mono_ns), each with its log and line. */
export function linesInTimeOrder(logs: readonly TestLog[]): { file: string; line: number; text: string }[] {
  return logs.flatMap((l) => l.lines.map((text, i) => ({ file: l.name, line: i + 2, text })))
    .sort((a, b) => Number(a.text.split(',')[0]) - Number(b.text.split(',')[0]));
}

/** [live, parsed, recorded]: the models of `logs` read the three ways. */
export function readThreeWays(logs: readonly TestLog[], opts: MonitorModelOptions): MonitorModel[] {
  const lines = linesInTimeOrder(logs);
  const live = new MonitorModel(opts);
  for (const l of lines) live.pushLine(l.file, l.line, l.text);
  const parsed = new MonitorModel(opts);
  parsed.pushAll(lines.map((l) => parseRecordLine(l.file, l.line, l.text)));
  const steps = recordedRunSteps(logs.map((l) => ({ name: l.name, text: `${CSV_HEADER}\n${l.lines.join('\n')}\n` })), 1000, opts);
  let step = steps.next();
  while (!step.done) step = steps.next();
  return [live, parsed, step.value.model];
}
