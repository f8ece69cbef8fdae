/**
 * A build whose output went past the output limit (outputBytesPerStream) says so where a CI reads:
 * among the job's warnings, in its text log (a `warning:` line and the step's last line) and in
 * its result's message. It ended with `build succeeded` and said it only in `result.truncated`,
 * although the lines after the cut are kept nowhere. The sandbox is a script
 * (test-support/scripted-sandbox.ts).
 */
import { describe, expect, test } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import { logText } from '../http/router.js';
import { scratchWorkspace, scriptedContext, scriptedSandbox } from '../test-support/scripted-sandbox.js';
import type { LineEvent } from './job-events.js';
import { buildOutputCutWarning, Job } from './job.js';

const LIMIT = 1024;

async function build(id: string, exitCode: number): Promise<{ job: Job; log: string }> {
  const job = new Job(id, { action: 'build', project: { files: { Makefile: 'all:\n\ttrue\n' } }, projectKey: null, kind: 'make', limits: { ...DEFAULT_LIMITS, outputBytesPerStream: LIMIT } }, 'none');
  const sandbox = scriptedSandbox({
    build: {
      start: (p) => {
        // 100 lines of 40 bytes on stdout: 4 KB, past the 1 KiB limit
        p.write('stdout', ...Array.from({ length: 100 }, (_, i) => `cc -c module_${String(i).padStart(3, '0')}.c -o module.o ...`));
        p.write('stderr', 'a warning that fits');
        setTimeout(() => p.exit(exitCode), 20);
      },
    },
  });
  await job.execute(scriptedContext(sandbox, scratchWorkspace()));
  return { job, log: logText(job.events.all.filter((e): e is LineEvent => e.type === 'line')) };
}

describe('a build whose output was cut at the output limit', () => {
  test('succeeds, and says the cut in its warnings, its text log and its result message (not only in `truncated`)', async () => {
    const { job, log } = await build('j-cut', 0);
    expect(job.status).toBe('succeeded');
    expect(job.result!.truncated).toEqual({ stdout: true, stderr: false });
    const warning = buildOutputCutWarning('stdout', LIMIT);
    expect(warning).toContain('cut at the output limit (1 KiB per stream, outputBytesPerStream)');
    expect(warning).toContain('the whole output cannot be got from this job');
    expect(job.warnings).toEqual([warning]);
    expect(job.toJSON().warnings).toEqual([warning]);
    expect(job.result!.message).toBe('build succeeded; its stdout was cut at the output limit (1 KiB per stream): the rest is not kept');
    expect(log).toContain(`build service system | warning: ${warning}\n`);
    expect(log).toMatch(/ build service system \| build finished in \d+ ms; its stdout was cut at the output limit \(1 KiB per stream\): the rest is not kept\n/);
  });

  test('a failed build says it too (its errors past the cut are not shown)', async () => {
    const { job, log } = await build('j-cut-failed', 2);
    expect(job.status).toBe('failed');
    expect(job.result!.message).toBe('build failed (make exit 2); its stdout was cut at the output limit (1 KiB per stream): the rest is not kept');
    expect(job.warnings).toEqual([buildOutputCutWarning('stdout', LIMIT)]);
    expect(log).toContain('build: exit 2; its stdout was cut at the output limit');
  });

  test('a build within the limit says nothing of the kind', async () => {
    const job = new Job('j-whole', { action: 'build', project: { files: { Makefile: 'all:\n\ttrue\n' } }, projectKey: null, kind: 'make', limits: { ...DEFAULT_LIMITS, outputBytesPerStream: LIMIT } }, 'none');
    await job.execute(scriptedContext(scriptedSandbox({ build: { start: (p) => (p.write('stdout', 'ok'), p.exit(0)) } }), scratchWorkspace()));
    expect(job.result!.message).toBe('build succeeded');
    expect(job.warnings).toEqual([]);
  });
});
