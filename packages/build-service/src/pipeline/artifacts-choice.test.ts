/**
 * Which logs a run's collection takes when logs/ holds more than its bounds (docs/build-service-api.md
 * "Artifacts"), one rule for every sandbox: the runtime's logs of the modules the launcher started
 * first, then other runtime-named logs, then anything else, by name within each. A program that
 * fills logs/ with 1500 files of its own no longer pushes the modules' logs out of the 256 taken
 * (they were taken by name: `A_0.csv` … before `ORD_…`). And a cancel during the collection ends the
 * job at once, cancelled: a read under way is stopped (a job whose collection read for 5 s ended
 * `succeeded` 5 s after the cancel).
 */
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { describe, expect, test } from 'vitest';
import { DEFAULT_LIMITS } from '../limits.js';
import type { Sandbox } from '../sandbox/types.js';
import { scratchWorkspace, scriptedContext, scriptedSandbox } from '../test-support/scripted-sandbox.js';
import { CANCELLED_REASON, collectRunArtifacts, listHostDir, selectArtifacts, type DirEntryInfo, type WorkDirReader } from './artifacts.js';
import type { LineEvent } from './job-events.js';
import { Job } from './job.js';
import { RunIssues } from './run-issues.js';

const ORD_LOG = 'ORD_7-Dec-2026-03h00m00s.csv';
const OTHER_LOG = 'XYZ_7-Dec-2026-03h00m01s.csv';
const RECORDS = 'mono_ns,wall,module,event,a,b,0,d\n1,2026-12-07T03:00:00Z,ORD,module_started,,,0,pid=1\n';

const file = (name: string, text = ''): DirEntryInfo => ({ name, kind: 'file', size: text.length, read: async (max) => Buffer.from(text).subarray(0, max) });

describe('the logs taken when logs/ holds more than the bounds', () => {
  test("the launched modules' logs first, then other runtime-named logs, then the rest by name", async () => {
    const junk = Array.from({ length: 1500 }, (_, i) => file(`A_${i}.csv`));
    const listing = { entries: [...junk, file(OTHER_LOG, RECORDS), file(ORD_LOG, RECORDS)] };
    const { files, skipped } = await selectArtifacts(listing, undefined, undefined, { launchedModules: new Set(['ORD']) });
    expect(files).toHaveLength(256);
    expect(files.slice(0, 3).map((f) => f.name)).toEqual([ORD_LOG, OTHER_LOG, 'A_0.csv']);
    // the entries past the 1024 looked at are junk, said once; the junk past 256 files is lost, said each
    expect(skipped.at(-1)).toEqual({ name: 'logs/', reason: 'more than 1024 entries: the others were not looked at' });
    expect(skipped.filter((s) => s.bound).length).toBe(1024 - 256);
    expect(skipped.some((s) => s.name === ORD_LOG || s.name === OTHER_LOG)).toBe(false);
  });

  test('the host listing (bwrap, none) gives the runtime\'s logs first: 1500 files left beside them do not push them out of the entries looked at', async () => {
    const work = mkdtempSync(join(tmpdir(), 'artifacts-choice-'));
    try {
      mkdirSync(join(work, 'logs'));
      writeFileSync(join(work, 'logs', ORD_LOG), RECORDS);
      for (let i = 0; i < 1500; i++) writeFileSync(join(work, 'logs', `F_${i}.csv`), '');
      writeFileSync(join(work, 'logs', OTHER_LOG), RECORDS);
      const listing = await listHostDir(work, 'logs', 10);
      const names = listing && 'entries' in listing ? listing.entries.map((e) => e.name) : [];
      expect(names).toHaveLength(10);
      expect(names.slice(0, 2).sort()).toEqual([ORD_LOG, OTHER_LOG]);
      expect(listing).toMatchObject({ more: true });
    } finally {
      rmSync(work, { recursive: true, force: true });
    }
  });

  test('the launcher\'s lines name the modules it started (run-issues.ts)', () => {
    const issues = new RunIssues();
    issues.line('module ORD (pid 12) exited with status 0', 'launcher');
    issues.line('module CTL (pid 13) died by signal 9 (Killed)', 'launcher');
    issues.line('module FAKE (pid 14) exited with status 0', 'CTL'); // a module's own line names nothing
    expect([...issues.launchedModules].sort()).toEqual(['CTL', 'ORD']);
  });

  test('a cancel (the signal) leaves the files not read yet out, said, not lost to a bound', async () => {
    const abort = new AbortController();
    const reader: WorkDirReader = async () => new Map([['logs', { entries: [
      { ...file('A.csv', 'a\n'), read: async () => (abort.abort(), null) },
      file('B.csv', 'b\n'),
    ] }]]);
    const a = await collectRunArtifacts(reader, '/w', undefined, undefined, { signal: abort.signal });
    expect(a.files).toEqual([]);
    expect(a.skipped).toEqual([{ name: 'A.csv', reason: CANCELLED_REASON }, { name: 'B.csv', reason: CANCELLED_REASON }]);
  });
});

