/**
 * Child process of the tests of what a killed service leaves behind (run compiled: `node
 * dist/test-support/orphan-service.js CACHE_DIR [docker|bwrap-realtime]`): a build service runs a
 * job whose program loops for ever, prints `LOOPING <job id>` once the loop runs, then waits to be
 * killed (kill -9). `docker` (sweep.docker.test.ts): the container it leaves is what the next
 * service must sweep. `bwrap-realtime` (cgroup-sweep.bwrap.test.ts): a real-time bwrap run, whose
 * cgroups (and the cpu cgroup's real-time budget) the next service must sweep.
 */
import { JobService } from '../job-service.js';
import { infiniteLoop, makeProject } from './c-projects.js';

const [cacheDir, mode = 'docker'] = process.argv.slice(2);
if (!cacheDir || (mode !== 'docker' && mode !== 'bwrap-realtime')) {
  process.stderr.write('usage: orphan-service.js CACHE_DIR [docker|bwrap-realtime]\n');
  process.exit(2);
}
const realtime = mode === 'bwrap-realtime';
const service = new JobService({ sandbox: realtime ? 'bwrap' : 'docker', concurrency: 1, cacheDir, log: (l) => process.stderr.write(`${l}\n`) });
const job = await service.submit({ action: 'run', kind: 'make', project: { files: makeProject(infiniteLoop) }, ...(realtime ? { realtime: true } : {}) });
job.events.subscribe(0, (e) => {
  if (e.type === 'line' && e.line === 'looping') process.stdout.write(`LOOPING ${job.id}\n`);
  if (e.type === 'end') process.stdout.write(`ENDED ${JSON.stringify(e.result)}\n`);
});
setInterval(() => {}, 60_000);
