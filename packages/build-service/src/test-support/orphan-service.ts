/**
 * Child process of sweep.docker.test.ts (run compiled: `node dist/test-support/orphan-service.js
 * CACHE_DIR`): a build service with the Docker sandbox runs a job whose program loops for ever,
 * prints `LOOPING <job id>` once the loop runs, then waits to be killed (kill -9: the container
 * it leaves behind is what the next service must sweep).
 */
import { JobService } from '../job-service.js';
import { infiniteLoop, makeProject } from './c-projects.js';

const cacheDir = process.argv[2];
if (!cacheDir) {
  process.stderr.write('usage: orphan-service.js CACHE_DIR\n');
  process.exit(2);
}
const service = new JobService({ sandbox: 'docker', concurrency: 1, cacheDir, log: (l) => process.stderr.write(`${l}\n`) });
const job = await service.submit({ action: 'run', kind: 'make', project: { files: makeProject(infiniteLoop) } });
job.events.subscribe(0, (e) => {
  if (e.type === 'line' && e.line === 'looping') process.stdout.write(`LOOPING ${job.id}\n`);
  if (e.type === 'end') process.stdout.write(`ENDED ${JSON.stringify(e.result)}\n`);
});
setInterval(() => {}, 60_000);
