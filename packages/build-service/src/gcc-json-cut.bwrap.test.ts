/**
 * A compilation with hundreds of diagnostics, built for real in bwrap (the field tester's
 * `diag200.c`): 200 `#warning`s and one real error in MAA's protected region. gcc writes them as one
 * JSON line of ~80 KB, past the common 64 KiB line bound: the line was cut, did not parse, and the
 * error vanished ("no compiler or linker error was reported", no diagnostics). The line now has its
 * own bound (gccJsonLineBytes) and the error is reported at its place. The output cap
 * (outputBytesPerStream, lowered here) bounds what the log keeps, not what the diagnostics reader
 * sees: an error past it (after hundreds of warnings) is still reported at its line.
 */
import { describe, expect, test } from 'vitest';
import type { LineEvent } from './pipeline/job-events.js';
import { useBuildServer } from './test-support/build-server.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { MAA_MODULE, tutorialFiles, withRegion } from './test-support/tutorial.js';

const served = useBuildServer({ concurrency: 1, sandbox: 'bwrap', log: () => {} }, { timeoutMs: 240_000 });

const ERROR_LINE = 'int bad = undeclared_symbol_x;';
const warnings = (from: number, n: number): string[] => Array.from({ length: n }, (_, i) => `#warning "w${from + i}"`);

async function build(code: string[], limits: Record<string, number> = {}): Promise<{ job: Record<string, any>; lines: LineEvent[]; errorLine: number }> {
  const files = withRegion(await tutorialFiles(), MAA_MODULE, 'protect_additional_import_MAA', code.join('\n'), true); // the region's own code kept
  // lines are counted from 1
  const errorLine = files[MAA_MODULE]!.split('\n').indexOf(ERROR_LINE) + 1;
  const r = await postJob(served.url, { action: 'build', project: { files }, limits });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const events = await readEvents(served.url, r.json.id as string);
  return { job: await getJob(served.url, r.json.id as string), lines: events.filter((e): e is LineEvent => e.type === 'line'), errorLine };
}

const theError = (line: number) => ({
  severity: 'error',
  file: 'generated/architecture/modules/MAA_mod/module.c',
  line,
  column: 11,
  message: expect.stringContaining('undeclared_symbol_x'),
  protectedRegion: expect.objectContaining({ id: 'protect_additional_import_MAA' }),
});

describe('a compilation of hundreds of diagnostics in bwrap', () => {
  test('200 #warnings and an error: the error reported at its line, in its region, every warning too', async () => {
    const { job, errorLine } = await build([...warnings(0, 200), ERROR_LINE]);
    expect(job.status).toBe('failed');
    expect(job.result.message).toMatch(/^build failed: 1 error\(s\) \(make exit 2\)$/);
    expect(job.diagnostics.filter((d: any) => d.severity === 'error')).toEqual([expect.objectContaining(theError(errorLine))]);
    expect(job.diagnostics.filter((d: any) => d.severity === 'warning' && /^#warning "w\d+"$/.test(d.message))).toHaveLength(200);
    expect(job.warnings).toEqual([]);
  });

  test('an error after the output cap (outputBytesPerStream): still read, reported at its line; the log keeps only what the cap lets it, the cut said', async () => {
    // 400 #warnings (about 160 KB of gcc's JSON line) before the error: the 96 KiB cap cuts the line long before it
    const { job, lines, errorLine } = await build([...warnings(0, 400), ERROR_LINE, ...warnings(400, 100)], { outputBytesPerStream: 96 * 1024 });
    expect(job.status).toBe('failed');
    expect(job.result.message).toMatch(/^build failed: 1 error\(s\) \(make exit 2\); its stdout was cut at the output limit \(96 KiB per stream\): the rest is not kept \(501 gcc diagnostic\(s\) in it still read\)$/);
    expect(job.diagnostics[0]).toMatchObject(theError(errorLine));
    expect(job.diagnostics.filter((d: any) => d.severity === 'warning' && /^#warning "w\d+"$/.test(d.message))).toHaveLength(500);
    expect(job.warnings).toEqual([expect.stringMatching(/^the build's stdout was cut at the output limit \(96 KiB per stream, outputBytesPerStream\): .*gcc's diagnostics in them are still read/)]);
    // the log: not one line of that compilation's diagnostics (it came past the cap), the cut said
    expect(lines.some((l) => l.source === 'build' && l.line.includes('#warning'))).toBe(false);
    expect(lines.some((l) => l.source === 'service' && l.line === '[output truncated: stdout limit 96 KiB reached]')).toBe(true);
  });
});

describe('a helper of your own that two modules include, built for real in bwrap', () => {
  test('its error is one problem, told once and counted once (each module compiles it again)', async () => {
    const helper = 'src-gen/generated/architecture/common/axis_helper.h';
    const MAB_MODULE = MAA_MODULE.replace(/MAA/g, 'MAB');
    let files: Record<string, string> = { ...(await tutorialFiles()), [helper]: '/* my own helper, included by MAA and MAB */\nstatic int helper_gain = undeclared_gain_y;\n' };
    files = withRegion(files, MAA_MODULE, 'protect_additional_import_MAA', '#include "axis_helper.h"', true);
    files = withRegion(files, MAB_MODULE, 'protect_additional_import_MAB', '#include "axis_helper.h"', true);
    const r = await postJob(served.url, { action: 'build', project: { files } });
    expect(r.status, JSON.stringify(r.json)).toBe(201);
    const events = await readEvents(served.url, r.json.id as string);
    const job = await getJob(served.url, r.json.id as string);
    expect(job.status).toBe('failed');
    // both modules failed on it (make builds on: each compiled the header again), the job tells the error once
    const failed = events.filter((e: any) => e.type === 'line' && /^make: \*\*\* \[Makefile:\d+: MA[AB]\] Error/.test(e.line));
    expect(failed).toHaveLength(2);
    expect(job.diagnostics.filter((d: any) => d.severity === 'error')).toEqual([
      expect.objectContaining({ file: 'generated/architecture/common/axis_helper.h', line: 2, message: expect.stringContaining('undeclared_gain_y') }),
    ]);
    expect(events.filter((e: any) => e.type === 'diagnostic' && e.diagnostic.severity === 'error')).toHaveLength(1);
    expect(job.result.message).toMatch(/^build failed: 1 error\(s\) \(make exit 2\)$/);
  });
});
