/**
 * Real-time mode in the Docker sandbox (docs/sandbox.md, "Real-time mode"), on the report's
 * tutorial: where the engine can grant it, MAA sees SCHED_FIFO 30 from inside its container; where
 * it cannot (no real-time budget for its containers, no CAP_SYS_RESOURCE to raise RLIMIT_RTPRIO),
 * the job fails with a message saying what the engine needs — never a module silently at a nice
 * level, never a bare engine error.
 */
import { expect, test } from 'vitest';
import type { LineEvent } from './pipeline/job-events.js';
import { DockerSandbox } from './sandbox/docker.js';
import { useBuildServer } from './test-support/build-server.js';
import { getJob, postJob, readEvents } from './test-support/client.js';
import { dockerUp } from './test-support/docker-env.js';
import { MAA_MODULE, tutorialFiles, withRegion } from './test-support/tutorial.js';

const docker = dockerUp();

const served = useBuildServer({ concurrency: 1, sandbox: 'docker' }, { skip: !docker.available, afterClose: () => docker.stop(), timeoutMs: 300_000 });

if (!docker.available) test.skip(`docker: SKIPPED — ${docker.reason}`, () => {});

test.skipIf(!docker.available)('a real-time run in docker: SCHED_FIFO at the module priority, or refused saying what the engine needs', async () => {
  const files = withRegion(
    withRegion(await tutorialFiles(), MAA_MODULE, 'protect_additional_import_MAA', '#include <sched.h>\n#include <stdio.h>', true),
    MAA_MODULE,
    'protect_init_MAA',
    '    { struct sched_param sp; sched_getparam(0, &sp); printf("policy=%s priority=%d\\n", (sched_getscheduler(0) & ~0x40000000 /* SCHED_RESET_ON_FORK */) == SCHED_FIFO ? "SCHED_FIFO" : "other", sp.sched_priority); fflush(stdout); }',
    true,
  );
  const support = await new DockerSandbox().realtimeSupport();
  const r = await postJob(served.url, { action: 'run', duration: 2, realtime: true, project: { files } });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const lines = (await readEvents(served.url, r.json.id as string)).filter((e): e is LineEvent => e.type === 'line');
  const job = await getJob(served.url, r.json.id as string);
  const run = lines.filter((l) => l.step === 'run');
  console.info(`docker real-time mode here: ${support.ok ? support.detail : support.reason} -> ${job.status}: ${job.result?.message}`);
  if (!support.ok) {
    expect(job.result.message).toBe(`real-time mode refused: ${support.reason}`);
    expect(support.reason).toMatch(/dockerd with --cpu-rt-runtime=/);
    expect(lines.some((l) => l.step === 'build')).toBe(false);
  } else if (job.status === 'succeeded') {
    expect(run.filter((l) => l.source === 'MAA' && l.line.startsWith('policy='))).toMatchObject([{ line: 'policy=SCHED_FIFO priority=30' }]);
    expect(run.filter((l) => /SCHED_FIFO not permitted/.test(l.line))).toEqual([]);
    expect(job.result.mechanisms.realtime).toMatch(/^SCHED_FIFO up to 99 \(ulimit rtprio\)/);
  } else {
    expect(job.result.message).toMatch(/^run failed: real-time mode refused by the Docker engine: .+ — it needs a real-time budget for its containers \(dockerd --cpu-rt-runtime=400000 or more\)/);
    expect(run.filter((l) => l.source === 'MAA')).toEqual([]);
  }
}, 600_000);