describe('a cancel during the collection of a run\'s logs', () => {
  test('ends the job cancelled at once: the read under way is stopped', async () => {
    const makefile = 'all:\n\ttrue\nrun:\n\ttrue\n';
    const job = new Job('j-collect-cancel', { action: 'run', project: { files: { Makefile: makefile } }, projectKey: null, kind: 'make', limits: { ...DEFAULT_LIMITS } }, 'none');
    let reading!: () => void;
    const readStarted = new Promise<void>((r) => (reading = r));
    // a slow read (a 256 MiB archive on a loaded engine): 5 s unless its signal aborts it
    const slowRead = (_max: number, signal?: AbortSignal): Promise<Buffer | null> => new Promise((resolve) => {
      reading();
      const timer = setTimeout(() => resolve(Buffer.from('x\n')), 5000);
      signal?.addEventListener('abort', () => {
        clearTimeout(timer);
        resolve(null);
      });
    });
    const sandbox: Sandbox = {
      ...scriptedSandbox({ run: { start: (p) => p.exit(0) } }),
      readWorkDirs: async (_w: string, rels: string[]) => new Map(rels.map((rel) => [rel, rel === 'logs' ? { entries: [{ name: 'BIG.csv', kind: 'file' as const, size: 2, read: slowRead }] } : null])),
      removeRunOutputs: async () => true,
    };
    const done = job.execute(scriptedContext(sandbox, scratchWorkspace()));
    await readStarted;
    const t0 = Date.now();
    await job.cancel();
    await done;
    expect(Date.now() - t0).toBeLessThan(2000);
    expect(job.status).toBe('cancelled');
    const lines = job.events.all.filter((e): e is LineEvent => e.type === 'line').map((e) => e.line);
    expect(lines).toContain(`collected 0 artifact(s) in ${job.artifactsJSON()!.collect_ms} ms; left out: BIG.csv (${CANCELLED_REASON})`);
  });

  test('a cancel during the run still lets the collection take what the stopped run wrote', async () => {
    const makefile = 'all:\n\ttrue\nrun:\n\ttrue\n';
    const job = new Job('j-run-cancel', { action: 'run', project: { files: { Makefile: makefile } }, projectKey: null, kind: 'make', limits: { ...DEFAULT_LIMITS } }, 'none');
    const sandbox: Sandbox = {
      ...scriptedSandbox({ run: { start: (p) => p.write('stdout', 'running'), terminate: async (p) => (setTimeout(() => p.exit(0), 10), true) } }),
      readWorkDirs: async (_w: string, rels: string[]) => new Map(rels.map((rel) => [rel, rel === 'logs' ? { entries: [file(ORD_LOG, RECORDS)] } : null])),
      removeRunOutputs: async () => true,
    };
    job.events.subscribe(0, (e) => {
      if (e.type === 'line' && e.line === 'running') void job.cancel();
    });
    await job.execute(scriptedContext(sandbox, scratchWorkspace()));
    expect(job.status).toBe('cancelled');
    expect(job.artifactsJSON()!.files.map((f) => f.name)).toEqual([ORD_LOG]);
  });
});
