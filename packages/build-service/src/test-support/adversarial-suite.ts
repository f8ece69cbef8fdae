/**
 * Adversarial programs in one sandbox, all submitted at once next to an honest job: each is
 * stopped with the right message, the honest job completes untouched, nothing outlives the jobs.
 * Used by adversarial.bwrap.test.ts and adversarial.docker.test.ts.
 */
import { existsSync, mkdtempSync, readdirSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { createServer, type Server } from 'node:net';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { freshWorkspaces } from './scratch.js';

import { createBuildServer, type BuildServer } from '../server.js';
import {
  bigAllocation,
  connectProgram,
  forkBomb,
  honestProgram,
  infiniteLoop,
  makeProject,
  nestedUserNamespace,
  outputFlood,
  writeOutsideProgram,
} from './c-projects.js';
import { postJob, readEvents, getJob } from './client.js';
import type { JobEvent, LineEvent } from '../pipeline/job-events.js';
import type { SandboxName } from '../sandbox/types.js';
import { descendantsOf } from '../sandbox/host-process.js';
import { CUT_LINE } from '../util/line-splitter.js';

interface Outcome {
  job: Record<string, any>;
  events: JobEvent[];
  lines: LineEvent[];
}

export function adversarialSuite(sandbox: SandboxName, mechanism: string, extraChecks: () => Promise<void> = async () => {}): void {
let server: BuildServer;
let url: string;
let listener: Server;
let connections = 0;
let hostDir: string;
let cacheDir: string;
const outcomes: Record<string, Outcome> = {};

async function runToEnd(name: string, files: Record<string, string>, limits: Record<string, number> = {}): Promise<void> {
  const r = await postJob(url, { action: 'run', kind: 'make', sandbox, project: { files }, limits });
  expect(r.status, JSON.stringify(r.json)).toBe(201);
  const events = await readEvents(url, r.json.id as string);
  outcomes[name] = { job: await getJob(url, r.json.id as string), events, lines: events.filter((e): e is LineEvent => e.type === 'line') };
}

beforeAll(async () => {
  hostDir = mkdtempSync(join(tmpdir(), 'contract-host-'));
  writeFileSync(join(hostDir, 'secret.txt'), 'host data\n');
  cacheDir = mkdtempSync(join(tmpdir(), 'contract-cache-'));
  listener = createServer((s) => {
    connections++;
    s.destroy();
  });
  await new Promise<void>((r) => listener.listen(0, '127.0.0.1', r));
  const port = (listener.address() as { port: number }).port;
  server = createBuildServer({ token: false, port: 0, concurrency: 8, queueSize: 0, cacheDir });
  url = (await server.listen()).url;
  await Promise.all([
    runToEnd('honest', makeProject(honestProgram(200))),
    runToEnd('forkBomb', makeProject(forkBomb)),
    runToEnd('allocation', makeProject(bigAllocation)),
    runToEnd('loop', makeProject(infiniteLoop), { runSeconds: 4 }),
    runToEnd('connect', makeProject(connectProgram(port))),
    runToEnd(
      'writeOutside',
      makeProject(writeOutsideProgram([join(hostDir, 'pwned.txt'), join(hostDir, 'secret.txt'), '/usr/pwned', '/etc/pwned', '/pwned', '/tmp/private-ok'])),
    ),
    runToEnd('flood', makeProject(outputFlood)),
    runToEnd('userns', makeProject(nestedUserNamespace)),
  ]);
}, 180_000);

afterAll(async () => {
  await server?.close();
  listener?.close();
  rmSync(hostDir, { recursive: true, force: true });
  rmSync(cacheDir, { recursive: true, force: true });
});

describe(`${sandbox} sandbox, adversarial jobs running together`, () => {
  test('the honest job completes with all its output', () => {
    const { job, lines } = outcomes.honest!;
    expect(job.status).toBe('succeeded');
    expect(lines.filter((l) => l.step === 'run' && l.stream === 'stdout' && /^out \d+$/.test(l.line))).toHaveLength(200);
    expect(lines.filter((l) => l.step === 'run' && l.stream === 'stderr' && /^err \d+$/.test(l.line))).toHaveLength(200);
    expect(lines.some((l) => l.line === 'honest done')).toBe(true);
    expect(job.result.mechanisms).toMatchObject({ memory: mechanism, processes: mechanism });
  });

  test('a fork bomb is stopped by the process limit', () => {
    const { job } = outcomes.forkBomb!;
    expect(job.status).toBe('failed');
    expect(job.result.message).toBe('killed: process limit 256');
    // the program whose forks filled the limit is named (its children keep its name)
    expect(job.result.limitHit).toMatchObject({ name: 'processes', value: 256, unit: 'count', mechanism, module: 'prog' });
    expect(job.result.limitHit.moduleProcesses).toBeGreaterThan(100);
  });

  test('a 4 GiB allocation is stopped by the memory limit', () => {
    const { job } = outcomes.allocation!;
    expect(job.status).toBe('failed');
    expect(job.result.message).toBe('killed: memory limit 512 MiB');
    expect(job.result.limitHit).toMatchObject({ name: 'memory', value: 512 * 1024 * 1024, mechanism });
  });

  test('an infinite loop is stopped by the run time limit', () => {
    const { job, events } = outcomes.loop!;
    expect(job.status).toBe('failed');
    expect(job.result.message).toBe('killed: run time limit 4 s');
    const limit = events.find((e) => e.type === 'limit')!;
    expect(limit).toBeDefined();
    // the kill is prompt: from the limit to the moment every process of the run is gone (the
    // step's `run: killed: ...` line, written once the sandbox reported the exit), within the cancel
    // deadline (docs/sandbox.md); artifact collection and the workspace's release come after it
    const killed = events.find((e): e is LineEvent => e.type === 'line' && e.stream === 'system' && e.line === 'run: killed: run time limit 4 s');
    expect(killed).toBeDefined();
    console.info(`${mechanism}: run time limit -> every process of the loop gone: ${killed!.t - limit.t} ms`);
    expect(killed!.t - limit.t).toBeLessThan(2000);
    expect(killed!.t).toBeGreaterThanOrEqual(limit.t);
  });

  test('connect() to a server listening on the host 127.0.0.1 fails (own empty network)', () => {
    const { job, lines } = outcomes.connect!;
    expect(job.status).toBe('succeeded');
    expect(lines.some((l) => /^connect failed: (Connection refused|Network is unreachable)$/.test(l.line))).toBe(true);
    expect(lines.some((l) => l.line === 'CONNECTED')).toBe(false);
    expect(connections).toBe(0);
  });

  test('writing outside the work dir is refused; the host is untouched', () => {
    const { job, lines } = outcomes.writeOutside!;
    expect(job.status).toBe('succeeded');
    const text = lines.map((l) => l.line);
    for (const p of [join(hostDir, 'pwned.txt'), join(hostDir, 'secret.txt'), '/usr/pwned', '/etc/pwned', '/pwned']) {
      expect(text.some((t) => t.startsWith(`refused ${p}:`)), p).toBe(true);
    }
    // /tmp inside the sandbox is private and writable (the compiler needs it), not the host's
    expect(text).toContain('WROTE /tmp/private-ok');
    expect(existsSync('/tmp/private-ok')).toBe(false);
    expect(existsSync(join(hostDir, 'pwned.txt'))).toBe(false);
    expect(readFileSync(join(hostDir, 'secret.txt'), 'utf8')).toBe('host data\n');
    expect(existsSync('/usr/pwned') || existsSync('/etc/pwned') || existsSync('/pwned')).toBe(false);
  });

  test('100 MiB of output is cut at 1 MiB per stream with a notice; the job is not confused by it', () => {
    const { job, lines } = outcomes.flood!;
    // the processes ended well, but the run's record is not whole: a run issue, not a success
    // (docs/build-service-api.md "Run issues")
    expect(job.status).toBe('failed');
    expect(job.result.exitCode).toBe(0);
    expect(job.result.issues.map((i: { kind: string }) => i.kind)).toEqual(['output-truncated']);
    expect(job.result.message).toMatch(/^run finished with 1 problem\(s\): the run's stdout went past the output limit/);
    expect(job.result.truncated.stdout).toBe(true);
    // the line the limit falls inside is kept as far as it goes and said cut (its mark is not output)
    const run = lines.filter((l) => l.step === 'run' && l.stream === 'stdout').map((l) => l.line);
    expect(run.filter((l) => l.endsWith(CUT_LINE)).length).toBeLessThanOrEqual(1);
    const kept = run.reduce((n, l) => n + Buffer.byteLength(l.endsWith(CUT_LINE) ? l.slice(0, -CUT_LINE.length) : l) + 1, 0);
    expect(kept).toBeLessThanOrEqual(1024 * 1024 + 1); // + the newline the cut last line did not have
    expect(kept).toBeGreaterThan(1000 * 1024);
    expect(lines.filter((l) => l.stream === 'system' && l.line === '[output truncated: stdout limit 1 MiB reached]')).toHaveLength(1);
    expect(lines.some((l) => l.line === 'flood done')).toBe(false);
  });

  test('no nested user namespace can be created', () => {
    const { job, lines } = outcomes.userns!;
    expect(job.status).toBe('succeeded');
    expect(lines.some((l) => /^unshare refused: /.test(l.line))).toBe(true);
    expect(lines.some((l) => l.line === 'USERNS CREATED')).toBe(false);
  });

  test('cancel mid-run stops the job within 2 s', async () => {
    const r = await postJob(url, { action: 'run', kind: 'make', sandbox, project: { files: makeProject(infiniteLoop) } });
    let t0 = 0;
    await readEvents(url, r.json.id as string, (e) => {
      if (!t0 && e.type === 'line' && e.line === 'looping') {
        t0 = Date.now();
        void fetch(`${url}/api/jobs/${r.json.id}`, { method: 'DELETE' });
      }
    });
    expect(Date.now() - t0).toBeLessThan(2000);
    expect((await getJob(url, r.json.id as string)).status).toBe('cancelled');
  });

  test('nothing outlives the jobs: no process of a job uid, no job cgroup, no fresh work dir', async () => {
    // only this test's jobs count: other services may run jobs on this machine at the same time
    const left = descendantsOf(process.pid).filter((p) => {
      try {
        return /^Name:\s+(bwrap|make|prog|sh|setpriv)$/m.test(readFileSync(`/proc/${p}/status`, 'utf8'));
      } catch {
        return false;
      }
    });
    expect(left).toEqual([]);
    const ownPids = readFileSync('/proc/self/cgroup', 'utf8').match(/^\d+:pids:(.*)$/m)?.[1] ?? '/';
    const ids = Object.values(outcomes).map((o) => o.job.id as string);
    expect(readdirSync(join('/sys/fs/cgroup/pids', ownPids)).filter((d) => ids.some((id) => d.startsWith(`contract-${id}`)))).toEqual([]);
    expect(freshWorkspaces(cacheDir)).toEqual([]);
    await extraChecks();
  });
});
}
