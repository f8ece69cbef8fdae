import { describe, it, expect } from 'vitest';
import type { MonitorModel } from './monitor-model.js';
import { readThreeWays } from './read-three-ways.test-support.js';
import { flowValueText } from './panel-text.js';

// a field tester's line follower with its rule waiting for "lsot": LFR takes CAM's "lost" and
// "found", which change no rule, then a "stop" that does (its records as the runtime writes them)
const W = '2026-12-07T14:40:02.413877Z';
const received = (ns: number, value: string, rules: number) =>
  `${ns},${W},LFR,event_received,CAM,0,256,"from_port=0 latency_ns=49593 rules=${rules} value=${value.replace(/"/g, '""')}"`;
const LFR = [
  `1000000000,${W},LFR,module_started,,,0,pid=49 priority=99`,
  received(2000000000, '"lost"', 0),
  received(2600000000, '"found"', 0),
  received(3000000000, '"lost"', 0),
  `3500000000,${W},LFR,sup_rule,,,0,"drive.FOLLOW inactive cause=CAM:0 value=""stop"""`,
  received(3500000001, '"stop"', 1),
];
const t = (ns: number) => ns - 1000000000;
const LOGS = [{ name: 'LFR_1.csv', lines: LFR }];

/** The three ways the Monitor reads a run: live lines read in place, parsed records, a recorded run's logs. */
function models(): MonitorModel[] {
  return readThreeWays(LOGS, { checkpointEvery: 2 });
}

describe('a supervisor\'s event flow under Deliveries', () => {
  it('keeps the last value received and counts the events that changed no rule, live, parsed and recorded alike, and at the cursor', () => {
    for (const m of models()) {
      // (and the longest delivery latency, which the flow-waits tooltip names: event-flood tests)
      expect(m.live.eventFlows.get('CAM:0->LFR:0')).toMatchObject({ count: 4, last: t(3500000001), lastValue: '"stop"', unmatched: 3 });
      expect(m.stateAt(t(2600000000))!.eventFlows.get('CAM:0->LFR:0')).toMatchObject({ count: 2, last: t(2600000000), lastValue: '"found"', unmatched: 2 });
    }
  });

  it('says them on the row: the last value, then how many changed no rule', () => {
    expect(flowValueText({ count: 3, last: 0, lastValue: '"lost"', unmatched: 3 })).toBe(' · value "lost" · ⚠ 3 changed no rule');
    expect(flowValueText({ count: 1, last: 0, lastValue: '12' })).toBe(' · value 12');
    // a module's event flow (no value in its records): nothing
    expect(flowValueText({ count: 1, last: 0 })).toBe('');
  });
});
