import { describe, it, expect } from 'vitest';
import { parseRecordLine } from '@contract-studio/build-service/trace';
import { MonitorModel } from './monitor-model.js';

const W = '2026-12-07T11:02:48.568320Z';

describe("an overrun's mark", () => {
  it("says ORD's line whole, the module its cycle still waits for included, live and parsed alike", () => {
    // ORD's line naming the module still running (another helper's change to the runtime), and one longer still
    const named = 'overrun: altHold cycle still running (EST has not finished its release #1202 of cycle 400), release skipped';
    const long = `overrun: altitudeHoldWithBarometerAndEstimator cycle still running, release skipped: ${'EST, '.repeat(20)}CTL still run their release`;
    const lines = [
      `1000000000,${W},ORD,scheduler,,,0,activate altHold (activation #4 from FLT)`,
      `1010000000,${W},ORD,scheduler,,,0,"${named}"`,
      `1020000000,${W},ORD,scheduler,,,0,"${long}"`,
    ];
    const live = new MonitorModel();
    lines.forEach((l, i) => live.pushLine('ORD_1.csv', i + 2, l));
    const parsed = new MonitorModel();
    parsed.pushAll(lines.map((l, i) => parseRecordLine('ORD_1.csv', i + 2, l)));
    for (const m of [live, parsed]) {
      expect(m.marks.filter((k) => k.kind === 'overrun').map((k) => [k.where, k.label])).toEqual([['altHold', named], ['altitudeHoldWithBarometerAndEstimator', long]]);
      expect(long.length).toBeGreaterThan(120);
    }
  });
});
