import { describe, it, expect } from 'vitest';
import { jobEndStatus, jobStatusText } from './job-end.js';

/** The status bar's text at a job's end, as the build panel and run-controller.ts make it. */
const statusBar = (result: { ok?: unknown; message?: unknown } | null, lastStatus?: string) => {
  const end = jobEndStatus(result, lastStatus);
  return jobStatusText(end.status, end.message, false);
};

describe("a job's end in the status bar", () => {
  it('a cancelled job says cancelled, not "failed: cancelled" (the Monitor says "ended: cancelled")', () => {
    expect(statusBar({ ok: false, message: 'cancelled' }, 'running')).toBe('■ cancelled');
    expect(statusBar({ ok: false, message: 'cancelled' })).toBe('■ cancelled');
    // the service said cancelled before the end, the result kept the run's own words
    expect(statusBar({ ok: false, message: 'run failed (exit 143, signal SIGTERM)' }, 'cancelled')).toBe('■ cancelled: run failed (exit 143, signal SIGTERM)');
    expect(jobEndStatus({ ok: false, message: 'cancelled' }).status).toBe('cancelled');
  });

  it('keeps the other statuses as they were', () => {
    expect(statusBar({ ok: true, message: 'run finished (exit 0)' }, 'succeeded')).toBe('✓ succeeded: run finished (exit 0)');
    expect(statusBar({ ok: false, message: 'run: MAA exited with status 3' }, 'failed')).toBe('■ failed: run: MAA exited with status 3');
    expect(statusBar({ ok: false, message: 'build failed (exit 2)' }, 'building')).toBe('■ failed: build failed (exit 2)');
    expect(statusBar(null)).toBe('■ failed');
    expect(statusBar({ ok: false, message: 42 })).toBe('■ failed');
    expect(jobStatusText('running', 'run', true)).toBe('⟳ running: run');
    expect(jobStatusText('disconnected', 'lost the connection to the build service', false)).toBe('■ disconnected: lost the connection to the build service');
  });
});
