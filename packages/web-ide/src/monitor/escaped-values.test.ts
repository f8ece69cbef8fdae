import { describe, it, expect } from 'vitest';
import type { MonitorModel } from './monitor-model.js';
import { readThreeWays } from './read-three-ways.test-support.js';
import { crashedModulesText, flowRow, flowWaitTitle, keptRequestsLine, quietDataFlowRow, ruleTexts, unheardEventsRow } from './panel-text.js';
import { markTooltip } from './marks-strip.js';
import { barTitle } from '../views/timeline-bars.js';

// A field tester's run: CAM posts string event values holding a bidirectional override (U+202E),
// a zero-width space and an ESC; LFR's rule changes on one. Shown raw, `"\u202estop"` read
// reversed in the rule's cause, its tooltip and the Deliveries row (docs/watching-a-run.md
// "Characters shown as escapes": they are written as their escapes, as the CLI writes them).
const W = '2026-12-07T14:40:02.413877Z';
const VALUE = '"\u202estop\u200b\x1b[2J"';
const SHOWN = '"\\u202estop\\u200b\\u001b[2J"';
const csv = (s: string) => `"${s.replace(/"/g, '""')}"`;
const LFR = [
  `1000000000,${W},LFR,module_started,,,0,pid=49 priority=99`,
  `1500000000,${W},LFR,supervisor,,,0,function drive started`,
  `2000000000,${W},LFR,event_received,CAM,0,256,${csv(`from_port=0 latency_ns=49593 rules=0 value=${VALUE}`)}`,
  `3500000000,${W},LFR,sup_rule,,,0,${csv(`drive.FOLLOW active cause=CAM:0 value=${VALUE}`)}`,
  `3500000001,${W},LFR,event_received,CAM,0,256,${csv(`from_port=0 latency_ns=49593 rules=1 value=${VALUE}`)}`,
];
const RAW = /[\u202a-\u202e\u200b\x1b]/;

function models(): MonitorModel[] {
  return readThreeWays([{ name: 'LFR_1.csv', lines: LFR }], { checkpointEvery: 2 });
}

describe('a recorded string value holding a bidi override, a zero-width space and an ESC', () => {
  it('is written as its escapes in the rule\'s cause, its accessible name and its tooltip, live, parsed and recorded alike', () => {
    for (const m of models()) {
      const rs = m.live.supervisors.get('LFR')!.rules.get('drive.FOLLOW')!;
      expect(rs.cause).toContain('\u202e'); // the state keeps the value as recorded
      const texts = ruleTexts('drive', 'FOLLOW', rs, false);
      expect(texts.shown).toBe(`← CAM:0 = ${SHOWN}`);
      expect(texts.label).toContain(`← CAM:0 = ${SHOWN}`);
      expect(texts.title).toMatch(new RegExp(`^drive\\.FOLLOW active since \\+2\\.500000 s ← CAM:0 = ${SHOWN.replace(/[\\[]/g, '\\$&')} · click`));
      for (const t of Object.values(texts)) expect(t).not.toMatch(RAW);
    }
  });

  it('is written as its escapes on the flow\'s Deliveries row', () => {
    for (const m of models()) {
      const f = m.live.eventFlows.get('CAM:0->LFR:0')!;
      expect(f.lastValue).toBe(VALUE);
      expect(flowRow('event', 'CAM:0->LFR:0', f)).toBe(`┅ CAM:0 → LFR:0 ×2 · last +2.500000 s · value ${SHOWN} · ⚠ 1 changed no rule`);
    }
  });

  it('names and lines of records are written visibly on every other row, tooltip and mark too', () => {
    const evil = 'M\u202eAB\u200b';
    const flow = { count: 3, last: 0, waits: 2, waitNs: 1e6, maxWaitNs: 1e6, maxLatencyNs: 2e6, dropped: 1, dropReason: 'queue full\u202e' };
    for (const text of [
      flowRow('data', `${evil}:0->X:0`, flow),
      flowWaitTitle(`${evil}:0->X:0`, flow),
      unheardEventsRow(`${evil}:1`, { count: 1, last: 0 }),
      quietDataFlowRow(`data flow ${evil}:1 -> X:0 connected`),
      keptRequestsLine(evil, { since: 0, request: `STOP ${evil}` }),
      crashedModulesText(new Map([[evil, { crashed: `crashed: signal 11 ${evil}`, since: 0 }]]) as never),
      markTooltip([{ t: 0, kind: 'miss', where: evil, label: `deadline miss ${evil}` }]),
      ruleTexts(`f${evil}`, `R${evil}`, undefined, false).title,
    ]) {
      expect(text).not.toMatch(RAW);
      expect(text).toContain('M\\u202eAB\\u200b');
    }
  });

  it('the Timeline\'s bar tooltip writes a record\'s words and module visibly', () => {
    const bar = (a: object) => barTitle({ x1: 0, x2: 1, count: 1, open: false, first: a as never, last: a as never }, 0);
    expect(bar({ module: 'C\u202eTL', start: 0, end: 1e6, detail: 'activation=1 \u2066x\u2069\ufeff' })).toBe('C\\u202eTL 0.000 ms → 1.000 ms activation=1 \\u2066x\\u2069\\ufeff');
    expect(bar({ module: 'CTL', start: 0, end: 1e6, detail: '', event: { from: 'CAM\u202e:0', records: 0, ended: true } })).toBe('CTL handled an event from CAM\\u202e:0 at 0.000 ms: handled in 1.000 ms');
  });
});
