/**
 * The log of a cancelled run reads in the order things happened: the user cancels, the service
 * says it is stopping the architecture, then come the lines the launcher printed while it stopped,
 * then the end. The service's line came after the launcher's (it was said once the launcher had
 * been asked, which takes an exec: the launcher was already printing). A run with no launcher to
 * ask says so. The sandbox is a script (test-support/scripted-sandbox.ts): the launcher prints
 * while it is being asked, before the asking returns, as a real one may.
 */
import { describe, expect, test } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import { scratchWorkspace, scriptedContext, scriptedSandbox, type ScriptedProcess } from '../test-support/scripted-sandbox.js';
import type { LineEvent } from './job-events.js';
import { Job, NO_LAUNCHER_ASKED } from './job.js';

const MAKEFILE = 'all:\n\ttrue\nrun:\n\ttrue\n';

function runJob(id: string): Job {
  return new Job(id, { action: 'run', project: { files: { Makefile: MAKEFILE } }, projectKey: null, kind: 'make', limits: { ...DEFAULT_LIMITS } }, 'none');
}

/** The run step's lines as `source: line`, from the first `looping` on, once the job ended. */
async function cancelledRunLines(job: Job, terminate: (p: ScriptedProcess) => Promise<boolean>): Promise<string[]> {
  const sandbox = scriptedSandbox({
    run: {
      start: (p) => p.write('stdout', 'looping'),
      terminate,
    },
  });
  job.events.subscribe(0, (e) => {
    if (e.type === 'line' && e.line === 'looping') void job.cancel();
  });
  await job.execute(scriptedContext(sandbox, scratchWorkspace()));
  const lines = job.events.all.filter((e): e is LineEvent => e.type === 'line' && e.step === 'run').map((e) => `${e.source}: ${e.line}`);
  return lines.slice(lines.indexOf('run: looping'));
}

describe('the log of a cancelled run', () => {
  test('says "stopping the architecture" before the lines the launcher printed as it stopped, then the end', async () => {
    const job = runJob('j-order');
    const lines = await cancelledRunLines(job, async (p) => {
      // the launcher gets the signal and prints while the service's asking has not returned yet
      p.write('stderr', 'contract-launch: stopping (SIGTERM)', 'contract-launch: every module ended');
      await new Promise((r) => setTimeout(r, 30));
      setTimeout(() => p.exit(0), 10);
      return true;
    });
    expect(job.status).toBe('cancelled');
    const stopping = lines.findIndex((l) => l.startsWith('service: stopping the architecture as at the end of a run ('));
    const launcher = lines.indexOf('launcher: stopping (SIGTERM)');
    expect(stopping, lines.join('\n')).toBeGreaterThan(0);
    expect(launcher, lines.join('\n')).toBeGreaterThan(stopping);
    expect(lines.indexOf('launcher: every module ended')).toBeGreaterThan(launcher);
    // then the end of the run step: its logs collected
    expect(lines.findIndex((l) => /^service: collected \d+ artifact\(s\)/.test(l))).toBeGreaterThan(launcher);
    expect(lines).not.toContain(`service: ${NO_LAUNCHER_ASKED}: killed`);
    expect(job.events.all.at(-1)!.type).toBe('end');
  });

  test('a run with no launcher to ask: the stopping line, then that none was asked and it was killed', async () => {
    const job = runJob('j-nolauncher');
    const lines = await cancelledRunLines(job, async () => false);
    expect(job.status).toBe('cancelled');
    const stopping = lines.findIndex((l) => l.startsWith('service: stopping the architecture as at the end of a run ('));
    expect(stopping).toBeGreaterThan(0);
    expect(lines[stopping + 1]).toBe(`service: ${NO_LAUNCHER_ASKED}: killed`);
  });
});
