import { describe, it, expect } from 'vitest';
import { jobOutcome } from './live-follow-protocol.js';

// a field tester's crashed run: its message, as the build service ends the job with it
const CRASHED = 'run failed: module EST crashed (died by signal 11 (Segmentation fault)) at src-gen/generated/architecture/modules/EST_mod/module.c:251 in its protected region protect_exec_EST (_exec_module_state) (contract-launch exit 1; make exit 2) [bwrap; prepare 1.0 s, build 0.3 s, run 10.7 s]';

describe('jobOutcome', () => {
  it('keeps a failed job\'s message whole (the run list shortens its entry, the header shows it all)', () => {
    expect(jobOutcome({ ok: false, message: CRASHED })).toBe(`failed: ${CRASHED}`);
    expect(jobOutcome({ ok: true })).toBe('succeeded');
    expect(jobOutcome({ ok: false, message: 'cancelled' })).toBe('cancelled');
    expect(jobOutcome({ ok: false, message: 'a\n  b' })).toBe('failed: a b');
  });

  it('ends a hostile message at a word with an ellipsis, never inside one', () => {
    const outcome = jobOutcome({ ok: false, message: 'word '.repeat(100_000) });
    expect(outcome.length).toBeLessThanOrEqual('failed: '.length + 1000);
    expect(outcome).toMatch(/^failed: (word )+word…$/);
  });
});
