/** The host trust boundary in bwrap (test-support/host-trust-suite.ts), plus an oversized model. */
import { afterAll, expect, test } from 'vitest';
import { createBuildServer } from './server.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { hostTrustSuite } from './test-support/host-trust-suite.js';
import { tutorialFiles } from './test-support/tutorial.js';

hostTrustSuite('bwrap');

const server = createBuildServer({ token: false, port: 0, concurrency: 1 });
afterAll(() => server.close());

test('an oversized model is refused by prepare with the named limit', async () => {
  const { url } = await server.listen();
  const files = { ...(await tutorialFiles()), 'padding.contract': `// ${'x'.repeat(1100 * 1024)}\n` };
  const r = await postJob(url, { action: 'build', kind: 'cactal', sandbox: 'bwrap', project: { files } });
  expect(r.status).toBe(201);
  const events = await readEvents(url, r.json.id as string);
  const job = await getJob(url, r.json.id as string);
  expect(job.status).toBe('failed');
  expect(job.result.message).toBe('prepare stopped: model size limit 1 MiB');
  expect(job.result.limitHit).toEqual({ name: 'modelBytes', value: 1024 * 1024, unit: 'bytes', mechanism: 'service-check' });
  expect(events.some((e: any) => e.type === 'limit' && e.limitHit.name === 'modelBytes')).toBe(true);
});
