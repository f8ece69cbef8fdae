import { describe, it, expect } from 'vitest';
import { parseRecordLine, parseTrace, renderStory } from '@contract-studio/build-service/trace';
import { MonitorModel } from './monitor-model.js';
import { CSV_HEADER as HEADER, linesInTimeOrder, readThreeWays } from './read-three-ways.test-support.js';
import { markTooltip } from './marks-strip.js';
import { crashedModulesText, unheardEventsRow } from './panel-text.js';
import { modulesText } from './monitor-panel.js';

// two faults a field tester planted, in the records their runs wrote (b-deadrule, e-crash): GCS posts
// "land" on its port 1 that nothing subscribes, and EST's code dereferences NULL after 300 cycles
const W = '2026-12-07T11:02:48.568320Z';
const GCS = [
  `1000000000,${W},GCS,module_started,,,0,pid=61 priority=30`,
  `1100000000,${W},GCS,event_posted,FLT,0,256,to_port=1`,
  `4306199000,${W},GCS,event_posted,,1,256,no subscriber`,
  `4400000000,${W},GCS,event_posted,FLT,0,256,to_port=1`,
  `5000000000,${W},GCS,event_posted,,1,256,no subscriber`,
  `5100000000,${W},GCS,event_posted,,2,256,no subscriber`,
  `6000000000,${W},GCS,event_posted,,1,256,no subscriber`,
];
const EST = [
  `1000500000,${W},EST,module_started,,,0,pid=60 priority=84`,
  `5240000000,${W},EST,run_started,ORD,,0,activation=301`,
  `5240958000,${W},EST,module_crashed,,,0,signal 11 (SIGSEGV) records=1808`,
];
const t = (ns: number) => ns - 1000000000;
const LOGS = [{ name: 'GCS_1.csv', lines: GCS }, { name: 'EST_1.csv', lines: EST }];
/** The run's records in time order, with their log and line. */
const LINES = linesInTimeOrder(LOGS);

/** The three ways the Monitor reads a run: live lines read in place, parsed records, a recorded run's logs. */
function models(): MonitorModel[] {
  return readThreeWays(LOGS, { checkpointEvery: 16 });
}

/** `contract trace`'s line for the record of `module` that says `what`, after its time and module. */
function told(what: string): string {
  const story = renderStory(parseTrace(LOGS.map((l) => ({ name: l.name, text: `${HEADER}\n${l.lines.join('\n')}\n` }))));
  return story.find((l) => l.includes(what))!.replace(/^\S+ \S+ +/, '');
}

describe('an event posted with no subscriber', () => {
  it('is counted per port at the cursor, a delivered one not, live, parsed and recorded alike', () => {
    for (const m of models()) {
      expect([...m.live.unheardEvents]).toEqual([['GCS:1', { count: 3, last: t(6000000000) }], ['GCS:2', { count: 1, last: t(5100000000) }]]);
      expect([...m.stateAt(t(4306199000))!.unheardEvents]).toEqual([['GCS:1', { count: 1, last: t(4306199000) }]]);
      expect(m.stateAt(t(4306199000) - 1)!.unheardEvents.size).toBe(0);
    }
  });

  it('marks its port\'s first on the strip in contract trace\'s words', () => {
    const story = told('GCS:1 posted with no subscriber');
    expect(story).toBe('event GCS:1 posted with no subscriber: no one received it (no supervisor or module subscribed to GCS:1 then); its later ones are counted at the end');
    for (const m of models()) {
      const marks = m.marks.filter((k) => k.kind === 'unheard');
      expect(marks.map((k) => [k.t, k.where, k.label])).toEqual([
        [t(4306199000), 'GCS', story.replace('its later ones are counted at the end', 'Deliveries counts its later ones')],
        [t(5100000000), 'GCS', expect.stringMatching(/^event GCS:2 posted with no subscriber: no one received it/)],
      ]);
      expect(markTooltip(marks.slice(0, 1))).toMatch(/^\+3\.306199 s GCS: event GCS:1 posted with no subscriber: no one received it/);
    }
  });

  it('is listed first under Deliveries', () => {
    expect(unheardEventsRow('GCS:1', { count: 3, last: t(6000000000) })).toBe('┅ GCS:1 → no subscriber ×3 · no one received them · last +5.000000 s');
    expect(unheardEventsRow('GCS:2', { count: 1, last: t(5100000000) })).toBe('┅ GCS:2 → no subscriber ×1 · no one received it · last +4.100000 s');
  });
});

describe('a module whose code crashed', () => {
  it('is said crashed from its module_crashed record on, marked on the strip in contract trace\'s words, live, parsed and recorded alike', () => {
    const story = told('EST  crashed');
    expect(story).toBe('crashed: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array');
    for (const m of models()) {
      expect(m.marks.filter((k) => k.kind === 'crash').map((k) => [k.t, k.where, k.label])).toEqual([[t(5240958000), 'EST', story]]);
      expect(m.live.modules.get('EST')).toMatchObject({ alive: false, running: false, crashed: story, since: t(5240958000) });
      expect(crashedModulesText(m.live.modules)).toBe('⚠ EST crashed at +4.240958 s: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array');
      // scrubbed back before it: not crashed yet
      expect(crashedModulesText(m.stateAt(t(5240958000) - 1)!.modules)).toBe('');
    }
  });

  it('is said crashed far back once the raw records there were dropped (its record is notable)', () => {
    const m = new MonitorModel({ checkpointEvery: 16, keepRecords: 32 });
    const filler = Array.from({ length: 200 }, (_, i) => parseRecordLine('BAR_1.csv', i + 2, `${5300000000 + i * 1000},${W},BAR,data_posted,EST,0,16,to_port=0`));
    m.pushAll([...LINES.map((l) => parseRecordLine(l.file, l.line, l.text)), ...filler]);
    expect(m.exactAt(t(5240958000) + 1)).toBe(false);
    expect(m.stateAt(t(5240958000) + 1)!.modules.get('EST')?.crashed).toBe('crashed: signal 11 (SIGSEGV): a bad pointer: NULL, freed, or past the end of an array');
  });

  it('is no longer said crashed once started again', () => {
    const m = new MonitorModel();
    for (const l of LINES) m.pushLine(l.file, l.line, l.text);
    m.pushLine('EST_1.csv', 5, `7000000000,${W},EST,module_started,,,0,pid=90 priority=84`);
    expect(m.live.modules.get('EST')?.crashed).toBeUndefined();
    expect(crashedModulesText(m.live.modules)).toBe('');
  });

  it('is named after the modules running now, apart from those with no exit record', () => {
    expect(modulesText(['FLT', 'BAT'], [], ['EST'])).toBe('Running now: BAT, FLT · crashed: EST');
    expect(modulesText([], ['HOG'], ['EST'])).toBe('Running now: none · crashed: EST · no exit record: HOG (crashed, killed, or ended by its code\'s exit(): the run\'s messages say which)');
  });
});
