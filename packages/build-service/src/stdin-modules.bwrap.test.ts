/**
 * A run request whose `stdin` names no module of the architecture (`{"MAX": "commands.txt"}` for
 * MAA) is refused before anything is built: the generated `make run` passes STDIN_<NAME> on to the
 * launcher only for its executables, so the file was dropped and every module read /dev/null,
 * silently (field test ft69). A real job in the bwrap sandbox, the tutorial's project.
 */
import { spawnSync } from 'node:child_process';
import { describe, expect, test } from 'vitest';
import { useBuildServer } from './test-support/build-server.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { tutorialFiles } from './test-support/tutorial.js';

const hasBwrap = spawnSync('bwrap', ['--ro-bind', '/', '/', 'true']).status === 0;
const served = useBuildServer({ concurrency: 1, sandbox: 'bwrap' }, { snapshotRuntime: false, skip: !hasBwrap });

describe.skipIf(!hasBwrap)('a run\'s stdin for no module', () => {
  test('fails the job in prepare, naming the module meant and the executables; nothing built or run', async () => {
    const files = { ...(await tutorialFiles()), 'commands.txt': 'connect\n' };
    const r = await postJob(served.url, { action: 'run', project: { files }, duration: 1, stdin: { MAX: 'commands.txt', MSC: 'commands.txt' } });
    expect(r.status).toBe(201);
    const events = await readEvents(served.url, r.json.id as string);
    const job = await getJob(served.url, r.json.id as string);
    expect(job.status).toBe('failed');
    expect(job.result.step).toBe('prepare');
    expect(job.result.message).toBe(
      "prepare failed: stdin.MAX: no module 'MAX' in this architecture. Did you mean 'MAA'? (its modules: ORD, MAA, MAB, MSA, MSB, MSC, MSD, SUP, GLB); nothing was built or run",
    );
    // no make, no launcher
    expect(events.some((e) => e.type === 'line' && (e.step === 'build' || e.step === 'run'))).toBe(false);
  });
});
