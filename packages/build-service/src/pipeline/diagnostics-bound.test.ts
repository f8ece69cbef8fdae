/**
 * A job keeps diagnosticsPerJob gcc diagnostics; an error past that bound still has a room of its
 * own (as many again): a build whose first compilations fill the bound with warnings still reports
 * the error a later one wrote (it was dropped, and the build failed with no error reported). The
 * sandbox is a script (test-support/scripted-sandbox.ts).
 */
import { describe, expect, test } from 'vitest';
import { DEFAULT_LIMITS, SERVICE_BOUNDS } from '../limits.js';
import { scratchWorkspace, scriptedContext, scriptedSandbox } from '../test-support/scripted-sandbox.js';
import { Job } from './job.js';

const diagnostic = (kind: string, message: string) => ({ kind, message, children: [], locations: [{ caret: { file: 'module.c', line: 3, 'display-column': 5, 'byte-column': 5, column: 5 } }] });
const line = (kind: string, n: number, from = 0) => JSON.stringify(Array.from({ length: n }, (_, i) => diagnostic(kind, `${kind} ${from + i}`)));

describe("the job's diagnostics bound", () => {
  test('warnings stop at diagnosticsPerJob; a later error is kept past it', async () => {
    const job = new Job('j-bound', { action: 'build', project: { files: { Makefile: 'all:\n\ttrue\n' } }, projectKey: null, kind: 'make', limits: { ...DEFAULT_LIMITS } }, 'none');
    const half = SERVICE_BOUNDS.diagnosticsPerJob / 2;
    const sandbox = scriptedSandbox({
      build: {
        start: (p) => {
          // three compilations: two of warnings that fill the bound, more warnings, then the error
          p.write('stderr', line('warning', half), line('warning', half, half), line('warning', 5, 2 * half), line('error', 1));
          setTimeout(() => p.exit(2), 20);
        },
      },
    });
    await job.execute(scriptedContext(sandbox, scratchWorkspace()));
    expect(job.diagnostics).toHaveLength(SERVICE_BOUNDS.diagnosticsPerJob + 1);
    expect(job.diagnostics.filter((d) => d.severity === 'warning')).toHaveLength(SERVICE_BOUNDS.diagnosticsPerJob);
    expect(job.diagnostics.at(-1)).toMatchObject({ severity: 'error', message: 'error 0' });
    expect(job.result!.message).toBe('build failed: 1 error(s) (make exit 2)');
  });
});
