/**
 * A field added to a record's detail (a `key=value` the runtime writes one day, at the end or
 * anywhere) changes nothing the readers conclude: the real recorded runs of fixtures/, with
 * ` spare_ns=41234` (a key no reader knows) after every run_finished's detail and `spare_ns=41234 ` before every
 * ack_sent's and ack_received's, tell the same story (`contract trace`: runs ended by their own
 * code, deadline misses with the module that had finished) and make the same Monitor (its parsed
 * records, and its lines read in place) as the logs as recorded.
 */
import { describe, expect, it } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseTrace, renderStory, type LogFile } from '@contract-studio/build-service/trace';
import { MonitorModel } from './monitor-model.js';
import { recordedRunSteps } from './recorded-run.js';

const FIXTURES = fileURLToPath(new URL('./fixtures', import.meta.url));
const FIELD = 'spare_ns=41234';

/** A fixture's logs (names without a date get one, as the runtime names them). */
function logsOf(run: string): LogFile[] {
  return readdirSync(join(FIXTURES, run)).filter((n) => n.endsWith('.csv'))
    .map((name) => ({ name: /_\d/.test(name) ? name : `${name.slice(0, -4)}_26-Nov-2026-12h29m45s.csv`, text: readFileSync(join(FIXTURES, run, name), 'utf8') }));
}

/** The record line with FIELD added to its detail: after it for run_finished, before it for the acks (unquoted details only). */
const withField = (line: string): string => {
  const m = /^((?:[^,]*,){3})(run_finished|ack_sent|ack_received),((?:[^,]*,){3})([^"].*)$/.exec(line);
  if (!m) return line;
  return m[2] === 'run_finished' ? `${line} ${FIELD}` : `${m[1]}${m[2]},${m[3]}${FIELD} ${m[4]}`;
};
const withFields = (files: LogFile[]): LogFile[] => files.map((f) => ({ ...f, text: f.text.split('\n').map(withField).join('\n') }));

function parsedModel(files: LogFile[]): MonitorModel {
  const m = new MonitorModel({ checkpointEvery: 64 });
  m.pushAll(parseTrace(files));
  return m;
}
function scannedModel(files: LogFile[]): MonitorModel {
  const steps = recordedRunSteps(files, 5000, { checkpointEvery: 64 });
  for (;;) {
    const step = steps.next();
    if (step.done) return step.value.model;
  }
}

// runs with deadline misses blamed on ORD's late read of an ack, and runs ended by their own code
const RUNS = ['killed-module-run', 'silent-flow-run', 'tutorial-run', 'async-handler-run', 'manip-run', 'silent-event-flow-run', 'killed-ord-run'];

describe('a field added to the details of run_finished and the acks changes no conclusion', () => {
  it('adds the field to real lines (the test changes what it says it changes)', () => {
    const changed = RUNS.flatMap(logsOf).flatMap((f) => f.text.split('\n')).filter((l) => withField(l) !== l);
    expect(changed.filter((l) => l.includes(',run_finished,')).length).toBeGreaterThan(1000);
    expect(changed.filter((l) => l.includes(',ack_sent,')).length).toBeGreaterThan(1000);
  });

  it.each(RUNS)('%s: contract trace tells the same story', (run) => {
    const files = logsOf(run);
    const story = renderStory(parseTrace(files));
    // what the story concludes from run_finished and ack_sent details is there to be changed
    expect(story.some((l) => / run #\d+ ended by its own code /.test(l) || / finished at .*\(its (ack sent|run finished)\)/.test(l))).toBe(true);
    expect(renderStory(parseTrace(withFields(files)))).toEqual(story);
  });

  const PATHS = [['parsed records (apply-record.ts)', parsedModel], ['lines read in place (hot-line.ts)', scannedModel]] as const;
  it.each(RUNS.flatMap((run) => PATHS.map(([path, model]) => [run, path, model] as const)))('%s: the Monitor from %s is the same', (run, _path, model) => {
    const files = logsOf(run);
    const as = model(files), changed = model(withFields(files));
    expect(changed.marks).toEqual(as.marks);
    for (let t = 0; t <= as.end; t += Math.max(1, as.end / 23)) expect(changed.stateAt(t), `t=${t}`).toEqual(as.stateAt(t));
  });
});
