/**
 * A cycle ORD itself released past its CRITICAL_DELAY (its `late release: ...` line: a loaded
 * machine stalled ORD, it sends no ORD:0 and writes no ord_deadline_miss) in the Monitor, from a real
 * recorded run (fixtures/late-release-run: ORD SIGSTOPped from outside in a bwrap run of the tutorial):
 * the schema counts it, as `contract trace` does (`lateReleases`), keeps it for its chips, and the
 * strip marks it with ORD's line, read live, parsed and replayed alike. Before, the Monitor read the
 * line as nothing: no count, no mark.
 */
import { describe, it, expect } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { readThreeWays, type TestLog } from './read-three-ways.test-support.js';
import { lateReleasesText } from './panel-text.js';

const DIR = join(__dirname, 'fixtures', 'late-release-run');
const logs: TestLog[] = readdirSync(DIR).filter((f) => f.endsWith('.csv')).sort().map((name) => ({
  name,
  lines: readFileSync(join(DIR, name), 'utf8').split('\n').slice(1).filter((l) => l.length > 0),
}));
const ORD_LINE = 'late release: schemaCommande1 cycle 1 released 663830 us after its tick, past CRITICAL_DELAY 200000 us (ORD late, no ORD:0)';

describe("ORD's late release in the Monitor (a real run)", () => {
  it('is counted for its schema, kept for its chip and marked with ORD\'s line, apart from the deadline misses', () => {
    const models = readThreeWays(logs, {});
    for (const m of models) {
      const end = m.stateAt(m.end);
      const p = end.periodic.get('schemaCommande1')!;
      expect(p.lateReleases).toBe(1);
      expect(p.deadlineMisses).toBe(0);
      expect(p.recentLateReleases.map((x) => x.cycle)).toEqual([1]);
      const marks = m.marks.filter((k) => k.kind === 'late');
      expect(marks.map((k) => [k.where, k.label])).toEqual([['schemaCommande1', ORD_LINE]]);
      // the chip's mark is found at its time, as a miss's is
      expect(m.marksBetween(p.recentLateReleases[0]!.t, p.recentLateReleases[0]!.t).some((k) => k.kind === 'late')).toBe(true);
      // before the line, none
      expect(m.stateAt(marks[0]!.t - 1).periodic.get('schemaCommande1')?.lateReleases ?? 0).toBe(0);
      expect(m.marks.filter((k) => k.kind === 'miss')).toEqual([]);
    }
  });

  it("says the count in contract trace's words", () => {
    expect(lateReleasesText(0)).toBe('');
    expect(lateReleasesText(1)).toBe(' · 1 cycle released past CRITICAL_DELAY (ORD itself late, no ORD:0)');
    expect(lateReleasesText(3)).toBe(' · 3 cycles released past CRITICAL_DELAY (ORD itself late, no ORD:0)');
  });
});
