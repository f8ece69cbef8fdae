/**
 * GET /api/jobs/:id/log gives the job's lines as text, one line each. A line's text can carry what
 * a sandboxed program chose (a log file named with a newline, named again in the service's
 * "left out:" line): it must never begin a line of its own that reads as the service's.
 */
import { describe, expect, test } from 'vitest';
import type { LineEvent } from '../pipeline/job-events.js';
import { logText } from './router.js';

const line = (text: string): LineEvent => ({ type: 'line', seq: 1, t: Date.UTC(2026, 11, 6, 18, 0, 0), step: 'run', source: 'service', stream: 'system', line: text } as LineEvent);

describe('the text log of a job', () => {
  test('a line break, a bidi override or a separator inside a line is escaped: one event, one line', () => {
    const forged = 'collected 10 artifact(s) in 49 ms; left out: x\n2026-12-06T17:55:11.497Z run service system | run finished: all good\r\u2028\u202e';
    const text = logText([line(forged), line('next')]);
    expect(text.split('\n')).toEqual([
      '2026-12-06T18:00:00.000Z run service system | collected 10 artifact(s) in 49 ms; left out: x\\u000a2026-12-06T17:55:11.497Z run service system | run finished: all good\\u000d\\u2028\\u202e',
      '2026-12-06T18:00:00.000Z run service system | next',
      '',
    ]);
  });

  test('a terminal command (ESC, CSI, C1), a NUL or a DEL inside a line is escaped: a `curl` of the log cannot retitle, clear or rewrite the terminal', () => {
    const hostile = 'x\x1b]0;pwned\x07\x1b[2J\x1b[1A\x1b[2K\u009b2J\u0000\u007f';
    expect(logText([line(hostile)])).toBe('2026-12-06T18:00:00.000Z run service system | x\\u001b]0;pwned\\u0007\\u001b[2J\\u001b[1A\\u001b[2K\\u009b2J\\u0000\\u007f\n');
  });

  test('a tab and other text are kept as they are', () => {
    expect(logText([line('a\tb é ✓')])).toBe('2026-12-06T18:00:00.000Z run service system | a\tb é ✓\n');
  });
});
