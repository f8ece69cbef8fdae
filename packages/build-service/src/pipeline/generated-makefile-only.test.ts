/**
 * A Cactal job's make is the generated Makefile's, named: `make -C src-gen/generated/architecture
 * -f Makefile all|run`. Without -f, a GNUmakefile or makefile put beside it would be read first and
 * be the build (its `run` echoing, the job "ok" with no module built or run). prepare refuses such a
 * file (prepare.test.ts); this is the second wall. A plain Makefile project's make chooses as it
 * always does. The sandbox is a script (test-support/scripted-sandbox.ts): the commands are seen,
 * not run.
 */
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, test } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import { scratchWorkspace, scriptedContext, scriptedSandbox, type ScriptedProcess } from '../test-support/scripted-sandbox.js';
import type { SandboxCommand } from '../sandbox/types.js';
import { Job } from './job.js';
import type { ProjectKind } from './prepare.js';

const TUTORIAL = fileURLToPath(new URL('../../../../examples/tutorial', import.meta.url));

/** The make command lines (from `make` on) of a run job's steps (build, run). */
async function makeCommands(kind: ProjectKind, files: Record<string, string>): Promise<string[]> {
  const seen: SandboxCommand[] = [];
  const step = { start: (p: ScriptedProcess) => { seen.push(p.command); p.exit(0); } };
  const sandbox = scriptedSandbox({ build: step, run: step });
  const job = new Job(`j-mk-${kind}`, { action: 'run', project: { files }, projectKey: null, kind, limits: { ...DEFAULT_LIMITS } }, 'none');
  await job.execute(scriptedContext(sandbox, scratchWorkspace()));
  expect(job.status, job.result?.message).toBe('succeeded');
  return seen.map((c) => c.argv.slice(c.argv.indexOf('make')).join(' '));
}

describe('the make of a job', () => {
  test('a Cactal build and run name the generated Makefile (-f Makefile); a plain Makefile project\'s do not', async () => {
    const files: Record<string, string> = {};
    for (const f of readdirSync(TUTORIAL)) if (f.endsWith('.contract')) files[f] = readFileSync(join(TUTORIAL, f), 'utf8');
    const [build, run] = await makeCommands('cactal', files);
    expect(build).toMatch(/^make -k -j\d+ --output-sync=recurse -C src-gen\/generated\/architecture -f Makefile all /);
    expect(run).toMatch(/^make -C src-gen\/generated\/architecture -f Makefile run /);
    const plain = await makeCommands('make', { Makefile: 'all:\n\ttrue\nrun:\n\ttrue\n' });
    expect(plain.map((c) => c.split(' ').slice(0, 4).join(' '))).toEqual(['make -C . all', 'make -C . run']);
  }, 120_000);
});
