/**
 * The field tester's protected region, built for real in bwrap: a `#warning` holding a raw BEL
 * before a real error. gcc 12 writes the BEL raw inside its JSON string: the compilation's line was
 * no JSON, and the build failed with no diagnostic at all ("no compiler or linker error was
 * reported", the IDE's Problems empty). Every diagnostic is now reported, the BEL as its escape.
 */
import { describe, expect, test } from 'vitest';
import type { LineEvent } from './pipeline/job-events.js';
import { useBuildServer } from './test-support/build-server.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { MAA_MODULE, tutorialFiles, withRegion } from './test-support/tutorial.js';

const served = useBuildServer({ concurrency: 1, sandbox: 'bwrap', log: () => {} }, { timeoutMs: 240_000 });

const REGION = ['#warning "plain warning one"', '#warning "bell \x07 here"', 'int undeclared_use(void){ return nosuchvar; }'];

describe('a #warning holding a control character, built in bwrap', () => {
  test('the real error is reported at its line, in its region, both warnings too, the BEL written \\u0007', async () => {
    const files = withRegion(await tutorialFiles(), MAA_MODULE, 'protect_additional_import_MAA', REGION.join('\n'), true);
    const lineOf = (text: string) => files[MAA_MODULE]!.split('\n').indexOf(text) + 1;
    const r = await postJob(served.url, { action: 'build', project: { files } });
    expect(r.status, JSON.stringify(r.json)).toBe(201);
    const events = await readEvents(served.url, r.json.id as string);
    const job = await getJob(served.url, r.json.id as string);
    expect(job.status).toBe('failed');
    expect(job.result.message).toBe('build failed: 1 error(s) (make exit 2)');
    const region = { protectedRegion: expect.objectContaining({ id: 'protect_additional_import_MAA' }), file: 'generated/architecture/modules/MAA_mod/module.c' };
    expect(job.diagnostics.filter((d: any) => d.severity === 'error')).toEqual([
      expect.objectContaining({ ...region, line: lineOf(REGION[2]!), message: expect.stringContaining('nosuchvar') }),
    ]);
    expect(job.diagnostics.filter((d: any) => d.severity === 'warning' && d.message.startsWith('#warning'))).toEqual([
      expect.objectContaining({ ...region, line: lineOf(REGION[0]!), message: '#warning "plain warning one"' }),
      expect.objectContaining({ ...region, line: lineOf(REGION[1]!), message: '#warning "bell \\u0007 here"' }),
    ]);
    expect(job.warnings).toEqual([]);
    // the log's lines are gcc's, rendered: no raw control character
    const logged = events.filter((e): e is LineEvent => e.type === 'line' && e.source === 'build').map((e) => e.line);
    expect(logged.some((l) => l.includes("'nosuchvar' undeclared") || l.includes('‘nosuchvar’ undeclared'))).toBe(true);
    expect(logged.join('\n')).not.toContain('\x07');
  });
});
